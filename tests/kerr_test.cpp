// tests/kerr_test.cpp
// Tests of Kerr (grtrace/metric/kerr.hpp, grtrace/metric/kerr_schild.hpp, grtrace/exact/kerr_exact.hpp):
//   * the metrics: a = 0 equals Schwarzschild; closed-form accelerations against the Christoffel tables and
//     against central finite differences of metric(); exact inverses; the Kretschmann formula against a
//     numerically built Riemann tensor in both charts; the KS chart pulled back to BL is the BL metric;
//   * the geometry: horizons, ergosphere, ZAMO frame;
//   * traced rays (DormandPrince54 + PIController): E, L_z, Carter Q and g(k, k) conserved; a circular photon
//     orbit stays circular; equatorial deflection against the Iyer-Hansen quadrature; the same ray traced in BL
//     and in KS ends at the same place; KS rays cross r_+;
//   * the exact formulas against independent conditions (ISCO = minimum of E(r); Keplerian orbits are
//     geodesics; photon orbits are double roots of the radial potential; the shadow edge separates capture
//     from escape); bad input refused.
// M = 1 throughout. Errors measured are printed, so the report can quote them.
#include "grtrace/metric/kerr.hpp"

#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/deflection.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace grtrace {
namespace {

constexpr double kPi = std::numbers::pi;
const std::vector<double> kSpins = {0.0, 0.3, -0.7, 0.99};

using Tracer = GeodesicTracer<KerrMetric, DormandPrince54, PIController>;
using KSTracer = GeodesicTracer<KerrSchildMetric, DormandPrince54, PIController>;

TraceSettings tight_settings(double rtol = 1e-10, double escape = 100.0) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-3 * rtol};
  s.escape_radius = escape;
  s.max_steps = 200000;
  return s;
}

/// Random BL event: r in (1.25 r_+, 25), theta away from the axis.
Vec4 random_bl_event(std::mt19937& rng, const KerrMetric& m) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double r_lo = 1.25 * m.outer_horizon(), r_hi = 25.0;
  return Vec4(100.0 * u(rng) - 50.0, r_lo + (r_hi - r_lo) * u(rng), 0.2 + (kPi - 0.4) * u(rng), 2.0 * kPi * u(rng));
}

Vec4 random_vector(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return Vec4(u(rng), u(rng), u(rng), u(rng));
}

/// Largest |a_i - b_i| over max |b_i| (a relative error that does not blow up on a vanishing component).
double rel_diff(const Vec4& a, const Vec4& b) { return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff(); }

/// d g_{mu nu} / d x^a by the five-point central difference of metric(); the r step (BL) scales with r - r_+.
template <class M>
std::array<Mat4, 4> fd_metric_derivatives(const M& metric, const Vec4& x, double h0) {
  std::array<Mat4, 4> dg;
  for (int a = 0; a < 4; ++a) {
    const double h = h0;
    auto at = [&](double s) {
      Vec4 y = x;
      y[a] += s * h;
      return metric.metric(y);
    };
    dg[static_cast<std::size_t>(a)] = (-at(2.0) + 8.0 * at(1.0) - 8.0 * at(-1.0) + at(-2.0)) / (12.0 * h);
  }
  return dg;
}

template <class M>
Christoffel fd_christoffel(const M& metric, const Vec4& x, double h) {
  return christoffel_from_derivatives(metric.metric(x).inverse(), fd_metric_derivatives(metric, x, h));
}

// -----------------------------------------------------------------------------------------------------------
// The metrics

TEST(KerrMetric, ZeroSpinIsSchwarzschild) {
  const KerrMetric kerr{1.0, 0.0};
  const SchwarzschildMetric schw{1.0};
  std::mt19937 rng(11);
  double worst_g = 0.0, worst_a = 0.0, worst_gamma = 0.0;
  for (int i = 0; i < 200; ++i) {
    const Vec4 x = random_bl_event(rng, kerr), k = random_vector(rng);
    const Mat4 gs = schw.metric(x);
    worst_g = std::max(worst_g, (kerr.metric(x) - gs).cwiseAbs().maxCoeff() / gs.cwiseAbs().maxCoeff());
    worst_a = std::max(worst_a, rel_diff(kerr.acceleration(x, k), schw.acceleration(x, k)));
    const Christoffel gk = kerr.christoffel(x), gsch = schw.christoffel(x);
    for (std::size_t mu = 0; mu < 4; ++mu)
      worst_gamma =
          std::max(worst_gamma, (gk[mu] - gsch[mu]).cwiseAbs().maxCoeff() / (1.0 + gsch[mu].cwiseAbs().maxCoeff()));
  }
  std::printf("a = 0 vs Schwarzschild: metric %.2e, acceleration %.2e, Christoffel %.2e (max relative)\n", worst_g,
              worst_a, worst_gamma);
  EXPECT_LT(worst_g, 1e-15);
  EXPECT_LT(worst_a, 1e-14);
  EXPECT_LT(worst_gamma, 1e-14);
  EXPECT_DOUBLE_EQ(kerr.horizon_radius(), schw.horizon_radius());
}

TEST(KerrMetric, AccelerationMatchesChristoffelAndFiniteDifferences) {
  std::mt19937 rng(12);
  double worst_table = 0.0, worst_fd = 0.0, worst_inv = 0.0;
  for (double a : kSpins) {
    const KerrMetric m{1.0, a};
    for (int i = 0; i < 50; ++i) {
      const Vec4 x = random_bl_event(rng, m), k = random_vector(rng);
      const Vec4 acc = m.acceleration(x, k);
      worst_table = std::max(worst_table, rel_diff(acc, acceleration_from_christoffel(m.christoffel(x), k)));
      worst_fd = std::max(worst_fd, rel_diff(acc, acceleration_from_christoffel(fd_christoffel(m, x, 1e-3), k)));
      worst_inv = std::max(worst_inv, (m.metric(x) * m.inverse_metric(x) - Mat4::Identity()).cwiseAbs().maxCoeff());
    }
  }
  std::printf("BL: acceleration vs Christoffel table %.2e, vs finite differences of g %.2e; |g g^-1 - 1| %.2e\n",
              worst_table, worst_fd, worst_inv);
  EXPECT_LT(worst_table, 1e-13);
  EXPECT_LT(worst_fd, 1e-9);
  EXPECT_LT(worst_inv, 1e-14);
}

/// Random KS event outside r = 1.25 r_+, away from the axis (|z| < 0.95 R).
Vec4 random_ks_event(std::mt19937& rng, const KerrSchildMetric& m) {
  const KerrMetric bl = m.boyer_lindquist();
  return bl_to_ks_position(m, random_bl_event(rng, bl));
}

TEST(KerrSchildMetric, AccelerationMatchesChristoffelAndFiniteDifferencesAndInverseIsExact) {
  std::mt19937 rng(13);
  double worst_table = 0.0, worst_fd = 0.0, worst_inv = 0.0, worst_null = 0.0, worst_ref = 0.0;
  for (double a : kSpins)
    for (auto slicing : {KerrSchildSlicing::ingoing, KerrSchildSlicing::outgoing}) {
      const KerrSchildMetric m{1.0, a, slicing};
      for (int i = 0; i < 50; ++i) {
        const Vec4 x = random_ks_event(rng, m), k = random_vector(rng);
        const Vec4 acc = m.acceleration(x, k);
        // the scalar form against the Eigen form it was rewritten from: the same up to round-off
        worst_ref = std::max(worst_ref, rel_diff(acc, m.acceleration_reference(x, k)));
        worst_table = std::max(worst_table, rel_diff(acc, acceleration_from_christoffel(m.christoffel(x), k)));
        worst_fd = std::max(worst_fd, rel_diff(acc, acceleration_from_christoffel(fd_christoffel(m, x, 1e-3), k)));
        worst_inv = std::max(worst_inv, (m.metric(x) * m.inverse_metric(x) - Mat4::Identity()).cwiseAbs().maxCoeff());
        const KerrSchildTerms q = m.terms(x);
        worst_null = std::max(worst_null, std::abs(q.l[0] * q.l[0] - q.l.tail<3>().squaredNorm()));
      }
    }
  std::printf(
      "KS: acceleration vs Christoffel table %.2e, vs finite differences %.2e; |g g^-1 - 1| %.2e, "
      "|l.l| %.2e; scalar vs Eigen form %.2e\n",
      worst_table, worst_fd, worst_inv, worst_null, worst_ref);
  EXPECT_LT(worst_ref, 1e-13);
  EXPECT_LT(worst_table, 1e-13);
  EXPECT_LT(worst_fd, 1e-9);
  EXPECT_LT(worst_inv, 1e-14);
  EXPECT_LT(worst_null, 1e-15);
}

/// Riemann tensor from Gamma (analytic) and d Gamma (five-point differences of christoffel()), contracted to
/// R_abcd R^abcd: an independent check of the Kretschmann formula (and of Gamma's second-order content).
template <class M>
double numerical_kretschmann(const M& metric, const Vec4& x, double h) {
  const Christoffel G = metric.christoffel(x);
  std::array<Christoffel, 4> dG;
  for (int c = 0; c < 4; ++c) {
    auto at = [&](double s) {
      Vec4 y = x;
      y[c] += s * h;
      return metric.christoffel(y);
    };
    const Christoffel p2 = at(2.0), p1 = at(1.0), m1 = at(-1.0), m2 = at(-2.0);
    for (std::size_t a = 0; a < 4; ++a)
      dG[static_cast<std::size_t>(c)][a] = (-p2[a] + 8.0 * p1[a] - 8.0 * m1[a] + m2[a]) / (12.0 * h);
  }
  // R^a_bcd = d_c G^a_db - d_d G^a_cb + G^a_ce G^e_db - G^a_de G^e_cb
  double Rud[4][4][4][4];
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 4; ++c)
        for (int d = 0; d < 4; ++d) {
          const auto A = static_cast<std::size_t>(a);
          double v = dG[static_cast<std::size_t>(c)][A](d, b) - dG[static_cast<std::size_t>(d)][A](c, b);
          for (int e = 0; e < 4; ++e) {
            const auto E = static_cast<std::size_t>(e);
            v += G[A](c, e) * G[E](d, b) - G[A](d, e) * G[E](c, b);
          }
          Rud[a][b][c][d] = v;
        }
  const Mat4 g = metric.metric(x), gi = g.inverse();
  // K = R^a_bcd R_a^bcd = g_ae g^bf g^cg g^dh R^a_bcd R^e_fgh
  double Rdu[4][4][4][4] = {};  // R_a^{fgh}
  for (int a = 0; a < 4; ++a)
    for (int f = 0; f < 4; ++f)
      for (int gg = 0; gg < 4; ++gg)
        for (int hh = 0; hh < 4; ++hh) {
          double v = 0.0;
          for (int e = 0; e < 4; ++e)
            for (int b = 0; b < 4; ++b)
              for (int c = 0; c < 4; ++c)
                for (int d = 0; d < 4; ++d) v += g(a, e) * gi(f, b) * gi(gg, c) * gi(hh, d) * Rud[e][b][c][d];
          Rdu[a][f][gg][hh] = v;
        }
  double K = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 4; ++c)
        for (int d = 0; d < 4; ++d) K += Rud[a][b][c][d] * Rdu[a][b][c][d];
  return K;
}

TEST(KerrMetric, KretschmannFormulaMatchesNumericalRiemannInBothCharts) {
  double worst_bl = 0.0, worst_ks = 0.0;
  for (double a : {0.0, 0.6, -0.95}) {
    const KerrMetric bl{1.0, a};
    const KerrSchildMetric ks{1.0, a, KerrSchildSlicing::ingoing};
    for (const Vec4& x : {Vec4(0.0, 3.0, 0.7, 0.4), Vec4(0.0, 2.2, 1.9, -1.0), Vec4(0.0, 6.0, 1.3, 2.0)}) {
      const double exact = bl.kretschmann(x);
      worst_bl = std::max(worst_bl, std::abs(numerical_kretschmann(bl, x, 1e-3) - exact) / std::abs(exact));
      const Vec4 xk = bl_to_ks_position(ks, x);
      EXPECT_NEAR(ks.kretschmann(xk), exact, 1e-13 * std::abs(exact));
      worst_ks = std::max(worst_ks, std::abs(numerical_kretschmann(ks, xk, 1e-3) - exact) / std::abs(exact));
    }
  }
  std::printf("Kretschmann formula vs numerical Riemann: BL %.2e, KS %.2e (relative)\n", worst_bl, worst_ks);
  EXPECT_LT(worst_bl, 1e-7);
  EXPECT_LT(worst_ks, 1e-7);
}

TEST(KerrSchildMetric, PullbackToBoyerLindquistIsTheBLMetricAndRoundTripsHold) {
  std::mt19937 rng(14);
  double worst_pull = 0.0, worst_x = 0.0, worst_k = 0.0;
  for (double a : kSpins)
    for (auto slicing : {KerrSchildSlicing::ingoing, KerrSchildSlicing::outgoing}) {
      const KerrSchildMetric ks{1.0, a, slicing};
      const KerrMetric bl = ks.boyer_lindquist();
      for (int i = 0; i < 50; ++i) {
        const Vec4 x = random_bl_event(rng, bl);
        const Mat4 J = bl_to_ks_jacobian(ks, x);
        const Mat4 gbl = bl.metric(x);
        const Mat4 pulled = J.transpose() * ks.metric(bl_to_ks_position(ks, x)) * J;
        worst_pull = std::max(worst_pull, (pulled - gbl).cwiseAbs().maxCoeff() / gbl.cwiseAbs().maxCoeff());
        const GeodesicState y = make_state(x, random_vector(rng));
        const GeodesicState back = ks_to_bl(ks, bl_to_ks(ks, y));
        Vec4 dx = back.head<4>() - x;
        dx[3] = std::remainder(dx[3], 2.0 * kPi);
        worst_x = std::max(worst_x, dx.cwiseAbs().maxCoeff() / x.cwiseAbs().maxCoeff());
        worst_k = std::max(worst_k, rel_diff(back.tail<4>(), y.tail<4>()));
      }
    }
  std::printf("KS pulled back to BL: %.2e; round trip BL->KS->BL: position %.2e, vector %.2e\n", worst_pull, worst_x,
              worst_k);
  EXPECT_LT(worst_pull, 1e-13);
  EXPECT_LT(worst_x, 1e-13);
  EXPECT_LT(worst_k, 1e-12);
}

/// One classical RK4 step of the geodesic equation (a small, independent integrator for pointwise checks).
template <class M>
GeodesicState rk4_step(const M& metric, const GeodesicState& y, double h) {
  const GeodesicEquation<M> f{&metric};
  const GeodesicState k1 = f(y), k2 = f(y + 0.5 * h * k1), k3 = f(y + 0.5 * h * k2), k4 = f(y + h * k3);
  return y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

TEST(KerrSchildMetric, TransformedBoyerLindquistGeodesicSolvesTheKerrSchildEquation) {
  // Along a BL geodesic y(lambda), the KS images must obey dx_KS/dlambda = k_KS (the vector map is the derivative
  // of the event map, dr terms included) and dk_KS/dlambda = KS acceleration. Central differences over +-h of
  // the transformed states (BL steps of h/8 by RK4: error ~1e-13), truncation O(h^2).
  std::mt19937 rng(16);
  double worst_x = 0.0, worst_k = 0.0;
  for (double a : {0.5, -0.9})
    for (auto slicing : {KerrSchildSlicing::ingoing, KerrSchildSlicing::outgoing}) {
      const KerrSchildMetric ks{1.0, a, slicing};
      const KerrMetric bl = ks.boyer_lindquist();
      for (int i = 0; i < 10; ++i) {
        const Vec4 x = random_bl_event(rng, bl);
        const auto e = bl.zamo_tetrad(x);
        const Eigen::Vector3d n = Eigen::Vector3d(random_vector(rng).head<3>()).normalized();
        const GeodesicState y = make_state(x, e[0] + n[0] * e[1] + n[1] * e[2] + n[2] * e[3]);
        const double h = 1e-3;
        GeodesicState yp = y, ym = y;
        for (int j = 0; j < 8; ++j) {
          yp = rk4_step(bl, yp, h / 8.0);
          ym = rk4_step(bl, ym, -h / 8.0);
        }
        const GeodesicState z = bl_to_ks(ks, y), zp = bl_to_ks(ks, yp), zm = bl_to_ks(ks, ym);
        const Vec4 dx = (zp.head<4>() - zm.head<4>()) / (2.0 * h), dk = (zp.tail<4>() - zm.tail<4>()) / (2.0 * h);
        worst_x = std::max(worst_x, rel_diff(dx, z.tail<4>()));
        worst_k = std::max(worst_k, rel_diff(dk, ks.acceleration(z.head<4>(), z.tail<4>())));
      }
    }
  std::printf("BL geodesic in KS: |dx/dl - k| %.2e, |dk/dl - a_KS| %.2e (relative, h = 1e-3)\n", worst_x, worst_k);
  EXPECT_LT(worst_x, 1e-6);
  EXPECT_LT(worst_k, 2e-6);
}

// -----------------------------------------------------------------------------------------------------------
// The geometry

TEST(KerrMetric, HorizonsErgosphereAndZamoFrame) {
  for (double a : {0.0, 0.5, -0.9, 0.999}) {
    const KerrMetric m{1.0, a};
    const double rp = m.outer_horizon(), rm = m.inner_horizon();
    EXPECT_NEAR(rp * rp - 2.0 * rp + a * a, 0.0, 1e-14);  // Delta(r_+) = 0
    EXPECT_NEAR(rm * rm - 2.0 * rm + a * a, 0.0, 1e-14);
    EXPECT_NEAR(rp + rm, 2.0, 1e-15);
    EXPECT_DOUBLE_EQ(m.horizon_radius(), rp);
    EXPECT_DOUBLE_EQ(rp, exact::outer_horizon(a));
    for (double th : {0.3, 1.0, kPi / 2.0, 2.5}) {
      const double re = m.ergosphere_radius(th);
      EXPECT_NEAR(m.metric(Vec4(0.0, re, th, 0.0))(0, 0), 0.0, 1e-14);  // static limit: g_tt = 0
      EXPECT_GE(re, rp - 1e-15);
      EXPECT_GT(m.metric(Vec4(0.0, re * 1.01, th, 0.0))(0, 0), 0.0);
      const Vec4 x(0.0, 1.7 * rp + 0.3, th, 0.2);
      const Mat4 g = m.metric(x);
      EXPECT_NEAR(m.frame_dragging(x[1], th), -g(0, 3) / g(3, 3), 1e-15);
      EXPECT_NEAR(m.inverse_metric(x)(0, 0), 1.0 / (m.lapse(x[1], th) * m.lapse(x[1], th)), 1e-13);
      const auto e = m.zamo_tetrad(x);
      for (std::size_t i = 0; i < 4; ++i)
        for (std::size_t j = 0; j < 4; ++j)
          EXPECT_NEAR(e[i].dot(g * e[j]), i != j ? 0.0 : (i == 0 ? 1.0 : -1.0), 1e-13) << a << " " << i << j;
      EXPECT_NEAR(m.angular_momentum(make_state(x, m.zamo_velocity(x))), 0.0, 1e-14);  // zero angular momentum
    }
  }
  const KerrMetric m6{1.0, 0.6};
  EXPECT_NEAR(m6.ergosphere_radius(0.0), 1.8, 1e-15);            // poles: touches r_+
  EXPECT_NEAR(m6.ergosphere_radius(kPi / 2), 2.0, 1e-15);        // equator: 2M
  EXPECT_TRUE(m6.metric(Vec4(0.0, 5.0, 0.0, 0.0)).allFinite());  // the axis is singular only for Gamma and g^-1
}

// -----------------------------------------------------------------------------------------------------------
// Traced rays

/// A future-directed photon at x sent along the unit direction n = (n_r, n_theta, n_phi) of the ZAMO frame.
GeodesicState zamo_photon(const KerrMetric& m, const Vec4& x, const Eigen::Vector3d& n) {
  const auto e = m.zamo_tetrad(x);
  const Eigen::Vector3d u = n.normalized();
  return make_state(x, e[0] + u[0] * e[1] + u[1] * e[2] + u[2] * e[3]);
}

struct Drift {
  double e = 0.0, l = 0.0, q = 0.0, null = 0.0;
  void add(const KerrMetric& m, const GeodesicState& y0, const GeodesicState& y) {
    const double e0 = m.energy(y0), l0 = m.angular_momentum(y0), q0 = m.carter_constant(y0), a = m.spin;
    // Scales: E; |L_z| + |a| E; |Q| + L_z^2 + a^2 E^2 (the size of the terms of Q).
    e = std::max(e, std::abs(m.energy(y) - e0) / std::abs(e0));
    l = std::max(l, std::abs(m.angular_momentum(y) - l0) / (std::abs(l0) + std::abs(a * e0)));
    q = std::max(q, std::abs(m.carter_constant(y) - q0) / (std::abs(q0) + l0 * l0 + a * a * e0 * e0));
    null = std::max(null, constraint_violation(m, y, 0.0));
  }
};

TEST(KerrRays, EnergyAngularMomentumCarterAndNullConstraintConserved) {
  const double spin = 0.9;
  const KerrMetric m{1.0, spin};
  const Tracer tracer(m, tight_settings(1e-10, 100.0));
  // Rays heading for the hole are checked at r = 1.05 r_+ (user event): closer in, the Boyer-Lindquist
  // chart's own singularity (k^t ~ 1/Delta) makes the steps and the constants' round-off grow; that part is
  // measured separately below, down to the tracer's guard (1 + 1e-3) r_+.
  const double r_check = 1.05 * m.outer_horizon();
  auto near_horizon = [&](const GeodesicState& y) { return y[1] - r_check; };
  std::mt19937 rng(15);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Drift outside, guard;
  int escaped = 0, captured = 0;
  for (int i = 0; i < 16; ++i) {
    // Half of the rays aimed inwards (most of those are captured), half anywhere.
    const Vec4 x(0.0, 8.0 + 4.0 * u(rng), 1.2 + 0.6 * u(rng), 0.0);
    Eigen::Vector3d n(u(rng), 0.5 * u(rng), 0.5 * u(rng));
    if (i % 2 == 0) n[0] = -1.0;
    const GeodesicState y0 = zamo_photon(m, x, n);
    const TraceResult res = tracer.trace(y0, near_horizon);
    ASSERT_TRUE(res.status == RayStatus::escaped || res.status == RayStatus::hit) << to_string(res.status);
    outside.add(m, y0, res.final_state);
    if (res.status == RayStatus::escaped) {
      ++escaped;
      continue;
    }
    ++captured;
    const TraceResult all_the_way = tracer.trace(y0);
    ASSERT_EQ(all_the_way.status, RayStatus::captured);
    guard.add(m, y0, all_the_way.final_state);
  }
  std::printf(
      "16 rays (%d escaped, %d captured), rtol 1e-10, to r = 100 or 1.05 r_+: drift E %.2e, L_z %.2e, "
      "Q %.2e, g(k,k) %.2e\n",
      escaped, captured, outside.e, outside.l, outside.q, outside.null);
  std::printf("  captured rays down to the guard 1.001 r_+: drift E %.2e, L_z %.2e, Q %.2e, g(k,k) %.2e\n", guard.e,
              guard.l, guard.q, guard.null);
  EXPECT_GT(escaped, 0);
  EXPECT_GT(captured, 0);
  EXPECT_LT(outside.e, 1e-9);
  EXPECT_LT(outside.l, 1e-9);
  EXPECT_LT(outside.q, 1e-9);
  EXPECT_LT(outside.null, 1e-9);
  EXPECT_LT(std::max({guard.e, guard.l, guard.q, guard.null}), 1e-7);
}

TEST(KerrRays, CircularEquatorialPhotonOrbitStaysCircular) {
  for (double a : {0.0, 0.7, -0.5})
    for (auto orbit : {exact::Orbit::prograde, exact::Orbit::retrograde}) {
      const KerrMetric m{1.0, a};
      const double r = exact::photon_orbit_radius(a, orbit);
      // Its impact parameter: xi of the spherical photon orbit at r (for a = 0: +-3 sqrt 3).
      const double sense = (orbit == exact::Orbit::prograde) == (a >= 0.0) ? 1.0 : -1.0;
      const double b = a == 0.0 ? sense * 3.0 * std::sqrt(3.0) : exact::spherical_photon_orbit(r, a).first;
      GeodesicState y0 = kerr_equatorial_photon(m, b, r);
      y0[5] = 0.0;
      TraceSettings s = tight_settings(1e-12, 100.0);
      s.max_steps = 4000;
      const Tracer tracer(m, s);
      double worst = 0.0;
      auto observe = [&](const Tracer::Integrator& integ, double theta) {
        worst = std::max(worst, std::abs(integ.dense(theta)[1] - r));
      };
      // Two full turns: stop at |phi| = 4 pi with a user event.
      auto turns = [](const GeodesicState& y) { return 4.0 * kPi - std::abs(y[3]); };
      const TraceResult res = tracer.trace_observed(y0, observe, turns);
      EXPECT_EQ(res.status, RayStatus::hit) << a;
      const double swept = res.final_state[3];
      std::printf("photon orbit a = %+.1f %s r = %.6f: max |r - r_ph| over %.1f turns %.2e\n", a,
                  orbit == exact::Orbit::prograde ? "pro " : "retro", r, std::abs(swept) / (2 * kPi), worst);
      EXPECT_LT(worst, 1e-5);
      EXPECT_GT(sense * swept, 0.0);
    }
}

/// Total deflection of an equatorial ray (b > 0 towards +phi) measured with measure_deflection: traced between
/// r_s and r_s, plus the exact outer legs. NaN unless the ray escapes.
double traced_equatorial_deflection(double a, double b, double rtol) {
  const Tracer tracer(KerrMetric{1.0, a}, tight_settings(rtol));
  return measure_deflection(tracer, b).deflection;
}

TEST(KerrExact, EquatorialDeflectionQuadratureConvergesAndReducesToDarwin) {
  for (double b : {6.0, 10.0, 100.0}) {
    const double d = exact::equatorial_deflection(b, 0.0);
    EXPECT_NEAR(d, exact::deflection_angle(b), 1e-13) << b;
    EXPECT_NEAR(exact::equatorial_deflection(-b, 0.0), d, 1e-14);
  }
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{
           {0.5, 4.5}, {0.5, -8.0}, {0.5, 20.0}, {-0.9, -4.5}, {-0.9, 8.0}, {-0.9, -20.0}}) {
    const double d64 = exact::equatorial_deflection(b, a, 1.0, 64), d256 = exact::equatorial_deflection(b, a, 1.0, 256);
    EXPECT_NEAR(d64, d256, 1e-13) << a << " " << b;
  }
  // Weak field: alpha = 4M/b + 15 pi M^2 / (4 b^2) -+ 4 a M / b^2 + O(b^-3) (upper sign prograde): prograde rays
  // are bent less. The odd-in-a part of the series, -+ (4 a M / b^2 + 10 pi a M^2 / b^3) (e.g. Sereno & De Luca,
  // Phys. Rev. D 74, 123009 (2006)), makes retrograde - prograde = 8 a M / b^2 + 20 pi a M^2 / b^3 + O(b^-4).
  for (double b : {1e3, 1e4}) {
    const double a = 0.9, pro = exact::equatorial_deflection(b, a), retro = exact::equatorial_deflection(-b, a);
    EXPECT_NEAR(pro, 4.0 / b + (15.0 * kPi / 4.0 - 4.0 * a) / (b * b), 50.0 / (b * b * b)) << b;
    EXPECT_NEAR(retro - pro, 8.0 * a / (b * b) + 20.0 * kPi * a / (b * b * b), 1e3 / (b * b * b * b)) << b;
  }
}

TEST(KerrRays, EquatorialDeflectionMatchesIyerHansen) {
  double worst = 0.0;
  // Impact parameters above the critical one of each sense (a = 0.9: b_c = +2.9, -6.8; a = -0.6: +6.2, -3.7 approx).
  const std::vector<std::pair<double, std::vector<double>>> cases = {
      {0.9, {3.5, 5.0, 6.0, 8.0, 15.0, 40.0, -7.0, -9.0, -20.0}},
      {-0.6, {6.5, 8.0, 15.0, 40.0, -4.5, -7.0, -9.0, -20.0}}};
  for (const auto& [a, bs] : cases)
    for (double b : bs) {
      const double exact_d = exact::equatorial_deflection(b, a);
      const double traced = traced_equatorial_deflection(a, b, 1e-11);
      const double err = std::abs(traced - exact_d);
      std::printf("a = %+.1f b = %+6.1f (%s): deflection %.12f traced %.12f error %.1e\n", a, b,
                  a * b > 0 ? "pro  " : "retro", exact_d, traced, err);
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-7) << a << " " << b;
    }
  std::printf("equatorial deflection, worst error %.2e rad\n", worst);
}

TEST(KerrRays, BoyerLindquistAndKerrSchildTracesAgree) {
  const double spin = 0.8;
  const KerrMetric bl{1.0, spin};
  const KerrSchildMetric ks{1.0, spin, KerrSchildSlicing::ingoing};
  const double far = 200.0;
  const Tracer tbl(bl, tight_settings(1e-11, far));
  const KSTracer tks(ks, tight_settings(1e-11, far));
  double worst_x = 0.0, worst_dir = 0.0, worst_const = 0.0;
  // Rays that pass close to the hole (periapsis near 3-4 M) and escape, in and out of the equatorial plane.
  for (const Eigen::Vector3d& n : {Eigen::Vector3d(-0.5, 0.2, 0.8), Eigen::Vector3d(-0.5, -0.3, -0.8),
                                   Eigen::Vector3d(0.2, 0.7, -0.3), Eigen::Vector3d(-0.4, 0.6, -0.6)}) {
    const GeodesicState y0 = zamo_photon(bl, Vec4(0.0, 7.0, 1.1, 0.5), n);
    const TraceResult rb = tbl.trace(y0);
    const TraceResult rk = tks.trace(bl_to_ks(ks, y0));
    ASSERT_EQ(rb.status, RayStatus::escaped);
    ASSERT_EQ(rk.status, RayStatus::escaped);
    const GeodesicState yb = bl_to_ks(ks, rb.final_state), yk = rk.final_state;
    worst_x = std::max(worst_x, (yb.head<4>() - yk.head<4>()).cwiseAbs().maxCoeff() / far);
    worst_dir = std::max(worst_dir, (yb.segment<3>(5).normalized() - yk.segment<3>(5).normalized()).norm());
    // KS constants of the KS trace against the BL constants of the start.
    worst_const = std::max({worst_const, std::abs(ks.energy(yk) - bl.energy(y0)) / std::abs(bl.energy(y0)),
                            std::abs(ks.angular_momentum(yk) - bl.angular_momentum(y0)) / std::abs(bl.energy(y0))});
    worst_const = std::max(worst_const, std::abs(ks.carter_constant(yk) - bl.carter_constant(y0)) /
                                            (std::abs(bl.carter_constant(y0)) + 1.0));
  }
  std::printf("BL vs KS traces to r = %.0f: position %.2e (relative to r), direction %.2e rad; KS constants %.2e\n",
              far, worst_x, worst_dir, worst_const);
  EXPECT_LT(worst_x, 1e-8);
  EXPECT_LT(worst_dir, 1e-8);
  EXPECT_LT(worst_const, 1e-9);
}

TEST(KerrRays, RayGrazingThePoleAgreesBetweenBoyerLindquistAndKerrSchild) {
  // Near the BL axis k^phi ~ L_z / sin^2 theta and the steps shrink; KS has no axis at all. (A ray with L_z = 0
  // exactly cannot be set up in BL Kerr: k^phi = omega k^t != 0 and the round-off left in L_z ~ 1e-17 sends the
  // ray within 1e-11 of the axis, where it ends as step_underflow. Such rays belong in KS.)
  const double spin = 0.7;
  const KerrMetric bl{1.0, spin};
  const KerrSchildMetric ks{1.0, spin, KerrSchildSlicing::ingoing};
  const double far = 150.0;
  const Tracer tbl(bl, tight_settings(1e-11, far));
  const KSTracer tks(ks, tight_settings(1e-11, far));
  // Start at theta = 0.4 heading towards the pole, slightly inwards, with a small L_z.
  const GeodesicState y0 = zamo_photon(bl, Vec4(0.0, 9.0, 0.4, 0.3), Eigen::Vector3d(-0.3, -0.9, 1e-3));
  double theta_min = kPi;
  auto observe = [&](const Tracer::Integrator& integ, double theta) {
    theta_min = std::min(theta_min, integ.dense(theta)[2]);
  };
  const TraceResult rb = tbl.trace_observed(y0, observe);
  const TraceResult rk = tks.trace(bl_to_ks(ks, y0));
  ASSERT_EQ(rb.status, RayStatus::escaped);
  ASSERT_EQ(rk.status, RayStatus::escaped);
  EXPECT_LT(theta_min, 1e-3);
  const GeodesicState yb = bl_to_ks(ks, rb.final_state), yk = rk.final_state;
  const double dx = (yb.head<4>() - yk.head<4>()).cwiseAbs().maxCoeff() / far;
  const double dd = (yb.segment<3>(5).normalized() - yk.segment<3>(5).normalized()).norm();
  Drift drift;
  drift.add(bl, y0, rb.final_state);
  std::printf(
      "ray grazing the pole (theta_min %.1e): BL %d steps, KS %d steps; BL vs KS position %.2e, direction "
      "%.2e; BL drift E %.2e L_z %.2e Q %.2e\n",
      theta_min, rb.accepted, rk.accepted, dx, dd, drift.e, drift.l, drift.q);
  EXPECT_LT(dx, 1e-8);
  EXPECT_LT(dd, 1e-8);
  EXPECT_LT(std::max({drift.e, drift.l, drift.q}), 1e-9);
}

TEST(KerrRays, KerrSchildRaysCrossTheHorizonTheSlicingIsRegularOn) {
  const double spin = 0.9;
  for (auto slicing : {KerrSchildSlicing::ingoing, KerrSchildSlicing::outgoing}) {
    const KerrSchildMetric ks{1.0, spin, slicing};
    const KSTracer tracer(ks, tight_settings(1e-10, 100.0));
    // Future-directed photons fall through the future horizon of the ingoing chart; past-directed ones through
    // the past horizon of the outgoing chart.
    const double time_dir = slicing == KerrSchildSlicing::ingoing ? 1.0 : -1.0;
    const KerrMetric bl = ks.boyer_lindquist();
    for (const Eigen::Vector3d& n : {Eigen::Vector3d(-1.0, 0.0, 0.0), Eigen::Vector3d(-0.95, 0.2, 0.2)}) {
      GeodesicState y = zamo_photon(bl, Vec4(0.0, 6.0, 1.0, 0.0), n);
      y.tail<4>() *= time_dir;
      y[5] = -std::abs(y[5]);  // inwards either way
      const TraceResult res = tracer.trace(bl_to_ks(ks, y));
      ASSERT_EQ(res.status, RayStatus::captured);
      const double r_end = ks.radius(res.final_state.head<4>());
      EXPECT_LT(r_end, ks.outer_horizon());
      EXPECT_LT(std::abs(res.final_state[4]), 100.0);  // k^t stays finite through r_+
      EXPECT_LT(res.accepted, 400);
      EXPECT_LT(constraint_violation(ks, res.final_state, 0.0), 1e-8);
      // E and L_z are defined in KS everywhere (d_t and d_phi are Killing fields of the chart): conserved through r_+.
      const GeodesicState y0 = bl_to_ks(ks, y);
      const double e0 = ks.energy(y0);
      EXPECT_NEAR(ks.energy(res.final_state), e0, 1e-9 * std::abs(e0));
      EXPECT_NEAR(ks.angular_momentum(res.final_state), ks.angular_momentum(y0), 1e-9 * (std::abs(e0) * spin + 1e-3));
      std::printf("KS %s: captured at r = %.4f (r_+ = %.4f) after %d steps, k^t %.3f\n",
                  slicing == KerrSchildSlicing::ingoing ? "ingoing, future-directed" : "outgoing, past-directed", r_end,
                  ks.outer_horizon(), res.accepted, res.final_state[4]);
    }
  }
}

TEST(KerrRays, KerrSchildRayAgainstItsSlicingIsCapturedOutsideAsInBoyerLindquist) {
  // A past-directed ray in the ingoing chart approaches the past horizon, where that chart is singular like BL
  // (k^t grows without bound): it can never reach the capture radius r_c inside r_+. The chart's capture_radius
  // trait gives such a ray the guard (1 + eps) r_+ outside instead, the Boyer-Lindquist decision.
  const KerrSchildMetric ks{1.0, 0.9, KerrSchildSlicing::ingoing};
  const KerrMetric bl = ks.boyer_lindquist();
  TraceSettings s = tight_settings(1e-10, 100.0);
  s.max_steps = 5000;
  const KSTracer tracer(ks, s);
  const auto e = bl.zamo_tetrad(Vec4(0.0, 6.0, 1.0, 0.0));
  const GeodesicState y = bl_to_ks(ks, make_state(Vec4(0.0, 6.0, 1.0, 0.0), -(e[0] + e[1])));  // past, inwards
  EXPECT_EQ(slicing_crossed_by(y[4]), KerrSchildSlicing::outgoing);
  EXPECT_EQ(slicing_crossed_by(-y[4]), KerrSchildSlicing::ingoing);
  EXPECT_EQ(ks.capture_radius(y), ks.outer_horizon());
  EXPECT_FALSE(ks.leaves_interior(y));  // outside r_+ and moving in
  GeodesicState future = y;
  future.tail<4>() = -y.tail<4>();
  EXPECT_EQ(ks.capture_radius(future), ks.horizon_radius());  // the ray the slicing carries across r_+
  const TraceResult res = tracer.trace(y);
  EXPECT_EQ(res.status, RayStatus::captured);
  const double r_end = ks.radius(res.final_state.head<4>());
  EXPECT_NEAR(r_end, (1.0 + s.horizon_epsilon) * ks.outer_horizon(), 1e-9);
  // It still agrees with the same ray traced in Boyer-Lindquist: E and L_z kept.
  EXPECT_NEAR(ks.energy(res.final_state), ks.energy(y), 1e-8 * std::abs(ks.energy(y)));
  std::printf("past-directed ray in the ingoing chart: %s at r - r_+ = %.1e after %d steps, k^t %.2e\n",
              std::string(to_string(res.status)).c_str(), r_end - ks.outer_horizon(), res.accepted, res.final_state[4]);
}

// -----------------------------------------------------------------------------------------------------------
// Exact formulas against independent conditions

/// Energy E = u_t of the circular equatorial geodesic at r, from the closed forms and the metric.
double circular_energy(double r, double a, exact::Orbit orbit) {
  const KerrMetric m{1.0, a};
  const double ut = exact::keplerian_ut(r, a, orbit), om = exact::keplerian_omega(r, a, orbit);
  return m.energy(make_state(Vec4(0.0, r, kPi / 2.0, 0.0), Vec4(ut, 0.0, 0.0, ut * om)));
}

TEST(KerrExact, IscoIsTheMinimumOfTheCircularOrbitEnergy) {
  EXPECT_NEAR(exact::isco_radius(0.0, exact::Orbit::prograde), 6.0, 1e-14);
  EXPECT_NEAR(exact::isco_radius(0.0, exact::Orbit::retrograde), 6.0, 1e-14);
  const double near1 = 1.0 - 1e-12;
  // r_isco - M ~ (4 (1 - a))^(1/3) M as a -> 1 prograde; retrograde -> 9M.
  EXPECT_NEAR(exact::isco_radius(near1, exact::Orbit::prograde), 1.0, 2e-4);
  EXPECT_NEAR(exact::isco_radius(near1, exact::Orbit::retrograde), 9.0, 1e-9);
  EXPECT_NEAR(exact::isco_radius(-near1, exact::Orbit::prograde), 1.0, 2e-4);
  double worst = 0.0;
  for (double a : {0.0, 0.3, 0.9, -0.5})
    for (auto orbit : {exact::Orbit::prograde, exact::Orbit::retrograde}) {
      const double ri = exact::isco_radius(a, orbit), h = 1e-4 * ri;
      const double dE = (circular_energy(ri + h, a, orbit) - circular_energy(ri - h, a, orbit)) / (2.0 * h);
      worst = std::max(worst, std::abs(dE));
      EXPECT_LT(circular_energy(ri, a, orbit), circular_energy(ri * 1.05, a, orbit));  // minimum, not maximum
      EXPECT_LT(circular_energy(ri, a, orbit), circular_energy(ri * 0.97, a, orbit));
    }
  std::printf("dE/dr at r_isco: %.2e (finite difference)\n", worst);
  EXPECT_LT(worst, 1e-8);
}

TEST(KerrExact, KeplerianOrbitsAreNormalisedGeodesicsAndRedshiftMatchesTheMetric) {
  double worst_norm = 0.0, worst_acc = 0.0, worst_g = 0.0;
  for (double a : {0.0, 0.6, -0.95})
    for (auto orbit : {exact::Orbit::prograde, exact::Orbit::retrograde})
      for (double r : {exact::isco_radius(a, orbit), 8.0, 30.0}) {
        const KerrMetric m{1.0, a};
        const Vec4 x(0.0, r, kPi / 2.0, 0.0);
        const double ut = exact::keplerian_ut(r, a, orbit), om = exact::keplerian_omega(r, a, orbit);
        const Vec4 u(ut, 0.0, 0.0, ut * om);
        worst_norm = std::max(worst_norm, std::abs(inner_product(m, x, u, u) - 1.0));
        worst_acc = std::max(worst_acc, m.acceleration(x, u).cwiseAbs().maxCoeff() / (ut * ut));
        // A photon at the emitter with E = 1, L_z = xi: f_obs / f_em = E / (u . p) = 1 / (u . p).
        for (double xi : {-4.0, 0.0, 3.0}) {
          const Vec4 p(1.0, 0.3, 0.0, -xi);  // covariant; the radial part does not enter u . p
          worst_g = std::max(worst_g, std::abs(1.0 / u.dot(p) - exact::keplerian_redshift(r, xi, a, orbit)));
        }
      }
  std::printf("Keplerian: |g(u,u) - 1| %.2e, |a(u,u)| / u^t^2 %.2e, redshift %.2e\n", worst_norm, worst_acc, worst_g);
  EXPECT_LT(worst_norm, 1e-13);
  EXPECT_LT(worst_acc, 1e-14);
  EXPECT_LT(worst_g, 1e-14);
}

TEST(KerrExact, PhotonOrbitsAreDoubleRootsOfTheRadialPotential) {
  EXPECT_NEAR(exact::photon_orbit_radius(0.0, exact::Orbit::prograde), 3.0, 1e-14);
  EXPECT_NEAR(exact::photon_orbit_radius(0.0, exact::Orbit::retrograde), 3.0, 1e-14);
  EXPECT_NEAR(exact::photon_orbit_radius(1.0 - 1e-12, exact::Orbit::prograde), 1.0, 1e-3);
  EXPECT_NEAR(exact::photon_orbit_radius(1.0 - 1e-12, exact::Orbit::retrograde), 4.0, 1e-9);
  double worst = 0.0;
  for (double a : {0.3, 0.9, -0.6, 0.999}) {
    const double r1 = exact::photon_orbit_radius(a, exact::Orbit::prograde);
    const double r2 = exact::photon_orbit_radius(a, exact::Orbit::retrograde);
    // Equatorial circular photon orbits: u^t's radicand r^3/2 - 3 r^1/2 + 2 s a vanishes there, and eta(r) = 0.
    EXPECT_NEAR(exact::spherical_photon_orbit(r1, a).second, 0.0, 1e-11) << a;
    EXPECT_NEAR(exact::spherical_photon_orbit(r2, a).second, 0.0, 1e-11) << a;
    for (int i = 0; i <= 10; ++i) {
      const double r = r1 + (r2 - r1) * i / 10.0;
      const auto [xi, eta] = exact::spherical_photon_orbit(r, a);
      const double scale = std::pow(r * r + a * a + std::abs(a * xi), 2);
      const double h = 1e-5;
      const double R = exact::radial_potential(r, xi, eta, a);
      const double dR =
          (exact::radial_potential(r + h, xi, eta, a) - exact::radial_potential(r - h, xi, eta, a)) / (2 * h);
      worst = std::max({worst, std::abs(R) / scale, std::abs(dR) * r / scale});
    }
  }
  std::printf("spherical photon orbits: |R|, |r R'| relative %.2e\n", worst);
  EXPECT_LT(worst, 1e-9);
}

TEST(KerrExact, CriticalCurveIsACircleAtZeroSpinAndSeparatesCaptureFromEscape) {
  for (const auto& p : exact::critical_curve(0.0, 1.0, 64))
    EXPECT_NEAR(std::hypot(p.alpha, p.beta), std::sqrt(27.0), 1e-13);
  for (const auto& p : exact::critical_curve(1e-5, 1.0, 64))
    EXPECT_NEAR(std::hypot(p.alpha, p.beta), std::sqrt(27.0), 1e-4) << p.r;
  // Edge-on, the ends of the curve are the equatorial photon orbits: alpha = -xi(r_ph).
  const double a = 0.9;
  const auto edge_on = exact::critical_curve(a, kPi / 2.0, 100);
  double amin = 1e9, amax = -1e9;
  for (const auto& p : edge_on) {
    amin = std::min(amin, p.alpha);
    amax = std::max(amax, p.alpha);
  }
  EXPECT_NEAR(amin, -exact::spherical_photon_orbit(exact::photon_orbit_radius(a, exact::Orbit::prograde), a).first,
              1e-9);
  EXPECT_NEAR(amax, -exact::spherical_photon_orbit(exact::photon_orbit_radius(a, exact::Orbit::retrograde), a).first,
              1e-9);
  EXPECT_LT(amin, 0.0);  // co-rotating side at alpha < 0
  // Rays with the constants of points just outside the curve escape, just inside are captured.
  const KerrMetric m{1.0, a};
  const double incl = 1.2, r0 = 60.0;
  const Tracer tracer(m, tight_settings(1e-11, 70.0));
  const auto curve = exact::critical_curve(a, incl, 12);
  for (const auto& p : curve) {
    for (double scale : {0.99, 1.01}) {
      const double al = scale * p.alpha, be = scale * p.beta;
      const double xi = -al * std::sin(incl);
      const double eta = be * be + (al * al - a * a) * std::cos(incl) * std::cos(incl);
      const Vec4 x(0.0, r0, incl, 0.0);
      Vec4 k = m.inverse_metric(x) * Vec4(1.0, 0.0, -be, -xi);  // p_theta = -+ beta; p_r set below
      const double sigma = r0 * r0 + a * a * std::cos(incl) * std::cos(incl);
      k[1] = -std::sqrt(exact::radial_potential(r0, xi, eta, a)) / sigma;
      const TraceResult res = tracer.trace(make_state(x, k));
      EXPECT_EQ(res.status, scale > 1.0 ? RayStatus::escaped : RayStatus::captured) << p.r << " " << scale;
    }
  }
  EXPECT_EQ(curve.size(), 24u);
}

TEST(KerrExact, MassScaling) {
  // Lengths scale with M at fixed a/M; Omega scales with 1/M.
  const double M = 2.5, chi = 0.6;
  for (auto orbit : {exact::Orbit::prograde, exact::Orbit::retrograde}) {
    EXPECT_NEAR(exact::isco_radius(chi * M, orbit, M), M * exact::isco_radius(chi, orbit), 1e-13);
    EXPECT_NEAR(exact::photon_orbit_radius(chi * M, orbit, M), M * exact::photon_orbit_radius(chi, orbit), 1e-13);
    EXPECT_NEAR(exact::keplerian_omega(7.0 * M, chi * M, orbit, M), exact::keplerian_omega(7.0, chi, orbit) / M, 1e-15);
    EXPECT_NEAR(exact::keplerian_ut(7.0 * M, chi * M, orbit, M), exact::keplerian_ut(7.0, chi, orbit), 1e-14);
  }
  EXPECT_NEAR(exact::equatorial_deflection(8.0 * M, chi * M, M), exact::equatorial_deflection(8.0, chi), 1e-13);
  const auto [xi, eta] = exact::spherical_photon_orbit(3.0 * M, chi * M, M);
  const auto [xi1, eta1] = exact::spherical_photon_orbit(3.0, chi);
  EXPECT_NEAR(xi, M * xi1, 1e-13);
  EXPECT_NEAR(eta, M * M * eta1, 1e-12);
  // The metrics: a(x, k) at (t, M r, theta, phi) with k scaled alike is a(x, k) / M.
  const KerrMetric m1{1.0, chi}, mM{M, chi * M};
  const Vec4 x(0.0, 4.0, 1.0, 0.5), k(1.3, -0.4, 0.05, 0.02);
  const Vec4 xs(0.0, 4.0 * M, 1.0, 0.5), ks(1.3, -0.4, 0.05 / M, 0.02 / M);
  // (lambda scales with M: a^t, a^r scale with 1/M, a^theta and a^phi with 1/M^2.)
  const Vec4 a1 = m1.acceleration(x, k);
  EXPECT_LT(rel_diff(mM.acceleration(xs, ks), Vec4(a1[0] / M, a1[1] / M, a1[2] / (M * M), a1[3] / (M * M))), 1e-14);
}

TEST(KerrInput, BadInputIsRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(KerrMetric::checked(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(KerrMetric::checked(1.0, -1.2), std::invalid_argument);
  EXPECT_THROW(KerrMetric::checked(1.0, nan), std::invalid_argument);
  EXPECT_THROW(KerrMetric::checked(0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(KerrMetric::checked(nan, 0.0), std::invalid_argument);
  EXPECT_NO_THROW(KerrMetric::checked(2.0, -1.9));
  EXPECT_THROW(KerrSchildMetric::checked(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(exact::isco_radius(1.0, exact::Orbit::prograde), std::invalid_argument);
  EXPECT_THROW(exact::photon_orbit_radius(nan, exact::Orbit::prograde), std::invalid_argument);
  EXPECT_THROW(exact::keplerian_ut(2.0, 0.5, exact::Orbit::prograde), std::invalid_argument);  // inside r_ph
  EXPECT_THROW(exact::critical_curve(0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(exact::critical_curve(0.5, nan), std::invalid_argument);
  EXPECT_THROW(exact::equatorial_deflection(3.0, 0.5), std::invalid_argument);  // captured
  EXPECT_THROW(exact::spherical_photon_orbit(3.0, 0.0), std::invalid_argument);
  try {
    KerrMetric::checked(1.0, 1.5);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("|a| < M"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace grtrace
