// grtrace/app/front_door.hpp
// The application library's one front door: what grtrace-render, its flights, grtrace-view and the Python module
// call to draw a frame or trace a ray, compiled once (the static library grtrace::app). The header-only core is
// what a program of your own instantiates for the one metric, method and scene it names; this library has the
// tools' declared list compiled already and takes names at run time. Shaped like pbrt-v4's Integrator::Create:
//
//   app::RenderRequest q;                       // typed: metric, scene, camera, method, tracer, device, threads
//   q.metric.name = "kerr";  q.metric.spin = 0.9;  q.scene = "disk";  q.camera.theta_degrees = 80;
//   const auto renderer = app::FrameRenderer::create(q);   // checks everything, builds the one tracer it names
//   app::RenderResult result = renderer->render();          // the channels and a typed report
//   std::printf("%s: %ld escaped\n", result.report.tracer.c_str(), result.report.stats.count(RayStatus::escaped));
//
// Reading a request from option names (the tools' spelling without dashes, e.g. "camera-r"), so that a command
// line, a scene file and Python keywords are read by the same code with the same refusals:
//
//   app::RenderRequest q = app::read_render_request(options);   // options: an app::OptionSource
//
// Takes:   a RenderRequest; for read_render_request an OptionSource (the option's text, whether it was given).
// Returns: an owned FrameRenderer (one virtual call per frame: below it the concrete tracer's own inlined loop), a
//          RenderResult (the image with every channel and the header record, a RenderReport), RayTracer paths.
// Refuses: RequestError (a std::invalid_argument) before any work, with the message the tools print: it names the
//          option and says what to change.
// Cancelling: RenderControl::cancel stops a render between tiles (RenderCancelled); RenderControl::pixels_done
//          counts its progress, for a caller that shows progress on another thread (the Python module).
#pragma once

#include "grtrace/app/tool_methods.hpp"
#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/sky_direction.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/flight_path.hpp"
#include "grtrace/observer/worldline.hpp"
#include "grtrace/render/flight.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/render/progress_bar.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/spectra/line_profile_result.hpp"
#include "grtrace/spectra/ring_image_result.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/ray_outcome.hpp"
#include "grtrace/trace/traced_path.hpp"

#include <array>
#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace grtrace::app {

/// A request the front door refuses, before any work: the message names the option and says what to change.
struct RequestError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// ---- the request ----------------------------------------------------------------------------------------------

/// Where the camera is and what it sees (grtrace-render's --camera-*, --observer, --velocity, --look, --up, --fov,
/// --width, --height). The event is given in Boyer-Lindquist-like (r, theta, phi) for every chart, r in the metric's
/// own radius (the proper distance l for the wormhole).
struct CameraRequest {
  double r = 200.0;
  double theta_degrees = 90.0;  ///< in [0, 180]; on the axis the camera is placed 1e-9 rad off it (off_axis)
  double phi_degrees = 0.0;
  std::string observer;          ///< static | zamo; "": zamo for kerr (valid in the ergosphere), static otherwise
  Vec3 velocity = Vec3::Zero();  ///< 3-velocity (fraction of c) in the observer's frame
  Vec3 look{-1.0, 0.0, 0.0};     ///< in the observer's (r, theta, phi) frame: at the hole
  Vec3 up{0.0, -1.0, 0.0};       ///< towards the north pole
  double fov_degrees = 90.0;     ///< horizontal field of view, in (0, 180)
  int width = 1024, height = 1024;
};

/// The integration method: one of the declared pairs (tool_methods.hpp) and its settings.
struct MethodRequest {
  std::string tableau = "rkf78", control = "i";
  double rtol = 1e-9, atol = 1e-11;
  double step = 0.0;       ///< initial step (0: automatic), or the step of control fixed
  int max_steps = 100000;  ///< accepted steps before a ray ends as max_steps
};

/// How a thin disk shines where its light is drawn (a frame with --disk-light, a line profile, a ring image): the
/// same options everywhere.
struct DiskLightRequest {
  bool transparent = false;       ///< --disk-transparent: every crossing inside the radii shines (else the first only)
  double emissivity_index = 3.0;  ///< --emissivity-index q: eps ~ r^-q
  std::optional<double> emissivity_index_outer;  ///< --emissivity-index-outer: beyond --emissivity-break
  std::optional<double> emissivity_break;        ///< --emissivity-break (M)
};

/// Everything a frame is drawn with, by name and number (grtrace-render's options; defaults are its defaults: the
/// seed report's main frame).
struct RenderRequest {
  MetricSpec metric;                 ///< metric/named_metrics.hpp
  /// checker | sky | redshift | disk (scene/standard_scenes.hpp) | accretion | riaf | torus
  std::string scene = "checker";
  int checker_squares = 18;          ///< checker: squares along theta on sky and horizon
  std::string sky_texture;           ///< sky and disk: an equirectangular EXR (R, G, B) replacing the stars
  std::optional<double> disk_inner;  ///< disk: inner edge; nothing: 6 M, or for kerr the ISCO of the disk's sense
  double disk_outer = 20.0;
  bool disk_retrograde = false;  ///< disk: the gas turns against the hole (default: with it)
  /// accretion: glowing gas around a Schwarzschild hole (medium/spherical_accretion.hpp), j ~ r^-power
  /// out to beyond the sky sphere, falling freely from rest at infinity ("free-fall") or at rest ("rest"); drawn
  /// with the default method, on the CPU, by one table of rays (tracer auto or planar) or every pixel integrated
  /// (general). Its channels: intensity (at nu_obs = 1, geometric units), optical_depth; R, G, B a picture of it.
  std::string accretion_gas = "free-fall";
  double accretion_power = 2.0;
  /// riaf: the hot accretion flow of M87* or Sgr A* (medium/riaf.hpp) around a Kerr hole (Boyer-Lindquist chart),
  /// thermal synchrotron light observed at `frequencies_ghz` (up to kMaxFrequencies, every pixel's ray traced once
  /// for all of them: a channel intensity_<f>GHz and a flux each; the first one's is also the picture, `intensity`
  /// and `flux`; one frequency alone is split by image order), in physical units: the
  /// source's mass and distance (core/physical_units.hpp) give the intensity in cgs, the flux in janskys and the
  /// pixel in microarcseconds; drawn with the default method, every pixel integrated, on the CPU, from a camera
  /// at least 100 M away (angles scale as seen from afar).
  std::string source = "m87";            ///< m87 | sgr-a (SourceScale and RiafParameters presets)
  std::optional<double> accretion_rate;  ///< solar masses a year; nothing: the source's (RiafParameters)
  std::vector<double> frequencies_ghz{230.0};  ///< the observed frequencies, distinct
  /// torus: a Polish doughnut of constant angular momentum around a Kerr hole (medium/polish_doughnut.hpp), its
  /// inner edge and pressure maximum on the equator, n = 3, j = rho, alpha = opacity rho (0: optically thin);
  /// geometric units, the default method, every pixel integrated, on the CPU.
  double torus_inner = 6.0;
  double torus_peak = 10.0;
  double torus_opacity = 0.0;
  /// disk: drawn by its light instead of its colour (--disk-light, implied by --disk-transparent): per pixel the
  /// ray's crossings of the disk in closed form (render/disk_light_frame.hpp), each crossing between the radii
  /// seen as g^redshift_power eps(r), by image order (channels intensity, intensity_n0 .. intensity_n3_up; R, G, B
  /// a picture of the intensity); --metric kerr (Boyer-Lindquist) or schwarzschild, on the CPU.
  std::optional<DiskLightRequest> disk_light;
  double redshift_power = 3.0;  ///< --redshift-power p (disk light): the observed intensity is g^p eps(r)
  CameraRequest camera;
  MethodRequest method;
  double sky_radius = 400.0;               ///< rays beyond it have escaped; the camera must be inside it
  std::string angle_correction = "exact";  ///< escaped rays' continuation: none | flat | exact
  std::string tracer = "auto";             ///< auto | general | planar | kerr-mino | kerr-closed-form | straight-line
  int table_rays = 0;  ///< planar tracer: table rays per side of the critical angle (0: default; a medium's, 512)
  std::string device = "auto";             ///< auto | cpu | cuda (choose_device)
  int threads = 0;                         ///< OpenMP threads (0: all cores)
  bool mirrors = true;                     ///< trace half or a quarter of a mirror-symmetric frame and reflect the rest
  bool error_map = false;  ///< add the "error" channel against the exact directions (schwarzschild, minkowski)
};

/// True for the frames that show light (an emitting medium's, a disk drawn by its light: intensity channels, no
/// sky): their angles and device follow from that.
bool draws_light(const RenderRequest& request);

/// A request as checked: the device chosen (cpu or cuda), the observer and the disk's edge filled in, the scene
/// built (texture read), the settings the tracer takes, and the camera. What FrameRenderer and RayTracer are made
/// from; check_request makes it.
struct CheckedRequest {
  RenderRequest request;  ///< as given, with device, observer and disk_inner filled in
  StandardSceneSpec scene;
  TraceSettings settings;  ///< tolerances, steps, escape radius
  AngleCorrection correction = AngleCorrection::exact;
  Camera camera;
};

/// Every check of the request, before any work; RequestError saying what to change (the tools' messages).
CheckedRequest check_request(const RenderRequest& request);

/// The checked request with another camera: a flight's (make_moving_camera refuses one inside the capture radius,
/// and flight_path a path that leaves the sky sphere), or the camera a frame's header records (its reader checks it).
CheckedRequest with_camera(CheckedRequest checked, const Camera& camera);

// ---- the frame -------------------------------------------------------------------------------------------------

/// How a render runs, beyond the request: progress and cancelling.
struct RenderControl {
  ProgressMode bar = ProgressMode::automatic;  ///< the progress bar on stderr (automatic: when it is a terminal)
  std::string label = "render";                ///< the first word of the bar
  ProgressBar* shared_bar = nullptr;           ///< a caller's bar to advance instead (flights)
  const std::atomic<bool>* cancel = nullptr;   ///< set: the render stops between tiles (RenderCancelled)
  std::atomic<long>* pixels_done = nullptr;    ///< advanced by the pixels finished, as they finish
};

/// The flat continuation's estimated error over a frame's escaped rays (trace/sky_continuation.hpp).
struct ContinuationEstimate {
  double error = 0.0;                ///< radians
  double impact = 0.0;               ///< the largest impact parameter among the escaped rays
  double sky_radius_for_rtol = 0.0;  ///< the sky radius that would bring the error down to rtol
};

/// --error-map's summary: every escaped or captured pixel against the exact elliptic-integral answer.
struct ErrorSummary {
  double max = 0.0, median = 0.0;  ///< radians (NaN when no pixel was judged)
  long judged = 0;                 ///< escaped pixels with an exact direction
  long mismatches = 0;             ///< escaped where the exact ray is captured, or the reverse
};

/// What a render reports, typed: the loop's statistics, where the time went, which tracer and device ran.
struct RenderReport {
  RenderStats stats;             ///< size, threads, status counts, steps, rays traced (render/parallel_render.hpp)
  double seconds = 0.0;          ///< the frame's whole time: building the tracer (setup) and tracing
  double setup_seconds = 0.0;    ///< building the tracer (the planar tracer's table)
  double rays_per_second = 0.0;  ///< stats.rays / seconds
  double mean_steps = 0.0;       ///< accepted steps a pixel (the planar tracer: its table's steps over the pixels)
  std::string tracer;            ///< the tracer that ran: planar, kerr-closed-form, kerr-mino, general, straight-line
  std::string device;            ///< "cpu", or the GPU's model
  std::optional<double> gpu_trace_seconds, gpu_seconds;  ///< the GPU kernel's time, and the GPU's whole share
  std::string mirrors;                                   ///< the reflections used ("" none; render/mirror_symmetry.hpp)
  std::string sky_continuation;                          ///< how escaped rays were continued to infinity
  std::optional<ContinuationEstimate> continuation_error;   ///< a flat continuation's estimated error
  long table_rays = 0, table_steps = 0, fallback_rays = 0;  ///< the planar tracer's table and fallback
  std::optional<ErrorSummary> error;                        ///< with RenderRequest::error_map
  /// An emitting medium's frame: the intensity integrated over the frame's solid angle (the sum of each pixel's
  /// intensity times its solid angle seen by the camera), in the intensity's units times steradians.
  std::optional<double> flux;
  /// A medium in physical units (riaf): the flux at the telescope in janskys and a pixel's width there.
  std::optional<double> flux_jy, microarcseconds_per_pixel;
  /// A disk drawn by its light, or a medium whose every pixel is integrated (not the accreting gas's table): the
  /// flux of each image order (n = 0, 1, 2, >= 3; they sum to `flux`); a disk's pixels whose ray the closed form
  /// does not follow (dark: render/disk_light_frame.hpp).
  std::optional<std::array<double, 4>> flux_by_order;
  std::optional<long> uncovered_rays;
  /// A medium's frame at several frequencies (riaf): each band's name (frequency_band_name), flux and flux in janskys.
  struct BandFlux {
    std::string band;
    double flux = 0.0;
    std::optional<double> flux_jy;
  };
  std::vector<BandFlux> band_fluxes;
};

/// One entry of a report as the JSON line and the Python dict give it.
struct ReportEntry {
  using Counts = std::vector<std::pair<std::string, long>>;
  std::string key;
  std::variant<long, double, std::string, Counts> value;
};

/// The report's entries, in the order of grtrace-render's JSON line (width, height, seconds, rays_per_second,
/// mean_steps, status_counts, tracer, tableau, control, device, ...): the one list both the tools' JSON and Python's
/// dict are made of.
std::vector<ReportEntry> report_entries(const RenderReport& report, const CheckedRequest& request);

struct RenderResult {
  Image image;  ///< channels R, G, B, object, status, redshift, sky_theta, sky_phi, steps, order (+ error)
  RenderReport report;
};

/// The tracer a checked request names, built and owned: render() draws its camera's frame.
class FrameRenderer {
 public:
  /// check_request, then the tracer (the planar tracer's table is built here: setup_seconds).
  static std::unique_ptr<FrameRenderer> create(const RenderRequest& request);
  static std::unique_ptr<FrameRenderer> create(const CheckedRequest& checked);

  virtual ~FrameRenderer() = default;
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  /// The frame: every channel, the header's record (describe_request, the report, the camera) and the report.
  /// May be called again (the same frame); from several threads at once only on different renderers.
  virtual RenderResult render(const RenderControl& control = {}) const = 0;

  const CheckedRequest& checked() const { return checked_; }
  const Camera& camera() const { return checked_.camera; }
  double setup_seconds() const { return setup_seconds_; }

 protected:
  explicit FrameRenderer(CheckedRequest checked) : checked_(std::move(checked)) {}
  CheckedRequest checked_;
  double setup_seconds_ = 0.0;
};

/// create + render.
RenderResult render(const RenderRequest& request, const RenderControl& control = {});

/// What a frame's header records of the request (beyond what render records of the camera and the report): the
/// scene, metric and its parameters, observer, disk, method, tolerances, sky radius, angle correction.
void describe_request(Image& image, const CheckedRequest& checked);

/// A flight drawn with the request's tracer, built per camera (render/flight.hpp's loop): sink(i, result) receives
/// each frame on a writer thread while the next is traced; skip(i): a frame already on disk.
using FlightSkip = std::function<bool(int)>;
using FlightSink = std::function<void(int, RenderResult&&)>;
FlightStats render_flight(const CheckedRequest& checked, const std::vector<Camera>& cameras, const FlightSkip& skip,
                          const FlightSink& sink, const RenderControl& control = {});

// ---- rays -------------------------------------------------------------------------------------------------------

/// What a traced path keeps (trace/traced_path.hpp).
struct PathOptions {
  int samples_per_step = 8;               ///< points per accepted step, from the dense output
  std::optional<Vec4> observer_velocity;  ///< the redshift along the path, against this 4-velocity (a camera's e_0)
  bool scene_objects = true;              ///< the scene's objects (the disk) end the ray; false: horizon and sky only
  /// Ends the path once phi has advanced by this much from its start (its sign gives the sense): orbits.
  std::optional<double> phi_advance;
};

/// A ray traced once: its path and what a frame's pixel shows for it (the general scene tracer's outcome).
struct TracedRay {
  TracedPath path;
  RayOutcome outcome;
  std::string object;      ///< the scene's name of outcome.object ("sky", "horizon", "disk", ...); "" for a failed ray
  bool cartesian = false;  ///< the metric's chart is Cartesian (t, x, y, z), else spherical (t, r, theta, phi)
};

/// Single rays in a checked request's metric, scene and method: the paths grtrace-view draws and grtrace.trace_ray
/// returns, each with the outcome a frame's pixel shows, from one integration. Owned; one virtual call per ray.
class RayTracer {
 public:
  static std::unique_ptr<RayTracer> create(const CheckedRequest& checked);
  virtual ~RayTracer() = default;
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  /// The ray from y0 (a state in the metric's chart), its path sampled as `options` say. Its outcome is the general
  /// scene tracer's for that ray (with scene_objects off: for the scene without its objects), bit for bit.
  virtual TracedRay trace(const GeodesicState& y0, const PathOptions& options = {}) const = 0;
  /// The scene's object names, by outcome.object.
  virtual std::vector<std::string> object_names() const = 0;

 protected:
  RayTracer() = default;
};

// ---- a named metric's geometry ----------------------------------------------------------------------------------

/// What a tool asks of a named metric outside the hot loop (cameras, flights, pictures of its surfaces), one
/// virtual call a question.
class MetricGeometry {
 public:
  static std::unique_ptr<MetricGeometry> create(const MetricSpec& spec);
  virtual ~MetricGeometry() = default;
  virtual Mat4 metric(const Vec4& x) const = 0;
  virtual Vec3 to_cartesian(const Vec4& x) const = 0;
  /// The metric's own radius of an event (Boyer-Lindquist-like r for Kerr-Schild) and its capture radius.
  virtual double radius(const Vec4& x) const = 0;
  virtual double horizon_radius() const = 0;
  /// An event given in (t, r, theta, phi) in the metric's chart, and back.
  virtual Vec4 from_spherical(const Vec4& x) const = 0;
  virtual Vec4 to_spherical(const Vec4& x) const = 0;
  virtual Camera make_camera(const CameraSpec& spec) const = 0;
  virtual Camera make_moving_camera(const Vec4& x, const Vec4& u, const CameraView& view) const = 0;
  /// flight_path (observer/flight_path.hpp) in this metric.
  virtual Worldline flight(const FlightPathSpec& spec) const = 0;
  /// A worldline as a path (one sample per worldline sample: position, state (x, u), lambda = tau).
  virtual TracedPath worldline_path(const Worldline& worldline) const = 0;

 protected:
  MetricGeometry() = default;
};

/// A camera flight's path in a named metric (observer/flight_path.hpp, the same samples bit for bit): what
/// grtrace-render renders and grtrace-view draws (Kerr-Schild flights use the ingoing slicing: MetricSpec::slicing).
/// std::invalid_argument with flight_path's words (a path the metric or its chart cannot fly, an unreadable csv).
Worldline flight_worldline(const MetricSpec& metric, const FlightPathSpec& spec);

/// The cameras of a flight: one per sample of its path, pointed by `view` (make_moving_camera).
std::vector<Camera> flight_cameras(const MetricSpec& metric, const Worldline& path, const CameraView& view);

// ---- reading a request by option names --------------------------------------------------------------------------

/// Where option values come from: a command line (with its scene file), a frame's header, Python keywords. Names
/// are the tools' option names without dashes ("camera-r").
class OptionSource {
 public:
  virtual ~OptionSource() = default;
  /// Whether the option was given (not a default).
  virtual bool given(const std::string& name) const = 0;
  /// The option's text: as given, else the source's default for it; nothing when the source has no such option
  /// (the render options' default applies: render_options()).
  virtual std::optional<std::string> text(const std::string& name) const = 0;
  /// Where a value came from, added to a refusal of its text (e.g. " (from the frame's header)"); "" by default.
  virtual std::string origin(const std::string& /*name*/) const { return ""; }
};

/// One option of the render request: its name, default text, help; a flag takes no value.
struct OptionInfo {
  std::string_view name;
  std::string_view default_text;
  std::string_view help;
  bool flag = false;
};

/// Every option read_render_request reads, with grtrace-render's defaults and help, in the order its --help lists
/// them: scene, metric and its parameters, chart, camera, size, method, tracer, device, and the rest.
const std::vector<OptionInfo>& render_options();

/// The request of the options, every option's text read (numbers as the tools read them: core/number_text.hpp)
/// and every check of check_request made, plus the refusals only names can see: a metric's parameter given with
/// another metric (--spin without --metric kerr), a disk option without the disk scene. RequestError otherwise.
RenderRequest read_render_request(const OptionSource& options);

/// The groups read_render_request reads, for a tool that reads only some (grtrace-view): the metric (one of
/// `offered`, its mass and chart, the parameter of that metric; another metric's parameter given is refused), the
/// camera (event, observer, velocity, look, up, fov; not the size) and the method (--<prefix>tableau,
/// --<prefix>control,
/// --<prefix>step, --<prefix>rtol, --<prefix>atol: a second integration's options carry a prefix, "orbit-").
/// The method's --<prefix>rtol and --<prefix>atol given with --<prefix>control fixed (whose step no tolerance
/// controls) are refused.
MetricSpec read_metric(const OptionSource& options, const std::vector<std::string>& offered);
CameraRequest read_camera(const OptionSource& options);
MethodRequest read_method(const OptionSource& options, const std::string& prefix);

/// Refuses (RequestError) a scene's option given for another scene: --disk-inner, --disk-outer, --disk-retrograde
/// without the disk, --checker-squares without the checker, --sky-texture without a scene that shows the sky
/// (sky, disk). read_render_request calls it; a tool that reads the scene itself (grtrace-view) calls it too.
void check_scene_options(const OptionSource& options, const std::string& scene);

/// One option's number, whole number or comma-separated numbers, read as the tools read them (RequestError naming
/// --name).
double option_number(const OptionSource& options, const std::string& name);
long option_integer(const OptionSource& options, const std::string& name);
std::vector<double> option_numbers(const OptionSource& options, const std::string& name, std::size_t count);
/// --frequency as every tool reads it: one number or a comma-separated list, each in GHz (check_request checks
/// their count and range).
std::vector<double> read_frequencies(const OptionSource& options);

// ---- what there is ----------------------------------------------------------------------------------------------

/// The tracers a request can name: auto (the fastest whose assumptions hold) and each one a report names
/// (trace/auto_tracer.hpp); check_request refuses one that cannot draw the request, saying why.
inline constexpr std::array<std::string_view, 6> kTracerNames = {"auto",      "general",          "planar",
                                                                 "kerr-mino", "kerr-closed-form", "straight-line"};
inline constexpr std::array<std::string_view, 3> kDeviceNames = {"auto", "cpu", "cuda"};

/// The scenes of emitting media (RenderRequest::accretion_gas), beside the surfaces' (kStandardSceneNames).
inline constexpr std::array<std::string_view, 3> kMediumSceneNames = {"accretion", "riaf", "torus"};
/// The most observing frequencies a riaf frame takes in one pass (its tracer of several bands is compiled for this
/// many; fewer are traced with the last one repeated).
inline constexpr std::size_t kMaxFrequencies = 8;
/// A band's name in channels and reports: the frequency in GHz, '.' as 'p' (an EXR channel name's '.' would make
/// it a layer): "230GHz", "345p5GHz".
std::string frequency_band_name(double ghz);
/// The sources --scene riaf offers (RenderRequest::source).
inline constexpr std::array<std::string_view, 2> kRiafSourceNames = {"m87", "sgr-a"};
/// The least camera radius of a medium in physical units: its angles are those seen from afar (to O(size / r)).
inline constexpr double kMinPhysicalCameraRadius = 100.0;
bool is_medium_scene(std::string_view scene);
/// Every scene a request can name: the standard scenes, then the media.
std::vector<std::string> scene_names();

/// The GPU this build can trace on: whether the CUDA backend was compiled in, and the first CUDA device's name or
/// why there is none. Asked once per process.
struct GpuStatus {
  bool built = false;
  bool present = false;
  std::string name;     ///< e.g. "NVIDIA H100 80GB HBM3"
  std::string why_not;  ///< when not present
};
const GpuStatus& gpu_status();

/// The name the report gives a device (cpu or cuda): "cpu", or the GPU's model.
std::string device_name(std::string_view device);

/// Why the GPU cannot draw the request (a method, tracer or metric it does not run, then no backend or no device),
/// in words that say what to use instead; nothing when it can.
std::optional<std::string> gpu_refusal(const RenderRequest& request);

/// Whether auto may pick the GPU: the CUDA backend passes its device checks (tests/gpu, cmake/gpu-check.sh on an
/// H200: the same statuses, redshifts and sky directions as the CPU's trace; docs/benchmarks.md, "GPU").
inline constexpr bool kAutoPicksGpu = true;

/// True when the CPU draws the request with its table tracer (tracer auto on a static spherical metric with a
/// horizon, Schwarzschild or Reissner-Nordstrom, whose preset scenes lie in the equatorial plane): one table of rays
/// for the whole frame, faster on the CPU than any GPU integrating every pixel (docs/benchmarks.md, "GPU"), so auto
/// keeps it there.
bool cpu_table_tracer_draws(const RenderRequest& request);

/// The device the request runs on when `asked` is asked for: cpu; cuda (RequestError saying what to change when
/// gpu_refusal refuses); auto: cuda where kAutoPicksGpu, the CPU's table tracer does not draw it and gpu_refusal has
/// nothing against it, else cpu. Refuses names outside kDeviceNames. check_request calls it with request.device.
std::string choose_device(std::string_view asked, const RenderRequest& request);

// ---- a disk seen from afar: its line profile and its photon ring by order -------------------------------------

/// A thin disk seen by a distant observer, each ray in closed form (a Kerr hole in Boyer-Lindquist coordinates, or
/// Schwarzschild's as spin 0): what a line profile and a ring image share.
struct DistantDisk {
  MetricSpec metric;                  ///< kerr (chart bl) or schwarzschild
  double inclination_degrees = 90.0;  ///< the observer's theta (--camera-theta), strictly between 0 and 180
  std::optional<double> disk_inner;   ///< nothing: 6 M, or for kerr the ISCO of the disk's sense (as for frames)
  double disk_outer = 20.0;
  bool disk_retrograde = false;
  DiskLightRequest light;  ///< transparency and emissivity
  int threads = 0;         ///< OpenMP threads (0: all cores)
};

/// A thin disk's line profile (spectra/line_profile.hpp): the flux per energy bin that a distant observer receives
/// from a line emitted at one energy by the disk's gas, in total and by image order n = 0, 1, 2, >= 3. What
/// grtrace-render --spectrum line reads.
struct LineProfileRequest {
  DistantDisk disk;
  double line_energy = 6.4;  ///< --line-energy: in the gas's frame, the bins' unit (keV for iron K-alpha)
  std::optional<std::array<double, 2>> energy_range;  ///< --energy-range lo,hi; nothing: around the light's
  int bins = 200;                                     ///< --energy-bins
  double finest_cell = 1.0 / 64.0;                    ///< --line-finest: the mesh's finest cell on the screen (M)
};

/// The options --spectrum line reads: the metric (kerr or schwarzschild), --camera-theta as the inclination, the
/// disk's, the line's, the bins', --threads. Any other option given (a frame's camera distance, size, method,
/// tracer, ...) is refused: the profile is a distant observer's and its rays are not integrated. RequestError
/// saying what to change, before any work.
LineProfileRequest read_line_profile_request(const OptionSource& options);

struct LineProfileResult {
  LineProfileRequest request;  ///< as checked: disk_inner filled in
  LineProfile profile;
  double seconds = 0.0;
  std::string csv;                  ///< spectra/line_profile_output.hpp's table, the request in its comments
  LineChart chart;                  ///< and its plot
  std::vector<ReportEntry> report;  ///< the JSON line's entries: seconds, rays, totals by order, the bins' range
};

/// Checks the request (RequestError), then computes the profile.
LineProfileResult line_profile(const LineProfileRequest& request);

/// A thin disk's photon ring by order (spectra/ring_image.hpp): its image in channels n = 0, 1, 2, >= 3, each ring
/// integrated across its width however thin, with each order's flux and the rings' diameters and widths. What
/// grtrace-render --rings reads.
struct RingImageRequest {
  DistantDisk disk;
  int width = 512, height = 512;      ///< --width, --height
  double field = 8.0;                 ///< --ring-field: the image's half width (M)
  int cuts = 0;                       ///< --ring-cuts: radial cuts for the rings (0: a pixel apart at 6 M)
  double redshift_power = 3.0;        ///< --redshift-power p: the observed intensity is g^p eps(r)
  std::optional<std::string> source;  ///< --source m87 | sgr-a: the rings' sizes in microarcseconds too
};

/// The options --rings reads: a distant disk's (as --spectrum line), --width, --height, --ring-field, --ring-cuts,
/// --redshift-power, --source. Any other option given is refused (RequestError saying what to change).
RingImageRequest read_ring_image_request(const OptionSource& options);

struct RingImageResult {
  RingImageRequest request;  ///< as checked: disk_inner filled in
  RingImage rings;
  double seconds = 0.0;
  /// channels I, I_n0 .. I_n3_up and R, G, B (spectra/ring_image_output.hpp), the request in the metadata
  Image image = Image::with_channels(1, 1, {});
  LineChart orders;                 ///< the orders side by side (ring_orders_picture)
  std::vector<ReportEntry> report;  ///< the JSON line's entries: seconds, rays, flux by order, rings' sizes
};

/// Checks the request (RequestError), then computes the ring image.
RingImageResult ring_image(const RingImageRequest& request);

}  // namespace grtrace::app
