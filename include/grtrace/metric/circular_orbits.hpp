// grtrace/metric/circular_orbits.hpp
// Equatorial circular geodesics of any stationary, axisymmetric metric in a spherical chart (t, r, theta, phi),
// from the metric policy alone (no per-metric formula to write).
//
// Takes:   a metric policy with Chart::spherical, a radius r, and the sense of the orbit (+1 towards +phi, -1
//          towards -phi).
// Returns: u = u^t (1, 0, 0, Omega) at (r, theta = pi/2), or nothing where no timelike circular orbit exists
//          (inside the photon orbit for that sense, or where the metric is not stationary there).
// Method:  with k^r = k^theta = 0 the radial geodesic equation reduces to
//              Gamma^r_tt + 2 Gamma^r_tphi Omega + Gamma^r_phiphi Omega^2 = 0,
//          a quadratic in the angular velocity Omega whose two roots are the two senses of rotation (opposite
//          signs outside the photon orbits); u^t then follows from g(u, u) = 1. For Schwarzschild this gives
//          Omega = sqrt(M / r^3) and u^t = 1 / sqrt(1 - 3M/r); for Kerr, Omega = +-1 / (r^(3/2) +- a)
//          (Bardeen, Press & Teukolsky 1972). Assumes reflection symmetry about the equator (Gamma^r_{t theta} etc.
//          play no part there).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/optional.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <cmath>
#include <numbers>

namespace grtrace {

template <MetricPolicy M>
requires(M::chart == Chart::spherical) GRTRACE_HD Optional<Vec4> circular_orbit_velocity(const M& metric, double r,
                                                                                         int sense = +1) {
  const Vec4 x(0.0, r, std::numbers::pi / 2.0, 0.0);
  const Christoffel gamma = metric.christoffel(x);
  const double a = gamma[1](3, 3), b = 2.0 * gamma[1](0, 3), c = gamma[1](0, 0);
  const double disc = b * b - 4.0 * a * c;
  if (!(disc >= 0.0) || a == 0.0) return no_value;
  // The two roots without cancellation: q = -(b + sign(b) sqrt(disc)) / 2, roots q / a and c / q.
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  const double r1 = q / a, r2 = q != 0.0 ? c / q : -r1;
  const double omega = (sense >= 0) == (r1 >= r2) ? r1 : r2;  // the larger root turns towards +phi
  const Mat4 g = metric.metric(x);
  const double norm = g(0, 0) + 2.0 * g(0, 3) * omega + g(3, 3) * omega * omega;
  if (!(norm > 0.0)) return no_value;
  const double ut = 1.0 / std::sqrt(norm);
  return Vec4(ut, 0.0, 0.0, ut * omega);
}

}  // namespace grtrace
