// grtrace/metric/examples/eddington_finkelstein.hpp
// Schwarzschild in ingoing Eddington-Finkelstein coordinates x = (v, r, theta, phi), v = t + r*,
// r* = r + 2M ln(r / 2M - 1):
//   ds^2 = (1 - 2M/r) dv^2 - 2 dv dr - r^2 dOmega^2.
// Regular at r = 2M (det g = -r^4 sin^2 theta), so a future-directed ray (k^v > 0) falls through the horizon
// with finite k: the chart is horizon-penetrating. With `outgoing = true` it is the outgoing chart (u = t - r*,
// +2 du dr), the time reverse, in which PAST-directed rays (a camera's rays traced backwards) cross instead.
//
// How capture is decided: the tracers capture a ray when radius(x) = r <= (1 + eps) horizon_radius(). Here
// horizon_radius() returns capture_radius() = capture_fraction * 2M (default M), INSIDE the event horizon
// (event_horizon_radius() = 2M). Inside r < 2M every future-directed causal curve has dr/dlambda < 0, so a ray
// that got there can never come back out; stopping it at r = M rather than at 2M gives the same verdict and shows
// the ray crossed the horizon without a blow-up. (Capture_fraction 1 stops at the horizon like Schwarzschild
// coordinates do; do not go near 0, the curvature singularity.)
// Takes:   mass M > 0, capture_fraction in (0, 1], outgoing. Returns: EddingtonFinkelstein (MetricComponents),
//          AutoEddingtonFinkelstein, and the state maps to and from Schwarzschild coordinates (outside r = 2M).
// Assumes: theta away from the axis; k^v > 0 (ingoing chart) for rays meant to cross the horizon.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/auto_metric.hpp"
#include "grtrace/metric/schwarzschild_lapse.hpp"

#include <array>
#include <cmath>

namespace grtrace {

struct EddingtonFinkelstein {
  static constexpr std::string_view name = "schwarzschild-eddington-finkelstein";
  static constexpr Chart chart = Chart::spherical;
  double mass = 1.0;
  double capture_fraction = 0.5;  ///< capture at r = capture_fraction * 2M (see the header comment)
  bool outgoing = false;          ///< false: ingoing v = t + r*; true: outgoing u = t - r*

  static constexpr std::array<int, 2> depends_on = {1, 2};  ///< g(r, theta): v and phi are Killing
  // Spherically symmetric: unchanged by theta -> pi - theta and phi -> 2 phi0 - phi (metric/metric_traits.hpp), so
  // a mirror-symmetric frame traces a half or a quarter of its pixels (render/mirror_symmetry.hpp).
  static constexpr bool equator_mirror_symmetric = true;
  static constexpr bool meridian_mirror_symmetric = true;

  template <class S>
  GRTRACE_HD Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S r = x[1], rs = r * sin(x[2]);
    Mat4Of<S> g = diagonal_metric<S>(schwarzschild_f(r, mass), S(0.0), -r * r, -rs * rs);
    g(0, 1) = g(1, 0) = S(outgoing ? 1.0 : -1.0);
    return g;
  }
  GRTRACE_HD double radius(const Vec4& x) const { return x[1]; }
  GRTRACE_HD double horizon_radius() const { return capture_radius(); }
  GRTRACE_HD double capture_radius() const { return capture_fraction * event_horizon_radius(); }
  GRTRACE_HD double event_horizon_radius() const { return 2.0 * mass; }

  /// sign of the cross term: v = t + sign r*, k^v = k^t + sign k^r / f.
  GRTRACE_HD double sign() const { return outgoing ? -1.0 : 1.0; }
  GRTRACE_HD double tortoise(double r) const { return r + 2.0 * mass * std::log(r / (2.0 * mass) - 1.0); }

  /// A state (t, r, theta, phi | k) in Schwarzschild coordinates (r > 2M) in this chart, and back.
  GRTRACE_HD GeodesicState from_schwarzschild(const GeodesicState& y) const {
    GeodesicState z = y;
    const double f = schwarzschild_f(y[1], mass);
    z[0] = y[0] + sign() * tortoise(y[1]);
    z[4] = y[4] + sign() * y[5] / f;
    return z;
  }
  GRTRACE_HD GeodesicState to_schwarzschild(const GeodesicState& z) const {
    GeodesicState y = z;
    const double f = schwarzschild_f(z[1], mass);
    y[0] = z[0] - sign() * tortoise(z[1]);
    y[4] = z[4] - sign() * z[5] / f;
    return y;
  }

  /// Killing energy E = g_(v) mu k^mu = f k^v - sign k^r, and L_z = r^2 sin^2(theta) k^phi.
  GRTRACE_HD double energy(const GeodesicState& y) const { return schwarzschild_f(y[1], mass) * y[4] - sign() * y[5]; }
  GRTRACE_HD double angular_momentum(const GeodesicState& y) const {
    const double rs = y[1] * std::sin(y[2]);
    return rs * rs * y[7];
  }
};

using AutoEddingtonFinkelstein = AutoMetric<EddingtonFinkelstein>;
static_assert(MetricComponents<EddingtonFinkelstein>);

}  // namespace grtrace
