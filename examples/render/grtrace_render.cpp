// grtrace-render: renders what a camera near a black hole (Schwarzschild, Kerr, charged, with a cosmological
// constant), in a wormhole or in flat space sees, to an OpenEXR file with data channels and an 8-bit PNG preview
// beside it, with a progress bar on a terminal, and ends with ONE line of JSON (contract in shared/DESIGN.md):
//   {"width","height","seconds","rays_per_second","mean_steps","status_counts":{...},"tracer","tableau","rtol",
//    "atol","out", ...}
// A thin client of the application library's front door (grtrace/app/front_door.hpp): the request is read and
// checked there (the same reading and refusals as the Python module's), the frame drawn there; this program adds
// the files (EXR, PNG, status and error maps, flights' frames and video) and the JSON line.
// All input is checked before any ray is traced; bad input exits with code 2 and leaves no file behind.
#include "app_options.hpp"
#include "command_line.hpp"
#include "flight_options.hpp"
#include "grtrace/app/front_door.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/flight_files.hpp"
#include "grtrace/render/frame_files.hpp"
#include "grtrace/render/png_preview.hpp"
#include "json_writer.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace grtrace;
using tools::CommandLine;
using tools::JsonObject;
using tools::UsageError;

CommandLine make_command_line() {
  CommandLine cli(
      "grtrace-render",
      "Render a camera's view of a black hole (Schwarzschild, Kerr, charged, with a cosmological constant),\n"
      "a wormhole or flat space to OpenEXR + PNG preview;\n"
      "prints one line of JSON. Defaults: the seed report's main frame (static camera at r = 200 M,\n"
      "fov 90, 1024x1024, sky sphere at 400 M). The default method (rkf78, I control, rtol 1e-9) is\n"
      "the cheapest whose largest error stays below 1e-6 both on that frame (angle, general tracer) and\n"
      "on the Kerr disk frame (hit radius, redshift); the planar tracer's table costs the same with it\n"
      "as with tsit5 (docs/benchmarks.md). The options are those of the Python module's grtrace.render.");
  tools::declare_render_options(cli);
  cli.option("out", "render.exr", "output EXR path; the PNG preview goes beside it with .png")
      .option("exr-compression", "zips",
              "EXR compression, all lossless (channels read back bit for bit): zips | zip "
              "(deflate level 1; zips: one scanline per chunk) | piz (smallest, slower) | "
              "rle | none (fastest, largest)")
      .flag("status-map",
            "also write <out>-status.png (with --flight: <stem>-NNNN-status.png for each frame): each pixel coloured "
            "by how its ray ended (legend in --help)");
  tools::declare_flight_options(cli,
                                "grtrace-render renders a sequence along it instead of one frame (aberration and "
                                "Doppler from the camera's u): <out stem>-NNNN.exr and .png; a re-run skips the "
                                "frames already written whole by the same flight",
                                "");
  cli.option("frame-range", "",
             "flight: render only frames A .. B-1 (A:B, 0-based, B one past the last): one part "
             "of a flight split over a cluster (a Slurm job array, see the README); any order, "
             "resumable; the frames are those of one whole run")
      .option("fps", "30", "flight --mp4: frames per second")
      .flag("mp4", "flight: also write <out stem>.mp4 from the PNG previews (ffmpeg, H.264)");
  return cli;
}

/// --flight: one frame per camera along a path (render/flight.hpp); empty cameras: a single frame.
struct FlightRequest {
  std::string name;  ///< --flight: seed | circular | orbit | infall | csv ("" = one frame)
  std::vector<Camera> cameras;
  std::vector<double> tau;                ///< each frame's proper time on the path
  double dtau = 0.0;                      ///< proper time between frames (csv: as given)
  std::optional<FlightFrameRange> range;  ///< --frame-range: only these frames (nothing: all)
};

/// What grtrace-render was asked to do: the library's checked request, and the files.
struct Request {
  app::CheckedRequest checked;
  std::string out;
  FlightRequest flight;
};

std::string png_path(const std::string& exr) { return exr.substr(0, exr.size() - 4) + ".png"; }
std::string status_map_path(const std::string& exr) { return exr.substr(0, exr.size() - 4) + "-status.png"; }
std::string error_map_path(const std::string& exr) { return exr.substr(0, exr.size() - 4) + "-error.png"; }

std::string flight_exr_path(const Request& q, int i) {
  return flight_frame_path(q.out, i, static_cast<int>(q.flight.cameras.size())).string();
}
std::string mp4_path(const std::string& exr) { return exr.substr(0, exr.size() - 4) + ".mp4"; }

/// Every file a run writes: the EXR, its PNG preview, and the maps asked for; for a flight every frame's EXR and
/// PNG (and status map if asked for) and the MP4 if asked for.
std::vector<std::string> output_paths(const Request& q, bool status_map, bool mp4) {
  if (!q.flight.cameras.empty()) {
    std::vector<std::string> out;
    for (int i = 0; i < static_cast<int>(q.flight.cameras.size()); ++i) {
      const std::string exr = flight_exr_path(q, i);
      out.push_back(exr);
      out.push_back(png_path(exr));
      if (status_map) out.push_back(status_map_path(exr));
    }
    if (mp4) out.push_back(mp4_path(q.out));
    return out;
  }
  std::vector<std::string> out{q.out, png_path(q.out)};
  if (status_map) out.push_back(status_map_path(q.out));
  if (q.checked.request.error_map) out.push_back(error_map_path(q.out));
  return out;
}

/// The camera path of --flight (checked, before any work): the start (a preset, or --camera-r/-theta/-phi with
/// --orbit-dr/--orbit-dphi), the proper-time step (--frame-dtau, or automatic: one revolution over the frames, or
/// the fall to 1.1 r_h), the path sampled (observer/worldline.hpp) and one camera per frame pointed by --look/--up
/// (make_moving_camera), both by the library (app::flight_worldline, app::flight_cameras). Refuses what a single
/// frame's camera would, plus a path that ends (horizon, sky sphere) before its last frame, and the options that
/// describe a single frame only.
void read_flight(const CommandLine& cli, const std::optional<FlightPathSpec>& spec, Request& q) {
  if (!spec) return;
  FlightRequest& f = q.flight;
  refuse_inapplicable_options(cli, {{"orbit-dr", spec->kind == "orbit", "--flight orbit"},
                                    {"orbit-dphi", spec->kind == "orbit", "--flight orbit"}});
  f.name = spec->kind;
  for (const char* name : {"velocity", "observer"})
    if (cli.given(name))
      throw UsageError(std::string("--") + name +
                       " sets a single frame's camera; a flight's camera moves with its "
                       "path (its 4-velocity): leave it out");
  if (q.checked.request.error_map) throw UsageError("--error-map is for single frames; leave it out with --flight");
  if (!(cli.number("fps") > 0.0 && cli.number("fps") <= 1000.0)) throw UsageError("--fps must lie in (0, 1000]");
  // The video's tool, before the first ray (not after the frames).
  if (cli.flag_set("mp4") && !program_on_path("ffmpeg"))
    throw UsageError(
        "--mp4 needs ffmpeg, which is not on PATH; install it (apt-get install ffmpeg, or bash "
        "cmake/install-deps.sh) or leave --mp4 out");
  const app::CameraRequest& c = q.checked.request.camera;
  const CameraView view{c.look, c.up, c.width, c.height, c.fov_degrees};
  const MetricSpec& metric = q.checked.request.metric;
  const Worldline path = tools::checked_flight_path(*spec, [&] { return app::flight_worldline(metric, *spec); });
  f.cameras = tools::as_usage_error([&] { return app::flight_cameras(metric, path, view); });
  f.dtau = frame_step(path);
  for (const WorldlineSample& s : path.samples) f.tau.push_back(s.tau);
  if (cli.given("frame-range")) {
    f.range = tools::as_usage_error(
        [&] { return parse_flight_frame_range(cli.text("frame-range"), static_cast<int>(f.cameras.size())); });
    if (cli.flag_set("mp4"))
      throw UsageError(
          "--mp4 assembles every frame of the flight, not --frame-range's part: once every part is "
          "done, run the same command without --frame-range, with --mp4 (the frames on disk are "
          "skipped)");
  }
  q.checked = app::with_camera(std::move(q.checked), f.cameras.front());
}

Request read_request(const CommandLine& cli) {
  const tools::CommandLineOptions options(cli);
  app::RenderRequest r = tools::as_usage_error([&] { return app::read_render_request(options); });
  const std::optional<FlightPathSpec> spec = tools::read_flight_spec(
      cli, r.metric.mass, r.sky_radius, {"fps", "mp4", "orbit-dr", "orbit-dphi", "frame-range"});
  // Kerr-Schild flights are flown in the ingoing slicing, regular where the falling camera crosses the horizon.
  if (spec && r.metric.chart == "ks") r.metric.slicing = KerrSchildSlicing::ingoing;
  Request q{tools::as_usage_error([&] { return app::check_request(r); }), cli.text("out"), {}};
  tools::check_exr_output_name("out", q.out);
  read_flight(cli, spec, q);
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
    const auto s =
        static_cast<std::size_t>(std::clamp(static_cast<int>(status[i]), 0, static_cast<int>(kRayStatusCount) - 1));
    for (std::size_t c = 0; c < 3; ++c) rgb[3 * i + c] = kStatusColours[s][c];
  }
  write_png_rgb8(set, path, image.width(), image.height(), rgb);
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

/// What a frame's header records beyond the library's record (app::describe_request, the report, the camera): the
/// command line and every option's effective value (given or default: the frame can be reproduced from its header
/// alone, and --config FRAME.exr reads them back).
void describe_command(Image& image, const CommandLine& cli, int argc, char** argv) {
  for (int i = 1; i < argc; ++i) image.metadata["command_line"] += (i > 1 ? " " : "") + std::string(argv[i]);
  for (const auto& [name, value] : cli.values()) image.metadata["option_" + name] = value;
  image.metadata["options_given"] = cli.given_names();  // so --config of this EXR tells given from default
}

JsonObject status_counts_json(const std::array<long, kRayStatusCount>& counts) {
  JsonObject json;
  for (std::size_t i = 0; i < kRayStatusCount; ++i) json.add(kRayStatusNames[i], counts[i]);
  return json;
}

/// Report entries (app::report_entries, app::LineProfileResult::report: the same lists as the Python module's dicts)
/// as JSON.
void add_entries(JsonObject& json, const std::vector<app::ReportEntry>& entries) {
  for (const app::ReportEntry& e : entries) {
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, app::ReportEntry::Counts>) {
            JsonObject counts;
            for (const auto& [name, n] : v) counts.add(name, n);
            json.add(e.key, counts);
          } else if constexpr (std::is_same_v<V, std::string>) {
            json.add(e.key, std::string_view(v));
          } else {
            json.add(e.key, v);
          }
        },
        e.value);
  }
}

/// A frame's status map from the frame on disk (read by the checked reader, read_exr): a frame a previous run of
/// the flight wrote whole is not traced again to inspect it.
void write_status_map_of(const std::string& exr) {
  OutputSet outputs;
  write_status_map(outputs, status_map_path(exr), read_exr(exr));
  outputs.commit();
}

/// --flight: every frame as <stem>-NNNN.exr + .png, and <stem>-NNNN-status.png with --status-map (skipping the
/// frames a previous run of the same flight wrote whole: same flight_signature; their status maps are drawn from
/// the frames on disk), then the MP4 if asked for; one line of JSON for the whole sequence, naming the frames that
/// have failed rays (max_steps, step_underflow, non_finite) so that one of them is one command to inspect.
int run_flight(Request& q, const CommandLine& cli, int argc, char** argv, const ExrWriteOptions& exr) {
  std::map<std::string, std::string> content;  // the options that decide what the frames show
  for (const auto& [name, value] : cli.values())
    if (name != "threads" && name != "mp4" && name != "fps" && name != "exr-compression" && name != "frame-range" &&
        name != "status-map")
      content[name] = value;  // a part's frames are the whole run's: --frame-range is not in the signature
  const std::string signature = flight_signature(content);
  const int frames = static_cast<int>(q.flight.cameras.size());
  const bool status_map = cli.flag_set("status-map");
  const auto skip = [&](int i) {
    if (q.flight.range && !q.flight.range->contains(i)) return true;  // another part's frame
    const std::string path = flight_exr_path(q, i);
    if (!flight_frame_done(path, png_path(path), signature)) return false;
    if (status_map && !whole_png_size(status_map_path(path))) write_status_map_of(path);
    return true;
  };
  std::string tracer = "none";  // the tracer that ran, and the frames' table statistics summed
  long table_rays = 0, table_steps = 0, fallback_rays = 0;
  std::vector<int> failed_frames;  // frames traced here with a ray that failed
  const auto sink = [&](int i, app::RenderResult&& result) {
    Image& image = result.image;
    describe_command(image, cli, argc, argv);
    image.metadata["observer"] = "moving (flight)";
    image.metadata["flight"] = q.flight.name;
    image.metadata["flight_frame"] = std::to_string(i);
    image.metadata["flight_frames"] = std::to_string(frames);
    image.metadata["flight_tau"] = JsonObject::number(q.flight.tau[static_cast<std::size_t>(i)]);
    image.metadata["flight_signature"] = signature;
    tracer = result.report.tracer;
    table_rays += result.report.table_rays;
    table_steps += result.report.table_steps;
    fallback_rays += result.report.fallback_rays;
    const auto& counts = result.report.stats.status_counts;
    if (counts[static_cast<std::size_t>(RayStatus::max_steps)] +
            counts[static_cast<std::size_t>(RayStatus::step_underflow)] +
            counts[static_cast<std::size_t>(RayStatus::non_finite)] >
        0)
      failed_frames.push_back(i);
    OutputSet outputs;
    const std::string path = flight_exr_path(q, i);
    write_exr_and_preview(outputs, path, png_path(path), image, exr);
    if (status_map) write_status_map(outputs, status_map_path(path), image);
    outputs.commit();
  };
  const FlightStats stats = app::render_flight(q.checked, q.flight.cameras, skip, sink);
  std::string mp4;
  if (cli.flag_set("mp4")) {
    mp4 = mp4_path(q.out);
    OutputSet outputs;
    assemble_mp4(outputs, flight_png_pattern(png_path(q.out), frames), frames, cli.number("fps"), mp4);
    outputs.commit();
  }
  const app::RenderRequest& r = q.checked.request;
  JsonObject json;
  const int other_parts = q.flight.range ? frames - q.flight.range->count() : 0;  // skipped as not ours
  json.add("flight", q.flight.name).add("frames", frames).add("frames_rendered", stats.rendered);
  if (q.flight.range) json.add("frame_range", q.flight.range->text());
  json.add("frames_skipped", stats.skipped - other_parts).add("width", q.checked.camera.width());
  json.add("height", q.checked.camera.height());
  json.add("proper_time_step", q.flight.dtau).add("seconds", stats.seconds);
  json.add("rays_per_second", static_cast<double>(stats.rays) / stats.seconds).add("traced_rays", stats.traced_rays);
  json.add("status_counts", status_counts_json(stats.status_counts));
  json.add("tracer", tracer).add("tableau", r.method.tableau).add("control", r.method.control);
  json.add("device", app::device_name(r.device));
  json.add("rtol", r.method.rtol).add("atol", r.method.atol);
  json.add("frames_with_failed_rays", failed_frames);
  // This run's frames: --frame-range's part, or the whole flight.
  const int first = q.flight.range ? q.flight.range->first : 0,
            last = q.flight.range ? q.flight.range->end - 1 : frames - 1;
  json.add("first_frame", flight_exr_path(q, first)).add("last_frame", flight_exr_path(q, last));
  if (status_map)
    json.add("first_status_map", status_map_path(flight_exr_path(q, first)))
        .add("last_status_map", status_map_path(flight_exr_path(q, last)));
  if (!mp4.empty()) json.add("mp4", mp4);
  if (tracer == "planar") {
    json.add("table_rays", table_rays).add("table_steps", table_steps).add("fallback_rays", fallback_rays);
    json.add("mean_steps", stats.rays > 0 ? static_cast<double>(table_steps) / static_cast<double>(stats.rays) : 0.0);
  }
  std::cout << json.str() << std::endl;
  return 0;
}

/// --spectrum line: the disk's line profile (app::line_profile) as --out NAME.csv and its plot NAME.png (both new or
/// both as they were), and one line of JSON with the request's totals. A frame's options are refused (the library
/// refuses the render options; the tool's own, such as --status-map or --flight, here).
int run_line_profile(CommandLine& cli) {
  const tools::CommandLineOptions options(cli);
  const app::LineProfileRequest request =
      tools::as_usage_error([&] { return app::read_line_profile_request(options); });
  for (const auto& [name, value] : cli.values()) {
    const bool render_option = std::any_of(app::render_options().begin(), app::render_options().end(),
                                           [&](const app::OptionInfo& o) { return o.name == name; });
    if (!render_option && name != "out" && cli.given(name))
      throw UsageError("--" + name + " is for frames; --spectrum line writes a CSV and its plot: leave it out");
  }
  const std::string out = cli.text("out");
  if (out.size() < 5 || out.substr(out.size() - 4) != ".csv")
    throw UsageError(
        "--spectrum line writes a table: give --out NAME.csv (its plot goes beside it as NAME.png), got '" + out + "'");
  const std::string png = out.substr(0, out.size() - 4) + ".png";
  for (const std::string& path : {out, png}) tools::check_command_output(cli, "out", path, {});
  if (cli.write_config_if_asked()) return 0;
  const app::LineProfileResult result = tools::as_usage_error([&] { return app::line_profile(request); });
  OutputSet outputs;
  TemporaryOutput& csv = outputs.add(out);
  csv.write(result.csv.data(), result.csv.size());
  csv.finish();
  write_png_rgb8(outputs, png, result.chart.width, result.chart.height, result.chart.rgb);
  outputs.commit();
  JsonObject json;
  add_entries(json, result.report);
  json.add("out", out).add("png", png);
  std::cout << json.str() << std::endl;
  return 0;
}

/// --rings: the disk's photon ring by order (app::ring_image) as --out NAME.exr (channels I, I_n0 .. I_n3_up, R, G,
/// B), its preview NAME.png and NAME-orders.png (all new or all as they were), and one line of JSON with each
/// order's flux and the rings' sizes. A frame's options are refused (the library refuses the render options; the
/// tool's own, such as --status-map or --flight, here).
int run_ring_image(CommandLine& cli) {
  const tools::CommandLineOptions options(cli);
  const app::RingImageRequest request = tools::as_usage_error([&] { return app::read_ring_image_request(options); });
  for (const auto& [name, value] : cli.values()) {
    const bool render_option = std::any_of(app::render_options().begin(), app::render_options().end(),
                                           [&](const app::OptionInfo& o) { return o.name == name; });
    if (!render_option && name != "out" && cli.given(name))
      throw UsageError("--" + name + " is for frames; --rings writes an EXR of the orders and two PNGs: leave it out");
  }
  const std::string out = cli.text("out");
  tools::check_exr_output_name("out", out);
  const std::string stem = out.substr(0, out.size() - 4), png = stem + ".png", orders = stem + "-orders.png";
  for (const std::string& path : {out, png, orders}) tools::check_command_output(cli, "out", path, {});
  if (cli.write_config_if_asked()) return 0;
  const app::RingImageResult result = tools::as_usage_error([&] { return app::ring_image(request); });
  OutputSet outputs;
  write_exr_and_preview(outputs, out, png, result.image);
  write_png_rgb8(outputs, orders, result.orders.width, result.orders.height, result.orders.rgb);
  outputs.commit();
  JsonObject json;
  add_entries(json, result.report);
  json.add("out", out).add("png", png).add("orders_png", orders);
  std::cout << json.str() << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  PhaseTimer phase;
  CommandLine cli = make_command_line();
  return tools::run_tool(cli, argc, argv, [&] {
    if (cli.given("spectrum")) return run_line_profile(cli);
    if (cli.given("rings")) return run_ring_image(cli);
    Request q = read_request(cli);
    const ExrWriteOptions exr = exr_options(cli, q.checked.request.threads);
    if (cli.write_config_if_asked()) return 0;  // checked as for a run: saved, nothing traced
    phase("input");
    if (!q.flight.cameras.empty()) return run_flight(q, cli, argc, argv, exr);
    app::RenderResult result = app::FrameRenderer::create(q.checked)->render();
    phase("trace");
    Image& image = result.image;
    describe_command(image, cli, argc, argv);
    phase("header");
    // The EXR, its preview and the maps: all written to temporaries first, then renamed together (all new or
    // all as they were; output_file.hpp).
    OutputSet outputs;
    const std::string png = png_path(q.out);
    write_exr_and_preview(outputs, q.out, png, image, exr);  // the preview is encoded while the EXR is written
    phase("exr+png");
    const bool status_map = cli.flag_set("status-map");
    if (status_map) write_status_map(outputs, status_map_path(q.out), image);
    if (q.checked.request.error_map) write_error_map(outputs, error_map_path(q.out), image);
    outputs.commit();
    phase("maps+commit");

    JsonObject json;
    add_entries(json, app::report_entries(result.report, q.checked));
    json.add("out", q.out).add("png", png);
    if (status_map) json.add("status_map", status_map_path(q.out));
    if (q.checked.request.error_map) json.add("error_map", error_map_path(q.out));
    std::cout << json.str() << std::endl;
    phase("json");
    return 0;
  });
}
