// examples/work_precision/work_precision.hpp
// The measuring core of grtrace-work-precision (shared with tests/work_precision_test.cpp).
//
// A configuration is (tableau, controller, sweep point); the sweep point is a relative tolerance for the
// adaptive controllers (doubling, i, pi) and a fixed step in the affine parameter for `fixed`.
// run_configuration<T, C>() traces a fixed ray set whose answers are known exactly and returns one error per
// ray plus the cost (right-hand-side evaluations, accepted/rejected steps, wall time):
//   * impact rays: a photon from infinity with impact parameter b (near-critical 5.25 .. weak field 1000),
//     traced with measure_deflection (the legs outside the start sphere are added exactly); error =
//     |deflection - exact::deflection_angle(b)|. In Kerr (RaySet::kerr) the impact rays are equatorial photons in
//     Boyer-Lindquist coordinates, b > 0 moving towards +phi (prograde for a > 0) and b < 0 against it; error =
//     |deflection - exact::equatorial_deflection(b, a)| (Iyer & Hansen 2009). Kerr ray sets have no camera rays:
//     there is no exact answer for a general Kerr pixel.
//   * camera rays: the pixels of a static camera at radius r_c in Schwarzschild (theta = pi/2, phi = 0,
//     looking at the hole, up = +z), traced with GeodesicTracer to the sky sphere; the exact continuation
//     exact::asymptotic_direction at the exit is compared (exact::angular_distance) with
//     exact::asymptotic_direction at the camera, i.e. the whole ray is judged against the elliptic integral.
//     Captured rays must be captured by the exact verdict too.
// A wrong verdict (escaped/captured) or a failed ray (max_steps, step_underflow, non_finite) scores pi, the
// largest angular error there is, so a method that fails can never look accurate.
// The exact continuation of an escaped ray starts where the tracer reports its end (ExitPoint::surface, the
// sky-sphere crossing, refined on the integrator's step map: TraceSettings::refine_events) or at the last accepted node
// (ExitPoint::node).
#pragma once

#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/trace/deflection.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace grtrace::work_precision {

/// A static camera in Schwarzschild: where it is and how its pixels are laid out (DESIGN.md pixel formula).
struct StaticCamera {
  double radius = 50.0;  ///< r_c (M = 1 units)
  double fov_degrees = 90.0;
  int width = 32;
  int height = 32;
};

/// The initial state of pixel (x, y): camera at (r_c, pi/2, 0), static tetrad e_0 = dt / sqrt(f),
/// e_1 (forward, towards the hole) = -sqrt(f) dr, e_2 (up, +z) = -dtheta / r, e_3 (right, +y) = dphi / r;
/// k = (e_1 + u e_2 + s e_3) / sqrt(1 + u^2 + s^2) - e_0 with s = tan(F/2)(2x/(W-1) - 1),
/// u = tan(F/2)(2y/(H-1) - 1) H/W: past-directed, unit energy in the camera frame, traced outwards.
inline GeodesicState static_camera_pixel(const StaticCamera& cam, double mass, int x, int y) {
  const double r = cam.radius, f = 1.0 - 2.0 * mass / r, sf = std::sqrt(f);
  const double t = std::tan(0.5 * cam.fov_degrees * std::numbers::pi / 180.0);
  const double sx = cam.width > 1 ? t * (2.0 * x / (cam.width - 1) - 1.0) : 0.0;
  const double uy = cam.height > 1 ? t * (2.0 * y / (cam.height - 1) - 1.0) * cam.height / cam.width : 0.0;
  const double n = std::sqrt(1.0 + uy * uy + sx * sx);
  const Vec4 pos(0.0, r, std::numbers::pi / 2.0, 0.0);
  const Vec4 k(-1.0 / sf, -sf / n, -uy / (r * n), sx / (r * n));
  return make_state(pos, k);
}

struct ImpactRay {
  double b;
  double exact_deflection;  ///< exact::deflection_angle(b) (Kerr: equatorial_deflection); NaN when captured
};

struct CameraRay {
  GeodesicState y0;
  std::optional<exact::SkyDirection> exact;  ///< nothing: the exact verdict is "captured"
};

/// The fixed ray set every configuration is judged on; exact answers are computed once, here.
struct RaySet {
  SchwarzschildMetric metric{1.0};
  std::optional<KerrMetric> kerr;  ///< set: the impact rays are equatorial Kerr photons (and there are no pixels)
  double sky_radius = 400.0;  ///< escape sphere of the camera rays
  StaticCamera camera{};
  std::vector<ImpactRay> impacts;
  std::vector<CameraRay> pixels;

  std::size_t size() const { return impacts.size() + pixels.size(); }
};

/// Default impact parameters: near-critical (b_c = 5.196) to weak field.
inline std::vector<double> default_impacts() { return {5.25, 5.3, 5.5, 6.0, 7.0, 10.0, 20.0, 50.0, 100.0, 1000.0}; }

inline RaySet make_ray_set(const std::vector<double>& impacts, const StaticCamera& camera, double sky_radius,
                           double mass = 1.0) {
  RaySet set;
  set.metric = SchwarzschildMetric{mass};
  set.sky_radius = sky_radius;
  set.camera = camera;
  for (const double b : impacts) set.impacts.push_back({b, exact::deflection_angle(b, mass)});
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const GeodesicState y0 = static_camera_pixel(camera, mass, x, y);
      set.pixels.push_back({y0, exact::asymptotic_direction(y0, mass)});
    }
  return set;
}

/// Takes the spin a (|a| < 1, M = 1); returns the default Kerr impact parameters: for each sense, prograde
/// (b > 0 for a >= 0) and retrograde, the critical b_c times 1.02, 1.1, 1.3, 2, 4, 10, 100 (near-critical to weak
/// field, all escaping, whatever the spin). a = 0.9: +2.91 .. +285 and -6.97 .. -683.
inline std::vector<double> default_kerr_impacts(double spin) {
  std::vector<double> out;
  for (const double sense : {1.0, -1.0}) {
    const double bc = exact::equatorial_critical_impact(spin, spin < 0.0 ? -sense : sense);
    for (const double f : {1.02, 1.1, 1.3, 2.0, 4.0, 10.0, 100.0}) out.push_back(f * bc);
  }
  return out;
}

/// Takes signed impact parameters (each beyond the critical value of its sense: checked by the caller, since
/// exact::equatorial_deflection throws for a captured ray), the spin and the mass; returns a Kerr ray set: the
/// equatorial impact rays with their Iyer-Hansen deflections and no camera rays.
inline RaySet make_kerr_ray_set(const std::vector<double>& impacts, double spin, double mass = 1.0) {
  RaySet set;
  set.metric = SchwarzschildMetric{mass};
  set.kerr = KerrMetric::checked(mass, spin);
  set.camera.width = set.camera.height = 0;
  for (const double b : impacts) set.impacts.push_back({b, exact::equatorial_deflection(b, spin, mass)});
  return set;
}

/// What is swept: a relative tolerance (adaptive) or the affine step (fixed step).
struct SweepPoint {
  bool fixed_step = false;
  double rtol = 1e-8;
  double atol = 1e-10;
  double step = 0.0;  ///< fixed step h (fixed_step only)
};

/// Where the exact continuation to infinity starts: the located exit point on the sky sphere (what
/// TraceResult::final_state reports, refined on the step map) or the last accepted node beyond it.
enum class ExitPoint { surface, node };

struct RunOptions {
  int max_steps = 100000;  ///< per ray
  int threads = 1;         ///< OpenMP threads over rays (1: a clean single-core cost)
  int repeat = 1;          ///< the wall time is the best of this many runs
  ExitPoint exit = ExitPoint::surface;
};

/// One configuration's outcome.
struct RunStats {
  std::vector<double> impact_errors;  ///< one per impact ray (radians)
  std::vector<double> camera_errors;  ///< one per camera ray (radians; 0 for agreed captures)
  long rhs_evals = 0;
  long accepted = 0;
  long rejected = 0;
  int failures = 0;            ///< max_steps, step_underflow or non_finite
  int max_steps_hits = 0;      ///< of which max_steps
  int verdict_mismatches = 0;  ///< escaped where the exact answer is captured, or the reverse
  double seconds = 0.0;        ///< wall time
  double cpu_seconds = 0.0;    ///< processor time of all threads (robust against a busy machine)
};

inline constexpr double kWrongAnswer = std::numbers::pi;

namespace detail {
struct RayOutcome {
  double error = 0.0;
  long rhs_evals = 0;
  int accepted = 0, rejected = 0;
  bool failed = false, max_steps = false, mismatch = false;
};

inline RayOutcome bookkeeping(const TraceResult& r) {
  RayOutcome o;
  o.rhs_evals = r.rhs_evals;
  o.accepted = r.accepted;
  o.rejected = r.rejected;
  o.failed = is_failure(r.status);
  o.max_steps = r.status == RayStatus::max_steps;
  return o;
}

/// Keeps the last accepted integrator node. The tracer reports the end of a ray on the surface that ended it,
/// refined on the step map (TraceSettings::refine_events); the node past the surface is a true integration point,
/// and the exact continuation to infinity is valid from any point of the ray, so it can be applied there instead.
/// One observer type for both kinds of ray: each method compiles one tracer loop, not two.
struct LastNode {
  GeodesicState* node;
  template <class Integrator>
  void operator()(const Integrator& integ, double /*theta_end*/) const {
    *node = integ.state();
  }
};

/// Takes a tracer over SchwarzschildMetric or KerrMetric, an impact ray and the exit point; returns its outcome.
template <class Metric, ExplicitTableau T, StepController C>
RayOutcome impact_ray(const GeodesicTracer<Metric, T, C>& tracer, const ImpactRay& ray, ExitPoint exit) {
  GeodesicState node = GeodesicState::Zero();
  const LastNode observer{&node};
  const DeflectionResult d = measure_deflection(tracer, ray.b, observer);
  RayOutcome o = bookkeeping(d.trace);
  const bool exact_escapes = std::isfinite(ray.exact_deflection);
  if (o.failed) {
    o.error = kWrongAnswer;
  } else if ((d.trace.status == RayStatus::escaped) != exact_escapes) {
    o.mismatch = true;
    o.error = kWrongAnswer;
  } else if (exact_escapes) {
    // ExitPoint::node: the same bookkeeping as measure_deflection, from the last node.
    const double deflection = exit == ExitPoint::node
                                  ? deflection_through(tracer.metric(), ray.b, d.start_radius, node)
                                  : d.deflection;
    o.error = std::abs(deflection - ray.exact_deflection);
  }
  return o;
}

template <ExplicitTableau T, StepController C>
RayOutcome camera_ray(const GeodesicTracer<SchwarzschildMetric, T, C>& tracer, const CameraRay& ray, double mass,
                      ExitPoint exit) {
  GeodesicState node = GeodesicState::Zero();
  const LastNode observer{&node};
  const TraceResult r = tracer.trace_observed(ray.y0, observer);
  RayOutcome o = bookkeeping(r);
  if (o.failed) {
    o.error = kWrongAnswer;
    return o;
  }
  if (r.status == RayStatus::escaped) {
    const auto at_exit = exact::asymptotic_direction(exit == ExitPoint::node ? node : r.final_state, mass);
    if (!ray.exact || !at_exit) {
      o.mismatch = true;
      o.error = kWrongAnswer;
    } else {
      o.error = exact::angular_distance(*at_exit, *ray.exact);
    }
  } else if (ray.exact) {  // captured (or hit), but the exact ray escapes
    o.mismatch = true;
    o.error = kWrongAnswer;
  }
  return o;
}
}  // namespace detail

namespace detail {
/// Takes the ray set, a tracer over Metric (Schwarzschild: impact and camera rays; Kerr: impact rays only, the
/// camera-ray code is not instantiated for it) and the run options; returns the errors and costs, the best wall
/// time of options.repeat runs.
template <class Metric, ExplicitTableau T, StepController C>
RunStats run_rays(const RaySet& set, const GeodesicTracer<Metric, T, C>& tracer, const RunOptions& options) {
  constexpr bool kCamera = std::is_same_v<Metric, SchwarzschildMetric>;
  [[maybe_unused]] const double mass = set.metric.mass;

  const long n_impact = static_cast<long>(set.impacts.size());
  const long n_total = n_impact + static_cast<long>(set.pixels.size());
  RunStats best;
  for (int rep = 0; rep < std::max(1, options.repeat); ++rep) {
    RunStats s;
    s.impact_errors.assign(set.impacts.size(), 0.0);
    s.camera_errors.assign(set.pixels.size(), 0.0);
    long evals = 0, acc = 0, rej = 0;
    int fails = 0, caps = 0, mism = 0;
    const std::clock_t c0 = std::clock();
    const auto t0 = std::chrono::steady_clock::now();
#if defined(_OPENMP)
#pragma omp parallel for schedule(dynamic, 4) num_threads(std::max(1, options.threads)) \
    reduction(+ : evals, acc, rej, fails, caps, mism)
#endif
    for (long i = 0; i < n_total; ++i) {
      const bool is_impact = i < n_impact;
      RayOutcome o;
      if (is_impact) o = impact_ray(tracer, set.impacts[static_cast<std::size_t>(i)], options.exit);
      else if constexpr (kCamera)
        o = camera_ray(tracer, set.pixels[static_cast<std::size_t>(i - n_impact)], mass, options.exit);
      if (is_impact) s.impact_errors[static_cast<std::size_t>(i)] = o.error;
      else s.camera_errors[static_cast<std::size_t>(i - n_impact)] = o.error;
      evals += o.rhs_evals;
      acc += o.accepted;
      rej += o.rejected;
      fails += o.failed ? 1 : 0;
      caps += o.max_steps ? 1 : 0;
      mism += o.mismatch ? 1 : 0;
    }
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    s.cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    s.rhs_evals = evals;
    s.accepted = acc;
    s.rejected = rej;
    s.failures = fails;
    s.max_steps_hits = caps;
    s.verdict_mismatches = mism;
    if (rep == 0 || s.seconds < best.seconds) best = std::move(s);
  }
  return best;
}
}  // namespace detail

/// Traces the whole ray set (Schwarzschild, or Kerr when set.kerr is set) with tableau T and controller C at one
/// sweep point.
template <ExplicitTableau T, StepController C>
RunStats run_configuration(const RaySet& set, const SweepPoint& point, const RunOptions& options) {
  TraceSettings settings;
  settings.max_steps = options.max_steps;
  settings.integrator.tolerance = {point.rtol, point.atol};
  settings.initial_step = point.fixed_step ? point.step : 0.0;
  settings.escape_radius = set.sky_radius;
  if (set.kerr) return detail::run_rays(set, GeodesicTracer<KerrMetric, T, C>(*set.kerr, settings), options);
  return detail::run_rays(set, GeodesicTracer<SchwarzschildMetric, T, C>(set.metric, settings), options);
}


// ---- summaries and the CSV ---------------------------------------------------------------------------------

/// Max and median of a list of errors (NaN for an empty list).
struct ErrorSummary {
  double max = std::numeric_limits<double>::quiet_NaN();
  double median = std::numeric_limits<double>::quiet_NaN();
};

inline ErrorSummary summarize(std::vector<double> errors) {
  ErrorSummary s;
  if (errors.empty()) return s;
  std::sort(errors.begin(), errors.end());
  const std::size_t n = errors.size();
  s.max = errors.back();
  s.median = n % 2 ? errors[n / 2] : 0.5 * (errors[n / 2 - 1] + errors[n / 2]);
  return s;
}

/// One row of the CSV: a configuration and what it cost and achieved.
struct Record {
  std::string tableau, controller;
  int order = 0;
  SweepPoint point;
  ExitPoint exit = ExitPoint::surface;
  std::string metric = "schwarzschild";  ///< schwarzschild | kerr (set by the caller, like spin)
  double spin = 0.0;
  std::size_t rays = 0;
  ErrorSummary all, impact, camera;
  RunStats stats;
};

inline Record make_record(std::string_view tableau, std::string_view controller, int order, const SweepPoint& p,
                          ExitPoint exit, RunStats stats) {
  Record r;
  r.exit = exit;
  r.tableau = std::string(tableau);
  r.controller = std::string(controller);
  r.order = order;
  r.point = p;
  r.rays = stats.impact_errors.size() + stats.camera_errors.size();
  r.impact = summarize(stats.impact_errors);
  r.camera = summarize(stats.camera_errors);
  std::vector<double> all = stats.impact_errors;
  all.insert(all.end(), stats.camera_errors.begin(), stats.camera_errors.end());
  r.all = summarize(std::move(all));
  stats.impact_errors.clear();
  stats.camera_errors.clear();
  r.stats = std::move(stats);
  return r;
}

/// The CSV header; the columns are part of the tool's contract (tests check them).
inline constexpr std::string_view kCsvHeader =
    "tableau,controller,order,sweep,rtol,atol,step,exit,rays,max_error,median_error,max_error_impact,"
    "median_error_impact,max_error_camera,median_error_camera,rhs_evals,accepted,rejected,failures,"
    "verdict_mismatches,seconds,cpu_seconds,ns_per_step,metric,spin";

inline void write_csv(std::ostream& out, const std::vector<Record>& records) {
  out << kCsvHeader << '\n';
  auto num = [&](double v) -> std::ostream& {
    if (std::isfinite(v)) out << v;
    return out;
  };
  out.precision(10);
  for (const Record& r : records) {
    const auto& s = r.stats;
    const long steps = s.accepted + s.rejected;
    out << r.tableau << ',' << r.controller << ',' << r.order << ',' << (r.point.fixed_step ? "step" : "rtol") << ',';
    num(r.point.fixed_step ? std::numeric_limits<double>::quiet_NaN() : r.point.rtol) << ',';
    num(r.point.fixed_step ? std::numeric_limits<double>::quiet_NaN() : r.point.atol) << ',';
    num(r.point.fixed_step ? r.point.step : std::numeric_limits<double>::quiet_NaN()) << ',';
    out << (r.exit == ExitPoint::node ? "node" : "surface") << ',' << r.rays << ',';
    num(r.all.max) << ',';
    num(r.all.median) << ',';
    num(r.impact.max) << ',';
    num(r.impact.median) << ',';
    num(r.camera.max) << ',';
    num(r.camera.median) << ',';
    out << s.rhs_evals << ',' << s.accepted << ',' << s.rejected << ',' << s.failures << ',' << s.verdict_mismatches
        << ',';
    num(s.seconds) << ',';
    num(s.cpu_seconds) << ',';
    num(steps > 0 ? s.seconds * 1e9 / static_cast<double>(steps) : std::numeric_limits<double>::quiet_NaN());
    out << ',' << r.metric << ',' << r.spin << '\n';
  }
}

}  // namespace grtrace::work_precision
