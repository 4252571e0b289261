// grtrace/metric/examples/ellis_wormhole.hpp
// The Ellis (Morris-Thorne) wormhole: ds^2 = dt^2 - dl^2 - (l^2 + b0^2) (dtheta^2 + sin^2(theta) dphi^2).
// Takes:   the throat radius b0 > 0; x = (t, l, theta, phi) with the proper radial distance l in (-inf, inf):
//          l > 0 is one universe, l < 0 the other, the throat is l = 0 (areal radius r(l) = sqrt(l^2 + b0^2)).
// Returns: EllisWormhole (MetricComponents) and AutoEllisWormhole. No horizon: horizon_radius() = 0, and radius()
//          is the areal radius r(l) >= b0 > 0, so the tracer's capture test never fires and a ray leaves through
//          the escape sphere r(l) = R on either side (the sign of l says which universe).
// Assumes: theta away from the axis. Flat as |l| -> infinity (g_thth / -l^2 - 1 = b0^2 / l^2).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/auto_metric.hpp"

#include <array>
#include <cmath>

namespace grtrace {

struct EllisWormhole {
  static constexpr std::string_view name = "ellis-wormhole";
  static constexpr Chart chart = Chart::spherical;
  double throat = 1.0;  ///< b0

  static constexpr std::array<int, 2> depends_on = {1, 2};  ///< g(l, theta): t and phi are Killing
  // Spherically symmetric: unchanged by theta -> pi - theta and phi -> 2 phi0 - phi (metric/metric_traits.hpp), so
  // a mirror-symmetric frame traces a half or a quarter of its pixels (render/mirror_symmetry.hpp).
  static constexpr bool equator_mirror_symmetric = true;
  static constexpr bool meridian_mirror_symmetric = true;

  template <class S>
  GRTRACE_HD Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S r2 = x[1] * x[1] + throat * throat, st = sin(x[2]);
    return diagonal_metric<S>(S(1.0), S(-1.0), -r2, -r2 * st * st);
  }
  GRTRACE_HD double areal_radius(double l) const { return std::sqrt(l * l + throat * throat); }
  GRTRACE_HD double radius(const Vec4& x) const { return areal_radius(x[1]); }
  GRTRACE_HD double horizon_radius() const { return 0.0; }
  /// Both universes drawn over one another at their areal radius.
  GRTRACE_HD Vec3 to_cartesian(const Vec4& x) const {
    Vec4 y = x;
    y[1] = areal_radius(x[1]);
    return spherical_to_cartesian(y);
  }

  GRTRACE_HD double energy(const GeodesicState& y) const { return y[4]; }
  GRTRACE_HD double angular_momentum(const GeodesicState& y) const {
    const double st = std::sin(y[2]);
    return (y[1] * y[1] + throat * throat) * st * st * y[7];
  }
};

using AutoEllisWormhole = AutoMetric<EllisWormhole>;
static_assert(MetricComponents<EllisWormhole>);

}  // namespace grtrace
