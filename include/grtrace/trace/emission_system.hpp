// grtrace/trace/emission_system.hpp
// The light an emitting medium (medium/emitting_medium.hpp) sends along one camera ray, integrated with the ray
// itself: the geodesic equation of a metric (MetricGeodesicSystem) with two more variables, the intensity that
// reaches the camera and the optical depth from the camera, so that the step control bounds the intensity's error
// as it bounds the ray's (a step that skips a thin bright layer is rejected like one that misses a turn).
//
// Takes:   a metric, a medium, a camera ray y0 (x, k) as a camera makes it (k past-directed: traced from the camera
//          backwards), the energy of that photon measured by the camera, E_cam = |g(k0, u_cam)|, and the observed
//          frequency nu_obs.
// Returns: trace_emission: the ray's TraceResult (status, final state: as the geodesic tracer's) with
//          intensity   I_nu(nu_obs) at the camera = integral of g^3 j_nu(nu_obs / g) e^-tau dl
//          optical_depth  tau = integral of alpha_nu(nu_obs / g) dl, from the camera to where the ray ended
//          redshift    the emission-weighted g: integral of g dI over I (the shift of the light the camera sees, as
//                      a surface's g is; NaN where I = 0)
//          (the invariant intensity is intensity / nu_obs^3; with alpha = 0 it is conserved through empty space).
// Method:  along the backward ray, g = nu_obs / nu_fluid = E_cam / E_fluid with E_fluid = |g(k, u)| (u the fluid's
//          velocity), and the proper length the photon crosses in the fluid's frame is dl = E_fluid d lambda
//          (lambda the ray's affine parameter, k = dx / d lambda); emission at a point is dimmed by the optical
//          depth between it and the camera, which is what tau holds when the ray gets there. Beyond the medium's
//          outer radius both derivatives are 0 without asking the medium. A medium with a boundary (an edge where
//          j and alpha jump or kink) has every step end where the ray crosses it (detail::end_step_on_boundary).
// Opaque matter: where the medium absorbs, all derivatives are slowed by sigma = 1 / (1 + alpha r) (r the metric's
//          radius), so the ray's parameter s (ds = d lambda / sigma) advances about one unit of optical depth per
//          r / E of parameter at most. Without it a step could cross an optically thick layer in one go, its stages
//          seeing the gas only where e^-tau is already 0, and the light emitted in the layer (S times its g^3 at
//          the surface) would be lost while the error estimate, which compares two such sums, saw nothing. A ray
//          whose transmission e^-tau falls below min_transmission (default 1e-16: nothing behind it can show) ends
//          there, as RayStatus::hit (EmissionResult::opaque); with alpha = 0, sigma = 1 and the parameter is the
//          affine one.
// Assumes: the ray starts at the camera (tau = 0, I = 0 there); the horizon, the sky sphere and the settings end
//          it as they end any ray (trace/geodesic_tracer.hpp).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/integrate/step_controller.hpp"
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/tableau/butcher_tableau.hpp"
#include "grtrace/trace/geodesic_system.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grtrace {

/// A geodesic system (trace/geodesic_system.hpp) of eleven variables: the ray's (x, k), the camera's intensity, the
/// optical depth and the intensity weighted by g (see the top of this file). Holds the metric and the medium by
/// reference: they outlive the trace.
template <MetricPolicy Metric, class Medium>
struct EmissionSystem {
  static constexpr int dimension = 11;
  using State = Vector<11>;
  static constexpr int kIntensity = 8, kOpticalDepth = 9, kRedshiftWeight = 10;  ///< I_nu, tau, integral g dI

  MetricGeodesicSystem<Metric> ray;
  const Medium* medium;
  double camera_energy;   ///< E_cam = |g(k0, u_cam)|
  double frequency;       ///< nu_obs
  /// For a medium with a boundary: the side of it the current step is on (> 0 outside: no light there, whatever
  /// the medium's coefficients say; else the medium's coefficients, continued smoothly across its boundary), set
  /// by trace_emission between steps, which end on the boundary. Null: the coefficients everywhere.
  const int* boundary_side = nullptr;

  GRTRACE_HD EmissionSystem(const Metric& metric, const Medium& m, const GeodesicState& y0, double e_cam, double nu_obs)
      : ray(metric, y0), medium(&m), camera_energy(e_cam), frequency(nu_obs) {
    static_assert(check_emitting_medium<Medium, Metric>());
  }

  /// (y0, I = 0, tau = 0).
  GRTRACE_HD State initial_state(const GeodesicState& y0) const {
    State z = State::Zero();
    z.template head<8>() = y0;
    return z;
  }

  GRTRACE_HD State operator()(const State& z) const {
    const GeodesicState y = z.template head<8>();
    State dz;
    dz.template head<8>() = ray(y);
    dz[kIntensity] = dz[kOpticalDepth] = dz[kRedshiftWeight] = 0.0;
    const Vec4 x = y.head<4>(), k = y.tail<4>();
    if (boundary_side != nullptr) {  // the side of the boundary decides (no cut within a step: it is smooth)
      if (*boundary_side > 0) return dz;
    } else if (!(ray.metric->radius(x) <= medium->outer_radius())) {
      return dz;
    }
    const Vec4 u = medium->fluid_velocity(*ray.metric, x);
    const double e_fluid = std::abs(inner_product(*ray.metric, x, k, u));
    const double g = camera_energy / e_fluid;
    const MediumCoefficients c = medium_coefficients(*medium, *ray.metric, x, k, u, frequency / g);
    dz[kIntensity] = g * g * g * c.emission * std::exp(-z[kOpticalDepth]) * e_fluid;
    dz[kOpticalDepth] = c.absorption * e_fluid;
    dz[kRedshiftWeight] = g * dz[kIntensity];
    if (c.absorption > 0.0) dz *= 1.0 / (1.0 + c.absorption * ray.metric->radius(x));  // sigma (top of this file)
    return dz;
  }

  GRTRACE_HD double radius(const State& z) const { return ray.radius(head(z)); }
  GRTRACE_HD double radial_coordinate(const State& z) const { return ray.radial_coordinate(head(z)); }
  static GRTRACE_HD double radial_coordinate_at(double r) { return MetricGeodesicSystem<Metric>::radial_coordinate_at(r); }
  GRTRACE_HD GeodesicState geodesic_state(const State& z) const { return head(z); }
  GRTRACE_HD double constraint_violation(const State& z) const { return ray.constraint_violation(head(z)); }
  GRTRACE_HD double constraint_drift(const State& z) const { return ray.constraint_drift(head(z)); }
  GRTRACE_HD double equatorial_latitude(const State& z) const { return ray.equatorial_latitude(head(z)); }
  /// The ray's re-charting at a spherical chart's axis, and its move onto the axis (MetricGeodesicSystem); the
  /// light's slots are kept.
  GRTRACE_HD bool wrap_chart(State& z) const {
    GeodesicState y = head(z);
    if (!ray.wrap_chart(y)) return false;
    z.template head<8>() = y;
    return true;
  }
  GRTRACE_HD bool align_with_axis(State& z) const {
    GeodesicState y = head(z);
    if (!ray.align_with_axis(y)) return false;
    z.template head<8>() = y;
    return true;
  }

 private:
  static GRTRACE_HD GeodesicState head(const State& z) { return z.template head<8>(); }
};

namespace detail {
/// An observer of the tracing loop that keeps the fraction of the last step it was shown (1, or where a surface
/// ended the ray).
struct StepFraction {
  double theta_end = 1.0;
  template <class Integrator>
  void operator()(const Integrator&, double theta) {
    theta_end = theta;
  }
};

/// A medium that says where its edge is (medium/emitting_medium.hpp: boundary).
template <class Medium, class Metric>
concept MediumWithBoundary = requires(const Medium m, const Metric g, const Vec4 x) {
  { m.boundary(g, x) } -> std::convertible_to<double>;
};

/// Ends a step where it crossed the medium's boundary (a hard edge, a torus's surface), so that no step is
/// integrated across it: there j and alpha jump or kink, and an error estimate that assumes a smooth solution does
/// not see the error (a hard edge: 1 % of the intensity; a torus's surface where rho ~ depth^3: 6e-5 at rtol 1e-9).
/// Each step is integrated with the light of the side it starts on (EmissionSystem::boundary_side: none outside,
/// the medium's coefficients continued smoothly inside), so the step is smooth; the crossing is bracketed on its
/// dense output (its ends and four points inside: a layer entered and left within one step is found too), refined
/// on the step map (refine_located), and the integration resumed there on the other side, the step size to come
/// unchanged. Takes the integrator right after an accepted step, the side it was on and whether the step was a
/// retake (below); returns the side the integration goes on from.
template <class Medium, class Metric, class System, class Integrator>
int end_step_on_boundary(const Medium& medium, const Metric& metric, const System& system, Integrator& integ,
                         int side, bool& retaken) {
  if (!(integ.last_step() != 0.0)) return side;
  const double sign = side > 0 ? 1.0 : -1.0;  // g > 0: still on the step's side
  const auto g_state = [&](const typename System::State& z) {
    return sign * medium.boundary(metric, Vec4(z.template head<4>()));
  };
  const auto g_dense = [&](double t) { return g_state(integ.dense(t)); };
  // A step that starts on the boundary (after a cut) starts on its own side, whatever the rounding there says.
  const double g0 = std::max(g_state(integ.dense(0.0)), std::numeric_limits<double>::min());
  const double g1 = g_state(integ.state());
  const auto c = locate_first_crossing(g_dense, g0, g1, 4);
  if (!c) {
    retaken = false;
    return side;
  }
  // A crossing within 1e-9 of the step's start is the boundary it started on: after a cut, or where a ray grazes
  // the surface along its tangent (cutting there again and again would never move on). The step stays whole; it
  // goes on from the side its end is on.
  if (!(c->theta > 1e-9)) {
    if (!(g1 < 0.0)) return side;
    // The whole step lies on the other side (it left the boundary the other way): taken again from its start with
    // that side's light, once (a ray exactly along the surface would otherwise turn back and forth there).
    side = -side;
    if (!retaken) {
      const typename System::State z0 = integ.dense(0.0);
      auto counters = integ.counters();
      counters.lambda = integ.previous_lambda();
      integ.resume_at(z0, integ.evaluate(system, z0), counters);
      retaken = true;
      return side;
    }
  }
  retaken = false;
  if (!(c->theta > 1e-9)) return side;
  if (c->theta >= 1.0 - 1e-12) return -side;  // the step ends on it
  const auto [theta, z] = refine_located(integ, system, g_dense, g_state, *c, true);
  auto counters = integ.counters();
  counters.lambda = integ.previous_lambda() + theta * integ.last_step();
  side = -side;  // before the derivative at z is taken: it is the other side's
  integ.resume_at(z, integ.evaluate(system, z), counters);
  return side;
}
}  // namespace detail

/// What trace_emission returns: the ray's trace, and the light it collected (see the top of this file).
struct EmissionResult {
  TraceResult trace;           ///< status hit where the medium became opaque; lambda is the parameter s
  double intensity = 0.0;      ///< I_nu at the camera, at nu_obs
  double optical_depth = 0.0;  ///< tau from the camera to the ray's end
  double redshift = std::numeric_limits<double>::quiet_NaN();  ///< emission-weighted g (NaN: no light)
  bool opaque = false;         ///< the transmission fell below min_transmission: the ray ended in the medium
};

/// The transmission e^-tau below which a ray through a medium ends where no value is named (see the top of this
/// file).
inline constexpr double default_min_transmission = 1e-16;

/// Integrates the ray y0 and the light of `medium` along it (see the top of this file) with the tableau and the
/// controller given, until the horizon guard, the sky sphere or the settings end it.
template <ExplicitTableau Tableau, StepController Controller = PIController, MetricPolicy Metric, class Medium>
EmissionResult trace_emission(const Metric& metric, const Medium& medium, const TraceSettings& settings,
                              const GeodesicState& y0, double camera_energy, double frequency,
                              const Controller& controller = {},
                              double min_transmission = default_min_transmission) {
  EmissionSystem<Metric, Medium> system(metric, medium, y0, camera_energy, frequency);
  using System = EmissionSystem<Metric, Medium>;
  int side = 1;  // of the medium's boundary, where it has one (end_step_on_boundary)
  bool retaken = false;
  if constexpr (detail::MediumWithBoundary<Medium, Metric>) {
    side = medium.boundary(metric, Vec4(y0.template head<4>())) > 0.0 ? 1 : -1;
    system.boundary_side = &side;
  }
  using Loop = TraceLoop<Tableau, Controller, System>;
  const Loop loop(system, settings, capture_radius_of(metric, y0));
  typename Loop::Integrator integ(settings.integrator, controller);
  typename Loop::Progress progress;
  EmissionResult out;
  const typename System::State z0 = system.initial_state(y0);
  if (auto ended = loop.begin(z0, leaves_interior_of(metric, y0), progress, integ)) {
    out.trace = *ended;
    return out;
  }
  // The light's slots at the end (the loop reports only (x, k)): the integrator's last accepted state, or, where a
  // surface cut the last step, that step taken again to the cut (the step map, as accurate as the integration; the
  // interpolant of a long last step towards the sky sphere was 5e-7 off at rtol 1e-10).
  detail::StepFraction observer;
  const double tau_stop = -std::log(min_transmission);
  for (;;) {
    if (integ.accepted() >= settings.max_steps) {
      out.trace = loop.out_of_steps(integ, progress);
      break;
    }
    if (auto ended = loop.step(integ, progress, observer)) {
      out.trace = *ended;
      break;
    }
    if constexpr (detail::MediumWithBoundary<Medium, Metric>)
      side = detail::end_step_on_boundary(medium, metric, system, integ, side, retaken);
    if (integ.state()[System::kOpticalDepth] > tau_stop) {  // opaque: nothing behind this point can show
      // The loop's end of a ray at its last accepted point (with its constraint check), as hit: no surface of the
      // scene (hit_event -1), the medium itself.
      out.trace = loop.out_of_steps(integ, progress);
      out.opaque = out.trace.status == RayStatus::max_steps;
      if (out.opaque) out.trace.status = RayStatus::hit;
      break;
    }
  }
  const typename System::State end =
      observer.theta_end == 1.0 ? integ.state() : integ.step_from_previous(system, observer.theta_end);
  out.intensity = end[System::kIntensity];
  out.optical_depth = end[System::kOpticalDepth];
  if (out.intensity > 0.0) out.redshift = end[System::kRedshiftWeight] / out.intensity;
  return out;
}

/// The same with the camera's 4-velocity u_cam at y0 in place of E_cam.
template <ExplicitTableau Tableau, StepController Controller = PIController, MetricPolicy Metric, class Medium>
EmissionResult trace_emission_seen_by(const Metric& metric, const Medium& medium, const TraceSettings& settings,
                                      const GeodesicState& y0, const Vec4& camera_velocity, double frequency,
                                      const Controller& controller = {}) {
  const Vec4 x0 = y0.head<4>(), k0 = y0.tail<4>();
  const double e_cam = std::abs(inner_product(metric, x0, k0, camera_velocity));
  return trace_emission<Tableau>(metric, medium, settings, y0, e_cam, frequency, controller);
}

}  // namespace grtrace
