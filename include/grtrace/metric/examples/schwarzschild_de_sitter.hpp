// grtrace/metric/examples/schwarzschild_de_sitter.hpp
// Schwarzschild-de Sitter (Kottler): a mass in a universe with a positive cosmological constant,
//   ds^2 = f dt^2 - dr^2 / f - r^2 dOmega^2,   f = 1 - 2M/r - Lambda r^2 / 3.
// Takes:   mass M > 0 and Lambda with 0 < 9 Lambda M^2 < 1 (two horizons); x = (t, r, theta, phi).
// Returns: SchwarzschildDeSitter (MetricComponents) and AutoSchwarzschildDeSitter. The horizons are the positive
//          roots of r f(r) = 0, i.e. of the cubic Lambda r^3 / 3 - r + 2M = 0, in closed (trigonometric) form:
//            r_k = (2 / sqrt(Lambda)) cos(arccos(-3 M sqrt(Lambda)) / 3 - 2 pi k / 3),
//          k = 0 the cosmological horizon r_c (~ sqrt(3 / Lambda)), k = 1 the black-hole horizon r_b (~ 2M), k = 2 a
//          negative root. Both are polished with Newton steps on the cubic (the trigonometric form loses digits to
//          cancellation for small Lambda). horizon_radius() is r_b (the tracer captures there).
// Assumes: r_b < r < r_c (the static region, where t is timelike): the tracer's escape radius must be below r_c.
//          Not asymptotically flat: g_tt -> -infinity beyond r_c.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/auto_metric.hpp"

#include <array>
#include <cmath>
#include <numbers>

namespace grtrace {

struct SchwarzschildDeSitter {
  static constexpr std::string_view name = "schwarzschild-de-sitter";
  static constexpr Chart chart = Chart::spherical;
  double mass = 1.0;
  double lambda = 1e-4;  ///< cosmological constant Lambda (units 1/M^2)

  static constexpr std::array<int, 2> depends_on = {1, 2};  ///< g(r, theta): t and phi are Killing
  // Spherically symmetric: unchanged by theta -> pi - theta and phi -> 2 phi0 - phi (metric/metric_traits.hpp), so
  // a mirror-symmetric frame traces a half or a quarter of its pixels (render/mirror_symmetry.hpp).
  static constexpr bool equator_mirror_symmetric = true;
  static constexpr bool meridian_mirror_symmetric = true;

  template <class S>
  GRTRACE_HD Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S r = x[1], f = 1.0 - 2.0 * mass / r - (lambda / 3.0) * r * r, rs = r * sin(x[2]);
    return diagonal_metric<S>(f, -1.0 / f, -r * r, -rs * rs);
  }
  GRTRACE_HD double radius(const Vec4& x) const { return x[1]; }
  GRTRACE_HD double horizon_radius() const { return black_hole_horizon_radius(); }

  /// The k-th root of Lambda r^3 / 3 - r + 2M (k = 0: r_c, 1: r_b, 2: the negative one), Newton-polished.
  GRTRACE_HD double cubic_root(int k) const {
    const double s = std::sqrt(lambda);
    const double angle = std::acos(-3.0 * mass * s) / 3.0 - 2.0 * std::numbers::pi * k / 3.0;
    double r = 2.0 / s * std::cos(angle);
    for (int i = 0; i < 3; ++i) r -= horizon_cubic(r) / (lambda * r * r - 1.0);
    return r;
  }
  GRTRACE_HD double black_hole_horizon_radius() const { return cubic_root(1); }
  GRTRACE_HD double cosmological_horizon_radius() const { return cubic_root(0); }
  /// r f(r) = r - 2M - Lambda r^3 / 3, up to sign: zero exactly at the horizons.
  GRTRACE_HD double horizon_cubic(double r) const { return lambda * r * r * r / 3.0 - r + 2.0 * mass; }

  GRTRACE_HD double energy(const GeodesicState& y) const {
    const double r = y[1];
    return (1.0 - 2.0 * mass / r - lambda * r * r / 3.0) * y[4];
  }
  GRTRACE_HD double angular_momentum(const GeodesicState& y) const {
    const double rs = y[1] * std::sin(y[2]);
    return rs * rs * y[7];
  }
};

using AutoSchwarzschildDeSitter = AutoMetric<SchwarzschildDeSitter>;
static_assert(MetricComponents<SchwarzschildDeSitter>);

}  // namespace grtrace
