// grtrace/metric/static_spherical.hpp
// Static, spherically symmetric metrics in a spherical chart (t, r, theta, phi):
//   ds^2 = A(r) dt^2 - B(r) dr^2 - r^2 (dtheta^2 + sin^2 theta dphi^2),
// i.e. Schwarzschild, Reissner-Nordstrom, Schwarzschild-de Sitter and any other "f(r)" spacetime. What the
// planar-path tracer (trace/planar_path_table.hpp) needs of a metric, and the reduced ray equation it integrates.
//
// Must provide (the StaticSphericalMetric concept):
//   a MetricPolicy in Chart::spherical whose horizon_radius() is that of the metric (> 0 for the planar tracer)
//   template <class S> S lapse_squared(const S& r) const     A(r) = g_tt, callable with double and Dual<1>
// May provide (detected at compile time):
//   template <class S> S radial_scale_squared(const S& r) const   B(r) = -g_rr; default 1 / A(r) (g_tt g_rr = -1,
//                                                                 true of every f(r) metric: no rounding noise)
//   double photon_sphere_radius() const                           default: the minimum of r^2 / A(r) outside the
//                                                                 horizon, found numerically (assumes there is one)
//   double planar_ray_curvature(double u) const                   G(u) below in closed form, for f(r) metrics
//                                                                 (B = 1 / A) only; default: by differentiation
//
// Why a ray reduces to one equation: every ray stays in a plane through the centre (symmetry), and in that plane
// its path u(psi) = 1 / r as a function of the swept angle psi obeys, with the impact parameter b = L / E,
//   (du/dpsi)^2 = F(u) = P(u) / b^2 - Q(u),   P = 1 / (A B),   Q = u^2 / B   (A, B at r = 1 / u),
// and, differentiated once, the second-order form u'' = (P'(u) / b^2 - Q'(u)) / 2 that has no turning-point
// trouble (u' changes sign smoothly at a periapsis). For f(r) metrics P = 1 and u'' = -(u^2 A(1/u))' / 2 is the
// same for every ray (Schwarzschild: u'' = 3 M u^2 - u; Chandrasekhar, The Mathematical Theory of Black Holes,
// ch. 3, eq. 16 and 85).
#pragma once

#include "grtrace/core/golden_section.hpp"
#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/dual.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <cmath>
#include <concepts>
#include <stdexcept>

namespace grtrace {

template <class M>
concept StaticSphericalMetric =
    MetricPolicy<M> && (M::chart == Chart::spherical) && requires(const M m, double r, Dual<1> d) {
      { m.lapse_squared(r) } -> std::convertible_to<double>;
      { m.lapse_squared(d) } -> std::convertible_to<Dual<1>>;
    };

/// True when the metric gives B(r) = -g_rr itself (else B = 1 / A).
template <class M>
concept HasRadialScale = requires(const M m, double r, Dual<1> d) {
  { m.radial_scale_squared(r) } -> std::convertible_to<double>;
  { m.radial_scale_squared(d) } -> std::convertible_to<Dual<1>>;
};

/// B(r) = -g_rr of a static spherical metric, in any scalar type.
template <StaticSphericalMetric M, class S>
GRTRACE_HD S radial_scale_squared(const M& metric, const S& r) {
  if constexpr (HasRadialScale<M>) return metric.radial_scale_squared(r);
  else return 1.0 / metric.lapse_squared(r);
}

/// The planar ray equation of one ray: u'' = G(u) for impact parameter b (see the top of this file).
template <StaticSphericalMetric M>
struct PlanarRayEquation {
  const M* metric;
  double inverse_b2;  ///< 1 / b^2 (only used when the metric has its own B(r))

  /// d/dpsi of (u, u'): (u', G(u)).
  GRTRACE_HD Vector<2> operator()(const Vector<2>& y) const { return {y[1], curvature(y[0])}; }

  /// G(u) = (P'(u) / b^2 - Q'(u)) / 2 from A, B and their r-derivatives (automatic differentiation in r), with
  /// dr/du = -r^2 folded in analytically so that u = 0 (r = infinity) and u < 0 (the continuation of an escaped
  /// ray past infinity) stay finite: Q' = 2u / B + B_r / B^2 and P' = (A B)_r / ((A B)^2 u^2).
  GRTRACE_HD double curvature(double u) const {
    if constexpr (requires { { metric->planar_ray_curvature(u) } -> std::convertible_to<double>; }) {
      static_assert(!HasRadialScale<M>, "planar_ray_curvature(u) is the f(r) form (B = 1 / A): it has no 1 / b^2 term");
      return metric->planar_ray_curvature(u);
    } else if constexpr (HasRadialScale<M>) {
      // P' has r^2 (A B)_r, finite as r -> infinity for an asymptotically flat metric but 0 * inf at u = 0.
      const double us = std::abs(u) < 1e-100 ? std::copysign(1e-100, u) : u;
      const Dual<1> r = Dual<1>::variable(1.0 / us, 0);
      const Dual<1> a = metric->lapse_squared(r), b = metric->radial_scale_squared(r);
      const Dual<1> ab = a * b;
      const double p_u = ab.d[0] / (us * us * ab.v * ab.v);  // dP/du = -(AB)_r / (AB)^2 * dr/du, dr/du = -1/u^2
      const double q_u = 2.0 * us / b.v + b.d[0] / (b.v * b.v);
      return 0.5 * (p_u * inverse_b2 - q_u);
    } else {
      // P = 1 exactly (no 1 / b^2 term, no rounding noise multiplied by it); Q = u^2 A, Q' = 2u A - A_r. Terms
      // such as Q^2 / r^2 overflow to inf / inf for |u| below ~1e-154: G is smooth there, so read it at 1e-100.
      const double us = std::abs(u) < 1e-100 ? std::copysign(1e-100, u) : u;
      const Dual<1> a = metric->lapse_squared(Dual<1>::variable(1.0 / us, 0));
      return 0.5 * a.d[0] - us * a.v;
    }
  }

  /// F(u) = (du/dpsi)^2 on the ray (for tests and for starting values).
  GRTRACE_HD double first_integral(double u) const {
    const double r = 1.0 / u, a = metric->lapse_squared(r), b = radial_scale_squared(*metric, r);
    return inverse_b2 / (a * b) - u * u / b;
  }
};

/// The photon-sphere radius: the minimum of r^2 / A(r) outside the horizon (the circular null orbit), the
/// metric's own photon_sphere_radius() when it has one. Numerically: golden-section search on (r_h, 1e4 r_h]
/// (the critical impact parameter sqrt(min r^2 / A) is accurate to rounding even though the argument of the
/// minimum is only found to ~1e-8 relative: the function is flat there).
template <StaticSphericalMetric M>
double photon_sphere_radius(const M& metric) {
  if constexpr (requires { { metric.photon_sphere_radius() } -> std::convertible_to<double>; })
    return metric.photon_sphere_radius();
  else {
    const double rh = metric.horizon_radius();
    if (!(rh > 0.0)) throw std::invalid_argument("photon_sphere_radius: the metric has no horizon");
    auto h = [&](double r) { return r * r / metric.lapse_squared(r); };
    return golden_section_minimum(h, rh * (1.0 + 1e-9), 1e4 * rh, {1e-13, 0.0}).x;
  }
}

/// b_c = r_ph / sqrt(A(r_ph)): rays with smaller impact parameter from outside the photon sphere are captured.
template <StaticSphericalMetric M>
GRTRACE_HD double critical_impact_parameter(const M& metric) {
  const double r = photon_sphere_radius(metric);
  return r / std::sqrt(metric.lapse_squared(r));
}

}  // namespace grtrace
