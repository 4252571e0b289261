// The light of an emitting medium collected along a ray (trace/emission_system.hpp) against exact answers:
// a uniform sphere in flat space (the chord times j, and the source function where it is optically thick), and the
// spherically accreting Schwarzschild hole of Narayan, Johnson & Gammie (2019) (medium/spherical_accretion.hpp,
// gas at rest and in free fall) against an independent quadrature along the exact ray, in long double; and the
// light split by image order: a thin glowing layer on a Kerr hole's equator against its crossings in closed form.
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/medium/spherical_accretion.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/spectra/kerr_disk_map.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/emission_system.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <vector>

namespace {

using namespace grtrace;

/// A user's own medium: a ball of gas at rest with a Gaussian profile, j = j0 exp(-r^2 / w^2), grey absorption
/// alpha = kappa j (a constant source function S = j / alpha = 1 / kappa). Smooth, so that no step has to land on an
/// edge; beyond 12 w (outer_radius) j is below 1e-62 j0 and taken as 0.
struct GaussianBall {
  static constexpr std::string_view kind = "gaussian-ball";
  static constexpr bool spherically_symmetric = true;
  double j0 = 1.0, width = 3.0, kappa = 0.0;
  double outer_radius() const { return 12.0 * width; }
  template <class M>
  MediumCoefficients coefficients(const M& metric, const Vec4& x, double) const {
    const double r = metric.radius(x), j = j0 * std::exp(-r * r / (width * width));
    return {j, kappa * j};
  }
  template <class M>
  Vec4 fluid_velocity(const M& metric, const Vec4& x) const {
    return Vec4(1.0 / std::sqrt(metric.metric(x)(0, 0)), 0.0, 0.0, 0.0);
  }
};
static_assert(EmittingMediumIn<GaussianBall, SchwarzschildMetric>);
static_assert(EmittingMediumIn<SphericalAccretion, SchwarzschildMetric>);
static_assert(medium_is_stationary<SphericalAccretion>() && medium_is_axisymmetric<SphericalAccretion>());

TraceSettings settings(double rtol, double sky) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, rtol * 1e-2};
  s.escape_radius = sky;
  s.max_steps = 1'000'000;
  return s;
}

/// The backward ray of a static camera at r_o on the equator with impact parameter b, heading inwards, photon energy
/// 1 at infinity (k_t = -1 as the future-directed photon's): k^t = -1 / f, k^phi = b / r_o^2.
GeodesicState camera_ray(double mass, double r_o, double b) {
  const double f = 1.0 - 2.0 * mass / r_o;
  GeodesicState y;
  y << 0.0, r_o, std::numbers::pi / 2, 0.0, -1.0 / f, -std::sqrt(1.0 - b * b * f / (r_o * r_o)), 0.0, b / (r_o * r_o);
  return y;
}

TEST(Emission, AGaussianBallInFlatSpaceShinesItsColumnExactly) {
  // Along a straight line at impact parameter b the column of j0 exp(-r^2 / w^2) is j0 w sqrt(pi) exp(-b^2 / w^2):
  // the intensity without absorption; with alpha = kappa j, tau is kappa times it and I = (1 - e^-tau) / kappa, the
  // source function where the ball is optically thick (a surface of that brightness).
  const SchwarzschildMetric flat{0.0};
  const double w = 3.0, column_at_0 = w * std::sqrt(std::numbers::pi);
  for (const double b : {0.5, 2.0, 5.0}) {  // not 0: flat space's origin is the spherical chart's singular point
    SCOPED_TRACE(b);
    const GeodesicState y0 = camera_ray(0.0, 100.0, b);
    const double column = 2.0 * column_at_0 * std::exp(-b * b / (w * w));
    const EmissionResult thin = trace_emission<Fehlberg78, IController>(flat, GaussianBall{2.0, w, 0.0},
                                                                        settings(1e-10, 1000.0), y0, 1.0, 1.0);
    ASSERT_EQ(thin.trace.status, RayStatus::escaped);
    EXPECT_NEAR(thin.intensity, column, 1e-8 * column);
    EXPECT_EQ(thin.optical_depth, 0.0);
    for (const double kappa : {0.2, 50.0}) {
      const EmissionResult grey = trace_emission<Fehlberg78, IController>(flat, GaussianBall{2.0, w, kappa},
                                                                          settings(1e-10, 1000.0), y0, 1.0, 1.0);
      const double expected = -std::expm1(-kappa * column) / kappa;
      EXPECT_NEAR(grey.intensity, expected, 5e-8 * expected) << kappa;  // measured 1e-8 at kappa = 50 (tau 250)
      if (kappa * column < -std::log(default_min_transmission)) {
        EXPECT_NEAR(grey.optical_depth, kappa * column, 1e-8 * kappa * column) << kappa;
        EXPECT_FALSE(grey.opaque);
        EXPECT_EQ(grey.trace.status, RayStatus::escaped);
      } else {  // opaque: the ray ends where its transmission falls below 1e-16, in the ball
        EXPECT_TRUE(grey.opaque);
        EXPECT_EQ(grey.trace.status, RayStatus::hit);
        EXPECT_GT(grey.optical_depth, -std::log(default_min_transmission));
        EXPECT_LT(grey.trace.final_state[1], y0[1]);  // it stopped before it came out again
      }
    }
  }
}

/// GaussianBall with a spectrum: j = j0 exp(-r^2 / w^2) nu^-s and alpha = kappa j nu^-2 (optically thick at low
/// frequencies, thin at high ones), the gas at rest around the hole.
struct SpectralBall {
  static constexpr std::string_view kind = "spectral-ball";
  static constexpr bool spherically_symmetric = true;
  double j0 = 1.0, width = 3.0, kappa = 0.0, slope = 0.7;
  double outer_radius() const { return 12.0 * width; }
  template <class M>
  MediumCoefficients coefficients(const M& metric, const Vec4& x, double nu) const {
    const double r = metric.radius(x), j = j0 * std::exp(-r * r / (width * width)) * std::pow(nu, -slope);
    return {j, kappa * j / (nu * nu)};
  }
  template <class M>
  Vec4 fluid_velocity(const M& metric, const Vec4& x) const {
    return Vec4(1.0 / std::sqrt(metric.metric(x)(0, 0)), 0.0, 0.0, 0.0);
  }
};

TEST(Emission, SeveralFrequenciesInOnePassAreEachFrequencysOwnTrace) {
  // One ray collects the light of three frequencies. Without absorption the spectrum is a power law at every point,
  // g^3 j(nu / g) = nu^-s g^(3 + s) j0 ..., so the bands' intensities are in the ratio (nu_b / nu_0)^-s to
  // rounding, on each order's piece too, with one emission-weighted g. With absorption, each band is its own
  // single-frequency trace within the integration's error (tau from 0.3 to beyond opaque here: a band that becomes
  // opaque alone ends its own trace there, and the light behind is below 1e-16 of it).
  const SchwarzschildMetric metric{1.0};
  const std::array<double, 3> nu{0.5, 1.0, 3.0};
  double worst = 0.0, tau_lo = 1e300, tau_hi = 0.0;
  for (const double b : {2.0, 5.3, 8.0}) {  // into the hole through the core, once round the hole, on the slope
    SCOPED_TRACE(b);
    const GeodesicState y0 = camera_ray(1.0, 100.0, b);
    const SpectralBall thin{2.0, 3.0, 0.0, 0.7};
    const SpectralEmissionResult<3> s =
        trace_emission<Verner65, IController>(metric, thin, settings(1e-10, 1000.0), y0, 1.0, nu);
    ASSERT_EQ(s.trace.status, b < 3.0 * std::sqrt(3.0) ? RayStatus::captured : RayStatus::escaped);
    ASSERT_GT(s.intensity[0], 0.0);
    for (std::size_t k = 1; k < 3; ++k) {
      const double ratio = std::pow(nu[k] / nu[0], -0.7);
      EXPECT_NEAR(s.intensity[k], ratio * s.intensity[0], 1e-13 * ratio * s.intensity[0]) << k;
      EXPECT_NEAR(s.redshift[k], s.redshift[0], 1e-13) << k;
      for (std::size_t n = 0; n < 4; ++n)
        EXPECT_NEAR(s.intensity_by_order[k][n], ratio * s.intensity_by_order[0][n], 1e-13 * s.intensity[k]);
    }
    const SpectralBall grey{2.0, 3.0, 15.0, 0.7};
    const SpectralEmissionResult<3> g =
        trace_emission<Verner65, IController>(metric, grey, settings(1e-10, 1000.0), y0, 1.0, nu);
    for (std::size_t k = 0; k < 3; ++k) {
      const EmissionResult one =
          trace_emission<Verner65, IController>(metric, grey, settings(1e-10, 1000.0), y0, 1.0, nu[k]);
      EXPECT_NEAR(g.intensity[k], one.intensity, 1e-8 * one.intensity) << k;
      EXPECT_NEAR(g.redshift[k], one.redshift, 1e-8) << k;
      worst = std::max(worst, std::abs(g.intensity[k] / one.intensity - 1.0));
      tau_lo = std::min(tau_lo, g.optical_depth[k]);
      tau_hi = std::max(tau_hi, g.optical_depth[k]);
      if (one.opaque) {  // it ended in the gas; the others' went on through it
        EXPECT_GT(g.optical_depth[k], one.optical_depth) << k;
      } else {
        EXPECT_EQ(one.trace.status, g.trace.status) << k;
        EXPECT_NEAR(g.optical_depth[k], one.optical_depth, 1e-8 * one.optical_depth) << k;
      }
    }
    EXPECT_GT(g.optical_depth[0], 30.0 * g.optical_depth[2]);  // the bands differ: thick at 0.5, thin at 3
  }
  std::printf("bands in one pass against one each: worst %.2e of the intensity; tau %.2g to %.3g\n", worst, tau_lo,
              tau_hi);
}

// ---- the reference: I(b) by quadrature along the exact Schwarzschild ray --------------------------------------

using Real = long double;

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
template <int N>
struct GaussLegendre {
  std::array<Real, static_cast<std::size_t>(N)> x{}, w{};
  GaussLegendre() {
    for (int i = 0; i < N; ++i) {
      Real z = std::cos(std::numbers::pi_v<Real> * (i + 0.75L) / (N + 0.5L)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        Real p0 = 1, p1 = z;
        for (int k = 2; k <= N; ++k) {
          const Real p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = N * (z * p1 - p0) / (z * z - 1);
        const Real step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-21L) break;
      }
      x[static_cast<std::size_t>(i)] = z;
      w[static_cast<std::size_t>(i)] = 2 / ((1 - z * z) * dp * dp);
    }
  }
  Real on(const std::function<Real(Real)>& f, Real a, Real b) const {
    Real sum = 0;
    for (std::size_t i = 0; i < static_cast<std::size_t>(N); ++i) sum += w[i] * f((a + b) / 2 + (b - a) / 2 * x[i]);
    return sum * (b - a) / 2;
  }
};

/// Adaptive Gauss-Legendre: halves an interval until its two halves agree with it to `tol` of the whole.
Real integrate(const std::function<Real(Real)>& f, Real a, Real b, Real tol, int depth = 0) {
  static const GaussLegendre<12> rule;
  const Real m = (a + b) / 2, whole = rule.on(f, a, b), halves = rule.on(f, a, m) + rule.on(f, m, b);
  if (depth > 40 || std::abs(halves - whole) <= tol) return halves;
  return integrate(f, a, m, tol / 2, depth + 1) + integrate(f, m, b, tol / 2, depth + 1);
}

/// I_nu at a static camera at r_o (M = 1) for impact parameter b, j = r^-2 out to r_out, sky sphere beyond r_out,
/// the horizon guard at r_g: E_cam^3 times the integral of j / E_fluid^2 dr / |k^r| over the ray's legs (inwards
/// from the camera, then, past the turning point, outwards), E_fluid = 1 / sqrt(f) at rest and
/// (1 +- |k^r| sqrt(2 / r)) / f in free fall (+ on the inward leg of the backward ray), |k^r| = sqrt(1 - b^2 f / r^2).
/// moment 1: the intensity weighted by g = E_cam / E_fluid (the emission-weighted redshift's numerator).
Real reference_intensity(SphericalAccretion::Gas gas, Real b, Real r_o, Real r_out, Real r_g, Real r_sky,
                         int moment = 0) {
  const Real e_cam = 1 / std::sqrt(1 - 2 / r_o), e_cam_power = std::pow(e_cam, static_cast<Real>(3 + moment));
  auto leg = [&](Real r, Real sign) {
    const Real f = 1 - 2 / r, kr = std::sqrt(std::max<Real>(0, 1 - b * b * f / (r * r)));
    const Real e_fluid = gas == SphericalAccretion::Gas::at_rest ? 1 / std::sqrt(f)
                                                                 : (1 + sign * kr * std::sqrt(2 / r)) / f;
    return std::pow(r, -2.0L) / std::pow(e_fluid, static_cast<Real>(2 + moment));
  };
  auto kr_of = [&](Real r) { return std::sqrt(std::max<Real>(0, 1 - b * b * (1 - 2 / r) / (r * r))); };
  const Real top = std::min(r_o, r_out), top_out = std::min(r_sky, r_out), tol = 1e-16L;
  // The turning point: the largest root of r^3 - b^2 r + 2 b^2 (r^2 = b^2 f), where b exceeds 3 sqrt(3).
  if (b > 3 * std::sqrt(3.0L)) {
    Real r = b;
    for (int it = 0; it < 200; ++it) r -= (r * r * r - b * b * r + 2 * b * b) / (3 * r * r - b * b);
    // r = r_min + s^2 takes out the turning point's 1 / sqrt: |k^r| = s sqrt(N'(r_min) + 3 r_min d + d^2) / r^(3/2)
    // with d = s^2 (N(r) = r^3 - b^2 r + 2 b^2 = r^3 k^r^2, expanded about its root), so 2 s / |k^r| has no 0 / 0.
    auto through = [&](Real sign, Real upto) -> Real {
      if (!(upto > r)) return 0;  // the ray turns outside the gas
      return integrate([&](Real s) {
        const Real d = s * s, rr = r + d;
        const Real kr_over_s = std::sqrt((3 * r * r - b * b + 3 * r * d + d * d) / (rr * rr * rr));
        return leg(rr, sign) * 2 / kr_over_s;
      }, 0, std::sqrt(upto - r), tol);
    };
    return e_cam_power * (through(+1, top) + through(-1, top_out));
  }
  return e_cam_power * integrate([&](Real rr) { return leg(rr, +1) / kr_of(rr); }, r_g, top, tol);
}

TEST(Emission, SphericalAccretionMatchesTheQuadratureOfTheExactRay) {
  // Out to beyond the sky sphere (smooth along every ray), and cut at 30 M: a hard edge where j jumps to 0, on
  // which the tracer ends its steps (SphericalAccretion::boundary; without that: 0.3 - 1 % off).
  const SchwarzschildMetric metric{1.0};
  const double r_o = 1000.0;
  const TraceSettings s = settings(1e-10, 2000.0);
  const double r_g = (1.0 + s.horizon_epsilon) * 2.0;
  for (const double r_out : {1e6, 30.0})
  for (const auto gas : {SphericalAccretion::Gas::at_rest, SphericalAccretion::Gas::free_fall}) {
    SphericalAccretion medium;
    medium.gas = gas;
    medium.outer = r_out;
    for (const double b : {0.0, 2.0, 4.5, 5.1, 5.3, 6.5, 10.0, 29.0, 40.0}) {
      SCOPED_TRACE(::testing::Message() << (gas == SphericalAccretion::Gas::at_rest ? "at rest" : "free fall")
                                        << ", b = " << b << ", out to " << r_out);
      const GeodesicState y0 = camera_ray(1.0, r_o, b);
      const Vec4 u_cam(1.0 / std::sqrt(1.0 - 2.0 / r_o), 0.0, 0.0, 0.0);
      const EmissionResult t = trace_emission_seen_by<Fehlberg78, IController>(metric, medium, s, y0, u_cam, 1.0);
      ASSERT_EQ(t.trace.status, b < 5.19 ? RayStatus::captured : RayStatus::escaped);
      const double ref = static_cast<double>(reference_intensity(gas, b, r_o, r_out, r_g, 2000.0));
      EXPECT_NEAR(t.intensity, ref, 1e-6 * ref);
      EXPECT_EQ(t.optical_depth, 0.0);
      // The emission-weighted redshift (above 1 where gas at rest beyond the camera's radius dominates); none
      // where the ray meets no gas.
      const double weighted = static_cast<double>(reference_intensity(gas, b, r_o, r_out, r_g, 2000.0, 1));
      if (ref > 0.0) {
        EXPECT_NEAR(t.redshift, weighted / ref, 1e-6 * weighted / ref);
      } else {
        EXPECT_TRUE(std::isnan(t.redshift));
      }
    }
  }
}

TEST(Emission, TheIntensityConvergesWithTheTolerance) {
  // Free fall, a ray that passes the photon sphere: the error falls with the tolerance (the intensity is inside the
  // step control), for two tableaux.
  const SchwarzschildMetric metric{1.0};
  SphericalAccretion medium;
  medium.outer = 1e6;  // beyond the sky sphere: a smooth medium all along the ray
  const double b = 5.3, r_o = 1000.0;
  const double ref = static_cast<double>(
      reference_intensity(SphericalAccretion::Gas::free_fall, b, r_o, 1e6, (1.0 + 1e-3) * 2.0, 2000.0));
  const Vec4 u_cam(1.0 / std::sqrt(1.0 - 2.0 / r_o), 0.0, 0.0, 0.0);
  auto error = [&]<class T>(double rtol) {
    const EmissionResult t =
        trace_emission_seen_by<T, IController>(metric, medium, settings(rtol, 2000.0), camera_ray(1.0, r_o, b), u_cam, 1.0);
    return std::abs(t.intensity - ref) / ref;
  };
  for (const auto& [coarse, fine] : {std::pair{error.operator()<Fehlberg78>(1e-6), error.operator()<Fehlberg78>(1e-10)},
                                     std::pair{error.operator()<Verner65>(1e-6), error.operator()<Verner65>(1e-10)}}) {
    EXPECT_LT(fine, 1e-7);
    EXPECT_LT(fine, coarse / 100.0) << coarse << " -> " << fine;
  }
}

/// A thin glowing layer on a Kerr hole's equator: j = eps(r) / (2 h) within the proper height h of the plane
/// (r |pi/2 - theta| < h: its boundary), eps = ((r - r_in) (r_out - r) / r^2)^2 between the radii (going to 0
/// smoothly at both), the gas on prograde Keplerian circles (inside r_in, where eps = 0: the ZAMO's frame).
/// Optically thin. As h -> 0 a ray collects at each crossing of the plane eps / (2 h) times its path through the
/// layer in the gas's frame, 2 h / mu (mu the cosine of its angle to the normal there): the intensity g^3 eps / mu.
struct GlowingLayer {
  static constexpr std::string_view kind = "glowing-layer";
  static constexpr bool stationary = true;
  double h, r_in, r_out;
  double outer_radius() const { return r_out; }
  double eps(double r) const {
    if (!(r > r_in && r < r_out)) return 0.0;
    const double q = (r - r_in) * (r_out - r) / (r * r);
    return q * q;
  }
  double boundary(const KerrMetric&, const Vec4& x) const { return x[1] * std::abs(0.5 * std::numbers::pi - x[2]) - h; }
  MediumCoefficients coefficients(const KerrMetric&, const Vec4& x, double) const {
    return {eps(x[1]) / (2.0 * h), 0.0};
  }
  Vec4 fluid_velocity(const KerrMetric& m, const Vec4& x) const {
    const Mat4 g = m.metric(x);
    if (!(x[1] > r_in)) return *zamo_velocity(g);
    // Bardeen, Press & Teukolsky (1972): prograde Omega = sqrt(M) / (r^(3/2) + a sqrt(M)).
    const double sqrt_m = std::sqrt(m.mass);
    const Vec4 u(1.0, 0.0, 0.0, sqrt_m / (x[1] * std::sqrt(x[1]) + m.spin * sqrt_m));
    return u / std::sqrt(u.dot(g * u));
  }
};

/// The test below, each ray's light from `trace(metric, layer, settings, y0)`.
template <class Trace>
void thin_layer_by_order_in_closed_form(const Trace& trace) {
  // Rays of a distant camera across the hole (beta fixed), out to the disk's edge and densely about the shadow's
  // edges, where the orders n = 1, 2, 3 are: each piece of the split against sum over the crossings of that order of
  // g^3 eps / mu, mu = g sqrt(Q) / r (the ray's momentum along the plane's normal, |k_theta| / r = sqrt(Q) / r at the
  // plane, over its energy in the gas's frame, 1 / g in the units of a camera's pixel), from the closed form's
  // radius and redshift (KerrDiskRays). A split at the crossings themselves would put half of each image in the
  // next order.
  const KerrMetric metric{1.0, 0.9};
  const GlowingLayer layer{2e-4, 2.5, 14.0};
  const double r_o = 300.0, sky = 3000.0, beta = 0.7;
  const KerrDiskMap screen(metric, r_o, 75.0 * std::numbers::pi / 180.0, layer.r_in, layer.r_out);
  const KerrDiskRays rays(metric, layer.r_in, layer.r_out, +1, sky);
  const TraceSettings s = settings(1e-12, sky);
  std::vector<double> alphas;
  for (int i = 0; i <= 80; ++i) alphas.push_back(-16.0 + 0.4 * i);
  for (const double side : {-1.0, 1.0}) {  // the shadow's edge on this side: where the ray stops escaping
    double in = 0.0, out = 16.0 * side;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (in + out);
      (screen.sample(mid, beta).escaped ? out : in) = mid;
    }
    for (int i = 0; i <= 24; ++i) alphas.push_back(out + side * 0.3 * std::pow(1e-5, i / 24.0));
  }
  std::array<int, 4> seen{};  // rays whose piece of that order is lit
  double worst = 0.0;
  for (const double alpha : alphas) {
    const GeodesicState y0 = screen.ray(alpha, beta);
    const DiskRaySample d = rays.sample(y0);
    ASSERT_TRUE(d.covered);
    const Vec4 x = y0.head<4>(), k_low = metric.metric(x) * y0.tail<4>();
    const double c = std::cos(x[2]), s2 = std::sin(x[2]) * std::sin(x[2]);
    const double carter =
        k_low[2] * k_low[2] + c * c * (-metric.spin * metric.spin * k_low[0] * k_low[0] + k_low[3] * k_low[3] / s2);
    std::array<double, 4> ref{};
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      if (d.where[n] != DiskRaySample::on_disk) continue;
      const double g = d.redshift[n], r = d.radius[n];
      ref[std::min<std::size_t>(n, 3)] += g * g * layer.eps(r) * r / std::sqrt(carter);
    }
    const EmissionResult e = trace(metric, layer, s, y0);
    SCOPED_TRACE(::testing::Message() << "alpha = " << alpha);
    ASSERT_EQ(e.trace.status, d.escaped ? RayStatus::escaped : RayStatus::captured);
    const double total = ref[0] + ref[1] + ref[2] + ref[3];
    double sum = 0.0;
    for (std::size_t n = 0; n < 4; ++n) {
      sum += e.intensity_by_order[n];
      EXPECT_NEAR(e.intensity_by_order[n], ref[n], 2e-4 * total) << "order " << n;
      if (total > 0.0) worst = std::max(worst, std::abs(e.intensity_by_order[n] - ref[n]) / total);
      if (ref[n] > 1e-3 * total) ++seen[n];
    }
    EXPECT_NEAR(sum, e.intensity, 1e-14 * e.intensity);
  }
  std::printf("thin layer by order: worst error %.2e of a ray's light; rays lit by n = 0..3: %d %d %d %d\n", worst,
              seen[0], seen[1], seen[2], seen[3]);
  EXPECT_GT(seen[1], 20);  // the test sees the rings it is about
  EXPECT_GT(seen[2], 10);
  EXPECT_GT(seen[3], 10);
}

TEST(Emission, AThinGlowingLayersLightByOrderIsEachCrossingsInClosedForm) {
  thin_layer_by_order_in_closed_form(
      [](const KerrMetric& metric, const GlowingLayer& layer, const TraceSettings& s, const GeodesicState& y0) {
        return trace_emission<Fehlberg78, IController>(metric, layer, s, y0, 1.0, 1.0);
      });
}

TEST(Emission, AThinGlowingLayersLightInMinoTimeIsEachCrossingsInClosedFormToo) {
  // The same light on Kerr's separated equations (trace_kerr_mino_emission), with Verner 6(5).
  thin_layer_by_order_in_closed_form(
      [](const KerrMetric& metric, const GlowingLayer& layer, const TraceSettings& s, const GeodesicState& y0) {
        return trace_kerr_mino_emission<Verner65, IController>(metric, layer, s, y0, 1.0, 1.0);
      });
}

}  // namespace
