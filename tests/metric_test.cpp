// tests/metric_test.cpp
// Tests of the metric policies (grtrace/metric/*): the analytic Christoffel symbols against central finite
// differences of g_{mu nu}(x), the closed-form geodesic acceleration against -Gamma^mu_ab k^a k^b, the
// signature and horizon, and the spherical chart against the pull-back of the Cartesian Minkowski metric.
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <string_view>

namespace grtrace {
namespace {

constexpr int kPoints = 50;

/// Random event in the chart of M: for spherical charts r in (r_lo, r_hi), theta away from the axis.
template <class M>
Vec4 random_event(std::mt19937& rng, const M& metric) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if constexpr (M::chart == Chart::cartesian) {
    return Vec4(20.0 * u(rng) - 10.0, 20.0 * u(rng) - 10.0, 20.0 * u(rng) - 10.0, 20.0 * u(rng) - 10.0);
  } else {
    const double rh = metric.horizon_radius();
    const double r_lo = rh > 0.0 ? 1.25 * rh : 0.5, r_hi = rh > 0.0 ? 25.0 * rh : 50.0;
    const double theta = 0.2 + (std::numbers::pi - 0.4) * u(rng);
    return Vec4(100.0 * u(rng) - 50.0, r_lo + (r_hi - r_lo) * u(rng), theta, 2.0 * std::numbers::pi * u(rng));
  }
}

/// d g_{mu nu} / d x^a by the five-point central difference (truncation error O(h^4)).
/// The step in r is a fixed fraction of the distance to the horizon, so the stencil never reaches it.
template <class M>
std::array<Mat4, 4> metric_derivatives(const M& metric, const Vec4& x) {
  std::array<Mat4, 4> dg;
  for (int a = 0; a < 4; ++a) {
    double h = 1e-3;
    if (M::chart == Chart::spherical && a == 1) h = 1e-3 * (x[1] - metric.horizon_radius());
    auto at = [&](double s) {
      Vec4 y = x;
      y[a] += s * h;
      return metric.metric(y);
    };
    dg[static_cast<std::size_t>(a)] = (-at(2.0) + 8.0 * at(1.0) - 8.0 * at(-1.0) + at(-2.0)) / (12.0 * h);
  }
  return dg;
}

/// Gamma^mu_ab = 1/2 g^{mu nu} (d_a g_{nu b} + d_b g_{nu a} - d_nu g_{ab}) from finite differences.
template <class M>
Christoffel christoffel_from_metric(const M& metric, const Vec4& x) {
  const Mat4 g_inv = metric.metric(x).inverse();
  const auto dg = metric_derivatives(metric, x);
  Christoffel G;
  for (int mu = 0; mu < 4; ++mu) {
    Mat4& Gm = G[static_cast<std::size_t>(mu)];
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        double s = 0.0;
        for (int nu = 0; nu < 4; ++nu)
          s += g_inv(mu, nu) * (dg[static_cast<std::size_t>(a)](nu, b) + dg[static_cast<std::size_t>(b)](nu, a) -
                                dg[static_cast<std::size_t>(nu)](a, b));
        Gm(a, b) = 0.5 * s;
      }
  }
  return G;
}

/// Largest |analytic - finite difference| over all 64 symbols, each scaled by 1 + |analytic|.
template <class M>
double worst_christoffel_mismatch(const M& metric, std::uint32_t seed, double* largest_symbol = nullptr) {
  std::mt19937 rng(seed);
  double worst = 0.0, largest = 0.0;
  for (int p = 0; p < kPoints; ++p) {
    const Vec4 x = random_event(rng, metric);
    const Christoffel exact = metric.christoffel(x);
    const Christoffel numeric = christoffel_from_metric(metric, x);
    for (std::size_t mu = 0; mu < 4; ++mu)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
          const double e = exact[mu](a, b), n = numeric[mu](a, b);
          worst = std::max(worst, std::abs(e - n) / (1.0 + std::abs(e)));
          largest = std::max(largest, std::abs(e));
        }
  }
  if (largest_symbol) *largest_symbol = largest;
  return worst;
}

// -----------------------------------------------------------------------------------------------------------
// Christoffel symbols against finite differences of the metric

TEST(Christoffel, SchwarzschildMassOneMatchesFiniteDifferences) {
  double largest = 0.0;
  const double worst = worst_christoffel_mismatch(SchwarzschildMetric{1.0}, 11u, &largest);
  std::printf("schwarzschild M=1: worst scaled mismatch %.3g (largest |Gamma| %.3g)\n", worst, largest);
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(largest, 1.0);  // the points do probe the strong field
}

TEST(Christoffel, SchwarzschildMassTwoAndAHalfMatchesFiniteDifferences) {
  double largest = 0.0;
  const double worst = worst_christoffel_mismatch(SchwarzschildMetric{2.5}, 12u, &largest);
  std::printf("schwarzschild M=2.5: worst scaled mismatch %.3g (largest |Gamma| %.3g)\n", worst, largest);
  EXPECT_LT(worst, 1e-9);
}

TEST(Christoffel, MinkowskiSphericalMatchesFiniteDifferences) {
  const double worst = worst_christoffel_mismatch(MinkowskiSpherical{}, 13u);
  std::printf("minkowski-spherical: worst scaled mismatch %.3g\n", worst);
  EXPECT_LT(worst, 1e-9);
}

TEST(Christoffel, MinkowskiCartesianVanishes) {
  const MinkowskiMetric m;
  std::mt19937 rng(14u);
  for (int p = 0; p < kPoints; ++p) {
    const Vec4 x = random_event(rng, m);
    const Christoffel exact = m.christoffel(x);
    const Christoffel numeric = christoffel_from_metric(m, x);
    for (std::size_t mu = 0; mu < 4; ++mu) {
      EXPECT_EQ(exact[mu].cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ(numeric[mu].cwiseAbs().maxCoeff(), 0.0);
    }
  }
}

TEST(Christoffel, AreSymmetricInTheLowerIndices) {
  std::mt19937 rng(15u);
  const SchwarzschildMetric m{1.0};
  for (int p = 0; p < kPoints; ++p) {
    const Christoffel G = m.christoffel(random_event(rng, m));
    for (const Mat4& Gm : G) EXPECT_EQ((Gm - Gm.transpose()).cwiseAbs().maxCoeff(), 0.0);
  }
}

/// Schwarzschild with M = 0 and MinkowskiSpherical are the same policy under two names.
TEST(Christoffel, SchwarzschildWithZeroMassIsMinkowskiSpherical) {
  std::mt19937 rng(16u);
  const SchwarzschildMetric s{0.0};
  const MinkowskiSpherical f;
  EXPECT_EQ(f.mass, 0.0);
  EXPECT_EQ(std::string_view(MinkowskiSpherical::name), "minkowski-spherical");
  for (int p = 0; p < kPoints; ++p) {
    const Vec4 x = random_event(rng, f);
    EXPECT_EQ((s.metric(x) - f.metric(x)).cwiseAbs().maxCoeff(), 0.0);
  }
}

// -----------------------------------------------------------------------------------------------------------
// Closed-form acceleration against the Christoffel table

template <class M>
double worst_acceleration_mismatch(const M& metric, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  double worst = 0.0;
  for (int p = 0; p < kPoints; ++p) {
    const Vec4 x = random_event(rng, metric);
    // Components of comparable physical size: angular rates scaled by 1/r in spherical charts.
    Vec4 k(n(rng), n(rng), n(rng), n(rng));
    if constexpr (M::chart == Chart::spherical) {
      k[2] /= x[1];
      k[3] /= x[1];
    }
    const Christoffel G = metric.christoffel(x);
    const Vec4 closed = metric.acceleration(x, k);
    const Vec4 table = acceleration_from_christoffel(G, k);
    for (int mu = 0; mu < 4; ++mu) {
      // Scale: the sum of the magnitudes of the terms -Gamma^mu_ab k^a k^b.
      const double scale = (G[static_cast<std::size_t>(mu)].cwiseAbs() * k.cwiseAbs()).dot(k.cwiseAbs());
      worst = std::max(worst, std::abs(closed[mu] - table[mu]) / (scale + 1e-300));
    }
  }
  return worst;
}

TEST(Acceleration, ClosedFormEqualsChristoffelContraction) {
  const double s1 = worst_acceleration_mismatch(SchwarzschildMetric{1.0}, 21u);
  const double s25 = worst_acceleration_mismatch(SchwarzschildMetric{2.5}, 22u);
  const double fs = worst_acceleration_mismatch(MinkowskiSpherical{}, 23u);
  std::printf("acceleration vs -Gamma k k: M=1 %.3g, M=2.5 %.3g, flat spherical %.3g (relative to term sum)\n", s1, s25,
              fs);
  EXPECT_LT(s1, 1e-13);
  EXPECT_LT(s25, 1e-13);
  EXPECT_LT(fs, 1e-13);

  const MinkowskiMetric m;
  std::mt19937 rng(24u);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int p = 0; p < kPoints; ++p) {
    const Vec4 x = random_event(rng, m), k(n(rng), n(rng), n(rng), n(rng));
    EXPECT_EQ(m.acceleration(x, k).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(acceleration_from_christoffel(m.christoffel(x), k).cwiseAbs().maxCoeff(), 0.0);
  }
}

/// The geodesic equation packs (k, acceleration) into the derivative of the 8-component state.
TEST(Acceleration, GeodesicEquationPacksPositionAndMomentum) {
  const SchwarzschildMetric m{1.0};
  const GeodesicEquation<SchwarzschildMetric> rhs{&m};
  const Vec4 x(3.0, 7.5, 1.1, 0.4), k(1.3, -0.4, 0.02, 0.05);
  const GeodesicState dy = rhs(make_state(x, k));
  EXPECT_EQ((dy.head<4>() - k).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((dy.tail<4>() - m.acceleration(x, k)).cwiseAbs().maxCoeff(), 0.0);
}

// -----------------------------------------------------------------------------------------------------------
// Signature, horizon, chart

int positive_eigenvalues(const Mat4& g) {
  const Eigen::SelfAdjointEigenSolver<Mat4> es(g);
  int n = 0;
  for (int i = 0; i < 4; ++i) n += es.eigenvalues()[i] > 0.0 ? 1 : 0;
  return n;
}

TEST(Signature, SchwarzschildIsLorentzianOutsideAndInsideTheHorizon) {
  for (double M : {1.0, 2.5}) {
    const SchwarzschildMetric m{M};
    EXPECT_EQ(m.horizon_radius(), 2.0 * M);
    std::mt19937 rng(31u);
    for (int p = 0; p < kPoints; ++p) {
      const Vec4 x = random_event(rng, m);
      const Mat4 g = m.metric(x);
      const double r = x[1], f = 1.0 - 2.0 * M / r, st = std::sin(x[2]);
      EXPECT_NEAR(g(0, 0), f, 1e-15);
      EXPECT_NEAR(g(1, 1) * f, -1.0, 1e-14);
      EXPECT_NEAR(g(2, 2), -r * r, 1e-12 * r * r);
      EXPECT_NEAR(g(3, 3), -r * r * st * st, 1e-12 * r * r);
      EXPECT_EQ(positive_eigenvalues(g), 1);  // (+,-,-,-)
      // det g = -r^4 sin^2 theta for every mass (the horizon is a coordinate singularity only).
      EXPECT_NEAR(g.determinant() / (r * r * r * r * st * st), -1.0, 1e-12);
    }
    // Inside the horizon t and r swap roles: g_tt < 0 < g_rr, still one positive eigenvalue.
    const Mat4 inside = m.metric(Vec4(0.0, M, 1.0, 0.0));
    EXPECT_LT(inside(0, 0), 0.0);
    EXPECT_GT(inside(1, 1), 0.0);
    EXPECT_EQ(positive_eigenvalues(inside), 1);
    // At the horizon itself g_tt vanishes.
    EXPECT_EQ(m.metric(Vec4(0.0, 2.0 * M, 1.0, 0.0))(0, 0), 0.0);
  }
}

TEST(Signature, MinkowskiChartsHaveNoHorizon) {
  EXPECT_EQ(MinkowskiMetric{}.horizon_radius(), 0.0);
  EXPECT_EQ(MinkowskiSpherical{}.horizon_radius(), 0.0);
  const Mat4 eta = MinkowskiMetric{}.metric(Vec4(1.0, 2.0, 3.0, 4.0));
  EXPECT_EQ((eta - Mat4(Vec4(1.0, -1.0, -1.0, -1.0).asDiagonal())).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(MinkowskiMetric{}.radius(Vec4(7.0, 3.0, 4.0, 12.0)), 13.0);
}

/// The spherical chart: g_spherical = J^T eta J with J = d(t, x, y, z)/d(t, r, theta, phi), J taken by finite
/// differences of to_cartesian. Checks the metric and the drawing map against each other.
TEST(Chart, SphericalMetricIsThePullBackOfCartesianMinkowski) {
  const MinkowskiSpherical m;
  const Mat4 eta = MinkowskiMetric{}.metric(Vec4::Zero());
  std::mt19937 rng(41u);
  double worst = 0.0;
  for (int p = 0; p < kPoints; ++p) {
    const Vec4 x = random_event(rng, m);
    EXPECT_NEAR(m.to_cartesian(x).norm(), x[1], 1e-13 * x[1]);
    EXPECT_EQ(m.radius(x), x[1]);
    Mat4 J = Mat4::Zero();
    J(0, 0) = 1.0;
    for (int a = 1; a < 4; ++a) {
      const double h = 1e-3;
      auto at = [&](double s) {
        Vec4 y = x;
        y[a] += s * h;
        return Vec3(m.to_cartesian(y));
      };
      J.block<3, 1>(1, a) = (-at(2.0) + 8.0 * at(1.0) - 8.0 * at(-1.0) + at(-2.0)) / (12.0 * h);
    }
    const Mat4 pulled = J.transpose() * eta * J;
    const Mat4 g = m.metric(x);
    worst = std::max(worst, (pulled - g).cwiseAbs().maxCoeff() / (1.0 + x[1] * x[1]));
  }
  std::printf("spherical chart vs pull-back of eta: worst scaled mismatch %.3g\n", worst);
  EXPECT_LT(worst, 1e-10);
}

}  // namespace
}  // namespace grtrace
