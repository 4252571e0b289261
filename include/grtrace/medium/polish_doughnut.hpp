// grtrace/medium/polish_doughnut.hpp
// A geometrically thick torus of gas in hydrostatic equilibrium around a rotating (or not) hole: the "Polish
// doughnut" of constant specific angular momentum (Abramowicz, Jaroszynski & Sikora 1978; Kozlowski, Jaroszynski &
// Abramowicz 1978), an emitting medium (medium/emitting_medium.hpp) for any stationary axisymmetric metric in a
// spherical chart (Kerr in Boyer-Lindquist coordinates, Schwarzschild, Reissner-Nordstrom).
//
// Takes:   the inner edge r_in and the pressure maximum r_c on the equator (r_in < r_c; prograde: the gas turns
//          towards +phi), the polytropic index n (p = K rho^(1 + 1/n)), the emissivity j0 and opacity kappa per
//          unit density: j_nu = j0 rho, alpha_nu = kappa rho (grey, frequency-independent: a constant source
//          function S = j0 / kappa where kappa > 0).
// Returns: rho (1 at r_c), j, alpha and the gas's 4-velocity at an event.
// Method:  the gas turns on circles with l = -u_phi / u_t the same everywhere, the Keplerian value at r_c. With
//          signature (+, -, -, -), g^{mu nu} u_mu u_nu = 1 gives u_t = A^(-1/2), A = g^tt - 2 l g^tphi + l^2 g^phiphi,
//          and the relativistic Euler equation of a barotropic gas integrates to h = exp(W_in - W), W = ln u_t (the
//          effective potential; h the specific enthalpy, 1 on the surface through r_in). A polytrope's enthalpy is
//          h = 1 + (n + 1) K rho^(1/n), so rho = ((h - 1) / (h_c - 1))^n. Where A <= 0 no orbit of this l is
//          timelike (near the axis and the horizon): no gas. The angular velocity is
//          Omega = -(g_tphi + l g_tt) / (g_phiphi + l g_tphi), given wherever that circle is timelike (on the
//          surface too); where it is not, the zero angular momentum observer's (any timelike one would do: no gas).
//          W also falls below W_in near the horizon (W -> -inf there: rho would grow without bound as g -> 0, and a
//          ray grazing the horizon collected 8 times a torus ray's light there). That region lies inside the radius
//          where W is largest on the equator between the horizon and r_in: the cusp, where l is below the
//          equatorial photon orbit's impact parameter (the torus through r_in lies within the critical
//          equipotential's outer lobe, whose tip the cusp is); else the outer edge of a band of radii where no
//          orbit of this l is timelike. The gas is the part outside that radius (cusp_radius_inside()).
// Assumes: r_c beyond the marginally bound orbit, so that the torus closes (W_in < 0: a finite outer edge, found on
//          the equator at construction; off the equator the surface lies inside that radius, as a constant-l
//          torus's does: tests/medium_torus_test.cpp checks it on a grid).
#pragma once

#include "grtrace/core/golden_section.hpp"
#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/metric/circular_orbits.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string_view>

namespace grtrace {

template <MetricPolicy Metric>
class PolishDoughnut {
  static_assert(Metric::chart == Chart::spherical,
                "PolishDoughnut: the torus is stated in a spherical chart (t, r, theta, phi) of a stationary "
                "axisymmetric metric (Kerr in Boyer-Lindquist coordinates, Schwarzschild)");

 public:
  static constexpr std::string_view kind = "polish-doughnut";
  static constexpr bool stationary = true;
  static constexpr bool axisymmetric = true;
  static constexpr bool equator_mirror_symmetric = true;
  static constexpr bool frequency_independent = true;

  /// Takes the metric (held by value: the torus's constants are computed from it), r_in < r_c, n > 0, j0 >= 0,
  /// kappa >= 0. std::invalid_argument when no torus exists for them (see the top of this file).
  PolishDoughnut(const Metric& metric, double r_in, double r_c, double n = 3.0, double j0 = 1.0, double kappa = 0.0)
      : metric_(metric), r_in_(r_in), r_c_(r_c), n_(n), j0_(j0), kappa_(kappa) {
    if (!(r_in > 0.0 && r_c > r_in && n > 0.0 && j0 >= 0.0 && kappa >= 0.0))
      throw std::invalid_argument("PolishDoughnut: need 0 < r_in < r_c, n > 0, j0 >= 0, kappa >= 0");
    if (n == std::round(n) && n <= 8.0) whole_n_ = static_cast<int>(n);
    const auto u = circular_orbit_velocity(metric, r_c, +1);
    if (!u) throw std::invalid_argument("PolishDoughnut: no circular orbit at r_c (inside the photon orbit)");
    const Vec4 lowered = metric.metric(Vec4(0.0, r_c, std::numbers::pi / 2.0, 0.0)) * *u;
    l_ = -lowered[3] / lowered[0];
    w_in_ = potential(equator(r_in));
    w_c_ = potential(equator(r_c));
    if (!(w_in_ < 0.0))
      throw std::invalid_argument(
          "PolishDoughnut: the torus through r_in is not bound (its surface is open); "
          "move r_in out or r_c in");
    if (!(w_c_ < w_in_)) throw std::invalid_argument("PolishDoughnut: no gas between r_in and r_c");
    h_c_minus_1_ = std::expm1(w_in_ - w_c_);
    exp_w_in_ = std::exp(w_in_);
    // The outer edge on the equator: W rises from W_c at r_c back to W_in (bracketed by doubling, then bisected).
    double lo = r_c, hi = 2.0 * r_c;
    while (potential(equator(hi)) < w_in_) {
      lo = hi;
      hi *= 2.0;
      if (hi > 1e12) throw std::invalid_argument("PolishDoughnut: no outer edge found");
    }
    for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (potential(equator(mid)) < w_in_ ? lo : hi) = mid;
    }
    r_out_ = hi;
    r_cusp_ = cusp_radius();
  }

  double outer_radius() const { return r_out_; }
  /// The equator's radius inside r_in where W is largest (the cusp of the critical equipotential, or the outer edge
  /// of a band where no orbit of this l is timelike): the gas is outside it (see the top of this file).
  double cusp_radius_inside() const { return r_cusp_; }
  /// No gas inside the cusp's radius (boundary()): a ray that falls in ends there.
  double inner_radius() const { return r_cusp_; }
  double inner_edge() const { return r_in_; }
  double pressure_maximum() const { return r_c_; }
  double angular_momentum() const { return l_; }  ///< l = -u_phi / u_t

  /// W = ln u_t at x (+infinity where no orbit of this l is timelike).
  double potential(const Vec4& x) const {
    const double a = orbit_norm(x);
    return a > 0.0 ? -0.5 * std::log(a) : std::numeric_limits<double>::infinity();
  }

  /// The specific enthalpy h = exp(W_in - W) = exp(W_in) sqrt(A) at x (> 1 inside the torus, 1 on its surface;
  /// 0 where no orbit of this l is timelike). With sqrt(A) = 1 / u_t it needs neither the log of W nor an exp: at
  /// every stage of a step through the gas those two were a tenth of a torus frame's time.
  double enthalpy(const Vec4& x) const { return enthalpy_from(metric_.metric(x)); }

  /// rho at x: 1 at the pressure maximum, 0 outside the torus.
  double density(const Vec4& x) const {
    if (!(x[1] > r_cusp_)) return 0.0;
    const double h = enthalpy(x);
    if (!(h > 1.0)) return 0.0;
    return signed_power((h - 1.0) / h_c_minus_1_);
  }

  /// Positive outside the torus, <= 0 inside (1 - h, which is W - W_in to first order at the surface and rises to 1
  /// where no orbit of this l is timelike; and the distance inside the cusp's radius, where W < W_in again near the
  /// horizon, capped at 1): the tracer ends its steps on the surface, where rho ~ depth^n is not smooth.
  template <MetricPolicy M>
  double boundary(const M&, const Vec4& x) const {
    return std::min(std::max(1.0 - enthalpy(x), r_cusp_ - x[1]), 1.0);
  }

  /// j and alpha from rho continued smoothly across the surface (odd in h - 1: negative outside), as the tracer
  /// needs them within a step that ends on the surface (boundary()); it takes none outside.
  template <MetricPolicy M>
  MediumCoefficients coefficients(const M& m, const Vec4& x, double nu) const {
    return coefficients(m, x, metric_.metric(x), nu);
  }
  /// The same given g_{mu nu} at x (the tracer's, emitting_medium.hpp).
  template <MetricPolicy M>
  MediumCoefficients coefficients(const M&, const Vec4&, const Mat4& g, double /*nu*/) const {
    // h - 1 with W capped at W_in + 1 (h >= 1 / e: where no orbit of this l is timelike, h - 1 ~ -0.6).
    const double h1 = std::max(enthalpy_from(g), 1.0 / std::numbers::e) - 1.0;
    const double rho = signed_power(h1 / h_c_minus_1_);
    return {j0_ * rho, kappa_ * rho};
  }

  template <MetricPolicy M>
  Vec4 fluid_velocity(const M& m, const Vec4& x) const {
    return fluid_velocity(m, x, metric_.metric(x));
  }
  /// The same given g_{mu nu} at x (the tracer's, emitting_medium.hpp).
  template <MetricPolicy M>
  Vec4 fluid_velocity(const M&, const Vec4&, const Mat4& g) const {
    double omega = -(g(0, 3) + l_ * g(0, 0)) / (g(3, 3) + l_ * g(0, 3));
    double norm = g(0, 0) + 2.0 * omega * g(0, 3) + omega * omega * g(3, 3);
    // The gas's circles wherever they are timelike (its surface included: a ray meeting it there is shaded by this
    // velocity); where they are not, no gas either: the zero angular momentum observer.
    if (!(norm > 0.0)) {
      omega = -g(0, 3) / g(3, 3);
      norm = g(0, 0) + 2.0 * omega * g(0, 3) + omega * omega * g(3, 3);
    }
    const double ut = 1.0 / std::sqrt(norm);
    return Vec4(ut, 0.0, 0.0, ut * omega);
  }

 private:
  /// |x|^n with the sign of x: by multiplication for a whole n up to 8 (pow is a tenth of a torus frame's time).
  double signed_power(double x) const {
    const double a = std::abs(x);
    double p = 1.0;
    if (whole_n_ > 0)
      for (int i = 0; i < whole_n_; ++i) p *= a;
    else p = std::pow(a, n_);
    return std::copysign(p, x);
  }

  static Vec4 equator(double r) { return Vec4(0.0, r, std::numbers::pi / 2.0, 0.0); }

  /// A = g^tt - 2 l g^tphi + l^2 g^phiphi = 1 / u_t^2 from g_{mu nu} at x (<= 0 where no orbit of this l is
  /// timelike).
  double orbit_norm(const Mat4& g) const {
    const double d = g(0, 0) * g(3, 3) - g(0, 3) * g(0, 3);
    return (g(3, 3) + 2.0 * l_ * g(0, 3) + l_ * l_ * g(0, 0)) / d;
  }
  double orbit_norm(const Vec4& x) const { return orbit_norm(metric_.metric(x)); }
  /// enthalpy() from g_{mu nu} at x.
  double enthalpy_from(const Mat4& g) const {
    const double a = orbit_norm(g);
    return a > 0.0 ? exp_w_in_ * std::sqrt(a) : 0.0;  // also 0 for a NaN A (on the axis), as W = +infinity there
  }

  /// Where W is largest on the equator between the horizon and r_in: on a geometric grid of 256 radii, then by
  /// golden section between the neighbours of the largest sample (W rises from -inf at the horizon to the cusp and
  /// falls to W_c at r_c, where l is below the photon orbit's impact parameter); where l is above it, a band of
  /// radii has no timelike orbit of this l (W = +inf), and its outer edge is found by bisection.
  double cusp_radius() const {
    const double r_h = std::max(metric_.horizon_radius(), 1e-3 * r_in_);
    constexpr int kSamples = 256;
    const double ratio = std::pow(r_in_ / r_h, 1.0 / kSamples);
    int best = kSamples;
    double w_best = -std::numeric_limits<double>::infinity(), r = r_in_;
    for (int i = kSamples; i > 0; --i, r /= ratio) {
      const double w = potential(equator(r));
      if (w > w_best) {
        w_best = w;
        best = i;
      }
    }
    const double at = r_h * std::pow(ratio, best);
    if (!std::isfinite(w_best)) {  // the band's outer edge, by bisection between its last sample and the next
      double in = at, out = std::min(at * ratio, r_in_);
      for (int i = 0; i < 100 && out - in > 1e-13 * out; ++i) {
        const double mid = 0.5 * (in + out);
        (std::isfinite(potential(equator(mid))) ? out : in) = mid;
      }
      return out;
    }
    return golden_section_maximum([&](double x) { return potential(equator(x)); }, at / ratio,
                                  std::min(at * ratio, r_in_), {1e-12, 0.0}, 100)
        .x;
  }

  Metric metric_;
  double r_in_, r_c_, n_, j0_, kappa_;
  int whole_n_ = 0;  ///< n where it is a whole number up to 8 (signed_power), else 0
  double l_ = 0.0, w_in_ = 0.0, w_c_ = 0.0, h_c_minus_1_ = 1.0, exp_w_in_ = 1.0, r_out_ = 0.0, r_cusp_ = 0.0;
};

}  // namespace grtrace
