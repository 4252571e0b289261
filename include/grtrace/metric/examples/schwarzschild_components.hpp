// grtrace/metric/examples/schwarzschild_components.hpp
// Schwarzschild (and flat space in spherical coordinates) written the automatic way: only g_{mu nu}.
// Takes:   mass M >= 0 (M = 0 is flat space in spherical coordinates), x = (t, r, theta, phi).
// Returns: SchwarzschildComponents (a MetricComponents type) and AutoSchwarzschild = AutoMetric<it>, whose
//          Christoffel symbols and acceleration come from differentiating g; the tests hold them to the closed
//          forms of SchwarzschildMetric, and the benchmark prices the automatic path against the hand-written one.
// Assumes: r > 2M and theta away from the axis, like SchwarzschildMetric.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/auto_metric.hpp"
#include "grtrace/metric/schwarzschild_lapse.hpp"

#include <array>
#include <cmath>

namespace grtrace {

struct SchwarzschildComponents {
  static constexpr std::string_view name = "schwarzschild-auto";
  static constexpr Chart chart = Chart::spherical;
  double mass = 1.0;

  static constexpr std::array<int, 2> depends_on = {1, 2};  ///< g(r, theta): t and phi are Killing
  // Spherically symmetric: unchanged by theta -> pi - theta and phi -> 2 phi0 - phi (metric/metric_traits.hpp), so
  // a mirror-symmetric frame traces a half or a quarter of its pixels (render/mirror_symmetry.hpp).
  static constexpr bool equator_mirror_symmetric = true;
  static constexpr bool meridian_mirror_symmetric = true;

  template <class S>
  GRTRACE_HD Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S r = x[1], f = schwarzschild_f(r, mass), rs = r * sin(x[2]);
    return diagonal_metric<S>(f, -1.0 / f, -r * r, -rs * rs);
  }
  GRTRACE_HD double radius(const Vec4& x) const { return x[1]; }
  GRTRACE_HD double horizon_radius() const { return 2.0 * mass; }

  /// Killing energy E = (1 - 2M/r) k^t and axial angular momentum L_z = r^2 sin^2(theta) k^phi.
  GRTRACE_HD double energy(const GeodesicState& y) const { return schwarzschild_f(y[1], mass) * y[4]; }
  GRTRACE_HD double angular_momentum(const GeodesicState& y) const {
    const double rs = y[1] * std::sin(y[2]);
    return rs * rs * y[7];
  }
};

using AutoSchwarzschild = AutoMetric<SchwarzschildComponents>;
static_assert(MetricComponents<SchwarzschildComponents>);
static_assert(MetricPolicy<AutoSchwarzschild>);

}  // namespace grtrace
