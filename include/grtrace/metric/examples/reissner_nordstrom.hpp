// grtrace/metric/examples/reissner_nordstrom.hpp
// Reissner-Nordstrom (charged, non-rotating) black hole, geometrised units with Q^2 in units of M^2:
//   ds^2 = f dt^2 - dr^2 / f - r^2 dOmega^2,   f = 1 - 2M/r + Q^2/r^2.
// Takes:   mass M > 0 and charge Q with |Q| < M (a black hole, not a naked singularity); x = (t, r, theta, phi).
// Returns: ReissnerNordstrom (MetricComponents) and AutoReissnerNordstrom. horizon_radius() is the outer horizon
//          r_+ = M + sqrt(M^2 - Q^2) (where rays are captured); inner_horizon_radius() is r_- = M - sqrt(M^2 - Q^2).
// Assumes: r > r_+ where it is evaluated (Schwarzschild-like coordinates, singular at both horizons).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/auto_metric.hpp"

#include <array>
#include <cmath>

namespace grtrace {

struct ReissnerNordstrom {
  static constexpr std::string_view name = "reissner-nordstrom";
  static constexpr Chart chart = Chart::spherical;
  double mass = 1.0;
  double charge = 0.5;

  static constexpr std::array<int, 2> depends_on = {1, 2};  ///< g(r, theta): t and phi are Killing

  /// f(r) = 1 - 2M/r + Q^2/r^2 = g_tt (any scalar type; with it the metric is a StaticSphericalMetric, so the
  /// planar tracer can draw it: metric/static_spherical.hpp).
  template <class S>
  GRTRACE_HD S lapse_squared(const S& r) const {
    return 1.0 - 2.0 * mass / r + charge * charge / (r * r);
  }

  template <class S>
  GRTRACE_HD Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S r = x[1], f = lapse_squared(r), rs = r * sin(x[2]);
    return diagonal_metric<S>(f, -1.0 / f, -r * r, -rs * rs);
  }
  GRTRACE_HD double radius(const Vec4& x) const { return x[1]; }
  GRTRACE_HD double horizon_radius() const { return mass + std::sqrt(mass * mass - charge * charge); }
  GRTRACE_HD double inner_horizon_radius() const { return mass - std::sqrt(mass * mass - charge * charge); }

  GRTRACE_HD double energy(const GeodesicState& y) const { return lapse_squared(y[1]) * y[4]; }
  GRTRACE_HD double angular_momentum(const GeodesicState& y) const {
    const double rs = y[1] * std::sin(y[2]);
    return rs * rs * y[7];
  }
};

using AutoReissnerNordstrom = AutoMetric<ReissnerNordstrom>;
static_assert(MetricComponents<ReissnerNordstrom>);

}  // namespace grtrace
