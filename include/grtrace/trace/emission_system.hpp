// grtrace/trace/emission_system.hpp
// The light an emitting medium (medium/emitting_medium.hpp) sends along one camera ray, integrated with the ray
// itself: the ray's equations (the geodesic equation of any metric, MetricGeodesicSystem, or Kerr's separated
// equations in Mino time, KerrMinoSystem, for a stationary medium) with more variables, the intensity that reaches
// the camera and the optical depth from the camera, so that the step control bounds the intensity's error as it
// bounds the ray's (a step that skips a thin bright layer is rejected like one that misses a turn).
//
// Takes:   a metric, a medium, a camera ray y0 (x, k) as a camera makes it (k past-directed: traced from the camera
//          backwards), the energy of that photon measured by the camera, E_cam = |g(k0, u_cam)|, and the observed
//          frequency nu_obs, or several (std::array<double, N>: the light of each band along the one ray).
// Returns: trace_emission: the ray's TraceResult (status, final state: as the geodesic tracer's) with
//          intensity   I_nu(nu_obs) at the camera = integral of g^3 j_nu(nu_obs / g) e^-tau dl
//          optical_depth  tau = integral of alpha_nu(nu_obs / g) dl, from the camera to where the ray ended
//          redshift    the emission-weighted g: integral of g dI over I (the shift of the light the camera sees, as
//                      a surface's g is; NaN where I = 0)
//          (the invariant intensity is intensity / nu_obs^3; with alpha = 0 it is conserved through empty space);
//          for several frequencies a SpectralEmissionResult, each of these a band.
// Several frequencies in one pass: each band has its three slots; the medium is asked once a stage for all of them
//          (its form for several frequencies, medium/emitting_medium.hpp, shares what does not depend on nu: the RIAF
//          at eight frequencies costs 2.3 times one, against 8.3 times for eight passes); every band's error is in the
//          step control; the absorbing medium's slowing down (below) takes the largest band's alpha, and the ray ends
//          as opaque only when every band is.
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
// By order: the light is also split by the order n of the image it belongs to (EmissionResult::intensity_by_order:
//          n = 0, 1, 2, >= 3). A thin disk's n-th image is where the ray crosses the equatorial plane the (n+1)-th
//          time; a ray through glowing matter is cut, from the camera backwards, at the first polar turning point
//          after each crossing (where it stops moving away from the plane: the latitude's rate changes sign), so
//          that piece n holds the (n+1)-th crossing and the gas around it, whatever side of the plane. The limit of
//          a thin glowing layer is then the thin disk's split; cutting at the crossings themselves would split each
//          image of a layer in two. The cut is located on the step's dense output, its intensity read off the
//          step map (as a surface's hit); a ray over a spherical chart's pole (re-charted there) is cut where it
//          is re-charted, at the end of that step. The pieces sum to the intensity up to rounding (and, where a
//          cut's intensity lies above the ray's end by the integration's error, that error: no piece is negative).
// Method's error estimate: the light is an integral along the ray, and a tableau's embedded estimate must see the
//          error of an integral to bound it (estimate_sees_integrals below): Fehlberg 7(8)'s does not (its stages 12
//          and 13 sit at the times of stages 1 and 11, so for an integral its two weight sets give the same rule and
//          the estimate is zero). The ray's own error then sets the steps, which the geodesic equation keeps short
//          enough in practice, but Kerr's separated equations in Mino time are smooth enough to cross a torus in
//          three steps: its light was 4e-4 off at rtol 1e-10, a RIAF's through the geodesic equation 2e-4. The
//          tools draw media with Verner 6(5) (1e-6 at rtol 1e-8 on both, converging with the tolerance).
// Assumes: the ray starts at the camera (tau = 0, I = 0 there); the horizon, the sky sphere and the settings end
//          it as they end any ray (trace/geodesic_tracer.hpp).
#pragma once

#include "grtrace/core/golden_section.hpp"
#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/exact/kerr_null_geodesic.hpp"
#include "grtrace/integrate/step_controller.hpp"
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/tableau/butcher_tableau.hpp"
#include "grtrace/trace/geodesic_system.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/kerr_mino_system.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <tuple>
#include <type_traits>
#include <utility>

namespace grtrace {

namespace detail {
/// The metric of a ray's geodesic system: MetricGeodesicSystem holds a pointer to it, KerrMinoSystem a copy.
template <class Ray>
GRTRACE_HD const auto& ray_metric(const Ray& ray) {
  if constexpr (std::is_pointer_v<decltype(ray.metric)>) return *ray.metric;
  else return ray.metric;
}
template <class Ray>
using RayMetric = std::remove_cvref_t<decltype(ray_metric(std::declval<const Ray&>()))>;

/// Whether a ray's system follows t (KerrMinoSystem does not: `static constexpr bool follows_time = false;`).
template <class Ray>
constexpr bool ray_follows_time() {
  if constexpr (requires { Ray::follows_time; }) return Ray::follows_time;
  else return true;
}
}  // namespace detail

/// The light a medium sends along a ray at one event, as the camera sees it: g = nu_obs / nu_fluid = E_cam / E_fluid
/// and each band's coefficients at its frequency in the fluid's frame (see the top of this file).
template <std::size_t Bands>
struct LocalLight {
  double g = 0.0;                                    ///< nu_obs / nu_fluid
  double fluid_energy = 0.0;                         ///< E_fluid = |g(k, u)|: dl = E_fluid d lambda
  std::array<MediumCoefficients, Bands> at_fluid{};  ///< j_nu, alpha_nu of band b at nu_obs[b] / g
  /// Band b's rates per unit of the affine parameter: the camera's intensity before the absorption in front of
  /// it, g^3 j E_fluid, and the optical depth, alpha E_fluid.
  GRTRACE_HD double emission_rate(std::size_t b) const { return g * g * g * at_fluid[b].emission * fluid_energy; }
  GRTRACE_HD double depth_rate(std::size_t b) const { return at_fluid[b].absorption * fluid_energy; }
};

/// Takes the medium, the event x and the ray's wave vector k there (the affine parameter's), the camera's photon
/// energy E_cam = |g(k0, u_cam)| and the observed frequencies; returns the light there (LocalLight). Assumes x in the
/// gas (medium_contains): the tracer's systems and every sampler of a ray's light (app/medium_view.hpp) share it.
template <class Metric, class Medium, std::size_t Bands>
GRTRACE_HD LocalLight<Bands> local_light(const Metric& metric, const Medium& medium, const Vec4& x, const Vec4& k,
                                         double camera_energy, const std::array<double, Bands>& nu_obs) {
  LocalLight<Bands> l;
  // g_{mu nu} once, for the redshift and for a medium that takes it (emitting_medium.hpp): a torus's velocity and
  // enthalpy asked the metric again each, three evaluations a stage where one does.
  const Mat4 g = metric.metric(x);
  const Vec4 u = medium_fluid_velocity(medium, metric, x, g);
  l.fluid_energy = std::abs(k.dot(g * u));  // inner_product(metric, x, k, u)
  l.g = camera_energy / l.fluid_energy;
  std::array<double, Bands> nu_fluid;
  for (std::size_t b = 0; b < Bands; ++b) nu_fluid[b] = nu_obs[b] / l.g;
  l.at_fluid = medium_coefficients(medium, metric, x, k, u, nu_fluid, g);
  return l;
}

/// A geodesic system (trace/geodesic_system.hpp) of the ray's own variables (Ray: MetricGeodesicSystem<Metric>, the
/// geodesic equation of any metric, or KerrMinoSystem, Kerr's separated equations in Mino time) and three more for
/// each of Bands observing frequencies: the camera's intensity, the optical depth and the intensity weighted by g
/// (see the top of this file). The light's derivatives are in the affine parameter times the system's rate of it
/// (Ray's optional affine_rate(z): Sigma in Mino time; 1 without it). Holds the metric (through the ray's system) and
/// the medium by reference: they outlive the trace.
template <class Ray, class Medium, std::size_t Bands = 1>
struct RayEmissionSystem {
  static_assert(Bands >= 1, "RayEmissionSystem: at least one observing frequency");
  using Metric = detail::RayMetric<Ray>;
  static constexpr int bands = static_cast<int>(Bands);
  static constexpr int ray_dimension = Ray::dimension;
  static constexpr int dimension = Ray::dimension + 3 * bands;
  using State = Vector<dimension>;
  /// The first band's slots of I_nu, tau and the integral of g dI; band b's are b further on.
  static constexpr int kIntensity = ray_dimension, kOpticalDepth = ray_dimension + bands,
                       kRedshiftWeight = ray_dimension + 2 * bands;

  Ray ray;
  const Medium* medium;
  double camera_energy;                 ///< E_cam = |g(k0, u_cam)|
  std::array<double, Bands> frequency;  ///< nu_obs of each band
  /// For a medium with a boundary: the side of it the current step is on (> 0 outside: no light there, whatever
  /// the medium's coefficients say; else the medium's coefficients, continued smoothly across its boundary), set
  /// by trace_emission between steps, which end on the boundary. Null: the coefficients everywhere.
  const int* boundary_side = nullptr;

  GRTRACE_HD RayEmissionSystem(const Metric& metric, const Medium& m, const GeodesicState& y0, double e_cam,
                               const std::array<double, Bands>& nu_obs)
      : ray(metric, y0),
        medium(&m),
        camera_energy(e_cam),
        frequency(nu_obs),
        rho_outer_(Ray::radial_coordinate_at(m.outer_radius())),
        rho_far_(Ray::radial_coordinate_at(1.01 * m.outer_radius())) {
    static_assert(check_emitting_medium<Medium, Metric>());
    static_assert(detail::ray_follows_time<Ray>() || medium_is_stationary<Medium>(),
                  "this ray's system does not follow t (Kerr's separated equations in Mino time): the medium must be "
                  "stationary (declare `static constexpr bool stationary = true;` if it is); others need the "
                  "geodesic equation (trace_emission)");
  }
  /// One observing frequency.
  GRTRACE_HD RayEmissionSystem(const Metric& metric, const Medium& m, const GeodesicState& y0, double e_cam,
                               double nu_obs) requires(Bands == 1)
      : RayEmissionSystem(metric, m, y0, e_cam, std::array<double, 1>{nu_obs}) {}

  /// (the ray's start, I = 0, tau = 0).
  GRTRACE_HD State initial_state(const GeodesicState& y0) const {
    State z = State::Zero();
    if constexpr (requires { ray.initial_state(y0); }) z.template head<ray_dimension>() = ray.initial_state(y0);
    else z.template head<ray_dimension>() = y0;
    return z;
  }

  GRTRACE_HD State operator()(const State& z) const {
    const RayState zr = ray_part(z);
    State dz;
    dz.template head<ray_dimension>() = ray(zr);
    dz.template tail<3 * bands>().setZero();
    if (boundary_side != nullptr) {  // the side of the boundary decides (no cut within a step: it is smooth)
      if (*boundary_side > 0) return dz;
    } else if (!(ray.radial_coordinate(zr) <= rho_outer_)) {  // beyond outer_radius (or past u = 0 in 1/r)
      return dz;
    }
    // A trial stage the ray's system refuses (NaN: KerrMinoSystem deep past a turning point) is not a place to ask
    // the medium about.
    if constexpr (!detail::ray_follows_time<Ray>())
      if (!std::isfinite(dz[0])) return dz;
    const GeodesicState y = ray.geodesic_state(zr);
    const Vec4 x = medium_event(y), k = y.template tail<4>();
    const LocalLight<Bands> l = local_light(detail::ray_metric(ray), *medium, x, k, camera_energy, frequency);
    double rate = 1.0;  // of the affine parameter per unit of the system's s
    if constexpr (requires { ray.affine_rate(zr); }) rate = ray.affine_rate(zr);
    double absorption = 0.0;  // the largest band's sets the slowing down (sigma)
    for (int b = 0; b < bands; ++b) {
      const auto ub = static_cast<std::size_t>(b);
      dz[kIntensity + b] = l.emission_rate(ub) * std::exp(-z[kOpticalDepth + b]) * rate;
      dz[kOpticalDepth + b] = l.depth_rate(ub) * rate;
      dz[kRedshiftWeight + b] = l.g * dz[kIntensity + b];
      absorption = std::max(absorption, l.at_fluid[ub].absorption);
    }
    if (absorption > 0.0) dz *= 1.0 / (1.0 + absorption * ray.radius(zr));  // sigma (top of this file)
    return dz;
  }

  /// The event of z where the medium is asked about it: the ray's x, its t 0 where the system does not follow it
  /// (the medium is then stationary).
  GRTRACE_HD Vec4 event(const State& z) const { return medium_event(ray.geodesic_state(ray_part(z))); }

  /// The medium's boundary at z (medium/emitting_medium.hpp: positive outside the gas; for a medium that has one),
  /// 1 beyond 1.01 outer_radius(), where the medium promises no gas: the ray's far steps (most of them) are not
  /// asked about, and a system in u = 1/r, which passes beyond infinity (u < 0) within a step towards the sky, does
  /// not ask the medium about a negative radius. (Not from outer_radius() itself: a boundary there, a cut at that
  /// radius, would become a jump from 1 to 0, which the crossing's secant refinement does not converge on.)
  GRTRACE_HD double boundary(const State& z) const {
    if (!(radial_coordinate(z) <= rho_far_)) return 1.0;
    return medium->boundary(detail::ray_metric(ray), event(z));
  }

  GRTRACE_HD double radius(const State& z) const { return ray.radius(ray_part(z)); }
  GRTRACE_HD double radial_coordinate(const State& z) const { return ray.radial_coordinate(ray_part(z)); }
  static GRTRACE_HD double radial_coordinate_at(double r) { return Ray::radial_coordinate_at(r); }
  GRTRACE_HD GeodesicState geodesic_state(const State& z) const { return ray.geodesic_state(ray_part(z)); }
  GRTRACE_HD double constraint_violation(const State& z) const { return ray.constraint_violation(ray_part(z)); }
  GRTRACE_HD double constraint_drift(const State& z) const { return ray.constraint_drift(ray_part(z)); }
  GRTRACE_HD double equatorial_latitude(const State& z) const { return ray.equatorial_latitude(ray_part(z)); }
  /// The rate of equatorial_latitude along the ray's k (positive: moving north), of which the split by order uses
  /// the sign.
  GRTRACE_HD double equatorial_latitude_rate(const State& z) const {
    const GeodesicState y = geodesic_state(z);
    if constexpr (Metric::chart == Chart::spherical) {
      return -y[6];
    } else {  // z / |x|: (k_z |x|^2 - z (x . k)) / |x|^3
      const double r2 = y[1] * y[1] + y[2] * y[2] + y[3] * y[3], xk = y[1] * y[5] + y[2] * y[6] + y[3] * y[7];
      return (y[7] * r2 - y[3] * xk) / (r2 * std::sqrt(r2));
    }
  }
  /// The ray's re-charting at a spherical chart's axis, and its move onto the axis (the ray's system, where it has
  /// one); the light's slots are kept.
  GRTRACE_HD bool wrap_chart(State& z) const {
    RayState zr = ray_part(z);
    if (!ray.wrap_chart(zr)) return false;
    z.template head<ray_dimension>() = zr;
    return true;
  }
  GRTRACE_HD bool align_with_axis(State& z) const {
    if constexpr (requires(RayState zr) {
                    { ray.align_with_axis(zr) } -> std::same_as<bool>;
                  }) {
      RayState zr = ray_part(z);
      if (!ray.align_with_axis(zr)) return false;
      z.template head<ray_dimension>() = zr;
      return true;
    } else {
      return false;
    }
  }

 private:
  using RayState = typename Ray::State;
  static GRTRACE_HD RayState ray_part(const State& z) { return z.template head<ray_dimension>(); }
  static GRTRACE_HD Vec4 medium_event(const GeodesicState& y) {
    Vec4 x = y.template head<4>();
    if constexpr (!detail::ray_follows_time<Ray>()) x[0] = 0.0;
    return x;
  }
  double rho_outer_;  ///< the ray's radial coordinate at the medium's outer_radius()
  double rho_far_;    ///< and at 1.01 outer_radius(), beyond which boundary() does not ask the medium
};

/// The light of a medium along the geodesic equation of any metric policy.
template <MetricPolicy Metric, class Medium>
using EmissionSystem = RayEmissionSystem<MetricGeodesicSystem<Metric>, Medium>;

namespace detail {
/// A boundary crossing within this step fraction of a step's start is the boundary the step started on (see
/// end_step_on_boundary).
inline constexpr double kOnItsStart = 1e-9;

/// An observer of the tracing loop that keeps the fraction of the last step it was shown (1, or where a surface
/// ended the ray).
struct StepFraction {
  double theta_end = 1.0;
  template <class Integrator>
  void operator()(const Integrator&, double theta) {
    theta_end = theta;
  }
};

/// Golden section on [a, b] towards the largest value of a unimodal f (core/golden_section.hpp), stopping at the
/// first probe that `found` accepts: returns its step fraction and f there, or nothing once the bracket is 1e-12
/// wide.
template <class F, class Found>
Optional<EventCrossing> golden_search(const F& f, double a, double b, const Found& found) {
  const GoldenSection s =
      golden_section_maximum(f, a, b, {0.0, 1e-12}, 60, [&](double, double value) { return found(value); });
  if (!s.stopped) return no_value;
  return EventCrossing{s.x, s.value};
}

/// Where a step first crosses a boundary g (> 0 on the side it starts on; its step fraction t -> g): bracketed by
/// g at the step's ends and four points inside, then located (locate_first_crossing). A layer thinner than the
/// step is found too: where no sample lies across the boundary but g dips (its smallest sample is inside the step,
/// or at an end it falls away from), the dip's lowest point by golden section; and a step that starts on the
/// boundary and is across it at the first sample is searched for the point in between where it was still on its
/// side (leaving the layer it just entered). Without these, a glowing layer 1e-3 M thick on the equator went
/// unseen by rays whose steps there were a few M long.
template <class G>
Optional<EventCrossing> locate_first_entry(const G& g, double g0, double g1) {
  constexpr int kPieces = 5;
  constexpr double kPiece = 1.0 / kPieces;
  // Where g's slope at an end is read: close enough that a layer a thousandth of the step wide starts beyond it.
  constexpr double kSlopeProbe = 1e-6;
  std::array<double, kPieces + 1> v{};
  v[0] = g0;
  v[kPieces] = g1;
  for (int j = 1; j < kPieces; ++j) v[static_cast<std::size_t>(j)] = g(j * kPiece);
  // The crossing located between two samples a < b (g(a) > 0, g(b) <= 0 or not finite).
  const auto between = [&](double a, double ga, double b, double gb) {
    const auto c = locate_first_crossing([&](double t) { return g(a + t * (b - a)); }, ga, gb);
    return EventCrossing{a + c->theta * (b - a), c->value};
  };
  for (int j = 1; j <= kPieces; ++j) {
    const double gb = v[static_cast<std::size_t>(j)];
    if (gb > 0.0) continue;
    const EventCrossing c = between((j - 1) * kPiece, v[static_cast<std::size_t>(j - 1)], j * kPiece, gb);
    if (j == 1 && !(c.theta > kOnItsStart))
      if (const auto on_side = golden_search(g, 0.0, kPiece, [](double x) { return x > 0.0; }))
        return between(on_side->theta, on_side->value, kPiece, gb);
    return c;
  }
  const auto lowest = static_cast<int>(std::min_element(v.begin(), v.end()) - v.begin());
  double a = (lowest - 1) * kPiece, b = (lowest + 1) * kPiece;
  if (lowest == 0) {  // g falls away from the start?
    if (!(g(kSlopeProbe) < g0)) return no_value;
    a = 0.0;
  } else if (lowest == kPieces) {  // g rises towards the end?
    if (!(g(1.0 - kSlopeProbe) < g1)) return no_value;
    b = 1.0;
  }
  const double ga = v[static_cast<std::size_t>(std::max(lowest - 1, 0))];
  const auto across =
      golden_search([&](double t) { return -g(t); }, a, b, [](double minus_g) { return !(minus_g < 0.0); });
  if (!across) return no_value;
  return between(a, ga, across->theta, -across->value);
}

/// Ends a step where it crossed the medium's boundary (a hard edge, a torus's surface), so that no step is
/// integrated across it: there j and alpha jump or kink, and an error estimate that assumes a smooth solution does
/// not see the error (a hard edge: 1 % of the intensity; a torus's surface where rho ~ depth^3: 6e-5 at rtol 1e-9).
/// Each step is integrated with the light of the side it starts on (EmissionSystem::boundary_side: none outside,
/// the medium's coefficients continued smoothly inside), so the step is smooth; the crossing is bracketed on its
/// dense output (locate_first_entry: a layer entered and left within one step is found too), refined
/// on the step map (refine_located), and the integration resumed there on the other side, the step size to come
/// unchanged. Takes the integrator right after an accepted step, the side it was on (the variable the system reads:
/// RayEmissionSystem::boundary_side), whether the step was a retake (below) and the fraction of the step that stands
/// (1, or where a surface ended the ray: a crossing of the boundary before it is cut there all the same, and the ray
/// goes on; without that, a step that left the gas and reached the sky sphere at once was integrated with the gas's
/// light all the way: a Mino-time step from 23 M to the sky, -2e3 times the ray's intensity); sets the side the
/// integration goes on from, and `kept`, the fraction of the step that stands (`stands` when it is not cut, 0 when
/// it is taken again, else where it was cut).
template <class System, class Integrator>
void end_step_on_boundary(const System& system, Integrator& integ, int& side, bool& retaken, double stands,
                          double& kept) {
  kept = stands;
  if (!(integ.last_step() != 0.0)) return;
  const double sign = side > 0 ? 1.0 : -1.0;  // g > 0: still on the step's side
  const auto g_state = [&](const typename System::State& z) { return sign * system.boundary(z); };
  const auto g_dense = [&](double t) { return g_state(integ.dense(t)); };
  // The integration goes on from z on the other side: the derivative there is that side's (the system reads
  // `side`), and the next step's first stage is that derivative.
  const auto resume_across = [&](const typename System::State& z, double lambda) {
    side = -side;
    auto counters = integ.counters();
    counters.lambda = lambda;
    integ.resume_at(z, integ.evaluate(system, z), counters);
  };
  // A step that starts on the boundary (after a cut) starts on its own side, whatever the rounding there says.
  const double g0 = std::max(g_state(integ.dense(0.0)), std::numeric_limits<double>::min());
  const double g1 = stands == 1.0 ? g_state(integ.state()) : g_dense(stands);
  auto c = locate_first_entry([&](double t) { return g_dense(t * stands); }, g0, g1);
  if (!c) {
    retaken = false;
    return;
  }
  c->theta *= stands;
  // A crossing within kOnItsStart of the step's start is the boundary it started on: after a cut, or where a ray
  // grazes the surface along its tangent (cutting there again and again would never move on). The step stays whole;
  // it goes on from the side its end is on.
  if (!(c->theta > kOnItsStart)) {
    if (!(g1 < 0.0)) return;
    // The whole step lies on the other side (it left the boundary the other way): taken again from its start with
    // that side's light, once (a ray exactly along the surface would otherwise turn back and forth there).
    if (!retaken) {
      kept = 0.0;
      resume_across(integ.dense(0.0), integ.previous_lambda());
      retaken = true;
      return;
    }
    side = -side;
    return;
  }
  retaken = false;
  if (c->theta >= stands - 1e-12) {  // the step ends on it: the ray's end, or where it goes on from
    if (stands == 1.0) resume_across(integ.state(), integ.lambda());
    return;
  }
  const auto [theta, z] = refine_located(integ, system, g_dense, g_state, *c, true);
  kept = theta;
  resume_across(z, integ.previous_lambda() + theta * integ.last_step());
}

/// Splits a ray's light by image order (see the top of this file), each of Bands observing frequencies' alike, fed
/// after every accepted step.
template <std::size_t Bands = 1>
class OrderSplit {
 public:
  using Light = std::array<double, Bands>;  ///< an intensity in each band
  struct Cut {
    double theta;     ///< the step fraction of the polar turning point
    Light intensity;  ///< the intensity there
  };

  /// A split whose light so far (none) began at order `order` (a ray that starts part way, its earlier orders
  /// empty: trace_kerr_medium_ray).
  GRTRACE_HD explicit OrderSplit(int order = 0) : order_(order) {}

  /// Where the light of the current order ends in the last accepted step of integ, of which the part [0, theta_hi]
  /// stands (1: all of it; less: a surface ended the ray there), given the crossings of the plane counted up to
  /// theta_hi: nothing while the ray has not crossed the plane once more or still moves away from it.
  template <class System, class Integrator>
  GRTRACE_HD Optional<Cut> find(const System& system, Integrator& integ, int crossings, double theta_hi) const {
    if (crossings <= order_) return no_value;
    if (!(integ.last_step() != 0.0)) return Cut{1.0, light<System>(integ.state())};  // re-charted at the pole
    const typename System::State z_hi = theta_hi == 1.0 ? integ.state() : integ.dense(theta_hi);
    const double side = system.equatorial_latitude(z_hi) < 0.0 ? -1.0 : 1.0;
    const auto away = [&](double t) { return side * system.equatorial_latitude_rate(integ.dense(t * theta_hi)); };
    const double away_hi = side * system.equatorial_latitude_rate(z_hi);
    if (away_hi > 0.0) return no_value;  // the turning point is ahead
    const auto c = locate_first_crossing(away, away(0.0), away_hi);
    const double theta = c ? c->theta * theta_hi : theta_hi;
    const Light start = light<System>(integ.previous_state());
    // A step without light (most turning points: far out, or outside the gas) gives the cut's intensity exactly
    // without taking the step again.
    if (!(theta > 0.0) || light<System>(integ.state()) == start) return Cut{theta, start};
    return Cut{theta, light<System>(integ.step_from_previous(system, theta))};
  }

  /// The current order's light ends at the intensities `at` (a cut find() returned). A piece is never negative: a
  /// cut read off the step map may lie above the intensity the integration goes on with by its error (or a
  /// rounding) where no more light comes.
  GRTRACE_HD void take(const Light& at) {
    for (std::size_t b = 0; b < Bands; ++b) {
      pieces_[b][static_cast<std::size_t>(std::min(order_, 3))] += std::max(at[b] - start_[b], 0.0);
      start_[b] = std::max(at[b], start_[b]);
    }
    ++order_;
  }

  /// Each band's pieces, the last one ending at the ray's end, where the intensities are `end`.
  GRTRACE_HD std::array<std::array<double, 4>, Bands> finish(const Light& end) {
    take(end);
    return pieces_;
  }

 private:
  template <class System>
  static GRTRACE_HD Light light(const typename System::State& z) {
    Light l;
    for (std::size_t b = 0; b < Bands; ++b) l[b] = z[System::kIntensity + static_cast<int>(b)];
    return l;
  }

  int order_ = 0;  ///< of the light being collected
  Light start_{};  ///< the intensity where it began
  std::array<std::array<double, 4>, Bands> pieces_{};
};
}  // namespace detail

/// Whether a tableau's embedded error estimate sees the error of an integral along the ray, y' = f(s) (see the top
/// of this file): its weight differences b - b_hat, summed over the stages at each time c, are not all zero (they
/// are for Fehlberg 7(8)).
template <ExplicitTableau T>
constexpr bool estimate_sees_integrals() {
  for (std::size_t i = 0; i < T::stages; ++i) {
    double at_c = 0.0;
    for (std::size_t j = 0; j < T::stages; ++j)
      if (T::c[j] == T::c[i]) at_c += T::b[j] - T::b_hat[j];
    if (at_c > 1e-12 || at_c < -1e-12) return true;
  }
  return false;
}

/// What trace_emission returns: the ray's trace, and the light it collected (see the top of this file).
struct EmissionResult {
  TraceResult trace;           ///< status hit where the medium became opaque; lambda is the parameter s
  double intensity = 0.0;      ///< I_nu at the camera, at nu_obs
  double optical_depth = 0.0;  ///< tau from the camera to the ray's end
  double redshift = std::numeric_limits<double>::quiet_NaN();  ///< emission-weighted g (NaN: no light)
  bool opaque = false;         ///< the transmission fell below min_transmission: the ray ended in the medium
  /// The intensity by image order n = 0, 1, 2, >= 3 (see the top of this file); sums to `intensity` up to rounding
  /// (and the integration's error).
  std::array<double, 4> intensity_by_order{};
};

/// What trace_emission returns for several observing frequencies at once (an array of them): one ray, each band's
/// light as EmissionResult's, in the order of the frequencies given.
template <std::size_t Bands>
struct SpectralEmissionResult {
  TraceResult trace;  ///< status hit where the medium became opaque in every band
  std::array<double, Bands> intensity{};
  std::array<double, Bands> optical_depth{};
  std::array<double, Bands> redshift{};  ///< NaN where a band has no light
  bool opaque = false;                   ///< every band's transmission fell below min_transmission
  std::array<std::array<double, 4>, Bands> intensity_by_order{};

  /// Band b's light alone.
  EmissionResult band(std::size_t b) const {
    return {trace, intensity[b], optical_depth[b], redshift[b], opaque, intensity_by_order[b]};
  }
};

/// What trace_emission takes as the observed frequency: one (a number) or several (std::array<double, N>: one ray
/// collects each one's light, with the medium asked once a stage for all of them where it can: emitting_medium.hpp).
template <class F>
concept ObservingFrequencies = std::convertible_to<F, double> || requires {
  requires std::same_as<F, std::array<double, std::tuple_size_v<F>>>;
};

/// The transmission e^-tau below which a ray through a medium ends where no value is named (see the top of this
/// file).
inline constexpr double default_min_transmission = 1e-16;

namespace detail {
/// How many observed frequencies F names (ObservingFrequencies).
template <class F>
constexpr std::size_t band_count() {
  if constexpr (std::is_convertible_v<F, double>) return 1;
  else return std::tuple_size_v<F>;
}

/// The observed frequencies as the loop takes them: an array of band_count<F>() bands.
template <class F>
std::array<double, band_count<F>()> frequency_array(const F& frequency) {
  if constexpr (std::is_convertible_v<F, double>) return {static_cast<double>(frequency)};
  else return frequency;
}

/// The loop's result as the caller asked for it: EmissionResult for one frequency given as a number, else the
/// SpectralEmissionResult.
template <class F, std::size_t Bands>
auto as_requested(const SpectralEmissionResult<Bands>& r) {
  if constexpr (std::is_convertible_v<F, double>) return r.band(0);
  else return r;
}

/// Where a ray traced from part way along starts its counts (trace_kerr_medium_ray): its crossings of the equatorial
/// plane so far, and the order of the light it collects first.
struct RayPartWay {
  int crossings = 0;
  int order = 0;
  double capture_radius = 0.0;  ///< where the ray counts as captured, if above the metric's own (0: the metric's)
};

/// The loop of trace_emission_along for Bands frequencies at once.
template <class Ray, ExplicitTableau Tableau, StepController Controller, class Medium, std::size_t Bands>
SpectralEmissionResult<Bands> trace_light(const RayMetric<Ray>& metric, const Medium& medium,
                                          const TraceSettings& settings, const GeodesicState& y0, double camera_energy,
                                          const std::array<double, Bands>& frequencies, const Controller& controller,
                                          double min_transmission, RayPartWay part_way = {}) {
  using Metric = RayMetric<Ray>;
  static_assert(std::is_same_v<Ray, MetricGeodesicSystem<Metric>> || estimate_sees_integrals<Tableau>(),
                "in Mino time a ray is smooth enough to cross the gas in a few steps, so the light's own error must "
                "set them: use a tableau whose error estimate sees an integral (Verner65, DormandPrince54, ...; "
                "Fehlberg78's is zero for one: see the top of trace/emission_system.hpp)");
  using System = RayEmissionSystem<Ray, Medium, Bands>;
  constexpr int kBands = System::bands;
  System system(metric, medium, y0, camera_energy, frequencies);
  int side = 1;  // of the medium's boundary, where it has one (end_step_on_boundary)
  bool retaken = false;
  if constexpr (MediumWithBoundary<Medium, Metric>) {
    side = system.boundary(system.initial_state(y0)) > 0.0 ? 1 : -1;
    system.boundary_side = &side;
  }
  using Loop = TraceLoop<Tableau, Controller, System>;
  const Loop loop(system, settings, std::max(capture_radius_of(metric, y0), part_way.capture_radius));
  typename Loop::Integrator integ(settings.integrator, controller);
  typename Loop::Progress progress;
  SpectralEmissionResult<Bands> out;
  out.redshift.fill(std::numeric_limits<double>::quiet_NaN());
  const typename System::State z0 = system.initial_state(y0);
  if (auto ended = loop.begin(z0, leaves_interior_of(metric, y0), progress, integ)) {
    out.trace = *ended;
    return out;
  }
  progress.crossings += part_way.crossings;
  // The light's slots at the end (the loop reports only (x, k)): the integrator's last accepted state, or, where a
  // surface cut the last step, that step taken again to the cut (the step map, as accurate as the integration; the
  // interpolant of a long last step towards the sky sphere was 5e-7 off at rtol 1e-10).
  StepFraction observer;
  OrderSplit<Bands> split(part_way.order);
  const double tau_stop = -std::log(min_transmission);
  for (;;) {
    if (integ.accepted() >= settings.max_steps) {
      out.trace = loop.out_of_steps(integ, progress);
      break;
    }
    const typename Loop::Progress before = progress;
    auto ended = loop.step(integ, progress, observer);
    // A surface (the horizon, the sky sphere, an event) ended the ray inside this step: the part up to it stands.
    const bool on_surface = ended && (ended->status == RayStatus::captured || ended->status == RayStatus::escaped ||
                                      ended->status == RayStatus::hit);
    if (ended && !on_surface) {
      out.trace = *ended;
      break;
    }
    const double stands = ended ? observer.theta_end : 1.0;
    // The turning point that ends an order, found on the part of the step that stands, stands only where the step
    // does.
    const auto cut = split.find(system, integ, ended ? ended->crossings : progress.crossings, stands);
    double kept = stands;
    if constexpr (MediumWithBoundary<Medium, Metric>) {
      end_step_on_boundary(system, integ, side, retaken, stands, kept);
      if (kept < stands) {  // resumed inside the step: its crossings of the plane are counted from there on
        if (ended) {        // and the ray goes on: the surfaces as they were at the step's start
          const long refinement_evals = progress.refinement_evals;
          progress = before;
          progress.refinement_evals = refinement_evals;
          ended = no_value;
          observer.theta_end = 1.0;
        } else {
          progress.crossings = before.crossings;
          progress.latitude_prev = before.latitude_prev;
        }
        loop.note_latitude(integ.state(), progress);
      }
    }
    if (cut && cut->theta <= kept) split.take(cut->intensity);
    if (ended) {
      out.trace = *ended;
      break;
    }
    // Opaque in every band: nothing behind this point can show.
    double tau_least = integ.state()[System::kOpticalDepth];
    for (int b = 1; b < kBands; ++b) tau_least = std::min(tau_least, integ.state()[System::kOpticalDepth + b]);
    if (tau_least > tau_stop) {
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
  std::array<double, Bands> intensity;
  for (int b = 0; b < kBands; ++b) {
    const auto i = static_cast<std::size_t>(b);
    intensity[i] = out.intensity[i] = end[System::kIntensity + b];
    out.optical_depth[i] = end[System::kOpticalDepth + b];
    if (out.intensity[i] > 0.0) out.redshift[i] = end[System::kRedshiftWeight + b] / out.intensity[i];
  }
  out.intensity_by_order = split.finish(intensity);
  return out;
}
}  // namespace detail

/// Integrates the ray y0 and the light of `medium` along it (see the top of this file) on the ray's system Ray
/// (MetricGeodesicSystem<Metric>: trace_emission below; KerrMinoSystem: trace_kerr_mino_emission) with the tableau
/// and the controller given, until the horizon guard, the sky sphere or the settings end it. The result's lambda is
/// the system's parameter (Mino time for KerrMinoSystem), its final state's t NaN where the system does not follow t.
/// `frequency`: nu_obs (a number: returns EmissionResult), or several (std::array<double, N>: returns
/// SpectralEmissionResult<N>, each band's light from the same ray, whose steps every band's error sets; the medium
/// asked for all of them at once where it has the form for it, medium/emitting_medium.hpp).
template <class Ray, ExplicitTableau Tableau, StepController Controller = PIController, class Medium,
          ObservingFrequencies Frequencies>
auto trace_emission_along(const detail::RayMetric<Ray>& metric, const Medium& medium, const TraceSettings& settings,
                          const GeodesicState& y0, double camera_energy, const Frequencies& frequency,
                          const Controller& controller = {}, double min_transmission = default_min_transmission) {
  return detail::as_requested<Frequencies>(detail::trace_light<Ray, Tableau>(
      metric, medium, settings, y0, camera_energy, detail::frequency_array(frequency), controller, min_transmission));
}

/// trace_emission_along the geodesic equation of any metric policy.
template <ExplicitTableau Tableau, StepController Controller = PIController, MetricPolicy Metric, class Medium,
          ObservingFrequencies Frequencies>
auto trace_emission(const Metric& metric, const Medium& medium, const TraceSettings& settings, const GeodesicState& y0,
                    double camera_energy, const Frequencies& frequency, const Controller& controller = {},
                    double min_transmission = default_min_transmission) {
  return trace_emission_along<MetricGeodesicSystem<Metric>, Tableau>(metric, medium, settings, y0, camera_energy,
                                                                     frequency, controller, min_transmission);
}

/// trace_emission_along Kerr's separated equations in Mino time (trace/kerr_mino_system.hpp: five variables, a few
/// polynomials a stage, in place of the eight of KerrMetric's geodesic equation), for a stationary medium in
/// Boyer-Lindquist coordinates. The light is the same integral (its derivative times d lambda / d lambda_M =
/// Sigma); the tolerances apply to the reduced variables (u = 1/r, theta, phi and their Mino-time rates) and the
/// light.
template <ExplicitTableau Tableau, StepController Controller = PIController, class Medium,
          ObservingFrequencies Frequencies>
auto trace_kerr_mino_emission(const KerrMetric& metric, const Medium& medium, const TraceSettings& settings,
                              const GeodesicState& y0, double camera_energy, const Frequencies& frequency,
                              const Controller& controller = {}, double min_transmission = default_min_transmission) {
  return trace_emission_along<KerrMinoSystem, Tableau>(metric, medium, settings, y0, camera_energy, frequency,
                                                       controller, min_transmission);
}

/// trace_kerr_mino_emission for a camera ray from outside the medium's outer radius, the empty space crossed in
/// closed form (exact/kerr_null_geodesic.hpp, Gralla & Lupsasca 2020): a ray that never comes within the outer
/// radius (its least radius beyond it) takes no step; one that does is carried to the outer radius on its ingoing
/// leg and integrated from there until it leaves it outwards (it cannot come back: an outward ray outside the
/// potential's barrier escapes), or falls in (below the medium's inner_radius where it has one: a ray without a
/// radial turning point falls into the hole), or the gas turns opaque. The light, optical depth, redshift and
/// light by order are the whole ray's within the integration's tolerance, and so are the status and
/// trace.crossings (the equatorial crossings outside, counted in closed form, included: the order split starts at
/// the right order); the trace's other fields are the integrated part's (final_state where it ended: on the outer
/// sphere for a ray that left the medium, y0 for one that never reached it; lambda and the steps from the entry).
/// Rays the closed form does not cover (vortical, eta <= 0; a camera on the axis or inside the outer radius) are
/// integrated from y0, as trace_kerr_mino_emission does.
template <ExplicitTableau Tableau, StepController Controller = PIController, class Medium,
          ObservingFrequencies Frequencies>
auto trace_kerr_medium_ray(const KerrMetric& metric, const Medium& medium, const TraceSettings& settings,
                           const GeodesicState& y0, double camera_energy, const Frequencies& frequency,
                           const Controller& controller = {}, double min_transmission = default_min_transmission) {
  constexpr std::size_t kBands = detail::band_count<Frequencies>();
  const std::array<double, kBands> nu = detail::frequency_array(frequency);
  const auto result = [](const SpectralEmissionResult<kBands>& r) { return detail::as_requested<Frequencies>(r); };
  const auto whole_ray = [&] {
    return result(detail::trace_light<KerrMinoSystem, Tableau>(metric, medium, settings, y0, camera_energy, nu,
                                                               controller, min_transmission));
  };
  const double r_outer = medium.outer_radius(), guard = (1.0 + settings.horizon_epsilon) * metric.horizon_radius();
  if (!(y0[1] > r_outer) || !(r_outer > guard)) return whole_ray();
  const KerrNullGeodesic ray(metric, y0, settings.escape_radius, guard);
  if (!ray.supported()) return whole_ray();
  if (ray.escapes() && ray.least_radius() > r_outer) {  // never reaches the gas
    SpectralEmissionResult<kBands> out;
    out.redshift.fill(std::numeric_limits<double>::quiet_NaN());
    out.trace.status = RayStatus::escaped;
    out.trace.final_state = out.trace.step_end_state = y0;  // no step taken (TraceResult's accepted 0)
    out.trace.crossings = ray.crossings_before(ray.end_mino_time());
    return result(out);
  }
  // Carried to the outer radius (an outward ray from beyond it never reaches it: above).
  const double tau = ray.ingoing_mino_time_to(r_outer);
  GeodesicState entry = ray.state_at(tau);
  entry[0] = 0.0;  // t is not followed (the medium is stationary)
  detail::RayPartWay part_way;
  part_way.crossings = ray.crossings_before(tau);
  part_way.order = part_way.crossings > 0 && !(ray.turning_mino_time_after(part_way.crossings - 1) < tau)
                       ? part_way.crossings - 1  // the turning point after the last crossing is still ahead
                       : part_way.crossings;
  TraceSettings inside = settings;
  inside.escape_radius = r_outer * (1.0 + 1e-9);  // leaving the gas outwards ends the integration
  const double r_inner = medium_inner_radius(medium);
  if (!ray.escapes() && r_inner > guard) part_way.capture_radius = r_inner / (1.0 + settings.horizon_epsilon);
  SpectralEmissionResult<kBands> r = detail::trace_light<KerrMinoSystem, Tableau>(
      metric, medium, inside, entry, camera_energy, nu, controller, min_transmission, part_way);
  const bool left = r.trace.status == RayStatus::escaped;
  if (left || (r.trace.status == RayStatus::captured && part_way.capture_radius > 0.0)) {
    // The crossings on the rest of its way (out to the sky sphere, or in to the horizon guard), in closed form.
    const KerrNullGeodesic rest(metric, r.trace.final_state, settings.escape_radius, guard);
    if (!rest.supported() || rest.escapes() != left) return whole_ray();
    r.trace.crossings += rest.crossings_before(rest.end_mino_time());
  }
  return result(r);
}

/// E_cam = |g(k0, u_cam)|: the energy of the camera ray y0's photon measured by a camera moving with u_cam.
template <MetricPolicy Metric>
double camera_photon_energy(const Metric& metric, const GeodesicState& y0, const Vec4& camera_velocity) {
  return std::abs(inner_product(metric, Vec4(y0.head<4>()), Vec4(y0.tail<4>()), camera_velocity));
}

/// The same as trace_emission with the camera's 4-velocity u_cam at y0 in place of E_cam.
template <ExplicitTableau Tableau, StepController Controller = PIController, MetricPolicy Metric, class Medium,
          ObservingFrequencies Frequencies>
auto trace_emission_seen_by(const Metric& metric, const Medium& medium, const TraceSettings& settings,
                            const GeodesicState& y0, const Vec4& camera_velocity, const Frequencies& frequency,
                            const Controller& controller = {}) {
  return trace_emission<Tableau>(metric, medium, settings, y0, camera_photon_energy(metric, y0, camera_velocity),
                                 frequency, controller);
}

}  // namespace grtrace
