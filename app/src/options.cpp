// A render request by option names (grtrace/app/front_door.hpp): the options' table (names, defaults, help) that
// grtrace-render's --help lists and the Python module's keywords follow, and the reading of their texts, so that a
// command line, a scene file, a frame's header and Python keywords are read by one piece of code.
#include "frame_tracers.hpp"
#include "grtrace/app/front_door.hpp"
#include "grtrace/core/number_text.hpp"
#include "grtrace/trace/critical_angle_grid.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <algorithm>
#include <array>
#include <deque>
#include <stdexcept>
#include <string>
#include <utility>

namespace grtrace::app {

namespace {

/// The texts the table points at that are built at run time (the metric list, the methods), kept for the process.
std::deque<std::string>& built_texts() {
  static std::deque<std::string> texts;
  return texts;
}
std::string_view keep(std::string text) { return built_texts().emplace_back(std::move(text)); }

std::vector<OptionInfo> make_render_options() {
  std::vector<OptionInfo> o;
  o.push_back({"scene", "checker",
               "checker | sky | redshift | disk | accretion (glowing gas falling onto --metric schwarzschild; "
               "channels intensity, optical_depth and the emission-weighted redshift) | riaf (the hot flow of M87* or "
               "Sgr A* around --metric kerr, thermal synchrotron in physical units: intensity in cgs, flux in Jy) | "
               "torus (a thick torus of constant angular momentum around --metric kerr; riaf and torus are traced on "
               "Kerr's separated equations in Mino time); media are drawn with vern6 + i; a medium whose every pixel "
               "is integrated (riaf, torus, accretion with --tracer general) splits its intensity by image order: "
               "channels intensity_n0 .. intensity_n3_up, flux_n0 .. flux_n3_up in the report"});
  std::string metrics;
  for_each_named_metric([&]<class E>() { metrics += (metrics.empty() ? "" : " | ") + std::string(E::help); });
  o.push_back({"metric", kMetricNames[0], keep(metrics)});
  o.push_back({"mass", "1", "black-hole mass M (G = c = 1)"});
  for (const NamedMetricParameter& p : named_metric_parameters())
    o.push_back({p.parameter.option, p.parameter.default_text, p.parameter.help});
  o.push_back({"chart", "bl",
               "kerr: bl (Boyer-Lindquist) | ks (Kerr-Schild, horizon-penetrating); the camera is placed in "
               "Boyer-Lindquist coordinates for both"});
  o.push_back({"camera-r", "200", "camera radius (must be outside the horizon guard and inside --sky-radius)"});
  o.push_back({"camera-theta", "90",
               "camera polar angle theta in degrees, 0 .. 180 (90: the equatorial plane; 0 and 180: on the spin axis, "
               "a face-on view, the camera placed 1e-9 rad off it)"});
  o.push_back({"camera-phi", "0", "camera azimuth phi in degrees"});
  o.push_back({"observer", "static",
               "static | zamo: the observer whose frame carries the camera (same for a non-rotating hole); "
               "--metric kerr defaults to zamo (valid in the ergosphere)"});
  o.push_back({"velocity", "0,0,0", "camera 3-velocity beta_r,beta_theta,beta_phi (fraction of c, observer's frame)"});
  o.push_back({"look", "-1,0,0", "look direction r,theta,phi in the observer's frame (-1,0,0: at the hole)"});
  o.push_back({"up", "0,-1,0", "up direction r,theta,phi in the observer's frame (0,-1,0: the north pole)"});
  o.push_back({"fov", "90", "horizontal field of view in degrees, in (0, 180)"});
  o.push_back({"width", "1024", "image width in pixels"});
  o.push_back({"height", "1024", "image height in pixels"});
  o.push_back({"tableau", "rkf78",
               keep("Runge-Kutta tableau: " + tool_tableau_names() + ". With --control, one of the offered methods: " +
                    tool_methods_list() + " (every pair: grtrace-work-precision, grtrace-geodesic)")});
  o.push_back({"control", "i", keep("step control: " + tool_control_names() + " (see --tableau for the pairs)")});
  o.push_back({"step", "0", "initial step (0 = automatic), or the step of --control fixed"});
  o.push_back({"rtol", "1e-9", "relative tolerance"});
  o.push_back({"atol", "1e-11", "absolute tolerance"});
  o.push_back({"sky-radius", "400", "radius of the sky sphere where rays are taken as escaped"});
  o.push_back({"angle-correction", "exact", "escaped rays: none | flat (seed eq. 7-8) | exact (bending to infinity)"});
  o.push_back({"max-steps", "100000", "step budget per ray"});
  o.push_back({"tracer", "auto",
               "auto | general | planar | kerr-mino | kerr-closed-form | straight-line. planar: one table of rays for "
               "the frame, every scene of a Schwarzschild or Reissner-Nordstrom hole, disk included (auto's choice "
               "there with an adaptive --control); kerr-closed-form: every pixel from Kerr's geodesics in closed "
               "form, nothing integrated (auto's choice for --metric kerr --chart bl with an adaptive --control); "
               "kerr-mino: every pixel on Kerr's separated equations in Mino time, 3x cheaper per ray than general "
               "(what the GPU runs for Kerr); straight-line: flat space (auto's choice for --metric minkowski); "
               "general: every pixel integrated (any curved metric)"});
  o.push_back({"device", "auto",
               "auto | cpu | cuda. cuda: rays traced on the GPU (a build with the CUDA backend and a CUDA device; "
               "--tableau rkf78 --control i; every pixel integrated: --tracer general, or auto = kerr-mino for "
               "--metric kerr --chart bl, general otherwise); auto: the GPU where it can draw the request and a "
               "device is present, except where the CPU's table tracer draws it (Schwarzschild and "
               "Reissner-Nordstrom with --tracer auto), else the CPU. The report and the EXR header (device) name "
               "the device that ran"});
  o.push_back({"table-rays", keep(std::to_string(grtrace::default_table_rays)),
               keep("planar tracer: table rays on each side of the critical angle (--scene accretion: " +
                    std::to_string(grtrace::default_medium_table_rays) + ")")});
  o.push_back({"sky-texture", "", "equirectangular EXR (R,G,B) for the sky of the sky and disk scenes"});
  o.push_back(
      {"checker-squares", "18", "checker scene: squares along theta on sky and horizon (twice as many in phi)"});
  o.push_back({"disk-inner", "6",
               "disk inner radius (disk scene); kerr: default and lower bound the ISCO of the disk's sense (BPT "
               "1972), e.g. 2.32 for a = 0.9 prograde"});
  o.push_back({"disk-outer", "20", "disk outer radius (disk scene)"});
  o.push_back({"disk-retrograde", "",
               "disk scene: the gas turns against the hole's rotation (default: with it; towards +phi for a "
               "non-rotating hole)",
               true});
  o.push_back({"spectrum", "",
               "line: instead of a frame, the disk's line profile seen from afar at --camera-theta (a CSV at --out "
               "NAME.csv and its plot NAME.png): the flux per energy bin, in total and by image order n = 0, 1, 2, "
               ">= 3, for --metric kerr or schwarzschild, every ray in closed form on an adaptive image-plane mesh"});
  o.push_back({"rings", "",
               "instead of a frame, the disk's photon ring by order seen from afar at --camera-theta (--out NAME.exr "
               "with channels I, I_n0 .. I_n3_up, NAME.png and NAME-orders.png): each ring integrated across its "
               "width however thin, the flux of each order and the rings' diameters and widths in the JSON line, "
               "for --metric kerr or schwarzschild, every ray in closed form",
               true});
  o.push_back({"ring-field", "8", "--rings: the image's half width (M), square pixels of 2 field / width"});
  o.push_back(
      {"ring-cuts", "0", "--rings: radial cuts for the rings n >= 2 (0: a pixel apart at 6 M from the centre)"});
  o.push_back({"redshift-power", "3",
               "--rings or --disk-light: the observed intensity is g^power eps(r) (3: a specific intensity, flat "
               "source spectrum; 4: bolometric)"});
  o.push_back({"line-energy", "6.4", "--spectrum line: the line's energy in the gas's frame (the bins' unit: keV)"});
  o.push_back({"emissivity-index", "3", "--spectrum line, --rings or --disk-light: the emissivity falls as r^-index"});
  o.push_back({"emissivity-index-outer", "",
               "--spectrum line, --rings or --disk-light: the index beyond --emissivity-break (a broken power law; "
               "default: the same)"});
  o.push_back({"emissivity-break", "",
               "--spectrum line, --rings or --disk-light: the radius (M) where the emissivity's index changes"});
  o.push_back({"energy-range", "",
               "--spectrum line: lo,hi of the bins (default: around the energies the disk's light arrives at)"});
  o.push_back({"energy-bins", "200", "--spectrum line: the number of energy bins, 1 .. 100000"});
  o.push_back({"line-finest", "0.015625",
               "--spectrum line: the image-plane mesh's finest cell (M); 1e-3 of the peak per bin at the default"});
  o.push_back({"disk-transparent", "",
               "--spectrum line, --rings or --scene disk (implies --disk-light): every crossing of the disk shines "
               "and the ray goes on (default: an opaque disk, the first crossing only)",
               true});
  o.push_back({"disk-light", "",
               "disk scene: the frame shows the disk's light g^p eps(r) (--redshift-power, --emissivity-*) by image "
               "order instead of its colour: EXR channels intensity, intensity_n0 .. intensity_n3_up, the picture in "
               "a hot-gas map, the flux of each order in the JSON line; --metric kerr or schwarzschild, every ray in "
               "closed form, on the CPU",
               true});
  o.push_back({"accretion-gas", "free-fall",
               "accretion scene: free-fall (from rest at infinity, Narayan, Johnson & Gammie 2019) | rest"});
  o.push_back({"accretion-power", "2", "accretion scene: the emissivity falls as r^-power, power in [0, 10]"});
  o.push_back({"source", "m87",
               "riaf scene: m87 (6.5e9 solar masses at 16.8 Mpc) | sgr-a (4.0e6 at 8.15 kpc): the scale of the "
               "image and its flux, and the accretion rate's default"});
  o.push_back({"accretion-rate", "",
               "riaf scene: solar masses a year reaching the hole, in (0, 1e3] (default: 5e-4 for m87, 1e-8 for "
               "sgr-a, near the flux the EHT measures)"});
  o.push_back({"frequency", "230",
               "riaf scene: the observed frequency in GHz, in (0, 1e7]; or up to 8, comma-separated (86,230,345), "
               "traced in one pass: a channel intensity_<f>GHz and a flux each, the first one's the picture"});
  o.push_back({"torus-inner", "6", "torus scene: the inner edge on the equator (M)"});
  o.push_back({"torus-peak", "10",
               "torus scene: the pressure maximum on the equator (M), beyond --torus-inner: its angular momentum is "
               "the circular orbit's there"});
  o.push_back({"torus-opacity", "0", "torus scene: alpha / j (0: optically thin; 1e3: nearly a surface), in [0, 1e6]"});
  o.push_back({"threads", "0", "OpenMP threads (0 = all cores)"});
  o.push_back({"error-map", "",
               "add an \"error\" channel: the angular error (rad) of each escaped pixel against the exact "
               "elliptic-integral direction from the camera (Schwarzschild/flat only); report max_error/median_error",
               true});
  o.push_back({"no-mirrors", "",
               "trace every pixel: by default a frame that is mirror symmetric (camera on the equator looking along "
               "its axes; no metric rotation or orbiting disk for the left-right mirror) traces half or a quarter of "
               "its pixels and reflects the rest (report traced_rays, EXR header mirrors)",
               true});
  return o;
}

/// The option's effective text: the source's, else the table's default.
std::string text_of(const OptionSource& s, const std::string& name) {
  if (auto t = s.text(name)) return *t;
  for (const OptionInfo& o : render_options())
    if (o.name == name) return std::string(o.default_text);
  throw std::logic_error("grtrace_app: option --" + name + " is not a render option");
}

template <class F>
decltype(auto) as_request_error(F&& f) {
  return refusal_as_request_error("", std::forward<F>(f));
}

/// An option given where it means nothing (a spin without Kerr, a disk's radius without the disk) is refused
/// instead of ignored silently.
void refuse_unless(const OptionSource& s, const std::string& option, bool applies, const std::string& needs) {
  if (!applies && s.given(option))
    throw RequestError("--" + option + " applies only with " + needs +
                       ", which this command does not have; leave it out or add " + needs);
}

/// A whole number in [lo, hi], or `message`.
int integer_in(const OptionSource& s, const std::string& name, long lo, long hi, const std::string& message) {
  const long v = option_integer(s, name);
  if (v < lo || v > hi) throw RequestError(message);
  return static_cast<int>(v);
}

Vec3 triple(const OptionSource& s, const std::string& name) {
  const std::vector<double> v = option_numbers(s, name, 3);
  return {v[0], v[1], v[2]};
}

/// The options only --spectrum line reads, only --rings reads, and both.
constexpr std::array<const char*, 5> kLineProfileOptions = {"spectrum", "line-energy", "energy-range", "energy-bins",
                                                            "line-finest"};
constexpr std::array<const char*, 3> kRingImageOptions = {"rings", "ring-field", "ring-cuts"};
/// How the disk shines: read wherever its light is drawn (a line profile, a ring image, a frame with --disk-light).
constexpr std::array<const char*, 4> kDiskLightOptions = {"emissivity-index", "emissivity-index-outer",
                                                          "emissivity-break", "disk-transparent"};
/// The options that describe a frame and say nothing of a disk drawn by its light (every ray in closed form).
constexpr std::array<const char*, 10> kNotForDiskLight = {"tableau",     "control",   "step",       "rtol",
                                                          "atol",        "max-steps", "table-rays", "angle-correction",
                                                          "sky-texture", "error-map"};

DiskLightRequest read_disk_light(const OptionSource& s) {
  DiskLightRequest d;
  d.transparent = s.given("disk-transparent");
  d.emissivity_index = option_number(s, "emissivity-index");
  if (s.given("emissivity-index-outer")) d.emissivity_index_outer = option_number(s, "emissivity-index-outer");
  if (s.given("emissivity-break")) d.emissivity_break = option_number(s, "emissivity-break");
  return d;
}

double read_redshift_power(const OptionSource& s) {
  const double p = option_number(s, "redshift-power");
  if (!(std::abs(p) <= 10.0))
    throw RequestError("--redshift-power must lie in [-10, 10], got " + text_of(s, "redshift-power"));
  return p;
}

/// The disk and observer a line profile and a ring image share; `what` names the command in messages, `own` the
/// options it reads besides. Every other option given is refused: it describes a frame.
DistantDisk read_distant_disk(const OptionSource& s, const std::string& what, const std::vector<std::string>& own) {
  std::vector<std::string> reads = own;
  reads.insert(reads.end(), kDiskLightOptions.begin(), kDiskLightOptions.end());
  for (const char* o :
       {"scene", "metric", "mass", "chart", "camera-theta", "disk-inner", "disk-outer", "disk-retrograde", "threads"})
    reads.emplace_back(o);
  for (const NamedMetricParameter& p : named_metric_parameters()) reads.emplace_back(p.parameter.option);
  for (const OptionInfo& o : render_options())
    if (s.given(std::string(o.name)) && std::find(reads.begin(), reads.end(), o.name) == reads.end())
      throw RequestError("--" + std::string(o.name) + " describes a frame; " + what +
                         " is a distant observer's view of the disk (at --camera-theta, every ray in closed form): "
                         "leave --" +
                         std::string(o.name) + " out");
  if (text_of(s, "scene") != "disk") throw RequestError(what + " is the disk's: add --scene disk");
  DistantDisk d;
  d.metric = read_metric(s, {"kerr", "schwarzschild"});
  d.inclination_degrees = option_number(s, "camera-theta");
  if (s.given("disk-inner")) d.disk_inner = option_number(s, "disk-inner");
  d.disk_outer = option_number(s, "disk-outer");
  d.disk_retrograde = s.given("disk-retrograde");
  d.light = read_disk_light(s);
  d.threads = integer_in(s, "threads", 0, 1024, "--threads must be 0 (all cores) .. 1024");
  return d;
}

}  // namespace

LineProfileRequest read_line_profile_request(const OptionSource& s) {
  if (text_of(s, "spectrum") != "line")
    throw RequestError("--spectrum must be line (the disk's line profile), got '" + text_of(s, "spectrum") + "'");
  if (s.given("rings"))
    throw RequestError("--spectrum line and --rings are two commands: give one (a spectrum or a ring image)");
  refuse_unless(s, "redshift-power", false,
                "--rings or --disk-light (a line profile's flux is g^4 eps: the line's energy)");
  refuse_unless(s, "disk-light", false, "--scene disk frames (a line profile is not a frame)");
  LineProfileRequest q;
  q.disk = read_distant_disk(s, "--spectrum line", {kLineProfileOptions.begin(), kLineProfileOptions.end()});
  q.line_energy = option_number(s, "line-energy");
  if (s.given("energy-range")) {
    const std::vector<double> r = option_numbers(s, "energy-range", 2);
    q.energy_range = std::array<double, 2>{r[0], r[1]};
  }
  q.bins = integer_in(s, "energy-bins", 1, 100'000, "--energy-bins must be in 1 .. 100000");
  q.finest_cell = option_number(s, "line-finest");
  return q;
}

RingImageRequest read_ring_image_request(const OptionSource& s) {
  if (!s.given("rings")) throw RequestError("read_ring_image_request: --rings is not given");
  RingImageRequest q;
  std::vector<std::string> own{kRingImageOptions.begin(), kRingImageOptions.end()};
  for (const char* o : {"width", "height", "source"}) own.emplace_back(o);
  own.emplace_back("redshift-power");
  refuse_unless(s, "disk-light", false, "--scene disk frames (a ring image is drawn by its light already)");
  q.disk = read_distant_disk(s, "--rings", own);
  q.width = integer_in(s, "width", 8, 16384, "--width must be 8 .. 16384 pixels");
  q.height = integer_in(s, "height", 8, 16384, "--height must be 8 .. 16384 pixels");
  q.field = option_number(s, "ring-field");
  if (!(q.field >= 6.0 && q.field <= 1e6))
    throw RequestError("--ring-field must be 6 .. 1e6 M (the rings lie ~5 M from the centre), got " +
                       text_of(s, "ring-field"));
  q.cuts = integer_in(s, "ring-cuts", 0, 100'000, "--ring-cuts must be 0 (automatic) or 2 .. 100000");
  if (q.cuts == 1) throw RequestError("--ring-cuts must be 0 (automatic) or 2 .. 100000");
  q.redshift_power = read_redshift_power(s);
  if (s.given("source")) {
    q.source = text_of(s, "source");
    if (*q.source != "m87" && *q.source != "sgr-a")
      throw RequestError("--source must be m87 or sgr-a, got '" + *q.source + "'");
  }
  return q;
}

const std::vector<OptionInfo>& render_options() {
  static const std::vector<OptionInfo> table = make_render_options();
  return table;
}

double option_number(const OptionSource& s, const std::string& name) {
  return as_request_error([&] { return grtrace::option_number(name, text_of(s, name), s.origin(name)); });
}

long option_integer(const OptionSource& s, const std::string& name) {
  return as_request_error([&] { return grtrace::option_integer(name, text_of(s, name), s.origin(name)); });
}

std::vector<double> option_numbers(const OptionSource& s, const std::string& name, std::size_t count) {
  return as_request_error([&] { return grtrace::option_numbers(name, text_of(s, name), count); });
}

std::vector<double> read_frequencies(const OptionSource& s) {
  const std::string text = text_of(s, "frequency");
  return option_numbers(s, "frequency", static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1);
}

MetricSpec read_metric(const OptionSource& s, const std::vector<std::string>& offered) {
  MetricSpec ms;
  ms.name = text_of(s, "metric");
  if (std::find(offered.begin(), offered.end(), ms.name) == offered.end())
    throw RequestError("--metric must be " + choice_list(offered) + ", got '" + ms.name + "'");
  ms.mass = option_number(s, "mass");
  ms.chart = text_of(s, "chart");
  if (ms.chart.empty()) ms.chart = "bl";
  for (const NamedMetricParameter& p : named_metric_parameters()) {
    if (std::find(offered.begin(), offered.end(), p.metric) == offered.end()) continue;
    const std::string option(p.parameter.option);
    refuse_unless(s, option, ms.name == p.metric, "--metric " + std::string(p.metric));
    if (ms.name == p.metric) ms.*p.parameter.field = option_number(s, option);
  }
  as_request_error([&] { check_metric_spec(ms); });
  return ms;
}

CameraRequest read_camera(const OptionSource& s) {
  CameraRequest c;
  c.r = option_number(s, "camera-r");
  c.theta_degrees = option_number(s, "camera-theta");
  c.phi_degrees = option_number(s, "camera-phi");
  c.fov_degrees = option_number(s, "fov");
  check_camera_angles(c, text_of(s, "camera-theta"), text_of(s, "fov"));  // in the words given
  if (s.given("observer")) c.observer = text_of(s, "observer");
  if (!c.observer.empty() && c.observer != "static" && c.observer != "zamo")
    throw RequestError("unknown --observer '" + c.observer + "'; choose static or zamo");
  c.velocity = triple(s, "velocity");
  c.look = triple(s, "look");
  c.up = triple(s, "up");
  return c;
}

MethodRequest read_method(const OptionSource& s, const std::string& prefix) {
  MethodRequest m;
  m.tableau = text_of(s, prefix + "tableau");
  m.control = text_of(s, prefix + "control");
  m.rtol = option_number(s, prefix + "rtol");
  m.atol = option_number(s, prefix + "atol");
  m.step = option_number(s, prefix + "step");
  check_method(m, prefix);
  // A fixed step is no tolerance's: a tolerance given with it would be silently without effect.
  for (const char* tolerance : {"rtol", "atol"})
    refuse_unless(s, prefix + tolerance, m.control != "fixed",
                  "an adaptive --" + prefix + "control (i, pi or doubling)");
  return m;
}

void check_scene_options(const OptionSource& s, const std::string& scene) {
  for (const char* line_option : kLineProfileOptions)
    if (std::string_view(line_option) != "spectrum") refuse_unless(s, line_option, false, "--spectrum line");
  for (const char* ring_option : kRingImageOptions)
    if (std::string_view(ring_option) != "rings") refuse_unless(s, ring_option, false, "--rings");
  for (const char* disk_option : {"disk-inner", "disk-outer", "disk-retrograde", "disk-light", "disk-transparent"})
    refuse_unless(s, disk_option, scene == "disk", "--scene disk");
  const bool light = scene == "disk" && (s.given("disk-light") || s.given("disk-transparent"));
  for (const char* disk_option : kDiskLightOptions)
    refuse_unless(s, disk_option, light, "--spectrum line, --rings or --scene disk --disk-light");
  refuse_unless(s, "redshift-power", light, "--rings or --scene disk --disk-light");
  for (const char* frame_option : kNotForDiskLight)
    if (light && s.given(frame_option))
      throw RequestError("--" + std::string(frame_option) +
                         " has no effect on a disk drawn by its light (--disk-light: every ray in closed form, no "
                         "sky): leave it out");
  refuse_unless(s, "checker-squares", scene == "checker", "--scene checker");
  refuse_unless(s, "sky-texture", scene == "sky" || scene == "disk", "--scene sky or disk");
  for (const char* medium_option : {"accretion-gas", "accretion-power"})
    refuse_unless(s, medium_option, scene == "accretion", "--scene accretion");
  for (const char* riaf_option : {"source", "accretion-rate", "frequency"})
    refuse_unless(s, riaf_option, scene == "riaf", "--scene riaf");
  for (const char* torus_option : {"torus-inner", "torus-peak", "torus-opacity"})
    refuse_unless(s, torus_option, scene == "torus", "--scene torus");
  // A medium's frame shows its light, not where escaped rays point.
  refuse_unless(s, "angle-correction", !is_medium_scene(scene), "a scene that shows the sky (not a medium's)");
}

RenderRequest read_render_request(const OptionSource& s) {
  RenderRequest q;
  q.scene = text_of(s, "scene");
  if (!is_standard_scene(q.scene) && !is_medium_scene(q.scene))
    throw RequestError("unknown scene '" + q.scene + "'; choose " + choice_list(scene_names()));
  if (s.given("spectrum"))
    throw RequestError(
        "--spectrum asks for the disk's line profile, not a frame (app::line_profile; grtrace-render "
        "computes it when --spectrum is given)");
  if (s.given("rings"))
    throw RequestError(
        "--rings asks for the disk's photon ring by order, not a frame (app::ring_image; grtrace-render "
        "computes it when --rings is given)");
  q.metric = read_metric(s, {kMetricNames.begin(), kMetricNames.end()});
  check_scene_options(s, q.scene);
  q.method = read_method(s, "");
  q.method.max_steps = integer_in(s, "max-steps", 1, 100'000'000, "--max-steps must be in 1 .. 1e8");
  q.sky_radius = option_number(s, "sky-radius");
  q.angle_correction = text_of(s, "angle-correction");
  q.camera = read_camera(s);
  q.camera.width = static_cast<int>(
      std::clamp(option_integer(s, "width"), -1L, 1L << 20));  // range checked with the height, by check_request
  q.camera.height = static_cast<int>(std::clamp(option_integer(s, "height"), -1L, 1L << 20));
  q.threads = integer_in(s, "threads", 0, 1024, "--threads must be 0 (all cores) .. 1024");
  // Not given: 0, the tracer's own default (check_request: the planar table's or a medium's).
  q.table_rays = s.given("table-rays")
                     ? integer_in(s, "table-rays", 8, 1'000'000, "--table-rays must be in 8 .. 1e6")
                     : 0;
  q.tracer = text_of(s, "tracer");
  // The table of rays is the planar tracer's (named, or auto's choice for a static spherically symmetric metric).
  refuse_unless(s, "table-rays", q.tracer == "planar" || (q.tracer == "auto" && planar_tracer_metric(q.metric)),
                "--tracer planar or auto with a static spherically symmetric metric (schwarzschild, rn or sds)");
  q.checker_squares = integer_in(s, "checker-squares", 1, 10000, "--checker-squares must be in 1 .. 10000");
  q.sky_texture = text_of(s, "sky-texture");
  if (s.given("disk-inner")) q.disk_inner = option_number(s, "disk-inner");
  q.disk_outer = option_number(s, "disk-outer");
  q.disk_retrograde = s.given("disk-retrograde");
  if (s.given("disk-light") || s.given("disk-transparent")) q.disk_light = read_disk_light(s);
  q.redshift_power = read_redshift_power(s);
  q.accretion_gas = text_of(s, "accretion-gas");
  q.accretion_power = option_number(s, "accretion-power");
  q.source = text_of(s, "source");
  if (s.given("accretion-rate")) q.accretion_rate = option_number(s, "accretion-rate");
  q.frequencies_ghz = read_frequencies(s);
  q.torus_inner = option_number(s, "torus-inner");
  q.torus_peak = option_number(s, "torus-peak");
  q.torus_opacity = option_number(s, "torus-opacity");
  q.error_map = s.given("error-map");
  q.mirrors = !s.given("no-mirrors");
  q.device = text_of(s, "device");
  return q;
}

}  // namespace grtrace::app
