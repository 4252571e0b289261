// examples/scenes/reissner_nordstrom.hpp
// A metric grtrace does not ship, written by its user: the charged, non-rotating black hole of Reissner and
// Nordstrom (G = c = 1, Gaussian units), in coordinates (t, r, theta, phi):
//   ds^2 = f dt^2 - dr^2 / f - r^2 dOmega^2,   f(r) = 1 - 2M/r + Q^2/r^2,   |Q| < M.
// Outer horizon r_+ = M + sqrt(M^2 - Q^2), photon sphere r_ph = (3M + sqrt(9M^2 - 8Q^2)) / 2, and a static observer
// at r_o sees the shadow's edge at sin(alpha) = b_c sqrt(f(r_o)) / r_o with b_c = r_ph / sqrt(f(r_ph)).
// Everything a MetricPolicy asks (metric/metric_concept.hpp): g, its Christoffel symbols, the geodesic
// acceleration in closed form, a radius, the horizon and an embedding. The thin disk, the cameras and the
// tracers work with it unchanged.
#pragma once

#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/spherical_chart.hpp"

#include <cmath>
#include <stdexcept>
#include <string_view>

struct ReissnerNordstromMetric {
  static constexpr std::string_view name = "reissner-nordstrom";
  static constexpr grtrace::Chart chart = grtrace::Chart::spherical;
  double mass = 1.0, charge = 0.0;

  /// Refuses what has no black hole: M <= 0, |Q| >= M (a naked singularity), or non-finite numbers.
  static ReissnerNordstromMetric checked(double mass, double charge) {
    if (!(mass > 0.0) || !std::isfinite(mass)) throw std::invalid_argument("mass must be a positive number");
    if (!std::isfinite(charge) || !(std::abs(charge) < mass))
      throw std::invalid_argument("charge must satisfy |Q| < M (|Q| >= M has no horizon); lower --charge");
    return {mass, charge};
  }

  double f(double r) const { return 1.0 - 2.0 * mass / r + charge * charge / (r * r); }
  double df(double r) const { return 2.0 * mass / (r * r) - 2.0 * charge * charge / (r * r * r); }
  double horizon_radius() const { return mass + std::sqrt(mass * mass - charge * charge); }
  double photon_sphere() const { return 0.5 * (3.0 * mass + std::sqrt(9.0 * mass * mass - 8.0 * charge * charge)); }
  double radius(const grtrace::Vec4& x) const { return x[1]; }
  grtrace::Vec3 to_cartesian(const grtrace::Vec4& x) const { return grtrace::spherical_to_cartesian(x); }

  grtrace::Mat4 metric(const grtrace::Vec4& x) const {
    const double r = x[1], s = std::sin(x[2]);
    return grtrace::Vec4(f(r), -1.0 / f(r), -r * r, -r * r * s * s).asDiagonal();
  }

  grtrace::Christoffel christoffel(const grtrace::Vec4& x) const {
    const double r = x[1], s = std::sin(x[2]), c = std::cos(x[2]), F = f(r), dF = df(r);
    grtrace::Christoffel G;
    for (auto& g : G) g.setZero();
    G[0](0, 1) = G[0](1, 0) = dF / (2.0 * F);
    G[1](0, 0) = F * dF / 2.0;
    G[1](1, 1) = -dF / (2.0 * F);
    G[1](2, 2) = -r * F;
    G[1](3, 3) = -r * F * s * s;
    G[2](1, 2) = G[2](2, 1) = G[3](1, 3) = G[3](3, 1) = 1.0 / r;
    G[2](3, 3) = -s * c;
    G[3](2, 3) = G[3](3, 2) = c / s;
    return G;
  }

  /// -Gamma^mu_ab k^a k^b written out (the hot loop builds no table).
  grtrace::Vec4 acceleration(const grtrace::Vec4& x, const grtrace::Vec4& k) const {
    const double r = x[1], s = std::sin(x[2]), c = std::cos(x[2]), F = f(r), h = df(r) / (2.0 * F);
    return {-2.0 * h * k[0] * k[1],
            -F * F * h * k[0] * k[0] + h * k[1] * k[1] + r * F * (k[2] * k[2] + s * s * k[3] * k[3]),
            -2.0 * k[1] * k[2] / r + s * c * k[3] * k[3],
            -2.0 * k[1] * k[3] / r - 2.0 * (c / s) * k[2] * k[3]};
  }
};
