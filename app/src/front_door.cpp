// The front door (grtrace/app/front_door.hpp): the checks of a request, the renderer's creation by metric, the
// report and the frame's header record, flights and the device choice. Compiled once; the tracers themselves are
// in the units frame_tracers.hpp lists.
#include "frame_tracers.hpp"
#include "gpu_tracers.hpp"
#include "grtrace/core/memory_limit.hpp"
#include "grtrace/core/number_text.hpp"
#include "grtrace/core/physical_units.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/medium/polish_doughnut.hpp"
#include "grtrace/medium/riaf.hpp"
#include "grtrace/medium/spherical_accretion.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/metric/static_spherical.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/render/disk_light_frame.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/scene/thin_disk.hpp"
#include "grtrace/spectra/kerr_disk_map.hpp"
#include "grtrace/spectra/line_profile.hpp"
#include "grtrace/spectra/line_profile_output.hpp"
#include "grtrace/spectra/ring_image.hpp"
#include "grtrace/spectra/ring_image_output.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace grtrace::app {

/// The named metrics the planar table tracer draws (trace/auto_tracer.hpp): static and spherically symmetric
/// (StaticSphericalMetric), with a horizon (Reissner-Nordstrom's |Q| < M, check_metric_spec, always gives it one).
/// Asked of the metric's type, so a metric added to the named metrics gets the table where it applies.
bool planar_tracer_metric(const MetricSpec& metric) {
  if (!is_named_metric(metric.name)) return false;
  return with_named_metric(metric, [](const auto& m) {
    if constexpr (StaticSphericalMetric<std::remove_cvref_t<decltype(m)>>) return m.horizon_radius() > 0.0;
    else return false;
  });
}

SourceScale source_scale(const RenderRequest& q) {
  return q.source == "sgr-a" ? SourceScale::sgr_a() : SourceScale::m87();
}

RiafParameters riaf_parameters(const RenderRequest& q) {
  RiafParameters p = q.source == "sgr-a" ? RiafParameters::sgr_a() : RiafParameters::m87();
  if (q.accretion_rate) p.accretion_rate = *q.accretion_rate;
  p.outer = q.sky_radius;  // the gas fills the sky sphere (at 400 M its 230 GHz light is below 1e-30 of the peak)
  return p;
}

PolishDoughnut<KerrMetric> polish_doughnut(const RenderRequest& q) {
  const KerrMetric metric{q.metric.mass, q.metric.spin};
  return PolishDoughnut<KerrMetric>(metric, q.torus_inner * q.metric.mass, q.torus_peak * q.metric.mass, 3.0, 1.0,
                                    q.torus_opacity);
}

std::string frequency_band_name(double ghz) {
  std::string name = shortest_number_text(ghz);
  std::replace(name.begin(), name.end(), '.', 'p');
  return name + "GHz";
}

bool is_medium_scene(std::string_view scene) {
  return std::find(kMediumSceneNames.begin(), kMediumSceneNames.end(), scene) != kMediumSceneNames.end();
}

/// The names of the order channels in reports and headers: n = 0, 1, 2 and >= 3.
constexpr std::array<const char*, 4> kOrderNames = {"n0", "n1", "n2", "n3_up"};

bool draws_light(const RenderRequest& q) { return is_medium_scene(q.scene) || (q.scene == "disk" && q.disk_light); }

namespace {

/// The emissivity a disk's light is asked with, checked (RequestError naming `what`).
DiskEmissivity disk_emissivity(const DiskLightRequest& q, const std::string& what) {
  DiskEmissivity emissivity;
  emissivity.index_inner = q.emissivity_index;
  emissivity.index_outer = q.emissivity_index_outer.value_or(q.emissivity_index);
  if (q.emissivity_break) emissivity.r_break = *q.emissivity_break;
  refusal_as_request_error("", [&] { disk_mesh::check_emissivity(emissivity, what); });
  return emissivity;
}

/// The light in words, for headers and reports (after disk_emissivity has checked it).
std::string describe_disk_light(const DiskLightRequest& q) {
  return std::string(q.transparent ? "transparent" : "opaque") + ", emissivity r^-" +
         shortest_number_text(q.emissivity_index) +
         (q.emissivity_break ? " inside " + shortest_number_text(*q.emissivity_break) + " M, r^-" +
                                   shortest_number_text(q.emissivity_index_outer.value_or(q.emissivity_index)) +
                                   " beyond"
                             : "");
}

}  // namespace

std::vector<std::string> scene_names() {
  std::vector<std::string> names(kStandardSceneNames.begin(), kStandardSceneNames.end());
  names.insert(names.end(), kMediumSceneNames.begin(), kMediumSceneNames.end());
  return names;
}

void check_camera_angles(const CameraRequest& c, const std::string& theta_text, const std::string& fov_text) {
  if (!(c.theta_degrees >= 0.0 && c.theta_degrees <= 180.0))
    throw RequestError("--camera-theta must lie in [0, 180] degrees (0 and 180: on the spin axis), got " + theta_text);
  if (!(c.fov_degrees > 0.0 && c.fov_degrees < 180.0))
    throw RequestError("--fov must lie in (0, 180) degrees, got " + fov_text);
}

namespace {

/// Flat space is drawn with straight lines (FlatMetric, metric/metric_traits.hpp), never integrated.
bool flat_metric(const MetricSpec& metric) {
  if (!is_named_metric(metric.name)) return false;
  return with_named_metric(metric, [](const auto& m) { return FlatMetric<std::remove_cvref_t<decltype(m)>>; });
}

/// The observer's name a request gets when it names none: the ZAMO for Kerr (it exists everywhere outside the
/// horizon, the static observer not inside the ergosphere), the static observer otherwise.
std::string observer_or_default(const RenderRequest& q) {
  if (!q.camera.observer.empty()) return q.camera.observer;
  return q.metric.name == "kerr" ? "zamo" : "static";
}

/// The disk's sense (+1: towards +phi; prograde follows the sign of the spin, +phi for a = 0) and, for Kerr, its
/// inner edge: the ISCO of that sense when none was asked for, refused inside it (no stable circular orbit there).
ThinDisk disk_of(const RenderRequest& q) {
  ThinDisk disk;
  const MetricSpec& ms = q.metric;
  const bool retrograde = q.disk_retrograde;
  const int hole = ms.name == "kerr" && ms.spin < 0.0 ? -1 : +1;
  disk.sense = retrograde ? -hole : hole;
  disk.r_out = q.disk_outer;
  disk.r_in = q.disk_inner.value_or(6.0);
  if (ms.name != "kerr") return disk;  // the others keep the inner edge as given (default 6)
  const exact::Orbit orbit = retrograde ? exact::Orbit::retrograde : exact::Orbit::prograde;
  const double isco = exact::isco_radius(ms.spin, orbit, ms.mass);
  if (!q.disk_inner) {
    disk.r_in = isco;
  } else if (!(disk.r_in >= isco * (1.0 - 1e-12))) {  // the printed ISCO itself is accepted
    std::ostringstream msg;
    msg.precision(10);
    msg << "--disk-inner " << shortest_number_text(disk.r_in) << " is inside the ISCO r_isco = " << isco
        << " M of this " << (retrograde ? "retrograde" : "prograde") << " disk (a = " << ms.spin
        << "): no stable circular orbit exists there; raise --disk-inner to at least the ISCO or leave it out";
    throw RequestError(msg.str());
  }
  return disk;
}

/// The settings a request's method and sky give the tracers.
TraceSettings settings_of(const RenderRequest& q) {
  TraceSettings s;
  s.integrator.tolerance = {q.method.rtol, q.method.atol};
  s.initial_step = q.method.step;
  s.max_steps = q.method.max_steps;
  s.escape_radius = q.sky_radius;
  return s;
}

AngleCorrection correction_of(const std::string& name) {
  if (name == "none") return AngleCorrection::none;
  if (name == "flat") return AngleCorrection::flat;
  if (name == "exact") return AngleCorrection::exact;
  throw RequestError("unknown --angle-correction '" + name + "'; choose none, flat or exact");
}

/// The farthest camera the Kerr-Schild chart draws, and its largest sky sphere (see check_camera_radius).
constexpr double kKerrSchildCameraRadius = 2e5;
constexpr double kKerrSchildSkyRadius = 1e50;

/// The camera's radius against the horizon guard and the sky sphere, in the metric's own radius (Boyer-Lindquist
/// r for Kerr in both charts, the areal radius r(l) of the wormhole), and whether emitters at rest exist at the sky
/// sphere (not beyond Schwarzschild-de Sitter's cosmological horizon).
void check_camera_radius(const MetricSpec& ms, double radius_asked, const Vec4& x_spherical, const TraceSettings& s) {
  const auto [camera_radius, guard, sky_ok] = with_named_metric(ms, [&](const auto& m) {
    const Vec4 x = event_from_spherical(m, x_spherical);
    const double rh = ms.name == "kerr" ? KerrMetric{ms.mass, ms.spin}.horizon_radius() : m.horizon_radius();
    const Vec4 sky_event(0.0, s.escape_radius, std::numbers::pi / 2.0, 0.0);
    const bool ok = static_velocity(m.metric(event_from_spherical(m, sky_event))).has_value();
    return std::tuple{m.radius(x), (1.0 + s.horizon_epsilon) * rh, ok};
  });
  if (!(camera_radius > guard))
    throw RequestError("--camera-r " + shortest_number_text(radius_asked) +
                       " is at or inside the horizon (guard r = " + exact_number(guard) + "); move the camera out");
  if (!(camera_radius < s.escape_radius)) throw RequestError("--camera-r must be inside --sky-radius");
  // Measured: the general tracer in Kerr-Schild's Cartesian chart draws the shadow of a camera at 2e5 M and none at
  // 5e5 M (the bending is lost in coordinates of that size); the Boyer-Lindquist chart draws it at 5e10 M.
  if (ms.name == "kerr" && ms.chart == "ks" && camera_radius > kKerrSchildCameraRadius)
    throw RequestError("--camera-r " + shortest_number_text(radius_asked) +
                       ": the Kerr-Schild chart draws cameras out to r = 2e5 M; use --chart bl for a camera farther "
                       "out (it draws the shadow of a camera where a telescope is, 5e10 M)");
  // Measured: every ray reaches a sky sphere at 1e50 M in Kerr-Schild's chart (94 steps a ray from r = 30) and none
  // one at 1e55 M (max_steps: the chart's derivatives hold r^6, which overflows beyond 1e51); beyond 1e60 the
  // metric itself overflows there and the sky's emitters were refused as "beyond a horizon".
  if (ms.name == "kerr" && ms.chart == "ks" && s.escape_radius > kKerrSchildSkyRadius)
    throw RequestError("--sky-radius " + shortest_number_text(s.escape_radius) +
                       ": the Kerr-Schild chart's sky sphere can lie out to r = 1e50 M; lower it or use --chart bl "
                       "(whose sky sphere can lie out to 1e100 M)");
  if (!sky_ok)
    throw RequestError("--sky-radius " + shortest_number_text(s.escape_radius) +
                       " lies beyond a horizon of this metric (no emitter can be at rest there); lower it");
}

/// The reduced Kerr tracer's metric (trace/auto_tracer.hpp kerr_mino_tracer_applies): KerrMetric, the
/// Boyer-Lindquist chart. Asked of the metric's type.
bool kerr_mino_tracer_metric(const MetricSpec& metric) {
  if (!is_named_metric(metric.name)) return false;
  return with_named_metric(metric,
                           [](const auto& m) { return std::is_same_v<std::remove_cvref_t<decltype(m)>, KerrMetric>; });
}

/// Which tracer can draw what: a tracer named (kTracerNames) that cannot draw the request is refused here, before
/// any work, saying why and what to ask for instead. Every standard scene is one both reduced tracers draw (its
/// objects equatorial and stationary: planar_supports_scene, kerr_mino_supports_scene; the frame units check it at
/// compile time), so what decides is the metric and the step control.
void check_tracer(const RenderRequest& q) {
  if (q.tracer == "symmetric")
    throw RequestError(
        "--tracer symmetric is retired: the planar tracer draws every frame it drew, with a "
        "smaller error; use --tracer planar (or auto, which picks it)");
  if (std::find(kTracerNames.begin(), kTracerNames.end(), q.tracer) == kTracerNames.end())
    throw RequestError("unknown --tracer '" + q.tracer + "'; choose " + choice_list(kTracerNames));
  if (q.tracer == "straight-line" && !flat_metric(q.metric))
    throw RequestError(
        "--tracer straight-line draws flat space only (--metric minkowski); this metric is curved: "
        "use auto or general");
  if (q.tracer == "planar" && !planar_tracer_metric(q.metric))
    throw RequestError(
        "--tracer planar needs a static spherically symmetric metric with a horizon "
        "(--metric schwarzschild or rn); use general");
  if ((q.tracer == "kerr-mino" || q.tracer == "kerr-closed-form") && !kerr_mino_tracer_metric(q.metric))
    throw RequestError("--tracer " + q.tracer +
                       " needs --metric kerr --chart bl (Kerr's separated equations in "
                       "Boyer-Lindquist coordinates); use general");
  if ((q.tracer == "planar" || q.tracer == "kerr-mino" || q.tracer == "kerr-closed-form") &&
      q.method.control == "fixed")
    throw RequestError("--tracer " + q.tracer + " integrates in " +
                       (q.tracer == "planar" ? "swept angle" : "Mino time") +
                       (q.tracer == "kerr-closed-form" ? " (the rays its closed form does not cover)" : "") +
                       ", where a fixed --step would mean something else; use --control i, pi or doubling, or "
                       "--tracer general");
}

/// Whether a request's method is the one media are drawn with, or the tools' default (which a request that names
/// no method has, and which a medium replaces by its own).
bool is_media_method(const MethodRequest& m) {
  for (const std::size_t i : {std::size_t{0}, kMediaMethod})
    if (m.tableau == kToolMethods[i].tableau && m.control == kToolMethods[i].control) return true;
  return false;
}

/// What an emitting medium's scene needs: its hole (accretion: Schwarzschild; riaf, torus: Kerr), the media's method
/// (kMediaMethod, the one the application library compiles media with), a tracer that draws media, the CPU.
void check_medium_request(const RenderRequest& q) {
  if (q.scene == "riaf" || q.scene == "torus") {
    if (q.metric.name != "kerr" || q.metric.chart != "bl")
      throw RequestError("--scene " + q.scene +
                         " flows around a Kerr hole in Boyer-Lindquist coordinates: use --metric kerr (--spin 0 for "
                         "Schwarzschild) and leave --chart out");
    if (q.scene == "riaf" && q.metric.mass != 1.0)
      throw RequestError("--scene riaf takes the hole's mass from --source (lengths in units of it): leave --mass out");
  } else if (q.metric.name != "schwarzschild") {
    // The tools compile the accreting gas for one hole (each metric is another instantiation of the medium's
    // tracers, 5 to 10 s of the render command's build); a program of its own draws it around any static
    // spherically symmetric one (SphericalMediumTracer).
    throw RequestError("--scene " + q.scene +
                       " falls onto a Schwarzschild hole in the tools: use --metric schwarzschild (other static "
                       "spherically symmetric holes: SphericalMediumTracer in a program of your own)");
  }
  const ToolMethod& m = kToolMethods[kMediaMethod];
  if (!is_media_method(q.method))
    throw RequestError("--scene " + q.scene + " is drawn with --tableau " + std::string(m.tableau) + " --control " +
                       std::string(m.control) +
                       " (an error estimate that sees the light integrated along a ray; the default rkf78's does "
                       "not); leave --tableau and --control out");
  if ((q.scene == "riaf" || q.scene == "torus") && q.tracer != "auto" && q.tracer != "kerr-mino")
    throw RequestError("--tracer " + q.tracer + " cannot draw --scene " + q.scene +
                       "; use auto or kerr-mino (every pixel integrated on Kerr's separated equations in Mino time)");
  if (q.scene == "accretion" && q.tracer != "auto" && q.tracer != "planar" && q.tracer != "general")
    throw RequestError("--tracer " + q.tracer + " cannot draw --scene " + q.scene +
                       "; use auto or planar (one table of rays) or general (every pixel integrated)");
  if (q.error_map)
    throw RequestError("--error-map judges where escaped rays point; --scene " + q.scene +
                       " shows the light of its gas instead: leave --error-map out");
  if (q.accretion_gas != "free-fall" && q.accretion_gas != "rest")
    throw RequestError("unknown --accretion-gas '" + q.accretion_gas + "'; choose free-fall or rest");
  if (!(q.accretion_power >= 0.0 && q.accretion_power <= 10.0))
    throw RequestError("--accretion-power must lie in [0, 10] (j ~ r^-power), got " +
                       shortest_number_text(q.accretion_power));
  if (std::find(kRiafSourceNames.begin(), kRiafSourceNames.end(), q.source) == kRiafSourceNames.end())
    throw RequestError("unknown --source '" + q.source + "'; choose " + choice_list(kRiafSourceNames));
  if (q.accretion_rate && !(*q.accretion_rate > 0.0 && *q.accretion_rate <= 1e3))
    throw RequestError("--accretion-rate must lie in (0, 1e3] solar masses a year, got " +
                       shortest_number_text(*q.accretion_rate));
  if (q.frequencies_ghz.empty() || q.frequencies_ghz.size() > kMaxFrequencies)
    throw RequestError("--frequency takes 1 to " + std::to_string(kMaxFrequencies) + " frequencies, got " +
                       std::to_string(q.frequencies_ghz.size()));
  for (std::size_t i = 0; i < q.frequencies_ghz.size(); ++i) {
    const double f = q.frequencies_ghz[i];
    if (!(f > 0.0 && f <= 1e7))
      throw RequestError("--frequency must lie in (0, 1e7] GHz, got " + shortest_number_text(f));
    for (std::size_t j = 0; j < i; ++j)
      if (frequency_band_name(q.frequencies_ghz[j]) == frequency_band_name(f))
        throw RequestError("--frequency names " + shortest_number_text(f) + " GHz twice: list each band once");
  }
  if (!(q.torus_opacity >= 0.0 && q.torus_opacity <= 1e6))
    throw RequestError("--torus-opacity must lie in [0, 1e6], got " + shortest_number_text(q.torus_opacity));
  if (q.scene == "torus") {
    try {
      (void)polish_doughnut(q);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      throw RequestError("--torus-inner " + shortest_number_text(q.torus_inner) + " --torus-peak " +
                         shortest_number_text(q.torus_peak) + ": " + what.substr(what.find(':') + 2) +
                         " (radii in M on the equator)");
    }
  }
  if (q.scene == "riaf" && !(q.camera.r >= kMinPhysicalCameraRadius))
    throw RequestError("--scene riaf gives angles and fluxes as a distant telescope sees them: use --camera-r " +
                       exact_number(kMinPhysicalCameraRadius) + " or more (got " + shortest_number_text(q.camera.r) +
                       ")");
}

/// What a disk drawn by its light needs: a hole whose rays are Kerr's in closed form, the tracer that draws them,
/// the CPU, an emissivity and a redshift power that make sense; no error map (no sky is shown).
void check_disk_light_request(const RenderRequest& q) {
  if (q.metric.name != "kerr" && q.metric.name != "schwarzschild")
    throw RequestError(
        "--disk-light follows the disk's rays in closed form (Kerr's): use --metric kerr or "
        "schwarzschild, got --metric " +
        q.metric.name);
  if (q.metric.name == "kerr" && q.metric.chart != "bl")
    throw RequestError("--disk-light traces Kerr in Boyer-Lindquist coordinates: leave --chart out or use bl");
  if (q.tracer != "auto" && q.tracer != "kerr-closed-form")
    throw RequestError("--tracer " + q.tracer +
                       " cannot draw a disk by its light (--disk-light: every ray in closed form); use auto or "
                       "kerr-closed-form");
  if (q.error_map)
    throw RequestError(
        "--error-map judges where escaped rays point; a disk drawn by its light shows no sky: leave "
        "--error-map out");
  if (!(std::abs(q.redshift_power) <= 10.0))
    throw RequestError("--redshift-power must lie in [-10, 10], got " + shortest_number_text(q.redshift_power));
  (void)disk_emissivity(*q.disk_light, "--disk-light");
}

}  // namespace

KerrDiskRays disk_light_rays(const RenderRequest& q, const ThinDisk& disk, double sky_radius) {
  KerrMetric metric;
  metric.mass = q.metric.mass;
  metric.spin = q.metric.name == "kerr" ? q.metric.spin : 0.0;
  return KerrDiskRays(metric, disk.r_in, disk.r_out, disk.sense, sky_radius);
}

DiskLight disk_light_of(const RenderRequest& q) {
  DiskLight light;
  light.emissivity = disk_emissivity(*q.disk_light, "--disk-light");
  light.redshift_power = q.redshift_power;
  light.transparent = q.disk_light->transparent;
  return light;
}

void check_method(const MethodRequest& m, const std::string& prefix) {
  const std::string o = "--" + prefix;
  refusal_as_request_error(o + "tableau / " + o + "control: ", [&] { check_tool_method(m.tableau, m.control); });
  if (!(m.rtol > 0.0 && m.rtol < 1.0))
    throw RequestError(o + "rtol must lie in (0, 1) (a relative error; e.g. 1e-9), got " +
                       shortest_number_text(m.rtol));
  if (!(m.atol >= 0.0 && m.atol < 1.0))
    throw RequestError(o + "atol must lie in [0, 1) (e.g. 1e-11), got " + shortest_number_text(m.atol));
  if (!(m.step >= 0.0)) throw RequestError(o + "step must be >= 0");
  if (m.control == "fixed" && m.step <= 0.0)
    throw RequestError(o + "control fixed needs a step: add " + o + "step H > 0");
}

// ---- devices ------------------------------------------------------------------------------------------------

std::optional<std::string> gpu_refusal(const RenderRequest& q) {
  if (is_medium_scene(q.scene))
    return "--scene " + q.scene + " is drawn on the CPU (the GPU does not trace emitting media yet); use --device cpu or auto";
  if (draws_light(q)) return "a disk drawn by its light (--disk-light) is drawn on the CPU; use --device cpu or auto";
  if (q.method.tableau != kGpuTableau || q.method.control != kGpuControl)
    return "the GPU traces with --tableau " + std::string(kGpuTableau) + " --control " + std::string(kGpuControl) +
           " only; use those, or --device cpu for the other methods";
  if (q.tracer == "planar")
    return "--tracer planar is the CPU's table tracer (the GPU integrates every pixel); use --tracer general or auto, "
           "or --device cpu";
  if (flat_metric(q.metric)) return "flat space is drawn with straight lines, on the CPU; use --device cpu";
  const GpuStatus& gpu = gpu_status();
  if (!gpu.built || !gpu.present) return gpu.why_not + "; use --device cpu";
  return std::nullopt;
}

bool cpu_table_tracer_draws(const RenderRequest& q) {
  return q.tracer == "planar" || (q.tracer == "auto" && planar_tracer_metric(q.metric));
}

std::string choose_device(std::string_view asked, const RenderRequest& q) {
  if (asked == "cpu") return "cpu";
  if (std::find(kDeviceNames.begin(), kDeviceNames.end(), asked) == kDeviceNames.end())
    throw RequestError("unknown --device '" + std::string(asked) + "'; choose auto, cpu or cuda");
  // Where auto keeps the CPU anyway, the driver is not asked (its start costs a tenth of a second where there is a
  // GPU, and nothing is gained).
  if (asked == "auto" && (!kAutoPicksGpu || cpu_table_tracer_draws(q) || draws_light(q))) return "cpu";
  const auto refusal = gpu_refusal(q);
  if (asked == "cuda" && refusal) throw RequestError("--device cuda: " + *refusal);
  return refusal ? "cpu" : "cuda";
}

std::string device_name(std::string_view device) { return device == "cuda" ? gpu_status().name : "cpu"; }

#if !defined(GRTRACE_APP_CUDA)
// A build without the CUDA backend (no CUDA compiler found, or GRTRACE_CUDA=OFF); with it, the backend's own unit
// (frame_tracers_gpu_exact.cu) asks the driver.
const GpuStatus& gpu_status() {
  static const GpuStatus status{false, false, "",
                                "this build has no CUDA backend (configured without a CUDA compiler, or with "
                                "-DGRTRACE_CUDA=OFF)"};
  return status;
}
#endif

// ---- the checks ---------------------------------------------------------------------------------------------

CheckedRequest check_request(const RenderRequest& in) {
  RenderRequest q = in;
  const bool medium = is_medium_scene(q.scene);
  if (!is_standard_scene(q.scene) && !medium)
    throw RequestError("unknown scene '" + q.scene + "'; choose " + choice_list(scene_names()));
  const bool disk = q.scene == "disk";
  refusal_as_request_error("", [&] { check_metric_spec(q.metric); });
  const MetricSpec& ms = q.metric;
  if (medium) {
    check_medium_request(q);
    // The media's method in place of the default the request left as it was (check_medium_request).
    q.method.tableau = kToolMethods[kMediaMethod].tableau;
    q.method.control = kToolMethods[kMediaMethod].control;
  }
  if (q.disk_light && !disk) throw RequestError("--disk-light draws the disk scene: add --scene disk");
  if (draws_light(q) && !medium) check_disk_light_request(q);
  if (ms.name == "minkowski" && disk)
    throw RequestError("--scene disk needs a metric with a mass (the disk orbits it), not --metric minkowski");

  check_method(q.method);
  if (q.method.max_steps < 1 || q.method.max_steps > 100'000'000) throw RequestError("--max-steps must be in 1 .. 1e8");
  const TraceSettings settings = settings_of(q);
  if (!(q.sky_radius > 0.0 && q.sky_radius <= 1e100))
    throw RequestError("--sky-radius must lie in (0, 1e100] (r^2 must not overflow), got " +
                       shortest_number_text(q.sky_radius));
  // A step longer than the sky's diameter crosses the whole scene in one go: meaningless, not just coarse.
  if (q.method.step > 2.0 * q.sky_radius)
    throw RequestError("--step " + shortest_number_text(q.method.step) +
                       " is longer than the sky's diameter (2 x --sky-radius = " + exact_number(2.0 * q.sky_radius) +
                       "); use a step in (0, " + exact_number(2.0 * q.sky_radius) + "]");
  const AngleCorrection correction = correction_of(q.angle_correction);

  // The camera: the event (r, theta, phi) in Boyer-Lindquist-like coordinates for every chart.
  const CameraRequest& c = q.camera;
  check_camera_angles(c, shortest_number_text(c.theta_degrees), shortest_number_text(c.fov_degrees));
  if (!std::isfinite(c.r) || !std::isfinite(c.phi_degrees))
    throw RequestError("--camera-r and --camera-phi must be finite numbers");
  q.camera.observer = observer_or_default(q);
  const auto observer = observer_kind_from_string(q.camera.observer);
  if (!observer) throw RequestError("unknown --observer '" + q.camera.observer + "'; choose static or zamo");
  constexpr double deg = std::numbers::pi / 180.0;
  // phi modulo a turn, exactly (fmod), before radians: 1e308 degrees is an angle, but not once multiplied by pi.
  const Vec4 x_spherical(0.0, c.r, c.theta_degrees * deg, std::fmod(c.phi_degrees, 360.0) * deg);
  check_camera_radius(ms, c.r, x_spherical, settings);
  if (c.width < 1 || c.height < 1 || c.width > 16384 || c.height > 16384)
    throw RequestError("--width and --height must be between 1 and 16384 pixels");
  {  // the image's memory, before anything is allocated: the channels (+ error channel and double directions with
     // the error map) and the 8-bit previews
    const double pixels = static_cast<double>(c.width) * static_cast<double>(c.height);
    // + the light's channels: a medium's intensity and optical depth (and its four orders where split: counted
    // always), a disk's intensity and its four orders
    const std::size_t orders = kOrderIntensityChannels.size();
    const std::size_t light_channels = medium ? 2 + orders : draws_light(q) ? 1 + orders : 0;
    const double channels =
        static_cast<double>(Image::kStandardChannels.size() + light_channels + (q.error_map ? 1 : 0));
    const double bytes = image_bytes(static_cast<double>(c.width), static_cast<double>(c.height), channels) +
                         pixels * (3.0 + (q.error_map ? 2.0 * sizeof(double) * 2.0 : 0.0));
    try {
      check_memory(bytes, "--width " + std::to_string(c.width) + " --height " + std::to_string(c.height));
    } catch (const MemoryLimitError& e) {
      throw RequestError(std::string(e.what()) + "; or choose a smaller --width/--height");
    }
  }
  if (q.threads < 0 || q.threads > 1024) throw RequestError("--threads must be 0 (all cores) .. 1024");
  if (q.table_rays == 0) q.table_rays = medium ? grtrace::default_medium_table_rays : grtrace::default_table_rays;
  if (q.table_rays < 8 || q.table_rays > 1'000'000) throw RequestError("--table-rays must be in 8 .. 1e6");

  CameraSpec spec;
  spec.position = x_spherical;
  spec.spherical_position = true;
  spec.observer = *observer;
  spec.velocity = c.velocity;
  spec.look = c.look;
  spec.up = c.up;
  spec.width = c.width;
  spec.height = c.height;
  spec.fov_degrees = c.fov_degrees;
  if (!c.velocity.allFinite() || !c.look.allFinite() || !c.up.allFinite())
    throw RequestError("--velocity, --look and --up must be finite numbers");
  const Camera camera = refusal_as_request_error(
      "", [&] { return with_named_metric(ms, [&](const auto& m) { return make_camera(m, spec); }); });

  StandardSceneSpec scene;
  // A medium does not end rays: its rays (a viewer's, Python's trace_ray) are the sky scene's.
  scene.name = medium ? "sky" : q.scene;
  // The wormhole's other universe (rays ending at l < 0) gets a sky of its own, seen through the throat.
  scene.far_side = ms.name == "wormhole";
  if (q.checker_squares < 1 || q.checker_squares > 10000) throw RequestError("--checker-squares must be in 1 .. 10000");
  scene.checker_squares = q.checker_squares;
  if (!q.sky_texture.empty()) {
    try {
      // Judged by its header before its pixels are decoded; then its R, G, B planes are moved into the sky, so the
      // texels are held once (the memory limit, which the reader applies to the file's channels, bounds them).
      const ExrInfo info = read_exr_info(q.sky_texture);
      if (!info.has_channel("R") || !info.has_channel("G") || !info.has_channel("B"))
        throw RequestError("--sky-texture '" + q.sky_texture + "' has no R, G, B channels");
      Image img = read_exr(q.sky_texture);
      scene.texture = TextureSky(img.width(), img.height(), std::move(img.channel("R")), std::move(img.channel("G")),
                                 std::move(img.channel("B")));
      check_texture(*scene.texture);  // a NaN texel would make every ray that sees it non_finite
    } catch (const RequestError&) {
      throw;
    } catch (const MemoryLimitError&) {
      throw;
    } catch (const std::exception& e) {
      throw RequestError("--sky-texture: " + std::string(e.what()));
    }
  }
  // The disk's sense and edge for every scene (a viewer draws the ISCO ring of that sense around any scene); its
  // orbits are checked where it is drawn.
  RenderRequest edge = q;
  if (!disk) edge.disk_inner.reset();  // an edge asked for where no disk is drawn is not judged
  scene.disk = disk_of(edge);
  if (disk) {
    if (!q.disk_inner) q.disk_inner = scene.disk.r_in;
    refusal_as_request_error("", [&] {
      try {
        with_named_metric(ms, [&](const auto& m) { check_disk_orbits(m, scene.disk); });
        // Drawn by its light: its rays in closed form outside the photon orbit, which must lie inside the disk.
        if (draws_light(q)) (void)disk_light_rays(q, scene.disk, settings.escape_radius);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string(e.what()) + " (--disk-inner, --disk-outer)");
      }
    });
  }
  if (q.error_map && ms.name != "schwarzschild" && ms.name != "minkowski")
    throw RequestError("--error-map needs --metric schwarzschild or minkowski (the exact elliptic-integral reference)");

  // Which tracer can draw this metric, scene and method, and on which device: auto picks the fastest tracer whose
  // assumptions hold (trace/auto_tracer.hpp); --device cuda where the GPU cannot draw the request is refused here.
  check_tracer(q);
  q.device = choose_device(q.device, q);
  return CheckedRequest{std::move(q), std::move(scene), settings, correction, camera};
}

CheckedRequest with_camera(CheckedRequest checked, const Camera& camera) {
  checked.camera = camera;
  checked.request.camera.width = camera.width();
  checked.request.camera.height = camera.height();
  checked.request.camera.fov_degrees = camera.fov_degrees();
  return checked;
}

// ---- the frame ----------------------------------------------------------------------------------------------

std::unique_ptr<FrameRenderer> FrameRenderer::create(const RenderRequest& request) {
  return create(check_request(request));
}

std::unique_ptr<FrameRenderer> FrameRenderer::create(const CheckedRequest& checked) {
  if (is_medium_scene(checked.request.scene)) return make_medium_renderer(checked);
  if (draws_light(checked.request)) return make_disk_light_renderer(checked);
  return with_named_metric(checked.request.metric,
                           [&](const auto& metric) { return make_frame_renderer(checked, metric); });
}

RenderResult render(const RenderRequest& request, const RenderControl& control) {
  return FrameRenderer::create(request)->render(control);
}

RenderOptions render_options(const CheckedRequest& checked, const RenderControl& control) {
  RenderOptions o;
  o.threads = checked.request.threads;
  o.mirror_symmetry = checked.request.mirrors;
  o.progress = control.bar;
  o.progress_label = control.label;
  o.shared_progress = control.shared_bar;
  o.cancel = control.cancel;
  o.pixels_done = control.pixels_done;
  return o;
}

namespace {

/// The "error" channel (radians; NaN where the ray did not escape; pi where the escaped/captured verdict disagrees
/// with the exact one) from the frame's double-precision directions, and its summary: every pixel against the
/// exact elliptic-integral direction from the camera (Schwarzschild and flat space).
ErrorSummary add_error_channel(const CheckedRequest& checked, Image& image,
                               const std::vector<SkyDirection>& directions) {
  const Camera& cam = checked.camera;
  const auto& status = image.channel("status");
  std::vector<float>& error = image.add_channel("error", std::numeric_limits<float>::quiet_NaN());
  std::vector<double> exact_error(image.pixel_count(), std::numeric_limits<double>::quiet_NaN());
  const long n = static_cast<long>(image.pixel_count());
  const double mass = checked.request.metric.name == "minkowski" ? 0.0 : checked.request.metric.mass;
  long mismatches = 0;
#if defined(_OPENMP)
  const int threads = checked.request.threads > 0 ? checked.request.threads : omp_get_max_threads();
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
  summary.max = summary.median = std::numeric_limits<double>::quiet_NaN();
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

/// What the header records of a report (for users: the tools and the Python module read the typed report).
void record_report(Image& image, const RenderReport& r) {
  auto& m = image.metadata;
  m["tracer"] = r.tracer;
  m["device"] = r.device;
  if (r.gpu_trace_seconds) m["gpu_trace_seconds"] = exact_number(*r.gpu_trace_seconds);
  if (r.gpu_seconds) m["gpu_seconds"] = exact_number(*r.gpu_seconds);
  if (!r.sky_continuation.empty()) m["sky_continuation"] = r.sky_continuation;
  if (r.continuation_error) {
    m["sky_continuation_error"] = exact_number(r.continuation_error->error);
    m["sky_continuation_impact"] = exact_number(r.continuation_error->impact);
    m["sky_radius_for_rtol"] = exact_number(r.continuation_error->sky_radius_for_rtol);
  }
  m["mirrors"] = r.mirrors;
  if (r.flux) m["flux"] = exact_number(*r.flux);
  if (r.flux_jy) m["flux_jy"] = exact_number(*r.flux_jy);
  if (r.microarcseconds_per_pixel) m["microarcseconds_per_pixel"] = exact_number(*r.microarcseconds_per_pixel);
  if (r.flux_by_order) {
    for (std::size_t n = 0; n < r.flux_by_order->size(); ++n)
      m[std::string("flux_") + kOrderNames[n]] = exact_number((*r.flux_by_order)[n]);
  }
  if (r.uncovered_rays) m["uncovered_rays"] = std::to_string(*r.uncovered_rays);
  for (const RenderReport::BandFlux& b : r.band_fluxes) {
    m["flux_" + b.band] = exact_number(b.flux);
    if (b.flux_jy) m["flux_jy_" + b.band] = exact_number(*b.flux_jy);
  }
  if (r.error) {
    m["error_max"] = exact_number(r.error->max);
    m["error_median"] = exact_number(r.error->median);
    m["error_mismatches"] = std::to_string(r.error->mismatches);
  }
  record_render_stats(image, r.stats);
}

}  // namespace

RenderResult finish_render(const CheckedRequest& checked, Frame&& frame, const FrameFacts& facts, double setup_seconds,
                           const std::vector<SkyDirection>& directions) {
  RenderResult result{std::move(frame.image), {}};
  RenderReport& r = result.report;
  r.stats = frame.stats;
  // The table (planar tracer) is part of the frame's cost: the whole thing is timed.
  r.setup_seconds = setup_seconds;
  r.seconds = setup_seconds + facts.trace_seconds;
  r.stats.seconds = r.seconds;
  r.rays_per_second = r.seconds > 0.0 ? static_cast<double>(r.stats.rays) / r.seconds : 0.0;
  r.stats.rays_per_second = r.rays_per_second;
  r.tracer = facts.tracer.name;
  r.table_rays = facts.tracer.table_rays;
  r.table_steps = facts.tracer.table_steps;
  r.fallback_rays = facts.tracer.fallback_rays;
  const bool tabulated = r.tracer == "planar";
  r.mean_steps = tabulated && r.stats.rays > 0 ? static_cast<double>(r.table_steps) / static_cast<double>(r.stats.rays)
                                               : r.stats.mean_steps;
  r.device = device_name(facts.device);
  r.gpu_trace_seconds = facts.gpu_trace_seconds;
  r.gpu_seconds = facts.gpu_seconds;
  r.mirrors = facts.mirrors;
  r.sky_continuation = facts.tracer.sky_continuation;
  r.continuation_error = facts.continuation_error;
  r.flux = facts.flux;
  r.flux_jy = facts.flux_jy;
  r.microarcseconds_per_pixel = facts.microarcseconds_per_pixel;
  r.flux_by_order = facts.flux_by_order;
  r.uncovered_rays = facts.uncovered_rays;
  r.band_fluxes = facts.band_fluxes;
  // Judged after the clock stopped: the exact reference costs an elliptic integral per pixel.
  if (checked.request.error_map) r.error = add_error_channel(checked, result.image, directions);
  describe_request(result.image, checked);
  record_report(result.image, r);
  return result;
}

void describe_request(Image& image, const CheckedRequest& checked) {
  const RenderRequest& q = checked.request;
  auto& m = image.metadata;
  m["scene"] = q.scene;
  m["metric"] = q.metric.name;
  m["mass"] = exact_number(named_metric_has_mass(q.metric.name) ? q.metric.mass : 0.0);
  for (const auto& [option, value] : metric_parameter_values(q.metric)) m[std::string(option)] = exact_number(value);
  if (q.metric.name == "kerr") {
    m["chart"] = q.metric.chart;
    if (q.metric.chart == "ks")
      m["kerr_schild_slicing"] = q.metric.slicing == KerrSchildSlicing::ingoing ? "ingoing" : "outgoing";
  }
  m["observer"] = q.camera.observer;
  if (q.scene == "accretion") {
    m["medium"] = std::string(SphericalAccretion::kind);
    m["accretion_gas"] = q.accretion_gas;
    m["accretion_power"] = exact_number(q.accretion_power);
  }
  if (q.scene == "torus") {
    const PolishDoughnut<KerrMetric> torus = polish_doughnut(q);
    m["medium"] = std::string(PolishDoughnut<KerrMetric>::kind);
    m["torus_inner"] = exact_number(q.torus_inner);
    m["torus_peak"] = exact_number(q.torus_peak);
    m["torus_outer"] = exact_number(torus.outer_radius() / q.metric.mass);
    m["torus_opacity"] = exact_number(q.torus_opacity);
    m["torus_polytropic_index"] = "3";
  }
  if (q.scene == "riaf") {
    const RiafParameters p = riaf_parameters(q);
    const SourceScale s = source_scale(q);
    m["medium"] = "riaf";
    m["source"] = q.source;
    m["mass_solar"] = exact_number(s.mass_solar);
    m["distance_pc"] = exact_number(s.distance_pc);
    m["accretion_rate"] = exact_number(p.accretion_rate);
    m["frequency_ghz"] = exact_number(q.frequencies_ghz.front());
    if (q.frequencies_ghz.size() > 1) {
      std::string list;
      for (const double f : q.frequencies_ghz) list += (list.empty() ? "" : ",") + exact_number(f);
      m["frequencies_ghz"] = list;
    }
    m["electron_temperature"] = exact_number(p.temperature);
    m["density_power"] = exact_number(p.density_power);
    m["temperature_power"] = exact_number(p.temperature_power);
    m["thickness"] = exact_number(p.thickness);
    m["plasma_beta"] = exact_number(p.beta);
    m["inflow_speed"] = exact_number(p.inflow_speed);
    m["intensity_unit"] = "erg s^-1 cm^-2 Hz^-1 sr^-1";
  }
  if (q.scene == "disk") {
    m["disk_sense"] = q.disk_retrograde ? "retrograde" : "prograde";
    m["disk_inner"] = exact_number(checked.scene.disk.r_in);
    m["disk_outer"] = exact_number(checked.scene.disk.r_out);
  }
  if (q.disk_light) {
    m["disk_light"] = describe_disk_light(*q.disk_light);
    m["disk_transparent"] = q.disk_light->transparent ? "true" : "false";
    m["redshift_power"] = exact_number(q.redshift_power);
    m["intensity_unit"] = "g^" + shortest_number_text(q.redshift_power) + " eps(r), eps(r = M) = 1";
  }
  m["tableau"] = q.method.tableau;
  m["control"] = q.method.control;
  m["rtol"] = exact_number(q.method.rtol);
  m["atol"] = exact_number(q.method.atol);
  m["max_steps"] = std::to_string(q.method.max_steps);
  m["sky_radius"] = exact_number(q.sky_radius);
  if (!draws_light(q)) m["angle_correction"] = q.angle_correction;
}

std::vector<ReportEntry> report_entries(const RenderReport& r, const CheckedRequest& checked) {
  const RenderRequest& q = checked.request;
  std::vector<ReportEntry> e;
  const auto add = [&e](std::string key, auto value) { e.push_back({std::move(key), value}); };
  add("width", static_cast<long>(r.stats.width));
  add("height", static_cast<long>(r.stats.height));
  add("seconds", r.seconds);
  add("rays_per_second", r.rays_per_second);
  add("mean_steps", r.mean_steps);
  ReportEntry::Counts counts;
  for (std::size_t i = 0; i < kRayStatusCount; ++i)
    counts.emplace_back(std::string(kRayStatusNames[i]), r.stats.status_counts[i]);
  add("status_counts", counts);
  if (!is_medium_scene(q.scene)) {  // the pixels that show an object, by the order of its image
    ReportEntry::Counts by_order;
    for (std::size_t n = 0; n < kOrderNames.size(); ++n) by_order.emplace_back(kOrderNames[n], r.stats.hits_by_order[n]);
    add("hits_by_order", by_order);
  }
  add("tracer", r.tracer);
  add("tableau", q.method.tableau);
  add("control", q.method.control);
  add("device", r.device);
  if (r.gpu_trace_seconds) add("gpu_trace_seconds", *r.gpu_trace_seconds);  // the kernel's share of "seconds"
  if (r.gpu_seconds) add("gpu_seconds", *r.gpu_seconds);                    // and the GPU's whole share
  if (!r.sky_continuation.empty()) add("sky_continuation", r.sky_continuation);  // a medium's frame has none
  if (r.continuation_error) {  // a flat continuation's estimated error
    add("sky_continuation_error", r.continuation_error->error);
    add("sky_radius_for_rtol", r.continuation_error->sky_radius_for_rtol);
  }
  add("rtol", q.method.rtol);
  add("atol", q.method.atol);
  add("threads", static_cast<long>(r.stats.threads));
  add("traced_rays", r.stats.traced_rays);
  add("mirrors", r.mirrors);
  if (r.error) {
    add("max_error", r.error->max);
    add("median_error", r.error->median);
    add("error_pixels", r.error->judged);
    add("error_mismatches", r.error->mismatches);
  }
  if (r.flux) add("flux", *r.flux);
  if (r.flux_jy) add("flux_jy", *r.flux_jy);
  if (r.microarcseconds_per_pixel) add("microarcseconds_per_pixel", *r.microarcseconds_per_pixel);
  if (r.flux_by_order) {
    for (std::size_t n = 0; n < r.flux_by_order->size(); ++n)
      add(std::string("flux_") + kOrderNames[n], (*r.flux_by_order)[n]);
  }
  for (const RenderReport::BandFlux& b : r.band_fluxes) {
    add("flux_" + b.band, b.flux);
    if (b.flux_jy) add("flux_jy_" + b.band, *b.flux_jy);
  }
  if (q.disk_light) {
    add("uncovered_rays", r.uncovered_rays.value_or(0));
    add("disk", std::string(q.disk_light->transparent ? "transparent" : "opaque"));
  }
  if (r.tracer == "planar") {
    add("table_rays", r.table_rays);
    add("table_steps", r.table_steps);
    add("fallback_rays", r.fallback_rays);
  }
  return e;
}

FlightStats render_flight(const CheckedRequest& checked, const std::vector<Camera>& cameras, const FlightSkip& skip,
                          const FlightSink& sink, const RenderControl& control) {
  RenderOptions options = render_options(checked, control);
  return render_frames(
      cameras,
      [&](const Camera& camera, const RenderOptions& o) {
        RenderControl c = control;
        c.shared_bar = o.shared_progress;
        return FrameRenderer::create(with_camera(checked, camera))->render(c);
      },
      [](const RenderResult& r) -> const RenderStats& { return r.report.stats; }, skip,
      [&](int i, RenderResult&& r) { sink(i, std::move(r)); }, options);
}

// ---- a disk seen from afar: its line profile and its photon ring by order ------------------------------------
// The request checked as a frame of the disk scene would be (the same disk: its inner edge, the ISCO by default for
// Kerr, and its sense), then spectra/line_profile.hpp or spectra/ring_image.hpp on the closed-form Kerr disk map
// seen from 1e7 M. Here rather than in a unit of its own: the front door's header alone is ~10 s of a compile.

namespace {

/// The observer's distance: far enough that the profile is the one at infinity to ~1e-7 (tests/line_profile_test).
constexpr double kObserverDistance = 1e7;

/// A distant disk checked: its map, the disk as the disk scene has it, its emissivity and a line describing it.
struct CheckedDistantDisk {
  ThinDisk disk;
  KerrDiskMap map;
  DiskEmissivity emissivity;
  std::string description;
};

/// Checks the disk and observer (RequestError naming `what`), fills in q.disk_inner.
CheckedDistantDisk check_distant_disk(DistantDisk& q, const std::string& what) {
  if (q.metric.name != "kerr" && q.metric.name != "schwarzschild")
    throw RequestError(what +
                       " needs --metric kerr or schwarzschild (its rays are Kerr's in closed form), got --metric " +
                       q.metric.name);
  if (q.metric.name == "kerr" && q.metric.chart != "bl")
    throw RequestError(what + " traces Kerr in Boyer-Lindquist coordinates: leave --chart out or use bl");
  if (!(q.inclination_degrees > 0.01 && q.inclination_degrees < 179.99))
    throw RequestError(what +
                       " needs an inclination --camera-theta strictly between 0.01 and 179.99 degrees (on the axis "
                       "the closed form is not defined), got " +
                       shortest_number_text(q.inclination_degrees));
  // The disk as a frame of the disk scene has it (inner edge, ISCO, sense), with that frame's refusals.
  RenderRequest frame;
  frame.metric = q.metric;
  frame.scene = "disk";
  frame.disk_inner = q.disk_inner;
  frame.disk_outer = q.disk_outer;
  frame.disk_retrograde = q.disk_retrograde;
  frame.camera.theta_degrees = q.inclination_degrees;
  frame.camera.width = frame.camera.height = 1;
  const CheckedRequest checked = check_request(frame);
  const ThinDisk& disk = checked.scene.disk;
  q.disk_inner = disk.r_in;
  const DiskEmissivity emissivity = disk_emissivity(q.light, what);
  KerrMetric metric;
  metric.mass = q.metric.mass;
  metric.spin = q.metric.name == "kerr" ? q.metric.spin : 0.0;
  const double inclination = q.inclination_degrees * std::numbers::pi / 180.0;
  const std::string spin = q.metric.name == "kerr" ? shortest_number_text(q.metric.spin) : "0";
  return CheckedDistantDisk{
      disk,
      refusal_as_request_error("",
                               [&] {
                                 return KerrDiskMap(metric, kObserverDistance * metric.mass, inclination, disk.r_in,
                                                    disk.r_out, disk.sense);
                               }),
      emissivity,
      "--metric " + q.metric.name + " (spin " + spin + ", mass " + shortest_number_text(q.metric.mass) +
          "), inclination " + shortest_number_text(q.inclination_degrees) + " deg, disk " +
          shortest_number_text(disk.r_in) + " .. " + shortest_number_text(disk.r_out) + " M, " +
          (disk.sense > 0 ? "gas towards +phi" : "gas towards -phi") + ", " + describe_disk_light(q.light)};
}

/// Runs `work` on `threads` OpenMP threads (0: as many as there are), the setting restored after; its seconds.
template <class F>
double timed_on_threads(int threads, F&& work) {
#ifdef _OPENMP
  const int threads_before = omp_get_max_threads();
  if (threads > 0) omp_set_num_threads(threads);
#else
  (void)threads;
#endif
  const auto start = std::chrono::steady_clock::now();
  work();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
#ifdef _OPENMP
  omp_set_num_threads(threads_before);
#endif
  return seconds;
}

/// The report entries both commands end with: the disk and the tracer.
void add_disk_entries(std::vector<ReportEntry>& report, const DistantDisk& q, const ThinDisk& disk) {
  report.push_back({"inclination_degrees", q.inclination_degrees});
  report.push_back({"disk_inner", disk.r_in});
  report.push_back({"disk_outer", disk.r_out});
  report.push_back({"disk", std::string(q.light.transparent ? "transparent" : "opaque")});
  report.push_back({"tracer", std::string("kerr-closed-form")});
}

}  // namespace

LineProfileResult line_profile(const LineProfileRequest& in) {
  LineProfileResult out;
  out.request = in;
  LineProfileRequest& q = out.request;
  const CheckedDistantDisk d = check_distant_disk(q.disk, "--spectrum line");

  LineProfileSpec spec;
  spec.line_energy = q.line_energy;
  spec.bins = q.bins;
  if (q.energy_range) spec.energy_min = (*q.energy_range)[0], spec.energy_max = (*q.energy_range)[1];
  spec.emissivity = d.emissivity;
  spec.transparent = q.disk.light.transparent;
  LineSampling sampling;
  sampling.finest_cell = q.finest_cell;
  refusal_as_request_error("", [&] { check_line_profile(spec, sampling); });

  out.seconds = timed_on_threads(q.disk.threads, [&] { out.profile = line_profile(d.map, spec, sampling); });

  const LineProfile& p = out.profile;
  out.csv = line_profile_csv(
      p, {"line profile of a thin disk: " + d.description, "line energy " + shortest_number_text(q.line_energy),
          "flux: F_E per unit energy, in eps(r = M) M^2 (a distant observer's flux times D^2 / M^2); orders n = 0, "
          "1, 2, >= 3 sum to it",
          std::to_string(p.rays) + " rays, " + std::to_string(p.triangles) + " triangles"});
  out.chart = line_profile_chart(p, q.line_energy);

  auto add = [&](const std::string& key, ReportEntry::Counts::value_type::second_type v) {
    out.report.push_back({key, v});
  };
  auto add_number = [&](const std::string& key, double v) { out.report.push_back({key, v}); };
  add_number("seconds", out.seconds);
  add("rays", p.rays);
  add("triangles", p.triangles);
  add("unresolved_triangles", p.unresolved);
  add("uncovered_rays", p.uncovered);
  add_number("total_flux", p.total);
  add_number("total_flux_n0", p.total_by_order[0]);
  add_number("total_flux_n1", p.total_by_order[1]);
  add_number("total_flux_n2", p.total_by_order[2]);
  add_number("total_flux_n3_up", p.total_by_order[3]);
  add_number("flux_outside_bins", p.outside);
  add_number("energy_min", p.edges.front());
  add_number("energy_max", p.edges.back());
  add("energy_bins", static_cast<long>(q.bins));
  add_disk_entries(out.report, q.disk, d.disk);
  return out;
}

RingImageResult ring_image(const RingImageRequest& in) {
  RingImageResult out;
  out.request = in;
  RingImageRequest& q = out.request;
  const CheckedDistantDisk d = check_distant_disk(q.disk, "--rings");
  RingImageSpec spec;
  spec.width = q.width;
  spec.height = q.height;
  spec.half_width = q.field;
  spec.emissivity = d.emissivity;
  spec.redshift_power = q.redshift_power;
  spec.transparent = q.disk.light.transparent;
  spec.ring_cuts = q.cuts;
  const RingImageSampling sampling;
  refusal_as_request_error("", [&] { check_ring_image(spec, sampling); });

  out.seconds = timed_on_threads(q.disk.threads, [&] { out.rings = ring_image(d.map, spec, sampling); });

  const RingImage& r = out.rings;
  out.image = ring_image_channels(r);
  out.orders = ring_orders_picture(r);
  const std::optional<SourceScale> scale =
      q.source ? std::optional(*q.source == "m87" ? SourceScale::m87() : SourceScale::sgr_a()) : std::nullopt;
  const double uas = scale ? scale->microarcseconds_per_m() / q.disk.metric.mass : 0.0;  // per M of length

  auto add = [&](const std::string& key, long v) { out.report.push_back({key, v}); };
  auto add_number = [&](const std::string& key, double v) { out.report.push_back({key, v}); };
  add("width", static_cast<long>(q.width));
  add("height", static_cast<long>(q.height));
  add_number("seconds", out.seconds);
  add("rays", r.rays);
  add("triangles", r.triangles);
  add("ring_cuts", static_cast<long>(r.rings.cut_angle.size()));
  add_number("field_half_width", r.half_width);
  add_number("pixel", r.pixel);
  for (std::size_t o = 0; o < RingImage::kOrderChannels; ++o)
    add_number(std::string("flux_") + kOrderNames[o], r.flux[o]);
  for (std::size_t n = 1; n < RingImage::kOrderChannels; ++n) {
    add_number("ring_diameter_n" + std::to_string(n), r.rings.diameter[n]);
    add_number("ring_width_n" + std::to_string(n), r.rings.width[n]);
  }
  if (scale) {
    out.report.push_back({"source", *q.source});
    add_number("microarcseconds_per_m", uas);
    for (std::size_t n = 1; n < RingImage::kOrderChannels; ++n) {
      add_number("ring_diameter_n" + std::to_string(n) + "_uas", r.rings.diameter[n] * uas);
      add_number("ring_width_n" + std::to_string(n) + "_uas", r.rings.width[n] * uas);
    }
  }
  add_number("redshift_power", q.redshift_power);
  add_disk_entries(out.report, q.disk, d.disk);

  out.image.metadata["ring_image"] = "photon ring by order of a thin disk: " + d.description;
  out.image.metadata["ring_units"] = "I: g^" + shortest_number_text(q.redshift_power) +
                                     " eps(r), eps(r = M) = 1, each pixel's mean; lengths in M (pixel " +
                                     shortest_number_text(r.pixel) + " M)";
  std::ostringstream rings;
  rings.precision(8);
  for (std::size_t n = 1; n < RingImage::kOrderChannels; ++n)
    rings << (n > 1 ? "; " : "") << "n" << n << ": diameter " << r.rings.diameter[n] << " M, width " << r.rings.width[n]
          << " M, flux " << r.flux[n];
  out.image.metadata["ring_sizes"] = rings.str();
  return out;
}

}  // namespace grtrace::app
