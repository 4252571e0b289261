// grtrace-view: the VTK frontend.
//   * 3D view (left): the reference surfaces of the Schwarzschild scene (horizon r = 2M, photon sphere 3M, ISCO 6M,
//     disk, sky sphere), the camera as a frustum with its tetrad axes, a bundle of traced rays (a subsampled grid of
//     the camera's pixels, a fan along its middle row or column, or a parallel beam in the equatorial plane), and
//     optionally the seed report's precessing timelike orbit as a tube.
//   * Frame (right): the picture the camera sees, from an EXR written by grtrace-render (--frame FILE.exr) or
//     rendered here; the bundle's pixels are marked, and each bundle ray keeps its pixel's colour.
//   * --plot orbit|norm|step: the seed's Figs. 1-3 for a timelike geodesic (VTK charts). --chart orbit|norm|step
//     is its older spelling, kept: --chart's other values, bl|ks, are grtrace-render's Kerr coordinate charts, and
//     the two sets of values are disjoint, so one option carries both meanings without ambiguity.
//   * --metric kerr --spin A with grtrace-render's Kerr options (the application library's table and reading):
//     --chart bl|ks, --observer zamo|static, --disk-retrograde (the ISCO default and refusal of --disk-inner).
//     Boyer-Lindquist rays and surfaces are drawn with (r, theta, phi) as spherical polar coordinates (the BL
//     embedding, KerrMetric::to_cartesian). Kerr-Schild rays are drawn in their own Cartesian x, y, z, which is the
//     point of that chart: they cross the horizon, where no BL position exists to map them back to. So with
//     --chart ks the surfaces move instead: each r = const surface (horizon, ergosphere, ISCO ring, sky) is drawn in
//     KS Cartesian coordinates, an oblate spheroid x + i y = (r + i e a) sin th e^{i ph}, z = r cos th
//     (viz::to_kerr_schild), so rays and surfaces share one picture in either chart.
//   * --flight KIND (grtrace-render's camera flights, options shared through examples/common/flight_options.hpp):
//     the whole path as a tube with its frames as beads (the orbit layer), and the camera, the frame and the
//     bundle at frame --flight-frame, its camera make_moving_camera's; --export adds flight.vtp.
//   * --scene accretion|riaf|torus (grtrace-render's glowing media, their options as there): the frame is the
//     medium's light; the 3D view draws the gas as translucent iso-surfaces of its emission (30 %, 3 % and 0.3 % of
//     its peak; key g; medium.vti in an export), and a picked ray is coloured by the light it collects from the
//     camera outwards (app/medium_view.hpp), its total listed with its outcome.
//   * Picks: a left click on the frame traces that pixel's ray (the general scene tracer) and draws it in the 3D
//     view (magenta), its outcome (status, object, hit radius, redshift, steps) listed there and printed; 'x' clears
//     the picks. --pick COL,ROW[/COL,ROW...] picks at start-up (so picked rays show in --screenshot and --export).
// Interactive when a display exists; --screenshot FILE.png --size WxH renders offscreen and exits.
// --export DIR writes the 3D scene (rays with their point data, surfaces, the frame as an image, scene.vtm) as VTK XML
// files for ParaView (grtrace/viz/vtk_export.hpp) and exits; alone it opens no window and needs no display.
// Rendering needs X: headless, run under  xvfb-run -a -s "-screen 0 1280x1024x24" grtrace-view ...
// With --frame, the camera (event and tetrad), the scene, mass, sky radius, angle correction and integration
// method are read from the EXR's header (as grtrace-render writes it), so the bundle is traced through the frame's
// own camera; options given on the command line override the method and scene settings, never the camera.
// Bad input: a message on stderr and exit status 2. Other failures: exit status 1.
#include "app_options.hpp"
#include "command_line.hpp"
#include "flight_options.hpp"
#include "grtrace/app/front_door.hpp"
#include "grtrace/app/medium_view.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/tetrad.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/scene/thin_disk.hpp"
#include "grtrace/viz/bundles.hpp"
#include "grtrace/viz/camera_glyph.hpp"
#include "grtrace/viz/charts.hpp"
#include "grtrace/viz/frame_from_image.hpp"
#include "grtrace/viz/frame_view.hpp"
#include "grtrace/viz/geodesic_data.hpp"
#include "grtrace/viz/orbits.hpp"
#include "grtrace/viz/scene_view.hpp"
#include "grtrace/viz/viewer_window.hpp"
#include "grtrace/viz/vtk_export.hpp"
#include "json_writer.hpp"
#include "view_request.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using namespace grtrace;
using tools::CommandLine;
using tools::UsageError;
using view::Request;

constexpr double kDeg = std::numbers::pi / 180.0;
/// The metrics the viewer draws (its surfaces, ISCO rings and orbit charts are Schwarzschild's and Kerr's).
const std::vector<std::string> kViewMetrics = {"schwarzschild", "kerr"};

/// The options the viewer shares with grtrace-render (the application library's table), with the viewer's defaults.
void declare_shared_options(CommandLine& cli, const std::set<std::string>& names,
                            const std::map<std::string, std::string>& defaults) {
  std::set<std::string> skip;
  for (const app::OptionInfo& o : app::render_options())
    if (!names.count(std::string(o.name))) skip.insert(std::string(o.name));
  tools::declare_render_options(cli, skip, defaults);
}

CommandLine make_command_line() {
  CommandLine cli(
      "grtrace-view",
      "The VTK frontend: traced rays in 3D beside the frame they make, and the seed's orbit charts.\n"
      "Interactive when a display exists; --screenshot renders offscreen and exits.\n"
      "Headless: xvfb-run -a -s \"-screen 0 1280x1024x24\" grtrace-view --screenshot view.png\n"
      "Window: mouse turns/pans/zooms the 3D view; a left click on the frame picks that pixel's ray; keys "
      "1-9, 0, g layers, m markers, c ray colouring, x clear picks, r reset view, s screenshot, h help, q quit.");
  cli.option("screenshot", "", "render offscreen to this PNG and exit")
      .option("export", "",
              "write the 3D scene (rays, surfaces, frame) as VTK XML files for ParaView into this "
              "directory (created if missing; open DIR/scene.vtm) and exit; needs no display")
      .option("size", "", "window / screenshot size WxH (default 1600x800; charts 900x800)")
      .option("plot", "", "draw a chart of the orbit instead of the 3D view: orbit | norm | step")
      .option("chart", "",
              tools::render_option_help("chart") +
                  " (default bl; with --frame: the frame's). Also orbit | norm | "
                  "step: the older spelling of --plot")
      // scene (as grtrace-render)
      .option("scene", "disk",
              "what the frame shows: checker | sky | redshift | disk (disk: a thin disk is traced) | accretion | "
              "riaf | torus (glowing gas, grtrace-render's media: its emission drawn in 3D as translucent "
              "iso-surfaces, key g; a picked ray coloured by the light it collects)");
  cli.option("metric", "schwarzschild",
             "schwarzschild | kerr (--chart bl or ks, --observer; draws the outer horizon, the ergosphere and the "
             "ISCO of the disk's sense)");
  // The rest of the options grtrace-render has too: the library's names and help (app::render_options), the
  // viewer's defaults; --chart is declared above with its older meaning.
  declare_shared_options(cli,
                         {"mass",
                          "spin",
                          "camera-r",
                          "camera-theta",
                          "camera-phi",
                          "observer",
                          "velocity",
                          "look",
                          "up",
                          "fov",
                          "width",
                          "height",
                          "sky-radius",
                          "disk-inner",
                          "disk-outer",
                          "disk-retrograde",
                          "angle-correction",
                          "tableau",
                          "control",
                          "step",
                          "rtol",
                          "atol",
                          "max-steps",
                          "threads",
                          "accretion-gas",
                          "accretion-power",
                          "source",
                          "accretion-rate",
                          "frequency",
                          "torus-inner",
                          "torus-peak",
                          "torus-opacity"},
                         {{"camera-r", "35"},
                          {"camera-theta", "84"},
                          {"fov", "55"},
                          {"width", "320"},
                          {"height", "240"},
                          {"tableau", "dopri5"},
                          {"control", "pi"},
                          {"rtol", "1e-8"},
                          {"atol", "1e-10"}});
  cli
      // frame / bundle
      .option("frame", "", "EXR written by grtrace-render to show on the right (default: render it here); its "
                           "camera, scene, mass, sky radius and method are read from its header")
      .option("exposure", "1", "linear exposure of the shown frame (as grtrace-render's PNG preview)")
      .option("bundle", "grid", "rays to draw: grid | row | column (camera pixels) | beam (parallel, equatorial) | none")
      .option("bundle-size", "9x7", "grid: COLSxROWS pixels; row, column, beam: a count")
      .option("beam-width", "", "beam: largest impact parameter (default 3 x the critical 3 sqrt(3) M)")
      .option("samples-per-step", "8", "points drawn per accepted step (dense output)")
      .option("color-by", "pixel", "ray colouring: pixel | redshift | h | lambda | status | none")
      .option("pick", "", "frame pixels to pick at start-up, COL,ROW (column, row from the top), several "
                          "separated by '/' (e.g. 160,120/40,200): each ray is traced, drawn in magenta and its outcome "
                          "printed, as a left click on the frame does; interactive keys: x clears the picks")
      // orbit
      .flag("orbit", "show the timelike orbit (a tube) in the 3D view")
      .option("orbit-r", "100", "orbit: start radius (equatorial plane, phi = 0; velocity --orbit-dr, --orbit-dphi)")
      .option("orbit-revolutions", "12", "orbit: turns in phi to trace");
  // The orbit's method: the seed's classic RK4 with step doubling by default (the method options again, prefixed).
  for (const char* name : {"tableau", "control", "step", "rtol", "atol"}) {
    const auto& table = app::render_options();
    const auto o = std::find_if(table.begin(), table.end(), [&](const app::OptionInfo& i) { return i.name == name; });
    const std::map<std::string, std::string> defaults = {
        {"tableau", "rk4"}, {"control", "doubling"}, {"step", "0"}, {"rtol", "1e-7"}, {"atol", "1e-10"}};
    std::string help(o->help);
    for (std::size_t at = 0; (at = help.find("--", at)) != std::string::npos; at += 8) help.insert(at + 2, "orbit-");
    cli.option(std::string("orbit-") + name, defaults.at(name), "orbit: " + help);
  }
  cli  // 3D view
      .option("hide", "",
              "comma-separated layers to hide: horizon,photon-sphere,isco,disk,sky,camera,rays,orbit,"
              "colorbar,picks,medium")
      .flag("checkerboard", "draw the horizon with the renderer's theta-phi checkerboard")
      .option("view-from", "", "3D view: eye position x,y,z (default: framing the hole and the camera)")
      .option("view-at", "0,0,0", "3D view: focal point x,y,z")
      .option("view-angle", "30", "3D view: vertical view angle in degrees");
  // One --orbit-dr/--orbit-dphi for the flight's orbit and the --orbit tube: both mean a timelike orbit's start
  // velocity, with the same defaults (grtrace-render's names).
  tools::declare_flight_options(
      cli, "Draws the whole path as a tube in the orbit layer (frames as white beads; not with --orbit) and puts "
           "the camera, the frame and the bundle at frame --flight-frame; --export also writes flight.vtp",
      "; also the --orbit tube's and --plot's start velocity");
  cli.option("flight-frame", "0", "flight: the frame (0 .. --frames - 1) whose camera the viewer uses");
  return cli;
}

/// Option values, with a frame's header attributes standing in for options not given on the command line.
class Params {
 public:
  Params(const CommandLine& cli, const std::map<std::string, std::string>* metadata) : cli_(cli), meta_(metadata) {}

  bool from_frame(const std::string& name) const { return !cli_.given(name) && attribute(name).has_value(); }
  std::string text(const std::string& name) const {
    if (!cli_.given(name))
      if (auto a = attribute(name)) return *a;
    return cli_.text(name);
  }
  double number(const std::string& name) const {
    return CommandLine::parse_number(name, text(name), from_frame(name) ? " (from the frame's header)" : "");
  }
  long integer(const std::string& name) const {
    return CommandLine::parse_integer(name, text(name), from_frame(name) ? " (from the frame's header)" : "");
  }

 private:
  std::optional<std::string> attribute(const std::string& name) const {
    if (!meta_) return std::nullopt;
    std::string underscored = name;
    std::replace(underscored.begin(), underscored.end(), '-', '_');
    if (name == "fov") underscored = "fov_degrees";
    // grtrace-render records every option's effective value as "option_<name>" (disk radii included).
    for (const std::string& key : {name, underscored, "option_" + name})
      if (auto it = meta_->find(key); it != meta_->end()) return it->second;
    return std::nullopt;
  }
  const CommandLine& cli_;
  const std::map<std::string, std::string>* meta_;
};

std::array<int, 2> parse_size(const std::string& name, const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> extra) || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw UsageError("--" + name + " expects WxH with positive whole numbers (e.g. 1600x800), got '" + text + "'");
  return {w, h};
}

/// The options as the application library reads them (app::read_metric, read_camera, read_method, check_request):
/// given on the command line, else the frame header's, else the viewer's defaults; --chart is the Kerr chart only
/// (its plot values are read_plot's).
class ViewOptions : public app::OptionSource {
 public:
  ViewOptions(const CommandLine& cli, const Params& p, std::string chart) : cli_(cli), p_(p), chart_(std::move(chart)) {}
  bool given(const std::string& name) const override { return cli_.given(name); }
  std::optional<std::string> text(const std::string& name) const override {
    if (name == "chart") return chart_;
    if (!cli_.declares(name)) return std::nullopt;
    return p_.text(name);
  }
  std::string origin(const std::string& name) const override {
    return p_.from_frame(name) ? " (from the frame's header)" : "";
  }

 private:
  const CommandLine& cli_;
  const Params& p_;
  std::string chart_;
};

double positive(const Params& p, const std::string& name) {
  const double v = p.number(name);
  if (!(v > 0.0)) throw UsageError("--" + name + " must be > 0, got " + p.text(name));
  return v;
}


Vec4 header_vec4(const std::map<std::string, std::string>& meta, const std::string& key) {
  const auto it = meta.find(key);
  if (it == meta.end()) throw UsageError("--frame: the header has no '" + key + "' (not written by grtrace-render?)");
  std::stringstream ss(it->second);
  Vec4 v;
  int n = 0;
  bool numeric = true;
  std::string item;
  for (; n < 4 && std::getline(ss, item, ','); ++n) {
    char* end = nullptr;
    v[n] = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0') numeric = false;
  }
  if (n != 4 || !numeric || std::getline(ss, item, ',') || !v.allFinite())
    throw UsageError("--frame: header '" + key + "' is not 4 finite numbers: '" + it->second + "'");
  return v;
}

/// The camera grtrace-render recorded: camera_position (t, r, theta, phi; Kerr-Schild frames: t, x, y, z),
/// tetrad_e0..3, fov_degrees. Takes the header, the frame's size and the request read so far (metric, chart).
Camera camera_from_header(const std::map<std::string, std::string>& meta, int width, int height, const Request& q) {
  Tetrad t;
  for (int a = 0; a < 4; ++a) {
    t.e[static_cast<std::size_t>(a)] = header_vec4(meta, "tetrad_e" + std::to_string(a));
    if (t.e[static_cast<std::size_t>(a)].isZero())
      throw UsageError("--frame: header 'tetrad_e" + std::to_string(a) + "' is the zero vector (not a camera frame)");
  }
  const auto fov = meta.find("fov_degrees");
  if (fov == meta.end()) throw UsageError("--frame: the header has no 'fov_degrees' (not written by grtrace-render?)");
  char* end = nullptr;
  const double fov_degrees = std::strtod(fov->second.c_str(), &end);
  if (fov->second.empty() || *end != '\0' || !(fov_degrees > 0.0 && fov_degrees < 180.0))
    throw UsageError("--frame: header 'fov_degrees' must be a number in (0, 180), got '" + fov->second + "'");
  const Vec4 x = header_vec4(meta, "camera_position");
  double mass = 1.0;
  if (const auto m = meta.find("mass"); m != meta.end()) {
    mass = std::strtod(m->second.c_str(), &end);
    if (m->second.empty() || *end != '\0' || !std::isfinite(mass) || mass < 0.0)
      throw UsageError("--frame: header 'mass' must be a number >= 0, got '" + m->second + "'");
  }
  // Outside the (outer) horizon: r_+ for Kerr, whose cameras may sit inside r = 2M (in the ergosphere).
  const double r_h = q.kerr ? KerrMetric{mass, q.spin}.outer_horizon() : 2.0 * mass;
  if (q.kerr && q.metric.chart == "ks") {  // Cartesian: no polar axis, the BL-like radius of the quadric
    MetricSpec at_mass = q.metric;
    at_mass.mass = mass;
    const double r = tools::as_usage_error([&] { return app::MetricGeometry::create(at_mass)->radius(x); });
    if (!(r > r_h))
      throw UsageError("--frame: header 'camera_position' puts the camera at Kerr-Schild r = " + std::to_string(r) +
                       ": it must be outside the horizon r_+ = " + std::to_string(r_h));
  } else if (!(x[1] > r_h) || !(x[2] > 0.0 && x[2] < std::numbers::pi)) {
    throw UsageError("--frame: header 'camera_position' puts the camera at r = " + std::to_string(x[1]) +
                     ", theta = " + std::to_string(x[2]) + " rad: it must be outside the horizon r = " +
                     std::to_string(r_h) + " and off the polar axis");
  }
  try {
    return Camera(x, t, width, height, fov_degrees);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--frame: ") + e.what());
  }
}

/// Takes --pick's text and the frame's size; returns the pixels (column, row from the top), in order. Throws
/// UsageError for a malformed list or a pixel outside the frame.
std::vector<std::array<int, 2>> parse_picks(const std::string& text, int width, int height) {
  std::vector<std::array<int, 2>> pixels;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, '/');) {
    int column = 0, row = 0;
    char comma = 0, extra = 0;
    std::istringstream in(item);
    if (!(in >> column >> comma >> row) || comma != ',' || (in >> extra))
      throw UsageError("--pick expects pixels COL,ROW (whole numbers, several separated by '/', e.g. 160,120/40,200), "
                       "got '" + item + "' in '" + text + "'");
    if (column < 0 || row < 0 || column >= width || row >= height)
      throw UsageError("--pick " + item + " is outside the " + std::to_string(width) + "x" + std::to_string(height) +
                       " frame: columns 0.." + std::to_string(width - 1) + ", rows 0.." + std::to_string(height - 1));
    pixels.push_back({column, row});
  }
  if (pixels.empty()) throw UsageError("--pick needs at least one pixel COL,ROW (e.g. 160,120)");
  return pixels;
}

/// Takes the command line, the flight spec of read_flight_spec and the request read so far (the metric, in the
/// ingoing slicing for a Kerr-Schild flight, and the checked single-frame request). Builds the path (the
/// application library's app::flight_worldline), checks --flight-frame against it and returns it with the camera of
/// that frame (make_moving_camera with --look/--up and the single-frame camera's size and field of view) put into
/// the checked request. Throws UsageError naming the option for what cannot fly.
view::FlightView read_flight_view(const CommandLine& cli, const Params& p, const FlightPathSpec& spec, Request& q) {
  for (const char* name : {"frame", "velocity", "observer"})
    if (cli.given(name))
      throw UsageError(std::string("--") + name + " sets a single frame's camera; a flight's camera moves with its "
                       "path (its 4-velocity): leave it out");
  if (cli.flag_set("orbit"))
    throw UsageError("--orbit draws the seed orbit in the orbit layer, where --flight draws its path: choose one");
  const long frame = cli.integer("flight-frame");
  auto check_frame = [&](long frames) {
    if (frame < 0 || frame >= frames)
      throw UsageError("--flight-frame " + cli.text("flight-frame") + " is not a frame of the flight: frames 0 .. " +
                       std::to_string(frames - 1) + " (--frames - 1)");
  };
  if (spec.kind != "csv") check_frame(spec.frames);  // before the path is sampled: no work for a bad index
  view::FlightView f;
  f.kind = spec.kind;
  f.frame = static_cast<int>(frame);
  const Camera& single = q.camera();
  const auto triple = [&](const char* name) {
    const std::vector<double> v = CommandLine::parse_numbers(name, p.text(name), 3);
    return Vec3(v[0], v[1], v[2]);
  };
  const CameraView look{triple("look"), triple("up"), single.width(),
                        single.height(), single.fov_degrees()};
  const Worldline path = tools::checked_flight_path(spec, [&] { return app::flight_worldline(q.metric, spec); });
  check_frame(static_cast<long>(path.samples.size()));
  const WorldlineSample& at = path.samples[static_cast<std::size_t>(f.frame)];
  const auto geometry = app::MetricGeometry::create(q.metric);
  const Camera camera = tools::as_usage_error([&] { return geometry->make_moving_camera(at.x, at.u, look); });
  q.checked = app::with_camera(*q.checked, camera);
  f.frames = static_cast<int>(path.samples.size());
  f.tau = at.tau;
  f.path = geometry->worldline_path(path);
  return f;
}

/// --plot orbit|norm|step, or its older spelling --chart orbit|norm|step. Takes the command line; returns the plot
/// ("": the 3D view). Throws UsageError for an unknown value, naming both options where --chart's two meanings
/// (Kerr coordinates bl|ks, or a plot) could be mixed up, and for a plot given both ways or beside --chart bl|ks.
std::string read_plot(const CommandLine& cli) {
  auto is_plot = [](const std::string& v) { return v == "orbit" || v == "norm" || v == "step"; };
  const std::string chart = cli.text("chart"), plot = cli.text("plot");
  if (cli.given("chart") && chart != "bl" && chart != "ks" && !is_plot(chart))
    throw UsageError("--chart must be bl or ks (Kerr coordinates, as grtrace-render's), or orbit, norm or step (the "
                     "older spelling of --plot), got '" + chart + "'");
  if (cli.given("plot") && !is_plot(plot))
    throw UsageError("--plot must be orbit, norm or step, got '" + plot + "'" +
                     (plot == "bl" || plot == "ks" ? " (Kerr coordinates are --chart " + plot + ")" : ""));
  if (cli.given("plot") && cli.given("chart"))
    throw UsageError(is_plot(chart) ? "--chart " + chart + " is the older spelling of --plot " + chart +
                                          "; give one of them, not both (--plot " + plot + ")"
                                    : "--plot " + plot + " draws a Schwarzschild orbit chart, --chart " + chart +
                                          " picks the Kerr coordinates of the 3D view: give one of them");
  return cli.given("plot") ? plot : is_plot(chart) ? chart : std::string();
}

Request read_request(const CommandLine& cli) {
  Request q;
  q.screenshot = cli.text("screenshot");
  if (cli.given("screenshot"))  // "" is refused, not taken as "interactive"
    tools::check_command_output(cli, "screenshot", q.screenshot, {{"frame", cli.text("frame")}});
  q.plot = read_plot(cli);
  const std::string plot_option = cli.given("plot") ? "--plot" : "--chart";
  if (cli.given("export")) {
    q.export_dir = cli.text("export");
    if (q.export_dir.empty()) throw UsageError("--export needs a directory name");
    if (!q.plot.empty()) throw UsageError("--export writes the 3D scene; not with " + plot_option + " " + q.plot);
    // The export's files (viz/vtk_export.hpp: .vtp, .vti and scene.vtm) must not take the screenshot's place.
    const std::filesystem::path shot(q.screenshot);
    const std::string ext = shot.extension().string();
    if (!q.screenshot.empty() && (ext == ".vtp" || ext == ".vti" || ext == ".vtm") &&
        same_file(shot.parent_path().empty() ? std::filesystem::path(".") : shot.parent_path(), q.export_dir))
      throw UsageError("--screenshot '" + q.screenshot + "' is a name --export writes VTK files under in '" +
                       q.export_dir + "'; give the screenshot a .png name or another directory");
  }
  q.size = cli.given("size") ? parse_size("size", cli.text("size"))
                             : (q.plot.empty() ? std::array<int, 2>{1600, 800} : std::array<int, 2>{900, 800});
  if (!q.plot.empty() && (q.size[0] < 200 || q.size[1] < 200)) throw UsageError("--size: charts need at least 200x200");
  if (q.plot.empty() && (q.size[0] < 64 || q.size[1] < 64)) throw UsageError("--size: at least 64x64");

  q.frame_file = cli.text("frame");
  if (!q.frame_file.empty()) {
    if (!std::filesystem::is_regular_file(q.frame_file)) throw UsageError("--frame: no such file '" + q.frame_file + "'");
    // Judged by its header before its pixels are decoded (an 8192 x 8192 file that is no frame costs nothing).
    const ExrInfo info = [&] {
      try {
        return read_exr_info(q.frame_file);
      } catch (const std::exception& e) {
        throw UsageError(std::string("--frame: ") + e.what());
      }
    }();
    for (const char* c : {"R", "G", "B"})
      if (!info.has_channel(c)) throw UsageError("--frame: '" + q.frame_file + "' has no '" + c + "' channel");
    std::string missing;  // a grtrace-render frame records its camera; anything else would be drawn wrongly
    for (const char* key : {"camera_position", "tetrad_e0", "tetrad_e1", "tetrad_e2", "tetrad_e3", "fov_degrees"})
      if (!info.metadata.count(key)) missing += (missing.empty() ? "" : ", ") + std::string(key);
    if (!missing.empty())
      throw UsageError("--frame: '" + q.frame_file + "' is not a grtrace-render frame: its header has no " + missing +
                       " (render the frame with grtrace-render)");
    try {
      q.frame = read_exr(q.frame_file);
    } catch (const std::exception& e) {
      throw UsageError(std::string("--frame: ") + e.what());
    }
  }
  const Params p(cli, q.frame ? &q.frame->metadata : nullptr);
  if (q.frame && q.frame->metadata.count("metric") && q.frame->metadata.at("metric") != "schwarzschild" &&
      q.frame->metadata.at("metric") != "kerr")
    throw UsageError("--frame: the frame was rendered with --metric " + q.frame->metadata.at("metric") +
                     "; the viewer draws Schwarzschild and Kerr (--chart bl or ks) scenes only");

  // The coordinate chart: --chart bl|ks, else the frame's, else bl (--chart orbit|norm|step is read_plot's).
  const bool chart_is_plot = cli.given("chart") && !q.plot.empty() && !cli.given("plot");
  std::string chart = chart_is_plot ? "bl" : p.text("chart");
  if (chart.empty()) chart = "bl";
  if (chart != "bl" && chart != "ks")
    throw UsageError("--chart: the frame's header names the chart '" + chart + "' (not bl or ks)");
  if (q.frame && cli.given("chart") && !chart_is_plot && q.frame->metadata.count("chart") &&
      q.frame->metadata.at("chart") != chart)
    throw UsageError("--chart " + chart + " conflicts with --frame: the frame was rendered with --chart " +
                     q.frame->metadata.at("chart") + " (its camera is recorded in that chart's coordinates)");

  // The frame's camera and pixels belong to the spacetime it was rendered in: the bundle is traced in that one.
  if (q.frame)
    for (const char* o : {"metric", "mass", "spin"})
      if (cli.given(o))
        throw UsageError(std::string("--") + o + " conflicts with --frame: the bundle is traced in the frame's own "
                         "spacetime (its --metric, --mass and --spin, read from its header); leave it out");
  q.scene = p.text("scene");
  if (!is_standard_scene(q.scene) && !app::is_medium_scene(q.scene))
    throw UsageError("--scene must be checker, sky, redshift, disk, accretion, riaf or torus, got '" + p.text("scene") +
                     "'");
  // The options shared with grtrace-render are read and checked by the application library, as there.
  const ViewOptions options(cli, p, chart);
  q.metric = tools::as_usage_error([&] { return app::read_metric(options, kViewMetrics); });
  tools::as_usage_error([&] { app::check_scene_options(options, q.scene); });
  q.mass = q.metric.mass;
  q.kerr = q.metric.name == "kerr";
  q.spin = q.metric.spin;
  if (q.kerr && !q.plot.empty()) throw UsageError(plot_option + " draws Schwarzschild orbits; not with --metric kerr");
  q.sky_radius = positive(p, "sky-radius");
  const bool header_camera = q.frame && q.frame->metadata.count("camera_position");
  if (header_camera)
    for (const char* o : {"camera-r", "camera-theta", "camera-phi", "velocity", "look", "up", "fov", "width", "height",
                          "observer"})
      if (cli.given(o))
        throw UsageError(std::string("--") + o + " conflicts with --frame: the bundle is traced through the frame's "
                         "own camera (read from its header)");
  const std::optional<FlightPathSpec> flight = tools::read_flight_spec(cli, q.mass, q.sky_radius, {"flight-frame"});
  if (flight && !q.plot.empty())
    throw UsageError("--flight draws a camera path in the 3D view; not with " + plot_option);
  // Kerr-Schild flights are flown in the ingoing slicing (the falling camera crosses the future horizon), as
  // grtrace-render's; the frame, the rays and the surfaces are then drawn in that chart too.
  if (flight && q.kerr && q.metric.chart == "ks") q.metric.slicing = KerrSchildSlicing::ingoing;

  // The frame's own camera, read (and its header checked) before the camera options that fall back on that header.
  std::optional<Camera> frame_camera;
  if (header_camera) frame_camera = camera_from_header(q.frame->metadata, q.frame->width(), q.frame->height(), q);
  app::RenderRequest r;
  r.metric = q.metric;
  r.scene = q.scene;
  r.sky_radius = q.sky_radius;
  r.camera = tools::as_usage_error([&] { return app::read_camera(options); });
  if (q.frame) {
    r.camera.width = q.frame->width();
    r.camera.height = q.frame->height();
  } else {
    r.camera.width = static_cast<int>(std::clamp(p.integer("width"), -1L, 1L << 20));
    r.camera.height = static_cast<int>(std::clamp(p.integer("height"), -1L, 1L << 20));
  }
  // The disk's sense: --disk-retrograde, else the frame's (grtrace-render records it); prograde follows the spin's
  // sign. Its inner edge, for a disk scene: --disk-inner, else the frame's, else (Kerr) the ISCO of that sense;
  // inside the ISCO refused as grtrace-render refuses it. The sense also picks the ISCO ring drawn.
  r.disk_retrograde = cli.flag_set("disk-retrograde") || (q.frame && q.frame->metadata.count("disk_sense") &&
                                                           q.frame->metadata.at("disk_sense") == "retrograde");
  if (q.scene == "disk" && (cli.given("disk-inner") || p.from_frame("disk-inner"))) r.disk_inner = p.number("disk-inner");
  r.disk_outer = p.number("disk-outer");
  r.angle_correction = p.text("angle-correction");
  r.method = tools::as_usage_error([&] { return app::read_method(options, ""); });
  if (app::is_medium_scene(q.scene)) {
    // A medium's gas, as grtrace-render reads it; drawn with the media's method unless one is named (then
    // check_request says what it must be).
    if (!cli.given("tableau") && !cli.given("control")) {
      r.method.tableau = app::kToolMethods[app::kMediaMethod].tableau;
      r.method.control = app::kToolMethods[app::kMediaMethod].control;
    }
    tools::as_usage_error([&] {
      r.accretion_gas = p.text("accretion-gas");
      r.accretion_power = app::option_number(options, "accretion-power");
      r.source = p.text("source");
      if (cli.given("accretion-rate") || p.from_frame("accretion-rate"))
        r.accretion_rate = app::option_number(options, "accretion-rate");
      r.frequencies_ghz = app::read_frequencies(options);
      r.torus_inner = app::option_number(options, "torus-inner");
      r.torus_peak = app::option_number(options, "torus-peak");
      r.torus_opacity = app::option_number(options, "torus-opacity");
    });
  }
  r.method.max_steps = static_cast<int>(std::clamp(p.integer("max-steps"), 0L, 1L << 30));
  r.threads = static_cast<int>(std::clamp(cli.integer("threads"), -1L, 1L << 20));
  q.checked = tools::as_usage_error([&] { return app::check_request(r); });
  if (frame_camera) q.checked = app::with_camera(*q.checked, *frame_camera);
  q.fov = p.number("fov");
  if (flight) q.flight = read_flight_view(cli, p, *flight, q);
  q.width = q.camera().width();
  q.height = q.camera().height();
  q.disk = {q.checked->scene.disk.r_in, q.checked->scene.disk.r_out};
  q.disk_sense = q.checked->scene.disk.sense;

  const double exposure = cli.number("exposure");
  if (!(exposure >= 0.0)) throw UsageError("--exposure must be >= 0");
  q.exposure = static_cast<float>(exposure);

  q.bundle = cli.text("bundle");
  if (q.bundle != "grid" && q.bundle != "row" && q.bundle != "column" && q.bundle != "beam" && q.bundle != "none")
    throw UsageError("--bundle must be grid, row, column, beam or none, got '" + q.bundle + "'");
  const std::string bs = cli.text("bundle-size");
  if (bs.find_first_of("xX") == std::string::npos) {
    const long n = cli.integer("bundle-size");
    if (n < 1 || n > 10000) throw UsageError("--bundle-size must be 1 .. 10000 rays, got '" + bs + "'");
    q.bundle_size = {static_cast<int>(n), 1};
  } else {
    q.bundle_size = parse_size("bundle-size", bs);
    if (q.bundle_size[0] * q.bundle_size[1] > 10000) throw UsageError("--bundle-size: at most 10000 rays");
  }
  if (q.kerr && q.bundle == "beam")
    throw UsageError("--bundle beam starts Schwarzschild photons from afar; with --metric kerr use grid, row or column");
  q.beam_width = cli.given("beam-width") ? positive(p, "beam-width") : 9.0 * std::sqrt(3.0) * q.mass;
  if (q.bundle == "beam" && !(view::beam_start_radius(q) < q.sky_radius))
    throw UsageError("--bundle beam starts at r = " + tools::JsonObject::number(view::beam_start_radius(q)) +
                     ", outside --sky-radius; make the beam narrower or the sky sphere larger");
  const long sps = cli.integer("samples-per-step");
  if (sps < 1 || sps > 1000) throw UsageError("--samples-per-step must be 1 .. 1000");
  q.samples_per_step = static_cast<int>(sps);
  const auto field = viz::scalar_field_from_string(cli.text("color-by"));
  if (!field)
    throw UsageError("--color-by must be pixel, redshift, h, lambda, status or none, got '" + cli.text("color-by") + "'");
  q.color_by = *field;
  if (q.color_by == viz::ScalarField::redshift && q.bundle == "beam")
    throw UsageError("--color-by redshift needs camera rays (a beam has no observer); use --bundle grid, row or column");

  if (cli.given("pick")) {
    if (!q.plot.empty()) throw UsageError("--pick picks frame pixels; not with " + plot_option);
    q.picks = parse_picks(cli.text("pick"), q.width, q.height);
  }

  q.show_orbit = cli.flag_set("orbit");
  if (q.kerr && q.show_orbit) throw UsageError("--orbit traces a Schwarzschild orbit; not with --metric kerr");
  q.orbit.mass = q.mass;
  q.orbit.r0 = cli.number("orbit-r");
  q.orbit.dphi_dtau = cli.number("orbit-dphi");
  q.orbit.dr_dtau = cli.number("orbit-dr");
  q.orbit.revolutions = positive(p, "orbit-revolutions");
  if (q.orbit.revolutions > 1000) throw UsageError("--orbit-revolutions: at most 1000");
  if (!(q.orbit.r0 > 2.0 * q.mass * 1.01)) throw UsageError("--orbit-r must lie outside the horizon r = 2M");
  if (q.show_orbit || !q.plot.empty()) {
    // The orbit's own request: the seed orbit in Schwarzschild with the orbit's method, its sky sphere far beyond
    // the orbit (1e6 r0) and a step budget for its revolutions; a camera at the orbit's start (unused).
    app::RenderRequest o;
    o.metric.mass = q.mass;
    o.scene = "sky";
    o.method = tools::as_usage_error([&] { return app::read_method(options, "orbit-"); });
    o.method.max_steps = 2'000'000;
    o.sky_radius = 1e6 * q.orbit.r0;
    o.camera.r = q.orbit.r0;
    o.camera.width = o.camera.height = 1;
    q.orbit_checked = tools::as_usage_error([&] { return app::check_request(o); });
  }

  // The viewer's own options that mean something only with others: refused where they would be ignored.
  const bool orbit_traced = q.show_orbit || !q.plot.empty();
  const bool flight_orbit = flight && flight->kind == "orbit";
  const char* const orbit_needs = "--orbit or --plot (the seed orbit)";
  tools::refuse_inapplicable_options(
      cli, {{"beam-width", q.bundle == "beam", "--bundle beam"},
            {"bundle-size", q.bundle != "none", "--bundle grid, row, column or beam"},
            {"orbit-r", orbit_traced, orbit_needs},
            {"orbit-revolutions", orbit_traced, orbit_needs},
            {"orbit-tableau", orbit_traced, orbit_needs},
            {"orbit-control", orbit_traced, orbit_needs},
            {"orbit-step", orbit_traced, orbit_needs},
            {"orbit-rtol", orbit_traced, orbit_needs},
            {"orbit-atol", orbit_traced, orbit_needs},
            {"orbit-dr", orbit_traced || flight_orbit, "--orbit, --plot or --flight orbit"},
            {"orbit-dphi", orbit_traced || flight_orbit, "--orbit, --plot or --flight orbit"}});
  if (!q.plot.empty())  // a chart of the orbit has no 3D view, bundle or frame
    for (const char* o : {"bundle", "bundle-size", "beam-width", "samples-per-step", "color-by", "hide", "checkerboard",
                          "view-from", "view-at", "view-angle", "exposure"})
      if (cli.given(o))
        throw UsageError(std::string("--") + o + " belongs to the 3D view; not with " + plot_option + " " + q.plot);

  std::stringstream hide(cli.text("hide"));
  for (std::string item; std::getline(hide, item, ',');) {
    if (item.empty()) continue;
    const auto l = viz::layer_from_string(item);
    if (!l)
      throw UsageError("--hide: unknown layer '" + item +
                       "' (horizon, photon-sphere, isco, disk, sky, camera, rays, orbit, colorbar, picks, medium)");
    q.hidden.push_back(*l);
  }
  q.checkerboard = cli.flag_set("checkerboard");
  if (cli.given("view-from")) {
    const auto v = cli.numbers("view-from", 3);
    q.view_from = Vec3(v[0], v[1], v[2]);
  }
  const auto at = cli.numbers("view-at", 3);
  q.view_at = Vec3(at[0], at[1], at[2]);
  q.view_angle = cli.number("view-angle");
  if (!(q.view_angle > 0.0 && q.view_angle < 180.0)) throw UsageError("--view-angle must lie in (0, 180) degrees");
  if (q.view_from && !((*q.view_from - q.view_at).norm() > 0.0))
    throw UsageError("--view-from and --view-at must differ");
  return q;
}

// ---- orbit and charts --------------------------------------------------------------------------------------

std::string orbit_note(const Request& q, const viz::TracedPath& path) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "r0 = %g M, dphi/dtau = %g, %g turns; %s + %s control, rtol %g, atol %g: %zu steps",
                q.orbit.r0, q.orbit.dphi_dtau, q.orbit.revolutions, q.orbit_checked->request.method.tableau.c_str(),
                q.orbit_checked->request.method.control.c_str(), q.orbit_checked->request.method.rtol,
                q.orbit_checked->request.method.atol, path.steps.empty() ? 0 : path.steps.size() - 1);
  return buf;
}

int run_chart(const Request& q) {
  const viz::TracedPath path = view::trace_orbit(q);
  const std::string note = orbit_note(q, path);
  const viz::ChartSpec spec = q.plot == "orbit"  ? viz::orbit_chart(path, q.mass, note)
                              : q.plot == "norm" ? viz::norm_chart(path, note)
                                                 : viz::step_chart(path, note);
  if (!q.screenshot.empty()) {
    viz::save_chart_png(spec, q.size[0], q.size[1], q.screenshot);
    std::cout << "wrote " << q.screenshot << " (" << q.size[0] << "x" << q.size[1] << ", " << note << ")\n";
  } else {
    viz::show_chart(spec, q.size[0], q.size[1]);
  }
  return 0;
}

// ---- the camera, the frame and the bundle ------------------------------------------------------------------

std::vector<std::array<int, 2>> bundle_pixels(const Request& q) {
  if (q.bundle == "grid") return viz::pixel_grid(q.width, q.height, q.bundle_size[0], q.bundle_size[1]);
  if (q.bundle == "row") return viz::pixel_row(q.width, q.height, q.bundle_size[0]);
  if (q.bundle == "column") return viz::pixel_column(q.width, q.height, q.bundle_size[0]);
  return {};
}

/// 8-bit sRGB of a linear colour, as the PNG preview encodes it.
viz::Rgb8 encode(const Rgb& c) { return {srgb_encode8(c[0]), srgb_encode8(c[1]), srgb_encode8(c[2])}; }

int run_view(const Request& q) {
  const Camera& camera = q.camera();
  const auto t0 = std::chrono::steady_clock::now();
  // The frame: the file's, or drawn here (its report says which tracer ran: auto picks the fastest exact one).
  std::optional<app::RenderResult> rendered;
  if (!q.frame) rendered = view::render_frame(q);
  const Image& frame_image = q.frame ? *q.frame : rendered->image;
  const double frame_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const viz::Rgb8Image frame_rgb = viz::frame_from_image(frame_image, q.exposure);

  viz::SceneLayout layout;
  layout.mass = q.mass;
  if (q.scene == "disk") layout.disk = q.disk;
  layout.sky_radius = q.sky_radius;
  const StandardSceneSpec& scene_spec = q.checked->scene;
  const HorizonPaint paint{scene_spec.checker_squares};  // the checker scene's horizon, drawn on the 3D sphere
  layout.horizon_checkerboard = q.checkerboard;
  layout.checker_theta = paint.squares;
  layout.checker_phi = 2 * paint.squares;
  layout.checker_a = encode(paint.dark);  // parity 0 (see checker_parity)
  layout.checker_b = encode(paint.light);
  if (q.kerr) {
    layout.spin = q.spin;
    const bool pro = q.disk_sense == (q.spin < 0.0 ? -1 : 1);
    layout.isco_radius = exact::isco_radius(q.spin, pro ? exact::Orbit::prograde : exact::Orbit::retrograde, q.mass);
    // Kerr-Schild rays are drawn in their chart's Cartesian x, y, z: the surfaces follow them there (see the top).
    if (q.metric.chart == "ks") layout.kerr_schild = q.metric.slicing;
  }
  // The camera's Boyer-Lindquist r and theta for the caption (a Kerr-Schild camera event is Cartesian).
  const auto geometry = app::MetricGeometry::create(q.metric);
  layout.camera = viz::make_camera_glyph(*geometry, camera.position(), camera.tetrad().e, q.fov, q.width, q.height);
  const Vec4 camera_bl = geometry->to_spherical(camera.position());

  const auto pixels = bundle_pixels(q);
  const std::vector<viz::TracedPath> rays = view::trace_bundle(q, pixels, frame_rgb);
  std::optional<viz::TracedPath> orbit;
  if (q.show_orbit) orbit = view::trace_orbit(q);
  std::optional<viz::MediumField> medium;  // the gas the frame shows, drawn as iso-surfaces of its emission
  if (app::is_medium_scene(q.scene)) {
    app::MediumVolume v = app::medium_volume(*q.checked, 72);
    medium = viz::MediumField{v.n, v.half_width, std::move(v.emission), v.peak};
  }
  std::vector<viz::RayPick> picks;
  for (const auto& pixel : q.picks) {
    picks.push_back(view::pick_ray(q, pixel, frame_rgb));
    std::cout << "pick " << viz::describe(picks.back()) << "\n";
  }

  if (!q.export_dir.empty()) {
    viz::SceneExport ex;
    ex.layout = layout;
    ex.hidden = q.hidden;
    std::vector<viz::TracedPath> exported = rays;  // the bundle, then the picked rays
    std::vector<std::vector<double>> light(rays.size());  // a medium's picks: the light they collect
    for (const auto& pick : picks) {
      exported.push_back(pick.path);
      light.push_back(pick.light);
    }
    ex.rays = exported;
    if (medium) ex.light = light;
    ex.orbit = orbit ? &*orbit : nullptr;
    const viz::CameraRecord record{camera.position(), camera.tetrad().e, q.fov, q.width, q.height};
    if (q.flight) ex.flight = viz::FlightExport{&q.flight->path, q.flight->kind, q.flight->frame, record};
    if (q.bundle != "beam") ex.camera = record;  // a beam does not start at the camera
    ex.frame = &frame_rgb;
    ex.frame_channels = &frame_image;
    if (medium) ex.medium = &*medium;
    const auto files = viz::export_scene(q.export_dir, ex);
    std::cout << "wrote " << files.back().path.string() << " (" << files.size() - 1 << " files: ";
    for (std::size_t i = 0; i + 1 < files.size(); ++i)
      std::cout << (i ? ", " : "") << files[i].path.filename().string();
    std::cout << "; " << rays.size() << " rays" << (picks.empty() ? "" : " + " + std::to_string(picks.size()) + " picked")
              << ")\n";
    if (q.screenshot.empty()) return 0;  // export only: no window
  }

  viz::SceneView scene(layout);
  if (medium) scene.set_medium(*medium);
  if (!rays.empty()) {
    viz::ScalarField field = q.color_by;
    if (field == viz::ScalarField::pixel_color && q.bundle == "beam") field = viz::ScalarField::status;  // no pixels
    scene.set_rays(viz::paths_to_polydata(rays), field);
  }
  if (orbit) scene.set_orbit(viz::paths_to_polydata(std::span(&*orbit, 1)), viz::ScalarField::lambda);
  if (q.flight) {
    std::vector<Vec3> frame_positions;
    for (const viz::PathSample& s : q.flight->path.samples) frame_positions.push_back(s.position);
    scene.set_orbit(viz::paths_to_polydata(std::span(&q.flight->path, 1)), viz::ScalarField::lambda, 0.0,
                    frame_positions);
  }
  for (viz::Layer l : q.hidden) scene.set_visible(l, false);
  viz::ViewPose pose = scene.default_view();
  if (q.view_from) {
    pose.from = *q.view_from;
    pose.at = q.view_at;
  }
  pose.view_angle_degrees = q.view_angle;
  scene.set_view(pose);

  viz::FrameView frame;
  frame.set_frame(frame_rgb);
  frame.set_markers(pixels);

  char frame_caption[256];
  const char* marked = pixels.empty() ? "" : ", bundle pixels marked";
  if (q.frame) {
    std::snprintf(frame_caption, sizeof frame_caption, "frame %s (%dx%d)%s",
                  std::filesystem::path(q.frame_file).filename().c_str(), q.width, q.height, marked);
  } else {
    const std::string which =
        q.flight ? " " + std::to_string(q.flight->frame) + " of flight " + q.flight->kind : std::string();
    std::snprintf(frame_caption, sizeof frame_caption, "frame%s (%dx%d, %s tracer, rendered in %.2f s)%s",
                  which.c_str(), q.width, q.height, rendered->report.tracer.c_str(), frame_seconds, marked);
  }
  char flight_caption[160] = "";
  if (q.flight)
    std::snprintf(flight_caption, sizeof flight_caption, "flight %s: frame %d of %d, tau = %.6g M; ",
                  q.flight->kind.c_str(), q.flight->frame, q.flight->frames, q.flight->tau);
  char scene_caption[400];
  char hole[80] = "";
  if (q.kerr)
    std::snprintf(hole, sizeof hole, ", a = %g (%s)", q.spin,
                  q.metric.chart == "ks" ? "Kerr-Schild" : "Boyer-Lindquist");
  std::snprintf(scene_caption, sizeof scene_caption,
                "%sM = %g%s; camera at r = %g, theta = %g deg, fov %g deg; %zu rays coloured by %s", flight_caption,
                q.mass, hole, camera_bl[1], camera_bl[2] / kDeg, q.fov, rays.size(),
                std::string(viz::to_string(scene.color_by(viz::Layer::rays))).c_str());

  viz::WindowOptions opt;
  opt.width = q.size[0];
  opt.height = q.size[1];
  opt.offscreen = !q.screenshot.empty();
  opt.scene_caption = scene_caption;
  opt.frame_caption = frame_caption;
  viz::ViewerWindow window(scene, &frame, opt);
  window.set_pick_handler([&](std::array<int, 2> pixel) { return view::pick_ray(q, pixel, frame_rgb); });
  for (auto& pick : picks) window.add_pick(std::move(pick));
  if (!q.screenshot.empty()) {
    window.save_png(q.screenshot);
    std::cout << "wrote " << q.screenshot << " (" << q.size[0] << "x" << q.size[1] << ")\n";
  } else {
    std::cout << viz::ViewerWindow::key_help() << std::endl;
    window.interact("grtrace-view");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli = make_command_line();
  try {
    if (!cli.parse(argc, argv)) return 0;
    const Request q = read_request(cli);
    if (cli.write_config_if_asked()) return 0;  // checked as for a run; the display is needed for a run only
    if (q.export_dir.empty() || !q.screenshot.empty()) {  // --export alone draws nothing: no display needed
      try {
        viz::require_display(cli.program(), "");
      } catch (const viz::NoDisplayError& e) {
        throw UsageError(std::string(e.what()) + " --screenshot FILE.png");
      }
    }
    if (!q.export_dir.empty()) {  // after every other check, so a directory is made only for real work
      try {
        viz::prepare_export_directory(q.export_dir);
      } catch (const viz::ExportPathError& e) {
        throw UsageError(std::string("--export: ") + e.what());
      }
    }
    return q.plot.empty() ? run_view(q) : run_chart(q);
  } catch (const UsageError& e) {
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {  // refusals from the library (camera, tetrad, surfaces)
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 2;
  } catch (const MemoryLimitError& e) {  // a size from input (--frame's data window, --size) above the limit
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << cli.program() << ": error: out of memory; use a smaller --size, frame or bundle\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 1;
  }
}
