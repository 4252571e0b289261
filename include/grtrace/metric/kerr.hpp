// grtrace/metric/kerr.hpp
// Kerr spacetime in Boyer-Lindquist coordinates x = (t, r, theta, phi), G = c = 1, signature (+,-,-,-).
//
// Takes:   mass M > 0 and spin a with |a| < M (a < 0: the hole rotates towards -phi); KerrMetric::checked()
//          refuses anything else. Events x with r > r_+ and theta away from the axis (sin theta != 0).
// Returns: g_{mu nu}, Gamma^mu_{ab}, the geodesic acceleration -Gamma^mu_{ab} k^a k^b in closed form, and the
//          quantities of the geometry (horizons, ergosphere, frame dragging, lapse, the constants E, L_z, Q of
//          a geodesic, the Kretschmann scalar).
// Formulas (shared/reference/kerr.md): Boyer & Lindquist, J. Math. Phys. 8, 265 (1967); Carter, Phys. Rev. 174,
// 1559 (1968) for Q; Visser, arXiv:0706.0622 for the horizons, ergosphere, ZAMO and the Kretschmann scalar.
//   Sigma = r^2 + a^2 cos^2 th,  Delta = r^2 - 2 M r + a^2,  A = (r^2 + a^2)^2 - a^2 Delta sin^2 th
//   g_tt = 1 - 2Mr/Sigma, g_tph = 2 M a r sin^2 th / Sigma, g_rr = -Sigma/Delta, g_thth = -Sigma,
//   g_phph = -(A/Sigma) sin^2 th = -(r^2 + a^2 + 2 M r a^2 sin^2 th / Sigma) sin^2 th
// Chart singularities: the horizons Delta = 0 (steps shrink to zero approaching r_+; capture at (1 + eps) r_+
// as for Schwarzschild; metric/kerr_schild.hpp crosses it) and the axis sin th = 0.
// With a = 0 every function equals SchwarzschildMetric's.
//
// The acceleration is derived from the Euler-Lagrange form of the geodesic equation, which needs only the
// first derivatives of the metric (it depends on r and theta only):
//   F_nu = 1/2 (d_nu g_ab) k^a k^b - (k^r d_r + k^th d_th) g_{nu b} k^b,     a^mu = g^{mu nu} F_nu,
// with g^{mu nu} block-diagonal and the (t, phi) block inverted exactly (its determinant is -Delta sin^2 th).
// Written with h = 2Mr/Sigma and T = k^t - a sin^2 th k^phi, the (t, phi) part of g(k, k) is
// (k^t)^2 - (r^2 + a^2) sin^2 th (k^phi)^2 - h T^2, which keeps the formulas short: ~115 flops, one sincos, three
// divisions, no 4x4 tables (about 2x SchwarzschildMetric::acceleration; tests/benchmarks/kerr_benchmark.cpp).
// christoffel() builds the full table from the analytic derivatives of the five metric components in
// KerrBLTerms (tests and tools); the tests check acceleration() against it and both against finite differences
// of metric().
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/sin_cos.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/spherical_chart.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>

namespace grtrace {

/// The repeated subexpressions of the Kerr metric at (r, theta) in Boyer-Lindquist form and its five distinct
/// components: what metric(), inverse_metric() and the constants of motion need (a medium asks for them at every
/// stage of every step: without the derivatives below, about half of KerrBLTerms' work).
struct KerrBLComponents {
  double r, sin_theta, cos_theta;
  double sigma, delta, big_a;                 ///< Sigma, Delta, A
  double inv_sigma, inv_delta, inv_tphi_det;  ///< 1/Sigma, 1/Delta, 1/(g_tt g_phph - g_tph^2) = -1/(Delta sin^2)
  double g_tt, g_tph, g_phph, g_rr, g_thth;

  // The inline sincos (core/sin_cos.hpp), not libm's: the same bits on a GPU as on the CPU (the device's sin and
  // cos differ from glibc's in the last bit), so a ray's constants of motion, and the reduced Kerr tracer's path
  // that they steer, are the CPU's.
  GRTRACE_HD KerrBLComponents(double mass, double a, double r_in, double theta)
      : KerrBLComponents(mass, a, r_in, polar_sin_cos(theta)) {}

  /// From theta's sine and cosine, where a caller has them without theta (a closed-form ray's cos theta).
  GRTRACE_HD KerrBLComponents(double mass, double a, double r_in, SinCos sin_cos_theta) : r(r_in) {
    const double m = mass, s = sin_cos_theta.sin, c = sin_cos_theta.cos;
    sin_theta = s;
    cos_theta = c;
    const double r2 = r * r, a2 = a * a, s2 = s * s, c2 = c * c, ra2 = r2 + a2;
    sigma = r2 + a2 * c2;
    delta = r2 - 2.0 * m * r + a2;
    big_a = ra2 * ra2 - a2 * delta * s2;
    // Three divisions in all. (1/Delta is not taken as sin^2 / (Delta sin^2): that would make metric() NaN on
    // the axis, where only the (t, phi) block is singular.)
    inv_sigma = 1.0 / sigma;
    inv_delta = 1.0 / delta;
    inv_tphi_det = -inv_delta / s2;
    const double two_mr = 2.0 * m * r;
    g_tt = 1.0 - two_mr * inv_sigma;
    g_tph = two_mr * a * s2 * inv_sigma;
    g_phph = -(ra2 + two_mr * a2 * s2 * inv_sigma) * s2;
    g_rr = -sigma * inv_delta;
    g_thth = -sigma;
  }

  /// g_tt g_phph - g_tph^2 = -Delta sin^2 theta (exact, no cancellation).
  GRTRACE_HD double tphi_determinant() const { return -delta * sin_theta * sin_theta; }
};

/// The components and the first derivatives of the five distinct metric components (d/dr and d/dtheta; nothing
/// depends on t or phi): what the Christoffel symbols need.
struct KerrBLTerms : KerrBLComponents {
  double dr_tt, dr_tph, dr_phph, dr_rr, dr_thth;       ///< d/dr
  double dth_tt, dth_tph, dth_phph, dth_rr, dth_thth;  ///< d/dtheta

  GRTRACE_HD KerrBLTerms(double mass, double a, double r_in, double theta) : KerrBLComponents(mass, a, r_in, theta) {
    const double m = mass, s = sin_theta, c = cos_theta;
    const double r2 = r * r, a2 = a * a, s2 = s * s, c2 = c * c, ra2 = r2 + a2;
    const double inv_sigma2 = inv_sigma * inv_sigma;
    const double two_mr = 2.0 * m * r;
    // d Sigma/dr = 2r, d Sigma/dth = -2 a^2 s c; (Sigma - 2 r^2) = -(r^2 - a^2 c^2) appears in every d/dr.
    const double w = (r2 - a2 * c2) * inv_sigma2;  // -(d/dr)(r / Sigma)
    const double sc = s * c;
    dr_tt = 2.0 * m * w;
    dr_tph = -2.0 * m * a * s2 * w;
    dr_phph = -2.0 * r * s2 + 2.0 * m * a2 * s2 * s2 * w;
    dr_rr = -(2.0 * r * delta - 2.0 * (r - m) * sigma) * inv_delta * inv_delta;
    dr_thth = -2.0 * r;
    dth_tt = -2.0 * two_mr * a2 * sc * inv_sigma2;
    dth_tph = 2.0 * two_mr * a * sc * ra2 * inv_sigma2;
    dth_phph = -2.0 * ra2 * sc - 2.0 * two_mr * a2 * s2 * sc * (2.0 * sigma + a2 * s2) * inv_sigma2;
    dth_rr = 2.0 * a2 * sc * inv_delta;
    dth_thth = 2.0 * a2 * sc;
  }
};

/// Gamma^mu_ab = 1/2 g^{mu nu} (d_a g_{nu b} + d_b g_{nu a} - d_nu g_ab) from the inverse metric and the four
/// matrices d_c g_{mu nu}. For christoffel() of metrics whose derivatives are known in closed form (tests and tools).
inline GRTRACE_HD Christoffel christoffel_from_derivatives(const Mat4& g_inv, const std::array<Mat4, 4>& dg) {
  Christoffel G;
  for (std::size_t mu = 0; mu < 4; ++mu) {
    const int m = static_cast<int>(mu);
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        double sum = 0.0;
        for (int nu = 0; nu < 4; ++nu) {
          const double lower = dg[static_cast<std::size_t>(a)](nu, b) + dg[static_cast<std::size_t>(b)](nu, a) -
                               dg[static_cast<std::size_t>(nu)](a, b);
          sum += g_inv(m, nu) * lower;
        }
        G[mu](a, b) = G[mu](b, a) = 0.5 * sum;
      }
  }
  return G;
}

struct KerrMetric {
  static constexpr std::string_view name = "kerr";
  static constexpr Chart chart = Chart::spherical;
  /// Optional trait (metric_traits.hpp): unchanged by theta -> pi - theta; not by phi -> -phi (it rotates).
  static constexpr bool equator_mirror_symmetric = true;
  double mass = 1.0;
  double spin = 0.0;  ///< a = J/M, |a| < M; the sign gives the sense of rotation about +z

  /// A KerrMetric after checking M > 0 finite and |a| < M; throws std::invalid_argument otherwise.
  static KerrMetric checked(double mass, double spin) {
    if (!std::isfinite(mass) || !(mass > 0.0))
      throw std::invalid_argument("KerrMetric: mass must be finite and > 0 (got " + std::to_string(mass) + ")");
    if (!std::isfinite(spin) || !(std::abs(spin) < mass))
      throw std::invalid_argument("KerrMetric: spin a must be finite with |a| < M (got a = " + std::to_string(spin) +
                                  ", M = " + std::to_string(mass) + "); use |a| <= 0.9999 M for a near-extremal hole");
    return KerrMetric{mass, spin};
  }

  /// The metric's terms at x with their derivatives (christoffel(), metric_derivatives()) or without (the rest).
  GRTRACE_HD KerrBLTerms terms(const Vec4& x) const { return KerrBLTerms(mass, spin, x[1], x[2]); }
  GRTRACE_HD KerrBLComponents components(const Vec4& x) const { return KerrBLComponents(mass, spin, x[1], x[2]); }

  GRTRACE_HD Mat4 metric(const Vec4& x) const {
    const KerrBLComponents q = components(x);
    Mat4 g = Mat4::Zero();
    g(0, 0) = q.g_tt;
    g(0, 3) = g(3, 0) = q.g_tph;
    g(1, 1) = q.g_rr;
    g(2, 2) = q.g_thth;
    g(3, 3) = q.g_phph;
    return g;
  }

  /// g^{mu nu}, exact: (t, phi) block over its determinant -Delta sin^2 theta, 1/g_rr, 1/g_thth.
  GRTRACE_HD Mat4 inverse_metric(const Vec4& x) const {
    const KerrBLComponents q = components(x);
    const double inv_det = q.inv_tphi_det;
    Mat4 gi = Mat4::Zero();
    gi(0, 0) = q.g_phph * inv_det;
    gi(0, 3) = gi(3, 0) = -q.g_tph * inv_det;
    gi(3, 3) = q.g_tt * inv_det;
    gi(1, 1) = 1.0 / q.g_rr;
    gi(2, 2) = 1.0 / q.g_thth;
    return gi;
  }

  /// d g_{mu nu} / d x^a for a = t, r, theta, phi (the t and phi derivatives vanish).
  GRTRACE_HD std::array<Mat4, 4> metric_derivatives(const Vec4& x) const {
    const KerrBLTerms q = terms(x);
    std::array<Mat4, 4> dg;
    for (auto& d : dg) d.setZero();
    auto fill = [](Mat4& d, double tt, double tph, double rr, double thth, double phph) {
      d(0, 0) = tt;
      d(0, 3) = d(3, 0) = tph;
      d(1, 1) = rr;
      d(2, 2) = thth;
      d(3, 3) = phph;
    };
    fill(dg[1], q.dr_tt, q.dr_tph, q.dr_rr, q.dr_thth, q.dr_phph);
    fill(dg[2], q.dth_tt, q.dth_tph, q.dth_rr, q.dth_thth, q.dth_phph);
    return dg;
  }

  /// Gamma^mu_ab from the analytic derivatives of g (tests and tools; the hot loop uses acceleration()).
  GRTRACE_HD Christoffel christoffel(const Vec4& x) const {
    return christoffel_from_derivatives(inverse_metric(x), metric_derivatives(x));
  }

  /// -Gamma^mu_ab k^a k^b in closed form (see the header comment). Written with h = 2 M r / Sigma and
  /// T = k^t - a sin^2 k^phi, in which the (t, phi) block is g(k, k)_tphi = k^t^2 - (r^2 + a^2) sin^2 k^phi^2 - h T^2,
  /// p_t = k^t - h T and p_phi = -(r^2 + a^2) sin^2 k^phi + h a sin^2 T; the only division by sin^2 is the one
  /// the chart needs (g^phiphi).
  GRTRACE_HD Vec4 acceleration(const Vec4& x, const Vec4& k) const {
    // The inline sincos (core/sin_cos.hpp) where the build has fused multiply-add: 0.87-0.9 of the step time in a
    // frame (tsit5, rkf78; frame_benchmark frame/metric/kerr_bl). Without it, libm's: the inline kernels measured
    // 2-4 % slower here then (docs/benchmarks-archive.md, "Fused multiply-adds where the chain waits").
    const SinCos sin_cos_theta = fused_mul_add ? polar_sin_cos(x[2]) : SinCos{std::sin(x[2]), std::cos(x[2])};
    const double m = mass, a = spin, r = x[1], s = sin_cos_theta.sin, c = sin_cos_theta.cos;
    const double kt = k[0], kr = k[1], kth = k[2], kph = k[3];
    const double r2 = r * r, a2 = a * a, s2 = s * s, sc = s * c, ra2 = r2 + a2;
    const double sigma = mul_add(a2 * c, c, r2), delta = ra2 - 2.0 * m * r;
    // 1/sin^2 is taken here, off the critical path (dividing at the end put a division's latency on every
    // right-hand side).
    const double inv_sigma = 1.0 / sigma, inv_delta = 1.0 / delta, inv_s2 = 1.0 / s2;
    const double h = 2.0 * m * r * inv_sigma;
    const double t_comb = mul_add(-a * s2, kph, kt);  // T
    // d_r h and d_th h; D = k^r d_r + k^th d_th applied to h and (at fixed k) to T.
    const double dh_r = -2.0 * m * (r2 - a2 * c * c) * inv_sigma * inv_sigma;
    const double dh_th = 2.0 * h * a2 * sc * inv_sigma;
    const double d_h = mul_add(kth, dh_th, kr * dh_r);
    const double d_t = -2.0 * a * sc * kth * kph;
    // Sigma / Delta = -g_rr and its derivatives.
    const double dq_r = 2.0 * (r * delta - (r - m) * sigma) * inv_delta * inv_delta;
    const double dq_th = -2.0 * a2 * sc * inv_delta;
    // F_nu = 1/2 d_nu g(k, k) - D(g_{nu b}) k^b = -D(p_nu) for nu = t, phi (Killing directions).
    // Sums of products below are chains of mul_add (core/mul_add.hpp), in the formula's order of additions.
    const double f_t = mul_add(h, d_t, d_h * t_comb);
    const double f_ph = 2.0 * (r * kr * s2 + ra2 * sc * kth) * kph -
                        a * (d_h * s2 * t_comb + 2.0 * h * sc * kth * t_comb + h * s2 * d_t);
    const double f_r = mul_add(dq_th * kr, kth,
                               mul_add(0.5 * dq_r * kr, kr,
                                       mul_add(-0.5 * dh_r * t_comb, t_comb, -r * mul_add(s2 * kph, kph, kth * kth))));
    const double f_th_sc = mul_add(2.0 * h * a * t_comb, kph,
                                   mul_add(-a2 * kth, kth, mul_add(a2 * inv_delta * kr, kr, -ra2 * kph * kph)));
    const double f_th = mul_add(2.0 * r * kr, kth, mul_add(-0.5 * dh_th * t_comb, t_comb, sc * f_th_sc));
    // g^tt = (r^2 + a^2 + h a^2 sin^2) / Delta, g^tphi = h a / Delta, g^phiphi = -(1 - h) / (Delta sin^2),
    // g^rr = -Delta / Sigma, g^thth = -1 / Sigma.
    Vec4 acc;
    acc[0] = mul_add(mul_add(h * a2, s2, ra2), f_t, h * a * f_ph) * inv_delta;
    acc[1] = -f_r * delta * inv_sigma;
    acc[2] = -f_th * inv_sigma;
    acc[3] = mul_add(h * a, f_t, -(1.0 - h) * f_ph * inv_s2) * inv_delta;
    return acc;
  }

  GRTRACE_HD double radius(const Vec4& x) const { return x[1]; }
  GRTRACE_HD double horizon_radius() const { return outer_horizon(); }
  /// The Euclidean embedding of (r, theta, phi) as in the Schwarzschild chart (not the oblate KS embedding).
  GRTRACE_HD Vec3 to_cartesian(const Vec4& x) const { return spherical_to_cartesian(x); }

  // ---- the geometry ------------------------------------------------------------------------------------------
  GRTRACE_HD double outer_horizon() const { return mass + std::sqrt(mass * mass - spin * spin); }
  GRTRACE_HD double inner_horizon() const { return mass - std::sqrt(mass * mass - spin * spin); }
  /// Omega_H = a / (r_+^2 + a^2) = a / (2 M r_+): the horizon's null generator is chi = d_t + Omega_H d_phi.
  GRTRACE_HD double horizon_angular_velocity() const { return spin / (2.0 * mass * outer_horizon()); }

  /// The radial potential of a null geodesic with energy E, axial angular momentum L_z and Carter constant Q:
  /// R(r) = (E (r^2 + a^2) - a L_z)^2 - Delta ((L_z - a E)^2 + Q), with (Sigma dr/dlambda)^2 = R (Carter 1968;
  /// Chandrasekhar 1983, sec. 63). Valid inside the horizons too (Delta < 0 there).
  GRTRACE_HD double radial_potential(double e, double lz, double q, double r) const {
    const double p = e * (r * r + spin * spin) - spin * lz, delta = r * r - 2.0 * mass * r + spin * spin;
    return p * p - delta * ((lz - spin * e) * (lz - spin * e) + q);
  }

  /// True when the photon (E, L_z, Q) has a radial turning point above the outer horizon: R(r) <= 0 for some
  /// r > r_+. A photon that comes out of the hole (R(r_+) = (E (r_+^2 + a^2) - a L_z)^2 > 0) then falls back in
  /// (into the past horizon, traced backwards); one without reaches infinity.
  /// Method:  R = E^2 r^4 + c2 r^2 + c1 r + c0 (no r^3 term), R -> +inf; its minima over (r_+, inf) are among the
  /// real roots of R'(r)/(4 E^2) = r^3 + p r + q (p = c2 / (2 E^2), q = c1 / (4 E^2)), found in closed form
  /// (trigonometric form for three real roots, Cardano's for one). E = 0: R -> -inf, a turning point.
  GRTRACE_HD bool radial_turning_point_outside(double e, double lz, double q) const {
    if (e == 0.0) return true;
    const double a = spin, k = (lz - a * e) * (lz - a * e) + q, w = e * a * a - a * lz;
    const double c2 = 2.0 * e * w - k, c1 = 2.0 * mass * k;
    const double p = c2 / (2.0 * e * e), qq = c1 / (4.0 * e * e), rp = outer_horizon();
    auto below = [&](double r) { return r > rp && radial_potential(e, lz, q, r) <= 0.0; };
    const double disc = qq * qq / 4.0 + p * p * p / 27.0;
    if (disc > 0.0) {  // one real root
      const double sq = std::sqrt(disc);
      return below(std::cbrt(-qq / 2.0 + sq) + std::cbrt(-qq / 2.0 - sq));
    }
    const double m = 2.0 * std::sqrt(-p / 3.0);  // p < 0 here
    const double phase = std::acos(std::clamp(3.0 * qq / (p * m), -1.0, 1.0)) / 3.0;
    for (int j = 0; j < 3; ++j)
      if (below(m * std::cos(phase - 2.0 * std::numbers::pi * j / 3.0))) return true;
    return false;
  }

  /// Static limit r_E(theta) = M + sqrt(M^2 - a^2 cos^2 theta): g_tt = 0 there; no static observers inside.
  GRTRACE_HD double ergosphere_radius(double theta) const {
    const double c = std::cos(theta);
    return mass + std::sqrt(mass * mass - spin * spin * c * c);
  }
  /// Angular velocity of the zero-angular-momentum observers, omega = -g_tph / g_phph = 2 M a r / A.
  GRTRACE_HD double frame_dragging(double r, double theta) const {
    const KerrBLComponents q(mass, spin, r, theta);
    return 2.0 * mass * spin * r / q.big_a;
  }
  /// Lapse of the ZAMO frame, alpha = sqrt(Sigma Delta / A) (0 on the horizon, 1 at infinity).
  GRTRACE_HD double lapse(double r, double theta) const {
    const KerrBLComponents q(mass, spin, r, theta);
    return std::sqrt(q.sigma * q.delta / q.big_a);
  }
  /// ZAMO 4-velocity (1/alpha)(d_t + omega d_phi) at x.
  GRTRACE_HD Vec4 zamo_velocity(const Vec4& x) const {
    const double alpha = lapse(x[1], x[2]);
    return Vec4(1.0 / alpha, 0.0, 0.0, frame_dragging(x[1], x[2]) / alpha);
  }

  /// Orthonormal frame of the ZAMO at x: e_0 = its 4-velocity, e_1 along +r, e_2 along +theta, e_3 along +phi
  /// (g(e_a, e_b) = diag(1, -1, -1, -1)). Off the axis and outside r_+.
  GRTRACE_HD std::array<Vec4, 4> zamo_tetrad(const Vec4& x) const {
    const KerrBLComponents q = components(x);
    const double alpha = std::sqrt(q.sigma * q.delta / q.big_a), omega = 2.0 * mass * spin * q.r / q.big_a;
    return {Vec4(1.0 / alpha, 0.0, 0.0, omega / alpha), Vec4(0.0, std::sqrt(q.delta / q.sigma), 0.0, 0.0),
            Vec4(0.0, 0.0, 1.0 / std::sqrt(q.sigma), 0.0), Vec4(0.0, 0.0, 0.0, 1.0 / std::sqrt(-q.g_phph))};
  }

  // ---- constants of geodesic motion (kerr.md sign conventions for +,-,-,-) -------------------------------------
  /// Killing energy E = p_t = g_tt k^t + g_tph k^phi.
  GRTRACE_HD double energy(const GeodesicState& y) const {
    const KerrBLComponents q = components(y.head<4>());
    return q.g_tt * y[4] + q.g_tph * y[7];
  }
  /// Axial angular momentum L_z = -p_phi = -(g_tph k^t + g_phph k^phi).
  GRTRACE_HD double angular_momentum(const GeodesicState& y) const {
    const KerrBLComponents q = components(y.head<4>());
    return -(q.g_tph * y[4] + q.g_phph * y[7]);
  }
  /// Carter's constant Q = p_th^2 - cos^2 th (a^2 (E^2 - mu^2) - L_z^2 / sin^2 th), p_th = -Sigma k^th,
  /// mu^2 = g(k, k) (0 for light). Q >= 0 for rays that cross the equatorial plane.
  GRTRACE_HD double carter_constant(const GeodesicState& y) const { return constants_of_motion(y).carter; }

  /// E, L_z and Q together, from one evaluation of the metric (what a closed-form ray needs of its start).
  struct ConstantsOfMotion {
    double energy, angular_momentum, carter;
  };
  GRTRACE_HD ConstantsOfMotion constants_of_motion(const GeodesicState& y) const {
    const KerrBLComponents q = components(y.head<4>());
    const double e = q.g_tt * y[4] + q.g_tph * y[7];
    const double lz = -(q.g_tph * y[4] + q.g_phph * y[7]);
    const double mu2 = q.g_tt * y[4] * y[4] + 2.0 * q.g_tph * y[4] * y[7] + q.g_rr * y[5] * y[5] +
                       q.g_thth * y[6] * y[6] + q.g_phph * y[7] * y[7];
    const double p_th = -q.sigma * y[6];
    const double c2 = q.cos_theta * q.cos_theta, s2 = q.sin_theta * q.sin_theta;
    return {e, lz, p_th * p_th - c2 * (spin * spin * (e * e - mu2) - lz * lz / s2)};
  }

  /// Kretschmann scalar R_abcd R^abcd = 48 M^2 (r^6 - 15 a^2 r^4 c^2 + 15 a^4 r^2 c^4 - a^6 c^6) / Sigma^6.
  GRTRACE_HD double kretschmann(const Vec4& x) const { return kretschmann_at(x[1], std::cos(x[2])); }
  GRTRACE_HD double kretschmann_at(double r, double cos_theta) const {
    const double r2 = r * r, ac2 = spin * spin * cos_theta * cos_theta;
    const double sigma = r2 + ac2, s3 = sigma * sigma * sigma;
    const double poly = r2 * r2 * r2 - 15.0 * r2 * r2 * ac2 + 15.0 * r2 * ac2 * ac2 - ac2 * ac2 * ac2;
    return 48.0 * mass * mass * poly / (s3 * s3);
  }
};

static_assert(MetricPolicy<KerrMetric>);

}  // namespace grtrace
