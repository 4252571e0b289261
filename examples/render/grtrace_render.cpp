// grtrace-render: renders what a camera near a Schwarzschild black hole (or in flat space) sees, to an OpenEXR
// file with data channels and an 8-bit PNG preview beside it, with a progress bar on a terminal, and ends with
// ONE line of JSON (contract in shared/DESIGN.md):
//   {"width","height","seconds","rays_per_second","mean_steps","status_counts":{...},"tracer","tableau","rtol",
//    "atol","out", ...}
// All input is checked before any ray is traced; bad input exits with code 2 and leaves no file behind.
#include "camera_options.hpp"
#include "command_line.hpp"
#include "flight_options.hpp"
#include "json_writer.hpp"
#include "kerr_options.hpp"
#include "method_options.hpp"
#include "metric_options.hpp"
#include "render_request.hpp"

#include "grtrace/app/flight_worldline.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/flight_path.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/flight_files.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/frame_files.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/scene/standard_scenes.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>

namespace {

using namespace grtrace;
using tools::CommandLine;
using tools::JsonObject;
using tools::UsageError;
using render_tool::Request;
using render_tool::SkyDirections;
using render_tool::FlightRequest;

CommandLine make_command_line() {
  CommandLine cli("grtrace-render",
                  "Render a camera's view of a black hole (Schwarzschild, Kerr, charged, with a cosmological constant),\n"
                  "a wormhole or flat space to OpenEXR + PNG preview;\n"
                  "prints one line of JSON. Defaults: the seed report's main frame (static camera at r = 200 M,\n"
                  "fov 90, 1024x1024, sky sphere at 400 M). The default method (rkf78, I control, rtol 1e-9) is\n"
                  "the cheapest whose largest error stays below 1e-6 both on that frame (angle, general tracer) and\n"
                  "on the Kerr disk frame (hit radius, redshift); the planar tracer's table costs the same with it\n"
                  "as with tsit5 (docs/benchmarks.md).");
  cli.option("scene", "checker", "checker | sky | redshift | disk");
  tools::declare_metric_options(
      cli, tools::all_metric_names(),
      "schwarzschild | minkowski (flat: straight lines, never integrated) | kerr | rn (Reissner-Nordstrom) | "
      "sds (Schwarzschild-de Sitter) | wormhole (Ellis) | schwarzschild-ef (Eddington-Finkelstein)");
  cli.option("chart", "bl", tools::kKerrChartHelp);
  tools::declare_camera_options(cli, {"200", "90", "90",
                                      "camera radius (must be outside the horizon guard and inside --sky-radius)"});
  cli.option("width", "1024", "image width in pixels")
      .option("height", "1024", "image height in pixels");
  tools::declare_method_options(cli, "", {});  // rkf78 + I, rtol 1e-9, atol 1e-11
  cli.option("sky-radius", "400", "radius of the sky sphere where rays are taken as escaped")
      .option("angle-correction", "exact", "escaped rays: none | flat (seed eq. 7-8) | exact (bending to infinity)")
      .option("max-steps", "100000", "step budget per ray")
      .option("tracer", "auto",
              "auto | general | planar. planar: one table of rays for the frame, every "
              "scene of a Schwarzschild hole, disk included (auto's choice there with an adaptive "
              "--control; it also draws every frame the retired symmetric table drew); general: "
              "every pixel integrated (any metric). auto picks kerr-mino for --metric kerr --chart "
              "bl with an adaptive --control: every pixel on Kerr's separated equations in Mino "
              "time, 3x cheaper per ray than general")
      .option("device", "auto",
              "auto | cpu | cuda. cuda: rays traced on the GPU (a build with the CUDA backend and "
              "a CUDA device; --tableau rkf78 --control i; every pixel integrated: --tracer "
              "general, or auto = kerr-mino for --metric kerr --chart bl, general otherwise; not yet "
              "verified on a GPU: see the README); auto: the CPU until the GPU backend passes its "
              "device checks. The JSON line and the EXR header (device) name the device that ran")
      .option("table-rays", std::to_string(grtrace::default_table_rays),
              "planar tracer: table rays on each side of the critical angle")
      .option("sky-texture", "", "equirectangular EXR (R,G,B) for the sky of the sky and disk scenes")
      .option("checker-squares", "18", "checker scene: squares along theta on sky and horizon (twice as many in phi)")
      .option("disk-inner", "6", tools::disk_inner_help())
      .option("disk-outer", "20", "disk outer radius (disk scene)")
      .option("threads", "0", "OpenMP threads (0 = all cores)")
      .option("out", "render.exr", "output EXR path; the PNG preview goes beside it with .png")
      .option("exr-compression", "zips",
              "EXR compression, all lossless (channels read back bit for bit): zips | zip "
              "(deflate level 1; zips: one scanline per chunk) | piz (smallest, slower) | "
              "rle | none (fastest, largest)")
      .flag("error-map",
            "add an \"error\" channel: the angular error (rad) of each escaped pixel against the exact "
            "elliptic-integral direction from the camera (Schwarzschild/flat only); write <out>-error.png "
            "(heat map, log scale 1e-12 .. 1e-2 rad) and report max_error/median_error in the JSON")
      .flag("status-map", "also write <out>-status.png: each pixel coloured by how its ray ended (legend in --help)")
      .flag("no-mirrors",
            "trace every pixel: by default a frame that is mirror symmetric (camera on the equator looking along its "
            "axes; no metric rotation or orbiting disk for the left-right mirror) traces half or a quarter of its "
            "pixels and reflects the rest (JSON traced_rays, EXR header mirrors)");
  tools::declare_disk_retrograde_flag(cli, "");
  tools::declare_flight_options(cli,
                                "grtrace-render renders a sequence along it instead of one frame (aberration and "
                                "Doppler from the camera's u): <out stem>-NNNN.exr and .png; a re-run skips the "
                                "frames already written whole by the same flight",
                                "");
  cli.option("frame-range", "", "flight: render only frames A .. B-1 (A:B, 0-based, B one past the last): one part "
                                "of a flight split over a cluster (a Slurm job array, see the README); any order, "
                                "resumable; the frames are those of one whole run")
      .option("fps", "30", "flight --mp4: frames per second")
      .flag("mp4", "flight: also write <out stem>.mp4 from the PNG previews (ffmpeg, H.264)");
  return cli;
}

std::string png_path(const std::string& exr) { return exr.substr(0, exr.size() - 4) + ".png"; }
std::string status_map_path(const std::string& exr) { return exr.substr(0, exr.size() - 4) + "-status.png"; }
std::string error_map_path(const std::string& exr) { return exr.substr(0, exr.size() - 4) + "-error.png"; }

std::string flight_exr_path(const Request& q, int i) {
  return flight_frame_path(q.out, i, static_cast<int>(q.flight.cameras.size())).string();
}
std::string mp4_path(const std::string& exr) { return exr.substr(0, exr.size() - 4) + ".mp4"; }

/// Every file a run writes: the EXR, its PNG preview, and the maps asked for; for a flight every frame's EXR and
/// PNG and the MP4 if asked for.
std::vector<std::string> output_paths(const Request& q, bool status_map, bool mp4) {
  if (!q.flight.cameras.empty()) {
    std::vector<std::string> out;
    for (int i = 0; i < static_cast<int>(q.flight.cameras.size()); ++i) {
      out.push_back(flight_exr_path(q, i));
      out.push_back(png_path(out.back()));
    }
    if (mp4) out.push_back(mp4_path(q.out));
    return out;
  }
  std::vector<std::string> out{q.out, png_path(q.out)};
  if (status_map) out.push_back(status_map_path(q.out));
  if (q.error_map) out.push_back(error_map_path(q.out));
  return out;
}

/// The camera path of --flight (checked, before any work): the start (a preset, or --camera-r/-theta/-phi with
/// --orbit-dr/--orbit-dphi), the proper-time step (--frame-dtau, or automatic: one revolution over the frames, or
/// the fall to 1.1 r_h), the path sampled (observer/worldline.hpp) and one camera per frame pointed by
/// --look/--up (`cam`, read with the single frame's camera; make_moving_camera). Refuses what a single frame's
/// camera would, plus a path that ends (horizon, sky sphere) before its last frame, and the options that describe a
/// single frame only.
void read_flight(const CommandLine& cli, const tools::CameraOptions& cam, Request& q) {
  FlightRequest& f = q.flight;
  const std::optional<FlightPathSpec> spec =
      tools::read_flight_spec(cli, q.metric.mass, q.settings.escape_radius,
                              {"fps", "mp4", "orbit-dr", "orbit-dphi", "frame-range"});
  if (!spec) return;
  refuse_inapplicable_options(cli, {{"orbit-dr", spec->kind == "orbit", "--flight orbit"},
                                    {"orbit-dphi", spec->kind == "orbit", "--flight orbit"}});
  f.name = spec->kind;
  for (const char* name : {"velocity", "observer"})
    if (cli.given(name))
      throw UsageError(std::string("--") + name + " sets a single frame's camera; a flight's camera moves with its "
                       "path (its 4-velocity): leave it out");
  if (cli.flag_set("status-map") || q.error_map)
    throw UsageError("--status-map and --error-map are for single frames; leave them out with --flight");
  if (!(cli.number("fps") > 0.0 && cli.number("fps") <= 1000.0)) throw UsageError("--fps must lie in (0, 1000]");
  // The video's tool, before the first ray (not after the frames).
  if (cli.flag_set("mp4") && !program_on_path("ffmpeg"))
    throw UsageError("--mp4 needs ffmpeg, which is not on PATH; install it (apt-get install ffmpeg, or bash "
                     "cmake/install-deps.sh) or leave --mp4 out");
  const CameraView view{cam.look, cam.up, q.camera->width(), q.camera->height(), q.camera->fov_degrees()};
  // Kerr-Schild flights are flown in the ingoing slicing, regular where the falling camera crosses the horizon.
  if (q.metric.chart == "ks") q.metric.slicing = KerrSchildSlicing::ingoing;
  const Worldline path = tools::checked_flight_path(*spec, [&] { return app::flight_worldline(q.metric, *spec); });
  with_named_metric(q.metric, [&](const auto& m) { f.cameras = flight_cameras(m, path, view); });
  f.dtau = frame_step(path);
  for (const WorldlineSample& s : path.samples) f.tau.push_back(s.tau);
  if (cli.given("frame-range")) {
    try {
      f.range = parse_flight_frame_range(cli.text("frame-range"), static_cast<int>(f.cameras.size()));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    if (cli.flag_set("mp4"))
      throw UsageError("--mp4 assembles every frame of the flight, not --frame-range's part: once every part is "
                       "done, run the same command without --frame-range, with --mp4 (the frames on disk are "
                       "skipped)");
  }
  q.camera = f.cameras.front();
}

Request read_request(const CommandLine& cli) {
  Request q;
  q.scene.name = cli.text("scene");
  if (!is_standard_scene(q.scene.name))
    throw UsageError("unknown scene '" + q.scene.name + "'; choose checker, sky, redshift or disk");
  const bool disk = q.scene.name == "disk";
  q.metric = tools::read_metric_options(cli, cli, tools::all_metric_names(), cli.text("chart"));
  const MetricSpec& ms = q.metric;
  refuse_inapplicable_options(cli, {{"disk-inner", disk, "--scene disk"},
                                    {"disk-outer", disk, "--scene disk"},
                                    {"disk-retrograde", disk, "--scene disk"}});
  // The wormhole's other universe (rays ending at l < 0) gets a sky of its own, seen through the throat.
  q.scene.far_side = ms.name == "wormhole";
  if (ms.name == "minkowski" && disk)
    throw UsageError("--scene disk needs a metric with a mass (the disk orbits it), not --metric minkowski");

  // The method group (examples/common/method_options.hpp): one of the offered methods, its tolerances and step.
  const app::MethodChoice method = tools::read_method_options(cli, "");
  q.tableau = method.tableau;
  q.control = method.control;
  TraceSettings& s = q.settings;
  s = method.settings;
  s.max_steps = tools::read_max_steps(cli);
  s.escape_radius = cli.number("sky-radius");
  if (!(s.escape_radius > 0.0 && s.escape_radius <= 1e100))
    throw UsageError("--sky-radius must lie in (0, 1e100] (r^2 must not overflow), got " + cli.text("sky-radius"));
  // A step longer than the sky's diameter crosses the whole scene in one go: meaningless, not just coarse.
  if (s.initial_step > 2.0 * s.escape_radius)
    throw UsageError("--step " + cli.text("step") + " is longer than the sky's diameter (2 x --sky-radius = " +
                     JsonObject::number(2.0 * s.escape_radius) + "); use a step in (0, " +
                     JsonObject::number(2.0 * s.escape_radius) + "]");

  q.correction_name = cli.text("angle-correction");
  q.correction = tools::read_angle_correction(cli);

  const tools::CameraOptions cam = tools::read_camera_options(cli, cli, ms.name);
  // In the metric's own radius (Boyer-Lindquist r for Kerr in both charts, the areal radius r(l) of the wormhole):
  // outside the horizon guard and inside the sky sphere.
  const auto [camera_radius, guard, sky_ok] = with_named_metric(ms, [&](const auto& m) {
    const Vec4 x = event_from_spherical(m, Vec4(0.0, cam.r, std::numbers::pi / 2.0, 0.0));
    const double rh = ms.name == "kerr" ? KerrMetric{ms.mass, ms.spin}.horizon_radius() : m.horizon_radius();
    const Vec4 sky_event(0.0, s.escape_radius, std::numbers::pi / 2.0, 0.0);  // emitters at rest must exist there
    const bool ok = static_velocity(m.metric(event_from_spherical(m, sky_event))).has_value();
    return std::tuple{m.radius(x), (1.0 + s.horizon_epsilon) * rh, ok};
  });
  tools::check_camera_radius(cli.text("camera-r"), camera_radius, guard, s.escape_radius);
  if (!sky_ok)
    throw UsageError("--sky-radius " + cli.text("sky-radius") +
                     " lies beyond a horizon of this metric (no emitter can be at rest there); lower it");
  const long width = cli.integer("width"), height = cli.integer("height");
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw UsageError("--width and --height must be between 1 and 16384 pixels");
  {  // the image's memory, before anything is allocated: the channels (+ error channel and double directions
     // with --error-map) and the 8-bit previews
    const bool error_map = cli.flag_set("error-map");
    const double pixels = static_cast<double>(width) * static_cast<double>(height);
    const double bytes = image_bytes(static_cast<double>(width), static_cast<double>(height),
                                     static_cast<double>(Image::kStandardChannels.size() + (error_map ? 1 : 0))) +
                         pixels * (3.0 + (error_map ? 2.0 * sizeof(double) * 2.0 : 0.0));
    try {
      check_memory(bytes, "--width " + std::to_string(width) + " --height " + std::to_string(height));
    } catch (const MemoryLimitError& e) {
      throw UsageError(std::string(e.what()) + "; or choose a smaller --width/--height");
    }
  }
  const long threads = cli.integer("threads");
  if (threads < 0 || threads > 1024) throw UsageError("--threads must be 0 (all cores) .. 1024");
  q.threads = static_cast<int>(threads);
  const long nodes = cli.integer("table-rays");
  if (nodes < 8 || nodes > 1'000'000) throw UsageError("--table-rays must be in 8 .. 1e6");
  q.table_nodes = static_cast<int>(nodes);

  const CameraSpec spec = cam.spec(static_cast<int>(width), static_cast<int>(height));
  try {
    q.camera.emplace(with_named_metric(ms, [&](const auto& m) { return make_camera(m, spec); }));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }

  q.tracer = cli.text("tracer");

  const long squares = cli.integer("checker-squares");
  if (squares < 1 || squares > 10000) throw UsageError("--checker-squares must be in 1 .. 10000");
  q.scene.checker_squares = static_cast<int>(squares);
  if (const std::string tex = cli.text("sky-texture"); !tex.empty()) {
    try {
      const Image img = read_exr(tex);
      if (!img.has_channel("R") || !img.has_channel("G") || !img.has_channel("B"))
        throw UsageError("--sky-texture '" + tex + "' has no R, G, B channels");
      q.scene.texture = TextureSky{img.width(), img.height(), img.channel("R"), img.channel("G"), img.channel("B")};
      check_texture(*q.scene.texture);  // a NaN texel would make every ray that sees it non_finite
    } catch (const UsageError&) {
      throw;
    } catch (const std::exception& e) {
      throw UsageError("--sky-texture: " + std::string(e.what()));
    }
  }
  q.scene.disk.r_in = cli.number("disk-inner");
  q.scene.disk.r_out = cli.number("disk-outer");
  if (disk) tools::set_disk_sense_and_isco(cli, ms, q.scene.disk);
  if (disk) {
    try {
      with_named_metric(ms, [&](const auto& m) { check_disk_orbits(m, q.scene.disk); });
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string(e.what()) + " (--disk-inner, --disk-outer)");
    }
  }

  q.error_map = cli.flag_set("error-map");
  q.mirror_symmetry = !cli.flag_set("no-mirrors");
  if (q.error_map && ms.name != "schwarzschild" && ms.name != "minkowski")
    throw UsageError("--error-map needs --metric schwarzschild or minkowski (the exact elliptic-integral reference)");

  // Which tracer can draw this metric, scene and method is the application layer's answer (check_frame_request);
  // auto picks the fastest tracer whose assumptions hold (trace/auto_tracer.hpp), and the JSON line and the EXR
  // header say which one ran.
  // The device likewise (choose_device): --device cuda where the GPU cannot draw the request is refused here,
  // before any work, saying what to use instead.
  try {
    q.device = app::choose_device(cli.text("device"), render_tool::frame_request(q));
    app::check_frame_request(render_tool::frame_request(q));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }

  q.out = cli.text("out");
  tools::check_exr_output_name("out", q.out);
  read_flight(cli, cam, q);
  // Every file this run writes, checked before any work: writable, not a directory or device, not an input (the
  // texture, the camera path, the --config file).
  for (const std::string& path : output_paths(q, cli.flag_set("status-map"), cli.flag_set("mp4")))
    tools::check_command_output(cli, "out", path,
                                {{"sky-texture", cli.text("sky-texture")}, {"flight-csv", cli.text("flight-csv")}});
  return q;
}

/// Status colours of the failure map: escaped light grey, captured black, hit blue, max_steps orange,
/// step_underflow red, non_finite magenta.
constexpr std::array<std::array<std::uint8_t, 3>, kRayStatusCount> kStatusColours = {
    {{200, 200, 200}, {0, 0, 0}, {40, 90, 220}, {255, 150, 0}, {220, 20, 20}, {230, 0, 230}}};

void write_status_map(OutputSet& set, const std::string& path, const Image& image) {
  const auto& status = image.channel("status");
  std::vector<std::uint8_t> rgb(status.size() * 3);
  for (std::size_t i = 0; i < status.size(); ++i) {
    const auto s = static_cast<std::size_t>(std::clamp(static_cast<int>(status[i]), 0, static_cast<int>(kRayStatusCount) - 1));
    for (std::size_t c = 0; c < 3; ++c) rgb[3 * i + c] = kStatusColours[s][c];
  }
  write_png_rgb8(set, path, image.width(), image.height(), rgb);
}

/// Sky direction of every pixel in double precision (the EXR channels are float), kept for --error-map.
using SkyDirections = std::vector<exact::SkyDirection>;

// ---- --error-map: every escaped pixel against the exact answer ------------------------------------------

struct ErrorSummary {
  double max = std::numeric_limits<double>::quiet_NaN();
  double median = std::numeric_limits<double>::quiet_NaN();
  long judged = 0;      ///< escaped pixels with an exact direction
  long mismatches = 0;  ///< escaped where the exact ray is captured, or captured where it escapes
};

/// Fills the "error" channel (radians; NaN where the ray did not escape; pi where the escaped/captured verdict
/// disagrees with the exact one) after the timed render, in double precision, and summarises it.
ErrorSummary compute_error_channel(const Request& q, Image& image, const SkyDirections& directions) {
  const Camera& cam = *q.camera;
  const auto& status = image.channel("status");
  std::vector<float>& error = image.add_channel("error", std::numeric_limits<float>::quiet_NaN());
  std::vector<double> exact_error(image.pixel_count(), std::numeric_limits<double>::quiet_NaN());
  const long n = static_cast<long>(image.pixel_count());
  const double mass = q.metric.name == "minkowski" ? 0.0 : q.metric.mass;
  long mismatches = 0;
#if defined(_OPENMP)
  const int threads = q.threads > 0 ? q.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : mismatches) num_threads(threads)
#endif
  for (long i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const auto s = static_cast<RayStatus>(static_cast<int>(status[k]));
    if (s != RayStatus::escaped && s != RayStatus::captured) continue;  // hit an object or failed: not judged
    const int col = static_cast<int>(i % image.width()), row = static_cast<int>(i / image.width());
    const auto truth = exact::asymptotic_direction(cam.pixel_state(col, row), mass);
    if ((s == RayStatus::escaped) != truth.has_value()) {
      ++mismatches;
      exact_error[k] = std::numbers::pi;
    } else if (truth) {
      exact_error[k] = exact::angular_distance(directions[k], *truth);
    }
    error[k] = static_cast<float>(exact_error[k]);
  }
  ErrorSummary summary;
  summary.mismatches = mismatches;
  std::vector<double> judged;
  for (const double e : exact_error)
    if (!std::isnan(e)) judged.push_back(e);
  summary.judged = static_cast<long>(judged.size());
  if (!judged.empty()) {
    const auto mid = judged.begin() + static_cast<std::ptrdiff_t>(judged.size() / 2);
    std::nth_element(judged.begin(), mid, judged.end());
    summary.median = *mid;
    summary.max = *std::max_element(judged.begin(), judged.end());
  }
  return summary;
}

/// Heat map of log10(error) from 1e-12 (dark blue) to 1e-2 rad (yellow); pixels not judged dark grey,
/// verdict mismatches white.
void write_error_map(OutputSet& set, const std::string& path, const Image& image) {
  const auto& error = image.channel("error");
  std::vector<std::uint8_t> rgb(error.size() * 3);
  // A perceptual ramp (viridis, 5 stops) from 1e-12 to 1e-2 rad.
  static constexpr std::array<std::array<double, 3>, 5> ramp = {
      {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}}};
  for (std::size_t i = 0; i < error.size(); ++i) {
    std::array<double, 3> c{45, 45, 45};
    const double e = error[i];
    if (e >= 3.0) {
      c = {255, 255, 255};
    } else if (!std::isnan(e)) {
      const double t = std::clamp((std::log10(std::max(e, 1e-300)) + 12.0) / 10.0, 0.0, 1.0) * (ramp.size() - 1);
      const std::size_t j = std::min(static_cast<std::size_t>(t), ramp.size() - 2);
      const double f = t - static_cast<double>(j);
      for (std::size_t ch = 0; ch < 3; ++ch) c[ch] = (1.0 - f) * ramp[j][ch] + f * ramp[j + 1][ch];
    }
    for (std::size_t ch = 0; ch < 3; ++ch) rgb[3 * i + ch] = static_cast<std::uint8_t>(std::lround(c[ch]));
  }
  write_png_rgb8(set, path, image.width(), image.height(), rgb);
}

/// --exr-compression (checked before any work) and the EXR writer's threads (--threads).
ExrWriteOptions exr_options(const CommandLine& cli, int threads) {
  ExrWriteOptions o;
  const auto c = exr_compression_from_name(cli.text("exr-compression"));
  if (!c)
    throw UsageError("unknown --exr-compression '" + cli.text("exr-compression") +
                     "'; choose zips, zip, piz, rle or none (lossless: the channels read back bit for bit)");
  o.compression = *c;
  o.threads = threads;
  return o;
}

/// GRTRACE_TIMING=1: the wall time of each phase of the run on stderr (not part of the JSON contract).
struct PhaseTimer {
  bool on = [] {
    const char* v = std::getenv("GRTRACE_TIMING");
    return v && *v && std::string(v) != "0";
  }();
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
  void operator()(const char* phase) {
    const auto now = std::chrono::steady_clock::now();
    if (on)
      std::fprintf(stderr, "grtrace-render: %-12s %8.1f ms\n", phase,
                   std::chrono::duration<double, std::milli>(now - last).count());
    last = now;
  }
};


/// Everything a frame's header records beyond what render_frame wrote: the command line, every option's effective
/// value (given or default: the frame can be reproduced from its header alone), the metric and scene, the method.
void describe_frame(Image& image, const Request& q, const CommandLine& cli, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) image.metadata["command_line"] += (i > 1 ? " " : "") + std::string(argv[i]);
  for (const auto& [name, value] : cli.values()) image.metadata["option_" + name] = value;
  image.metadata["options_given"] = cli.given_names();  // so --config of this EXR tells given from default
  auto num = [](double v) { return JsonObject::number(v); };
  image.metadata["scene"] = q.scene.name;
  image.metadata["metric"] = q.metric.name;
  image.metadata["mass"] = num(q.metric.name == "minkowski" ? 0.0 : q.metric.mass);
  if (q.metric.name == "kerr") {
    image.metadata["spin"] = num(q.metric.spin);
    image.metadata["chart"] = q.metric.chart;
    if (q.metric.chart == "ks")
      image.metadata["kerr_schild_slicing"] = q.metric.slicing == KerrSchildSlicing::ingoing ? "ingoing" : "outgoing";
  }
  if (q.metric.name == "rn") image.metadata["charge"] = num(q.metric.charge);
  if (q.metric.name == "sds") image.metadata["lambda"] = num(q.metric.lambda);
  if (q.metric.name == "wormhole") image.metadata["throat"] = num(q.metric.throat);
  image.metadata["observer"] = q.flight.cameras.empty() ? tools::observer_name(cli, q.metric.name) : "moving (flight)";
  if (q.scene.name == "disk") {
    image.metadata["disk_sense"] = cli.flag_set("disk-retrograde") ? "retrograde" : "prograde";
    image.metadata["disk_inner"] = num(q.scene.disk.r_in);
    image.metadata["disk_outer"] = num(q.scene.disk.r_out);
  }
  image.metadata["tableau"] = q.tableau;
  image.metadata["control"] = q.control;
  image.metadata["rtol"] = num(q.settings.integrator.tolerance.rtol);
  image.metadata["atol"] = num(q.settings.integrator.tolerance.atol);
  image.metadata["max_steps"] = std::to_string(q.settings.max_steps);
  image.metadata["sky_radius"] = num(q.settings.escape_radius);
  image.metadata["angle_correction"] = q.correction_name;
}

/// The frame (or, for a flight, every frame through q.flight.sink, and nothing returned), drawn by the
/// application layer (grtrace/app/frame_tracer.hpp).
std::optional<Frame> render_request(const Request& q, SkyDirections* where, TracerReport& table) {
  const app::FrameRequest request = render_tool::frame_request(q);
  const RenderOptions options = q.render_options();
  if (q.flight.cameras.empty()) return app::render_frame(request, *q.camera, options, where, &table);
  const FlightStats stats = app::render_flight(
      request, q.flight.cameras, q.flight.skip,
      [&](int i, Frame&& frame, const TracerReport& report) { q.flight.sink(i, frame, report); }, options);
  if (q.flight.stats) *q.flight.stats = stats;
  return std::nullopt;
}

JsonObject status_counts_json(const std::array<long, kRayStatusCount>& counts) {
  JsonObject json;
  for (std::size_t i = 0; i < kRayStatusCount; ++i) json.add(kRayStatusNames[i], counts[i]);
  return json;
}

/// --flight: every frame as <stem>-NNNN.exr + .png (skipping those a previous run of the same flight wrote whole:
/// same flight_signature), then the MP4 if asked for; one line of JSON for the whole sequence.
int run_flight(Request& q, const CommandLine& cli, int argc, char** argv, const ExrWriteOptions& exr) {
  std::map<std::string, std::string> content;  // the options that decide what the frames show
  for (const auto& [name, value] : cli.values())
    if (name != "threads" && name != "mp4" && name != "fps" && name != "exr-compression" && name != "frame-range")
      content[name] = value;  // a part's frames are the whole run's: --frame-range is not in the signature
  const std::string signature = flight_signature(content);
  const int frames = static_cast<int>(q.flight.cameras.size());
  q.flight.skip = [&](int i) {
    if (q.flight.range && !q.flight.range->contains(i)) return true;  // another part's frame
    return flight_frame_done(flight_exr_path(q, i), png_path(flight_exr_path(q, i)), signature);
  };
  TracerReport table;  // the frames' table statistics summed, and the tracer that ran
  table.name = "none";
  q.flight.sink = [&](int i, Frame& frame, const TracerReport& t) {
    Image& image = frame.image;
    describe_frame(image, q, cli, argc, argv);
    image.metadata["flight"] = q.flight.name;
    image.metadata["flight_frame"] = std::to_string(i);
    image.metadata["flight_frames"] = std::to_string(frames);
    image.metadata["flight_tau"] = JsonObject::number(q.flight.tau[static_cast<std::size_t>(i)]);
    image.metadata["flight_signature"] = signature;
    table.name = t.name;
    table.table_rays += t.table_rays;
    table.table_steps += t.table_steps;
    table.fallback_rays += t.fallback_rays;
    OutputSet outputs;
    const std::string path = flight_exr_path(q, i);
    write_exr_and_preview(outputs, path, png_path(path), image, exr);
    outputs.commit();
  };
  FlightStats stats;
  q.flight.stats = &stats;
  render_request(q, nullptr, table);
  std::string mp4;
  if (cli.flag_set("mp4")) {
    mp4 = mp4_path(q.out);
    OutputSet outputs;
    assemble_mp4(outputs, flight_png_pattern(png_path(q.out), frames), frames, cli.number("fps"), mp4);
    outputs.commit();
  }
  JsonObject json;
  const int other_parts = q.flight.range ? frames - q.flight.range->count() : 0;  // skipped as not ours
  json.add("flight", q.flight.name).add("frames", frames).add("frames_rendered", stats.rendered);
  if (q.flight.range) json.add("frame_range", q.flight.range->text());
  json.add("frames_skipped", stats.skipped - other_parts).add("width", q.camera->width());
  json.add("height", q.camera->height());
  json.add("proper_time_step", q.flight.dtau).add("seconds", stats.seconds);
  json.add("rays_per_second", static_cast<double>(stats.rays) / stats.seconds).add("traced_rays", stats.traced_rays);
  json.add("status_counts", status_counts_json(stats.status_counts));
  json.add("tracer", table.name).add("tableau", q.tableau).add("control", q.control);
  json.add("device", app::device_name(q.device));
  json.add("rtol", q.settings.integrator.tolerance.rtol).add("atol", q.settings.integrator.tolerance.atol);
  json.add("first_frame", flight_exr_path(q, 0)).add("last_frame", flight_exr_path(q, frames - 1));
  if (!mp4.empty()) json.add("mp4", mp4);
  if (table.name == "planar") {
    json.add("table_rays", table.table_rays).add("table_steps", table.table_steps).add("fallback_rays", table.fallback_rays);
    json.add("mean_steps", stats.rays > 0 ? static_cast<double>(table.table_steps) / static_cast<double>(stats.rays) : 0.0);
  }
  std::cout << json.str() << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  PhaseTimer phase;
  CommandLine cli = make_command_line();
  return tools::run_tool(cli, argc, argv, [&] {
    Request q = read_request(cli);
    const ExrWriteOptions exr = exr_options(cli, q.threads);
    if (cli.write_config_if_asked()) return 0;  // checked as for a run: saved, nothing traced
    phase("input");
    if (!q.flight.cameras.empty()) return run_flight(q, cli, argc, argv, exr);
    SkyDirections directions;  // --error-map only
    SkyDirections* const where = q.error_map ? &directions : nullptr;
    const auto t0 = std::chrono::steady_clock::now();
    TracerReport table;
    std::optional<Frame> frame = render_request(q, where, table);
    // The table (planar tracer) is part of the frame's cost: time the whole thing.
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    Image& image = frame->image;
    RenderStats& st = frame->stats;
    st.seconds = seconds;
    st.rays_per_second = static_cast<double>(st.rays) / seconds;
    phase("trace");
    // Judged after the clock stopped: the exact reference costs an elliptic integral per pixel.
    const ErrorSummary errors = q.error_map ? compute_error_channel(q, image, directions) : ErrorSummary{};

    describe_frame(image, q, cli, argc, argv);
    auto num = [](double v) { return JsonObject::number(v); };
    const std::string tracer = image.metadata["tracer"];  // the tracer that ran (render_frame records it)
    if (q.error_map) {
      image.metadata["error_max"] = num(errors.max);
      image.metadata["error_median"] = num(errors.median);
      image.metadata["error_mismatches"] = std::to_string(errors.mismatches);
    }
    record_render_stats(image, st);
    phase("header");
    // The EXR, its preview and the maps: all written to temporaries first, then renamed together (all new or
    // all as they were; output_file.hpp).
    OutputSet outputs;
    const std::string png = png_path(q.out);
    write_exr_and_preview(outputs, q.out, png, image, exr);  // the preview is encoded while the EXR is written
    phase("exr+png");
    const bool status_map = cli.flag_set("status-map");
    if (status_map) write_status_map(outputs, status_map_path(q.out), image);
    if (q.error_map) write_error_map(outputs, error_map_path(q.out), image);
    outputs.commit();
    phase("maps+commit");

    const JsonObject counts = status_counts_json(st.status_counts);
    JsonObject json;
    json.add("width", st.width).add("height", st.height).add("seconds", seconds);
    json.add("rays_per_second", st.rays_per_second);
    const bool tabulated = tracer == "planar";
    const double mean_steps = tabulated ? static_cast<double>(table.table_steps) / static_cast<double>(st.rays) : st.mean_steps;
    json.add("mean_steps", mean_steps).add("status_counts", counts);
    json.add("tracer", tracer).add("tableau", q.tableau).add("control", q.control);
    json.add("device", image.metadata["device"]);
    if (image.metadata.count("gpu_trace_seconds")) {  // the GPU kernel's share of "seconds", and the GPU's whole share
      json.add("gpu_trace_seconds", std::stod(image.metadata["gpu_trace_seconds"]));
      json.add("gpu_seconds", std::stod(image.metadata["gpu_seconds"]));
    }
    json.add("sky_continuation", image.metadata["sky_continuation"]);
    if (image.metadata.count("sky_continuation_error"))  // a flat continuation's estimated error (render_frame)
      json.add("sky_continuation_error", std::stod(image.metadata["sky_continuation_error"]))
          .add("sky_radius_for_rtol", std::stod(image.metadata["sky_radius_for_rtol"]));
    json.add("rtol", q.settings.integrator.tolerance.rtol).add("atol", q.settings.integrator.tolerance.atol);
    json.add("out", q.out).add("png", png).add("threads", st.threads);
    json.add("traced_rays", st.traced_rays).add("mirrors", image.metadata["mirrors"]);
    if (status_map) json.add("status_map", status_map_path(q.out));
    if (q.error_map) {
      json.add("max_error", errors.max).add("median_error", errors.median);
      json.add("error_pixels", errors.judged).add("error_mismatches", errors.mismatches);
      json.add("error_map", error_map_path(q.out));
    }
    if (tabulated) json.add("table_rays", table.table_rays).add("table_steps", table.table_steps);
    if (tracer == "planar") json.add("fallback_rays", table.fallback_rays);
    std::cout << json.str() << std::endl;
    phase("json");
    return 0;
  });
}
