// grtrace/trace/geodesic_tracer.hpp
// Traces one geodesic (null or timelike) through a metric with a chosen tableau and step controller.
//
// Takes:   the initial state (x^mu, k^mu), settings, and any number of user events: callables
//          g(const GeodesicState&) -> double that are positive outside a surface and <= 0 on or inside it.
// Returns: a TraceResult with the status (captured, escaped, hit, max_steps, step_underflow, non_finite),
//          the final state (on the surface that ended the ray: bracketed on the dense output, then refined on
//          the integrator's step map, see refine_located), the counts of accepted/rejected steps and
//          right-hand-side evaluations (refinement steps included), and the drift of g(k, k).
// Assumes: the ray starts inside the escape sphere and outside the horizon guard (else it ends at once), except
//          in a horizon-penetrating chart that says the ray comes out of the hole (metric/metric_traits.hpp
//          leaves_interior: a camera inside the horizon): the guard then takes effect once the ray is outside it.
// Termination surfaces are events like any other: horizon guard r = (1 + eps) r_cap (r_cap: the metric's
// horizon_radius(), or its capture_radius(y0) where that depends on the ray's time direction), sky sphere r = R.
// An observer, if given, sees every accepted step (and the last, cut at the surface) with the integrator's
// dense output, so paths can be drawn as smooth curves (the last drawn point, dense(theta), differs from the
// refined final state by the interpolant's error).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/optional.hpp"
#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"
#include "grtrace/integrate/event_locator.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/trace/geodesic_system.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <type_traits>
#include <utility>

namespace grtrace {

struct TraceSettings {
  IntegratorSettings integrator{};
  double initial_step = 0.0;      ///< <= 0: chosen automatically (adaptive) ; the step itself for FixedStep
  int max_steps = 100000;         ///< accepted steps before the ray ends as max_steps
  double escape_radius = 1000.0;  ///< the ray has escaped when radius(x) >= this
  double horizon_epsilon = 1e-3;  ///< captured when r <= (1 + eps) r_h (Schwarzschild coordinates never cross r_h)
  /// Constraint guard: the ray ends as non_finite when |g(k,k) - g(k0,k0)| exceeds this fraction of the size of
  /// g(k,k)'s terms (sum |g_mn k^m k^n|) or, for an adaptive step, kConstraintGuardPerTolerance times the
  /// integrator's rtol where that is larger (constraint_guard). The numbers then no longer describe a geodesic
  /// (typically a fixed step too large near the horizon, where k^t grows without bound). <= 0 switches the guard off.
  double constraint_tolerance = 1e-2;
  /// An adaptive step at rtol lets the constraint drift by up to about rtol, and a ray's drift is largest where
  /// its terms are (a pass by the polar axis, L^2 / sin^2 theta): a fixed 1e-2 ended good rays at loose tolerances
  /// (a Kerr torus frame of 65,536 rays in Mino time: 93 non_finite at rtol 1e-3, 19,411 at 1e-2, 2 at 1e-3 still
  /// with a guard of 300 rtol; with the guard off each of them was as accurate as the rest of its frame).
  static constexpr double kConstraintGuardPerTolerance = 1e3;
  /// The guard's threshold (see constraint_tolerance) for an adaptive step or, adaptive false, a fixed one (no
  /// tolerance: constraint_tolerance itself); <= 0: off. No default: a fixed step's caller must not get the
  /// adaptive threshold by omission.
  GRTRACE_HD double constraint_guard(bool adaptive) const {
    if (!(constraint_tolerance > 0.0) || !adaptive) return constraint_tolerance;
    const double scaled = kConstraintGuardPerTolerance * integrator.tolerance.rtol;
    return scaled > constraint_tolerance ? scaled : constraint_tolerance;
  }
  /// Where a surface crossing ends the ray: true, on the integration's own step map (re-taking the step that
  /// contains it, shortened to end there: as accurate as the integration, a few steps per crossing); false,
  /// on the step's interpolant only (cheaper, but cubic Hermite for tableaux without their own dense output).
  bool refine_events = true;
  /// The same for the sky sphere alone. A scene tracer that continues escaped rays exactly from the last accepted
  /// step (AngleCorrection::exact) reads only the redshift at the sphere, for which the interpolant is ample, and
  /// switches this off to save the refinement steps on every escaping ray.
  bool refine_escape = true;
  /// The constraint guard is checked every this many accepted steps, and always where the ray ends (a surface,
  /// max_steps, a step underflow), so a ray that went bad still ends as non_finite, at most this many steps later
  /// than with a check after every step; its verdict on every other ray is the same. The guard is a
  /// detector of a lost geodesic (a fixed step too large near the horizon, where k^t and the drift grow without
  /// bound within a few steps), not a correction, and a check costs a 4x4 metric (about as much as a right-hand
  /// side): 1 restores the check after every step.
  int constraint_check_interval = 8;
};

struct TraceResult {
  RayStatus status = RayStatus::max_steps;
  GeodesicState final_state = GeodesicState::Zero();
  GeodesicState step_end_state = GeodesicState::Zero();  ///< end of the last accepted step (y0 if none)
  double lambda = 0.0;           ///< affine parameter at the end
  int accepted = 0;
  int rejected = 0;
  long rhs_evals = 0;             ///< all of them, the refinement steps' included
  long refinement_evals = 0;      ///< of rhs_evals, those spent refining crossings (see refine_located)
  double constraint_drift = 0;   ///< g(k,k) at the end minus g(k,k) at the start
  int hit_event = -1;            ///< index of the user event that ended the ray (status hit)
  int chart_wraps = 0;           ///< times the ray crossed the polar axis of a spherical chart (see wrap_polar_axis)
  /// Times the ray crossed the equatorial plane before its end: the order n of the image it ends on (0 direct,
  /// 1 the first ring, ...). A hit on the plane itself (a thin disk) is not counted: it is the (n+1)-th crossing.
  /// -1 where the system does not say where the plane is (GeodesicSystem's optional equatorial_latitude).
  int crossings = -1;
};

/// Optional: how many interior points of each step an event samples (to catch a surface entered and left
/// within one step). Events declare `static constexpr int interior_samples = n;`; default 0.
template <class E>
constexpr GRTRACE_HD int event_interior_samples() {
  if constexpr (requires { E::interior_samples; }) return E::interior_samples;
  else return 0;
}

/// Optional: `static constexpr bool two_sided = true;` makes any sign change of g a crossing (a surface with no
/// inside, such as a thin disk: g = cos theta); the ray may start on either side.
template <class E>
constexpr GRTRACE_HD bool event_is_two_sided() {
  if constexpr (requires { E::two_sided; }) return E::two_sided;
  else return false;
}

/// Optional: `bool accepts(const GeodesicState&) const` filters located crossings (e.g. the disk's plane is
/// crossed but outside its radii); a refused crossing does not end the ray.
template <class E>
GRTRACE_HD bool event_accepts(const E& e, const GeodesicState& y) {
  if constexpr (requires { { e.accepts(y) } -> std::convertible_to<bool>; }) return e.accepts(y);
  else return true;
}

struct NullObserver {
  template <class Integrator>
  GRTRACE_HD void operator()(const Integrator&, double /*theta_end*/) const {}
};

namespace detail {
template <class Tuple, class F>
GRTRACE_HD void for_each_event(const Tuple& events, F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(I, std::get<I>(events)), ...);
  }(std::make_index_sequence<std::tuple_size_v<Tuple>>{});
}

inline GRTRACE_HD RayStatus status_of(std::size_t event_index) {
  if (event_index == 0) return RayStatus::captured;
  if (event_index == 1) return RayStatus::escaped;
  return RayStatus::hit;
}

/// Where refine_located puts a crossing: the step fraction and the state there.
template <class State>
struct LocatedCrossing {
  double theta;
  State z;
};

// Moves a crossing located on the dense output onto the integrator's own step map, so that a hit is as
// accurate as the integration and not only as its interpolant (cubic Hermite for tableaux without their own
// is ~1e-5 M off on the long steps of a high-order method at tight tolerance).
// Takes:   the integrator right after the accepted step that contains the crossing, the system (its right-hand
//          side), the oriented event on the dense output (g_dense(theta) = side * e(dense(theta))), the event on
//          the integrated state (g_state(z) = side * e(geodesic_state(z))) and the dense crossing c.
// Returns: the crossing's step fraction and state on the step map, found by refine_crossing (secant from
//          c.theta with g_dense's slope there); its last, tiny correction is applied to first order,
//          z + dtheta h f(z), for one right-hand side instead of another step. Typically 1 step + 1 evaluation
//          with a tableau's own interpolant, 2 steps + 1 with Hermite; a step costs (stages - 1) right-hand
//          sides (3 (stages - 1) + 1 for step doubling); all counted in rhs_evals. The dense crossing itself
//          when refinement is off (refine: settings().refine_events, refine_escape) or impossible (c is at
//          theta = 0 or non-finite, or the step map is non-finite there).
// Assumes: c came from locate_first_crossing on this step.
template <class Integrator, class System, class GDense, class GState>
GRTRACE_GPU_CALLED GRTRACE_HD LocatedCrossing<typename System::State> refine_located(
    Integrator& integ, const System& system, const GDense& g_dense, const GState& g_state, const EventCrossing& c,
    bool refine) {
  using State = typename System::State;
  if (!refine || !(c.theta > 0.0) || !std::isfinite(c.value)) return {c.theta, integ.dense(c.theta)};
  // The interpolant's slope at the crossing (central difference; it is a polynomial in theta), for the first
  // secant correction.
  constexpr double delta = 1e-4;
  const double lo = std::max(0.0, c.theta - delta), hi = std::min(1.0, c.theta + delta);
  const double slope0 = (g_dense(hi) - g_dense(lo)) / (hi - lo);
  auto probe = [&](double t) {
    State z = integ.step_from_previous(system, t);
    return Probed<State>{g_state(z), std::move(z)};
  };
  const auto refined = refine_crossing(probe, c.theta, slope0);
  if (!refined) return {c.theta, integ.dense(c.theta)};
  if (refined->pending == 0.0) return {refined->theta, refined->payload};
  const State& z_probed = refined->payload;
  const State z = z_probed + (refined->pending * integ.last_step()) * integ.evaluate(system, z_probed);
  if (!all_finite(z)) return {refined->theta, refined->payload};
  return {refined->theta + refined->pending, z};
}
}  // namespace detail

/// What the tracing loop carries from one accepted step to the next besides the integrator: each surface's value at
/// the last accepted point, whether the horizon guard is armed, the steps since the last constraint check, the side
/// of the equatorial plane the ray was last seen on, and the counts TraceResult reports (chart wraps, right-hand
/// sides spent refining crossings, crossings of the equatorial plane).
template <std::size_t K>
struct TraceProgress {
  std::array<double, K> g_prev{};
  bool guard_armed = true;
  int steps_since_check = 0;
  int chart_wraps = 0;
  long refinement_evals = 0;
  double latitude_prev = 0.0;  ///< equatorial_latitude at the last accepted point off the plane (0: none yet)
  int crossings = 0;
};

/// The tracing loop of one ray through a geodesic system (trace/geodesic_system.hpp), split into its start, its
/// steps from any accepted point, and the test a batched lane needs (trace/batched_trace.hpp): whether an accepted
/// step leaves the loop anything to do. trace_geodesic_system below is begin() then run().
/// Slots 0 and 1 of the event list are the horizon guard and the sky sphere, both read off the system's radial
/// coordinate rho(r) (increasing in r); the others are the user's events on geodesic_state(z).
/// Holds references to the settings and the events: they must outlive it (one trace call).
template <ExplicitTableau Tableau, StepController Controller, GeodesicSystem System, class... Events>
class TraceLoop {
  struct RadiusSlot {};  // placeholder in the event list for the two radial surfaces

 public:
  using Integrator = ControlledIntegrator<Tableau, Controller, System::dimension>;
  using State = typename System::State;
  static constexpr std::size_t K = 2 + sizeof...(Events);
  using Progress = TraceProgress<K>;

  /// Takes the system built for this ray, the settings, the capture radius r_cap of the ray (<= 0: no horizon,
  /// e.g. flat space or a wormhole) and the events.
  GRTRACE_HD TraceLoop(const System& system, const TraceSettings& settings, double r_capture, const Events&... events)
      : system_(system),
        settings_(settings),
        all_(RadiusSlot{}, RadiusSlot{}, events...),
        has_horizon_(r_capture > 0.0),
        rho_guard_(system.radial_coordinate_at((1.0 + settings.horizon_epsilon) * r_capture)),
        rho_escape_(system.radial_coordinate_at(settings.escape_radius)) {}

  GRTRACE_HD const System& system() const { return system_; }

  /// Prepares the progress for a ray starting at z0 and starts the integrator there. A ray that starts inside the
  /// guard and comes out (leaves_interior: a camera inside the hole, in a chart that penetrates the horizon) is
  /// not captured there: its guard is armed once it is outside (a ray that then falls back in is captured as any
  /// other). Returns the result when the ray ends at its start (non-finite, or on the wrong side of a surface).
  GRTRACE_HD Optional<TraceResult> begin(const State& z0, bool leaves_interior, Progress& p, Integrator& integ) const {
    p = Progress{};
    note_latitude(z0, p);
    p.guard_armed = !(has_horizon_ && !(system_.radial_coordinate(z0) > rho_guard_) && leaves_interior);
    detail::for_each_event(all_, [&](std::size_t i, const auto& e) { p.g_prev[i] = on_state(i, e, z0, p); });
    if (!all_finite(z0)) return finish(RayStatus::non_finite, z0, 0.0, integ, p);
    for (std::size_t i = 0; i < K; ++i)
      if (!two_sided(i) && !(p.g_prev[i] > 0.0)) return finish(detail::status_of(i), z0, 0.0, integ, p, i);
    State z = z0;
    align_with_axis(z);  // a start at a pass by the axis (a camera on the axis): the surfaces' sides are z0's
    integ.start(system_, z, settings_.initial_step);
    return no_value;
  }

  /// Integrates from the integrator's current (accepted) point until a surface, a failure or max_steps ends the
  /// ray; the step count goes on from integ.accepted(). The observer sees every accepted step.
  template <class Observer>
  GRTRACE_HD TraceResult run(Integrator& integ, Progress& p, Observer&& observer) const {
    while (integ.accepted() < settings_.max_steps)
      if (auto ended = step(integ, p, observer)) return *ended;
    return out_of_steps(integ, p);
  }

  /// One accepted step of run() and what follows it (surfaces, guards, the chart): the result when it ends the
  /// ray, nothing when the ray goes on (a caller that stops at integ.accepted() == max_steps ends it with
  /// out_of_steps).
  template <class Observer>
  GRTRACE_HD Optional<TraceResult> step(Integrator& integ, Progress& p, Observer&& observer) const {
    const int check_interval = std::max(1, settings_.constraint_check_interval);
    const StepOutcome outcome = integ.advance(system_);
    if (outcome != StepOutcome::ok) {
      // An underflow where the right-hand side itself is not finite (e.g. a start on the polar axis of a
      // spherical chart, where cot(theta) diverges) is a non-finite ray, not a step-size problem.
      // A state that fails the constraint guard (not checked since the last interval) is non_finite too.
      const bool rhs_finite = outcome == StepOutcome::step_underflow && all_finite(system_(integ.state())) &&
                              !(p.steps_since_check > 0 && violated(integ.state()));
      return finish(rhs_finite ? RayStatus::step_underflow : RayStatus::non_finite, integ.state(), integ.lambda(),
                    integ, p);
    }
    // The earliest surface crossed inside this step ends the ray.
    double theta_first = std::numeric_limits<double>::infinity();
    State z_first = State::Zero();
    std::size_t first = K;
    // The horizon and the sky sphere test the same radial coordinate: computed once per step (a square root or
    // two for Kerr-Schild).
    const double rho_now = system_.radial_coordinate(integ.state());
    detail::for_each_event(all_, [&](std::size_t i, const auto& e) {
      const double g1 = i < 2 ? radial_event(i, rho_now, p) : on_state(i, e, integ.state(), p);
      // Two-sided surfaces are seen from the side the step starts on (a start exactly on it does not count).
      const double side = two_sided(i) && p.g_prev[i] < 0.0 ? -1.0 : 1.0;
      if (!needs_location(i, p.g_prev[i], g1)) {
        p.g_prev[i] = g1;
        return;
      }
      auto g_state = [&](const State& z) { return side * on_state(i, e, z, p); };
      auto g_of_theta = [&](double t) { return g_state(integ.dense(t)); };
      // Bracketed on the dense output (cheap), then refined on the step map (a few steps); a crossing the
      // dense output puts after an already accepted one is not refined: it cannot end the ray.
      if (auto c = locate_first_crossing(g_of_theta, side * p.g_prev[i], side * g1, samples(i));
          c && c->theta < theta_first) {
        const long evals_before = integ.rhs_evals();
        const bool refine = settings_.refine_events && (i != 1 || settings_.refine_escape);  // 1: the sky sphere
        const auto [theta_hit, z_hit] = detail::refine_located(integ, system_, g_of_theta, g_state, *c, refine);
        p.refinement_evals += integ.rhs_evals() - evals_before;
        if (theta_hit < theta_first && event_accepts(e, system_.geodesic_state(z_hit))) {
          theta_first = theta_hit;
          z_first = z_hit;
          first = i;
        }
      }
      p.g_prev[i] = g1;
    });
    if (first < K) {
      observer(integ, theta_first);
      const double lambda_hit = integ.previous_lambda() + theta_first * integ.last_step();
      if (violated(z_first)) return finish(RayStatus::non_finite, z_first, lambda_hit, integ, p);
      return finish(detail::status_of(first), z_first, lambda_hit, integ, p, first);
    }
    if (!p.guard_armed && rho_now > rho_guard_) {  // out of the hole: from here on a fall back inside is a capture
      p.guard_armed = true;
      p.g_prev[0] = rho_now - rho_guard_;
    }
    if (++p.steps_since_check >= check_interval) {
      p.steps_since_check = 0;
      if (violated(integ.state())) return finish(RayStatus::non_finite, integ.state(), integ.lambda(), integ, p);
    }
    observer(integ, 1.0);
    note_latitude(integ.state(), p);
    State z = integ.state();
    const bool wrapped = system_.wrap_chart(z);
    if (wrapped) ++p.chart_wraps;
    if (align_with_axis(z) || wrapped) {
      integ.reseat(system_, z);
      detail::for_each_event(all_, [&](std::size_t i, const auto& e) { p.g_prev[i] = on_state(i, e, z, p); });
    }
    return no_value;
  }

  /// The end of a ray that used its max_steps steps (a last constraint check, then max_steps).
  GRTRACE_HD TraceResult out_of_steps(const Integrator& integ, const Progress& p) const {
    if (p.steps_since_check > 0 && violated(integ.state()))
      return finish(RayStatus::non_finite, integ.state(), integ.lambda(), integ, p);
    return finish(RayStatus::max_steps, integ.state(), integ.lambda(), integ, p);
  }

  /// The system's optional equatorial_latitude (trace/geodesic_system.hpp): a change of side since the last
  /// accepted point off the plane is a crossing. A step crosses the plane at most once where it matters: a second
  /// crossing takes half an orbit, far longer than the steps near the hole, and a ray far away is a straight line.
  static constexpr bool counts_crossings = requires(const System s, const State z) {
    { s.equatorial_latitude(z) } -> std::convertible_to<double>;
  };
  /// Moves p's count of crossings on to the accepted point z (step() does it; a caller that resumes the
  /// integration inside the last step, trace/emission_system.hpp, counts from its progress before the step).
  GRTRACE_HD void note_latitude(const State& z, Progress& p) const {
    if constexpr (counts_crossings) {
      const double latitude = system_.equatorial_latitude(z);
      if (!(std::abs(latitude) > kOnEquatorialPlane)) return;
      if (latitude * p.latitude_prev < 0.0) ++p.crossings;
      p.latitude_prev = latitude;
    }
  }

  /// For a step taken outside run() (a batched lane) from an accepted point with progress p to the accepted point
  /// z: true when run() would do nothing after it but go on (no surface to locate, no constraint check that fails,
  /// no change of the guard or the chart); p then moves on to z exactly as run() would move it. False leaves p
  /// as it was: the step must be taken again by run() from its start, which then does what is due.
  GRTRACE_HD bool uneventful(const State& z, Progress& p) const {
    if (!p.guard_armed) return false;
    std::array<double, K> g{};
    bool quiet = true;
    const double rho = system_.radial_coordinate(z);
    detail::for_each_event(all_, [&](std::size_t i, const auto& e) {
      g[i] = i < 2 ? radial_event(i, rho, p) : on_state(i, e, z, p);
      quiet = quiet && !needs_location(i, p.g_prev[i], g[i]);
    });
    if (!quiet) return false;
    const bool check_due = p.steps_since_check + 1 >= std::max(1, settings_.constraint_check_interval);
    if (check_due && violated(z)) return false;
    if (State wrapped = z; system_.wrap_chart(wrapped) || align_with_axis(wrapped)) return false;
    p.g_prev = g;
    p.steps_since_check = check_due ? 0 : p.steps_since_check + 1;
    note_latitude(z, p);
    return true;
  }

 private:
  // Functions, not static arrays: device code cannot read a host variable (core/host_device.hpp).
  static GRTRACE_HD constexpr int samples(std::size_t i) {
    constexpr std::array<int, K> all = {0, 0, event_interior_samples<Events>()...};
    return all[i];
  }
  static GRTRACE_HD constexpr bool two_sided(std::size_t i) {
    constexpr std::array<bool, K> all = {false, false, event_is_two_sided<Events>()...};
    return all[i];
  }

  // True when the step from g_prev to g1 may cross surface i (a sign change, or interior samples to look at).
  static GRTRACE_HD bool needs_location(std::size_t i, double g_prev, double g1) {
    const double side = two_sided(i) && g_prev < 0.0 ? -1.0 : 1.0;
    return !((two_sided(i) && g_prev == 0.0) || (side * g1 > 0.0 && samples(i) == 0));
  }
  // The horizon (slot 0) and the sky sphere (slot 1) at the radial coordinate rho.
  GRTRACE_HD double radial_event(std::size_t i, double rho, const Progress& p) const {
    if (i == 0) return has_horizon_ && p.guard_armed ? rho - rho_guard_ : 1.0;
    return rho_escape_ - rho;
  }
  // The system's optional align_with_axis (a ray that passes a chart's axis closer than it resolves, moved onto
  // its parallel through the axis: MetricGeodesicSystem); true when it changed z.
  GRTRACE_HD bool align_with_axis(State& z) const {
    if constexpr (requires { { system_.align_with_axis(z) } -> std::same_as<bool>; }) return system_.align_with_axis(z);
    else return false;
  }
  // Every event on the integrated state: the two radial ones on its rho, the others on its (x, k).
  template <class E>
  GRTRACE_HD double on_state(std::size_t i, const E& e, const State& z, const Progress& p) const {
    if constexpr (std::is_same_v<E, RadiusSlot>) return radial_event(i, system_.radial_coordinate(z), p);
    else return e(system_.geodesic_state(z));
  }
  GRTRACE_HD bool violated(const State& z) const {
    const double guard = settings_.constraint_guard(Controller::estimate != ErrorEstimate::none);
    return guard > 0.0 && system_.constraint_violation(z) > guard;
  }
  // The result of a ray that ends at z (event: the surface that ended it, for status hit).
  GRTRACE_GPU_CALLED GRTRACE_HD TraceResult finish(RayStatus status, const State& z, double lambda,
                                                   const Integrator& integ, const Progress& p,
                                                   std::size_t event = 0) const {
    TraceResult result;
    result.status = status;
    if (status == RayStatus::hit) result.hit_event = static_cast<int>(event) - 2;
    result.chart_wraps = p.chart_wraps;
    if constexpr (counts_crossings) {
      Progress end = p;
      note_latitude(z, end);  // a crossing inside the last step, before the surface that ended it
      result.crossings = end.crossings;
    }
    result.refinement_evals = p.refinement_evals;
    result.final_state = system_.geodesic_state(z);
    result.step_end_state = integ.accepted() > 0 ? system_.geodesic_state(integ.state()) : result.final_state;
    result.lambda = lambda;
    result.accepted = integ.accepted();
    result.rejected = integ.rejected();
    result.rhs_evals = integ.rhs_evals();
    result.constraint_drift = system_.constraint_drift(z);
    return result;
  }

  System system_;
  const TraceSettings& settings_;
  std::tuple<RadiusSlot, RadiusSlot, const Events&...> all_;
  bool has_horizon_;
  double rho_guard_, rho_escape_;
};

/// The tracing loop, for any geodesic system (trace/geodesic_system.hpp): integrates z0 until the horizon guard,
/// the sky sphere or one of the events ends it (see the top of this file for the statuses and the guard).
/// Takes:   the system built for this ray, the settings, a controller, z0, the capture radius r_cap of the ray
///          (<= 0: no horizon), whether a ray that starts inside the guard leaves the hole (its guard is then
///          armed once it is outside), an observer (called with the integrator; its dense output is in the
///          system's variables) and the events (on geodesic_state(z)).
/// Returns: the TraceResult, its states mapped to (x, k) by the system; lambda is the system's parameter.
/// The system is taken by value: a small local object, which the optimiser keeps in registers.
template <ExplicitTableau Tableau, StepController Controller, GeodesicSystem System, class Observer, class... Events>
GRTRACE_HD TraceResult trace_geodesic_system(const System system, const TraceSettings& settings,
                                             const Controller& controller, const typename System::State& z0,
                                             double r_capture, bool leaves_interior, Observer&& observer,
                                             const Events&... events) {
  using Loop = TraceLoop<Tableau, Controller, System, Events...>;
  const Loop loop(system, settings, r_capture, events...);
  typename Loop::Integrator integ(settings.integrator, controller);
  typename Loop::Progress progress;
  if (auto ended = loop.begin(z0, leaves_interior, progress, integ)) return *ended;
  return loop.run(integ, progress, observer);
}

/// The tracer of any metric policy: the geodesic equation (MetricGeodesicSystem) through trace_geodesic_system.
template <MetricPolicy Metric, ExplicitTableau Tableau, StepController Controller = PIController>
class GeodesicTracer {
 public:
  using Integrator = ControlledIntegrator<Tableau, Controller, 8>;

  GRTRACE_HD GeodesicTracer(Metric metric, TraceSettings settings, Controller controller = {})
      : metric_(metric), settings_(settings), controller_(controller) {}

  GRTRACE_HD const Metric& metric() const { return metric_; }
  GRTRACE_HD const TraceSettings& settings() const { return settings_; }
  GRTRACE_HD const Controller& controller() const { return controller_; }

  template <class... Events>
  GRTRACE_HD TraceResult trace(const GeodesicState& y0, const Events&... events) const {
    return trace_observed(y0, NullObserver{}, events...);
  }

  template <class Observer, class... Events>
  GRTRACE_HD TraceResult trace_observed(const GeodesicState& y0, Observer&& observer, const Events&... events) const {
    const MetricGeodesicSystem<Metric> system(metric_, y0);
    return trace_geodesic_system<Tableau>(system, settings_, controller_, y0, capture_radius_of(metric_, y0),
                                          leaves_interior_of(metric_, y0), observer, events...);
  }

 private:
  Metric metric_;
  TraceSettings settings_;
  Controller controller_;
};

}  // namespace grtrace
