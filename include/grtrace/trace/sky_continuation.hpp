// grtrace/trace/sky_continuation.hpp
// Where on the sky an escaped ray is seen: its direction at infinity, continued from the traced region (inside the
// sky sphere) outwards. One place for every tracer that integrates rays (general, reduced Kerr), so that a metric
// reads the same sky in every chart and tracer.
//
// Takes:   the metric, the tracer's tableau and tolerance, the AngleCorrection, and two states of
//          the escaping ray: `from`, any point of its outgoing leg (the tracers pass the end of the last accepted
//          step, which carries the integrator's error only), and `at_sphere`, where it crossed the sky sphere.
// Returns: the sky direction (theta, phi in the chart's Euclidean embedding, phi in (-pi, pi]).
// Method:  which continuation runs (SkyContinuation):
//   exact, elliptic   the metric's own asymptotic_direction (Schwarzschild: the elliptic integral of the orbit).
//   exact, Mino       Kerr, in Boyer-Lindquist or Kerr-Schild coordinates: the ray's Mino-time system
//                     (trace/kerr_mino_system.hpp) carries u = 1/r, and u = 0 (infinity) is an ordinary point of it
//                     (u' -> -E there), so the ray is carried to u = 0 by steps of the tracer's own tableau
//                     (kerr_direction_at_infinity), and (theta, phi) read there are its asymptotic direction. In
//                     the Kerr-Schild chart the azimuth differs from Boyer-Lindquist's by e a int dr / Delta, which
//                     vanishes at infinity (metric/kerr_schild.hpp), so both charts share the direction at infinity.
//   flat              the straight line of the embedded velocity at the sky sphere (seed eq. 7-8): exact only where
//                     the metric is flat beyond the sphere; around a mass its error falls as M b^3 / R^4
//                     (flat_continuation_error).
//   sky sphere        AngleCorrection::none: the point where the ray met the sphere.
// Assumes: `from` lies outside the photon region, moving outwards (an escaped ray's end does).
// The redshift of the sky stays that of an emitter at rest on the sky sphere (scene_tracer.hpp): the continuation
// changes where a ray is seen, not the frequency it arrives with.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/optional.hpp"
#include "grtrace/core/sky_direction.hpp"
#include "grtrace/integrate/error_norm.hpp"
#include "grtrace/integrate/runge_kutta_stepper.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/kerr_mino_system.hpp"
#include "grtrace/trace/sky_continuation_kind.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <concepts>
#include <limits>
#include <numbers>
#include <optional>
#include <type_traits>

namespace grtrace {

/// True for the charts of Kerr whose escaped rays are continued on the Mino-time system.
template <class M>
inline constexpr bool continues_on_kerr_mino = std::is_same_v<M, KerrMetric> || std::is_same_v<M, KerrSchildMetric>;

/// The continuation a tracer of metric M runs for escaped rays under a correction (see the top of this file).
template <MetricPolicy M>
constexpr GRTRACE_HD SkyContinuation sky_continuation_of(AngleCorrection correction) {
  if (correction == AngleCorrection::none) return SkyContinuation::sky_sphere;
  if constexpr (FlatMetric<M>) return SkyContinuation::straight_line;
  if (correction == AngleCorrection::flat) return SkyContinuation::flat;
  if constexpr (HasExactContinuation<M>) return SkyContinuation::exact_elliptic;
  else if constexpr (continues_on_kerr_mino<M>) return SkyContinuation::exact_mino;
  else return SkyContinuation::flat;
}

/// True when the tracer of metric M continues escaped rays exactly from any point of their outgoing leg: it then
/// needs the sky sphere's crossing only for the redshift, and need not refine it (TraceSettings::refine_escape).
template <MetricPolicy M>
constexpr GRTRACE_HD bool continues_exactly(AngleCorrection correction) {
  const SkyContinuation c = sky_continuation_of<M>(correction);
  return c == SkyContinuation::exact_elliptic || c == SkyContinuation::exact_mino;
}

/// Estimated error (radians) of the flat continuation from radius R of a ray with impact parameter b around a
/// non-rotating mass M: the first order in M of the exact continuation minus the straight line, (3/4) M b^3 / R^4
/// for b << R. Schwarzschild's orbit integral int_0^{1/R} du / sqrt(1/b^2 - u^2 + 2 M u^3) falls short of the flat
/// arc by M b^3 / (4 R^4); the embedded velocity's direction at R falls short by M b^3 / R^4. (A rotating hole adds
/// a frame-dragging term of order a M / R^2: Kerr's flat continuation was off by 4e-6 to 7e-6 rad at R = 400 M,
/// which is why Kerr is continued exactly.)
inline double flat_continuation_error(double mass, double impact, double sky_radius) {
  const double x = impact / sky_radius;
  return 0.75 * mass * x * x * x / sky_radius;
}

/// The sky radius at which flat_continuation_error falls to `tolerance` (radians).
inline double sky_radius_for_flat_error(double mass, double impact, double tolerance) {
  return std::pow(0.75 * mass * impact * impact * impact / tolerance, 0.25);
}

/// The impact parameter of the straight line a ray leaves the traced region on (flat continuation): the distance
/// of the line through its embedded position with its embedded velocity from the centre of the embedding.
template <MetricPolicy M>
GRTRACE_HD double flat_impact_parameter(const M& metric, const GeodesicState& y) {
  const Vec3 p = metric.to_cartesian(y.template head<4>()), v = embedded_velocity_of(metric, y);
  return p.cross(v).norm() / v.norm();
}

/// A metric that names its mass (a `mass` member): what flat_continuation_error needs.
template <class M>
concept HasMass = requires(const M m) {
  { m.mass } -> std::convertible_to<double>;
};

/// True when flat_continuation_error describes the metric's flat continuation: it has a mass (a `mass` member) and is
/// flat far outside the sky sphere (|g_tt - 1| < 1e-2 at 100 R on the equator: not Schwarzschild-de Sitter, whose
/// g_tt falls without bound). The estimate is the mass's leading term; a metric flat at infinity for other reasons
/// (the massless Ellis wormhole) gets none.
template <MetricPolicy M>
bool has_flat_continuation_estimate(const M& metric, double sky_radius) {
  if constexpr (HasMass<M>) {
    const Vec4 far = event_from_spherical(metric, Vec4(0.0, 100.0 * sky_radius, std::numbers::pi / 2.0, 0.0));
    return std::abs(metric.metric(far)(0, 0) - 1.0) < 1e-2;
  } else {
    return false;
  }
}

/// A largest value that threads raise concurrently while a frame is traced (relaxed: a statistic, not a
/// synchronisation); a copy starts from the value copied. What a tracer keeps to report its frame's flat
/// continuation error (the largest impact parameter of its escaped rays).
class ConcurrentMax {
 public:
  ConcurrentMax() = default;
  ConcurrentMax(const ConcurrentMax& o) : value_(o.get()) {}
  ConcurrentMax& operator=(const ConcurrentMax& o) {
    value_.store(o.get(), std::memory_order_relaxed);
    return *this;
  }
  void raise(double v) const {
    double seen = value_.load(std::memory_order_relaxed);
    while (v > seen && !value_.compare_exchange_weak(seen, v, std::memory_order_relaxed)) {
    }
  }
  double get() const { return value_.load(std::memory_order_relaxed); }

 private:
  mutable std::atomic<double> value_{0.0};
};

/// The frame-level estimate a tracer with a flat continuation reports: flat_continuation_error at the largest impact
/// parameter of the frame's escaped rays, and the sky radius that would bring it down to `tolerance`.
struct FlatContinuationEstimate {
  double error = 0.0;           ///< radians
  double impact = 0.0;          ///< the largest impact parameter of the escaped rays
  double radius_for_tolerance = 0.0;  ///< sky radius at which the error would be `tolerance`
};

/// The estimate for a frame traced in `metric` with sky radius R, whose escaped rays reached impact parameters up to
/// `largest_impact`; nothing when the metric has no such estimate (has_flat_continuation_estimate) or no ray escaped.
template <MetricPolicy M>
std::optional<FlatContinuationEstimate> flat_continuation_estimate(const M& metric, double sky_radius,
                                                                   double largest_impact, double tolerance) {
  if constexpr (HasMass<M>) {
    if (!(largest_impact > 0.0) || !has_flat_continuation_estimate(metric, sky_radius)) return std::nullopt;
    return FlatContinuationEstimate{flat_continuation_error(metric.mass, largest_impact, sky_radius), largest_impact,
                                    sky_radius_for_flat_error(metric.mass, largest_impact, tolerance)};
  } else {
    return std::nullopt;
  }
}

/// The asymptotic direction of an escaping Kerr ray (exact_mino above): its Mino-time system carried from z, a
/// point of its outgoing leg, to u = 1/r = 0 with steps of the tableau T (Fehlberg 7(8) for a tableau without an
/// embedded error estimate) at the tolerance tol. z may lie beyond infinity (u < 0: the reduced tracer's last step
/// can cross it), the step is then taken backwards. Nothing when z is not moving outwards or the steps fail (the
/// caller falls back on the flat continuation).
/// Method: Newton's iteration on the Mino time d to u = 0, each iterate a step of the tableau from z itself (split
/// in 2, 4, ... equal steps until each one's embedded error estimate meets tol): d0 from the radial potential cut
/// after u^2 (KerrMinoSystem::mino_time_to_infinity), then d += -u(d) / u'(d) (u' read off the right-hand side, in the
/// system's time), each iterate still on the way out (u' < 0), which keeps it on the first root. The last correction,
/// once its second-order term is below the tolerance, is applied to first order, z(d) + delta f(z(d)), as event
/// refinement does (trace/geodesic_tracer.hpp). Typically two steps and two right-hand sides beyond f(z): about as much
/// as the sky sphere's refinement it replaces in the tracers.
template <ExplicitTableau T>
GRTRACE_GPU_CALLED GRTRACE_HD Optional<SkyDirection> kerr_direction_at_infinity(const KerrMinoSystem& system,
                                                                                const Tolerance& tol,
                                                                                const KerrMinoSystem::State& z) {
  using State = KerrMinoSystem::State;
  if constexpr (!has_embedded_pair<T>) {
    return kerr_direction_at_infinity<Fehlberg78>(system, tol, z);
  } else {
    if (!all_finite(z) || !(z[3] < 0.0)) return no_value;  // u' = du/dlambda_M < 0: outwards
    RungeKuttaStepper<T, KerrMinoSystem::dimension> stepper;
    const State fz = system(z);
    const double angle_tolerance = tol.atol + tol.rtol * std::numbers::pi;
    // In the system's time (Mino time, or tau for a ray slowed near the axis: KerrMinoSystem::time_scale).
    double d = system.mino_time_to_infinity(z) / system.time_scale(z);
    int pieces = 1;
    for (int attempt = 0; attempt < 16; ++attempt) {
      State y = z, fy = fz;
      bool accurate = true;
      for (int p = 0; p < pieces && accurate; ++p) {
        State y_new, err;
        stepper.step(system, y, fy, d / pieces, y_new, err);
        accurate = all_finite(y_new) && RmsNorm{}(err, y, y_new, tol) <= 1.0;
        y = y_new;
        fy = system(y);
      }
      if (!accurate) {
        pieces *= 2;
        continue;
      }
      if (!all_finite(fy) || !(y[3] < 0.0)) return no_value;
      const double delta = -y[0] / fy[0];  // fy[0] = u' (times the time scale)
      // z'' over the step, (f(z(d)) - f(z)) / d, bounds the first-order finish's error: delta^2 |z''| / 2.
      const double curvature = d != 0.0 ? std::max(std::abs(fy[1] - fz[1]), std::abs(fy[2] - fz[2])) / std::abs(d)
                                        : std::numeric_limits<double>::infinity();
      if (delta == 0.0 || 0.5 * delta * delta * curvature <= angle_tolerance)
        return sky_direction_of(unit_vector_of({y[1] + delta * fy[1], y[2] + delta * fy[2]}));
      d += delta;
    }
    return no_value;
  }
}

/// The Mino-time continuation from a Boyer-Lindquist state of an escaping ray, with the tableau T.
template <ExplicitTableau T>
GRTRACE_HD Optional<SkyDirection> kerr_direction_at_infinity(const KerrMetric& metric, const Tolerance& tol,
                                                             const GeodesicState& y) {
  if (!(y[1] > metric.horizon_radius())) return no_value;
  const KerrMinoSystem system(metric, y);
  return kerr_direction_at_infinity<T>(system, tol, system.initial_state(y));
}

/// The sky direction of an escaped ray traced with the tableau T at the tolerance tol (see the top of this file):
/// `from` a point of the outgoing leg (the last accepted step's end), `at_sphere` the sky sphere's crossing.
template <ExplicitTableau T, MetricPolicy M>
GRTRACE_GPU_CALLED GRTRACE_HD SkyDirection escaped_direction(const M& metric, const Tolerance& tol,
                                                             AngleCorrection correction, const GeodesicState& from,
                                                             const GeodesicState& at_sphere) {
  if constexpr (continues_on_kerr_mino<M>) {
    if (correction == AngleCorrection::exact) {
      Optional<SkyDirection> d;
      if constexpr (std::is_same_v<M, KerrSchildMetric>) {
        if (metric.radius(from.template head<4>()) > metric.horizon_radius())
          d = kerr_direction_at_infinity<T>(metric.spherical_chart(), tol, ks_to_bl(metric, from));
      } else {
        d = kerr_direction_at_infinity<T>(metric, tol, from);
      }
      if (d) return *d;
    }
  }
  return continued_direction(metric, from, at_sphere, correction);
}

}  // namespace grtrace
