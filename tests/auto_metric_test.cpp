// tests/auto_metric_test.cpp
// Tests of automatic differentiation (grtrace/metric/dual.hpp, auto_metric.hpp) and of the example metrics
// written with it (grtrace/metric/examples/): Dual arithmetic against hand derivatives (and in constant
// expressions); differentiated Christoffel symbols and accelerations against the closed forms of
// SchwarzschildMetric, MinkowskiMetric and MinkowskiSpherical to 1e-13 relative; an AutoMetric-traced Schwarzschild
// deflection against the exact one and against the closed-form tracer; the MetricComponents concept's verdicts;
// the example metrics' physics (Schwarzschild-de Sitter horizons, a ray through the wormhole throat,
// Eddington-Finkelstein against Schwarzschild coordinates and through r = 2M with fixed-step RK4, the outgoing
// chart for past-directed rays).
#include "grtrace/metric/auto_metric.hpp"

#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/dual.hpp"
#include "grtrace/metric/examples/eddington_finkelstein.hpp"
#include "grtrace/metric/examples/ellis_wormhole.hpp"
#include "grtrace/metric/examples/minkowski_components.hpp"
#include "grtrace/metric/examples/reissner_nordstrom.hpp"
#include "grtrace/metric/examples/schwarzschild_components.hpp"
#include "grtrace/metric/examples/schwarzschild_de_sitter.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/tableau/classic_rk4.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

namespace grtrace {
namespace {

constexpr double kPi = std::numbers::pi;

// -----------------------------------------------------------------------------------------------------------
// Dual numbers

// The arithmetic is usable in constant expressions: d/dx (x^2 + 3x) / x at x = 2 is 1 (the function is x + 3).
constexpr Dual<1> kX = Dual<1>::variable(2.0, 0);
constexpr Dual<1> kF = (kX * kX + 3.0 * kX) / kX;
static_assert(kF.v == 5.0 && kF.d[0] == 1.0);
static_assert(sizeof(Dual<4>) == 5 * sizeof(double));
static_assert(std::is_trivially_copyable_v<Dual<4>>);

TEST(Dual, ElementaryFunctionsHaveTheirDerivatives) {
  using D = Dual<2>;
  const D x = D::variable(0.7, 0), y = D::variable(1.3, 1);
  using std::atan2, std::cos, std::exp, std::log, std::pow, std::sin, std::sqrt, std::tan;
  const D f = sin(x) * exp(y) + sqrt(x * y) - log(y) / x + pow(x, 2.5) + tan(x) * cos(y) + atan2(y, x);
  const double xv = 0.7, yv = 1.3;
  const double dfdx = std::cos(xv) * std::exp(yv) + 0.5 * yv / std::sqrt(xv * yv) + std::log(yv) / (xv * xv) +
                      2.5 * std::pow(xv, 1.5) + std::cos(yv) / (std::cos(xv) * std::cos(xv)) - yv / (xv * xv + yv * yv);
  const double dfdy = std::sin(xv) * std::exp(yv) + 0.5 * xv / std::sqrt(xv * yv) - 1.0 / (yv * xv) -
                      std::tan(xv) * std::sin(yv) + xv / (xv * xv + yv * yv);
  EXPECT_NEAR(f.d[0], dfdx, 1e-14 * std::abs(dfdx));
  EXPECT_NEAR(f.d[1], dfdy, 1e-14 * std::abs(dfdy));
  EXPECT_TRUE(x < y && y > 1.0 && x == 0.7);  // comparisons read the value
  EXPECT_EQ(primal_value(f), f.v);
  EXPECT_EQ(primal_value(0.25), 0.25);
}

// -----------------------------------------------------------------------------------------------------------
// The MetricComponents concept

struct NotATemplate {  // the commonest mistake: g written on doubles only
  static constexpr std::string_view name = "not-a-template";
  static constexpr Chart chart = Chart::spherical;
  Mat4 metric_components(const Vec4& /*x*/) const { return Mat4::Identity(); }
  double radius(const Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 0.0; }
};
struct NotConst {
  static constexpr std::string_view name = "not-const";
  static constexpr Chart chart = Chart::spherical;
  template <class S>
  Mat4Of<S> metric_components(const Vec4Of<S>& /*x*/) {
    return Mat4Of<S>::Identity();
  }
  double radius(const Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 0.0; }
};
struct NoHorizon {
  static constexpr std::string_view name = "no-horizon";
  static constexpr Chart chart = Chart::spherical;
  template <class S>
  Mat4Of<S> metric_components(const Vec4Of<S>& /*x*/) const {
    return Mat4Of<S>::Identity();
  }
  double radius(const Vec4& x) const { return x[1]; }
};

static_assert(!MetricComponents<NotATemplate>);
static_assert(auto_metric_detail::components_of_double<NotATemplate>);
static_assert(!auto_metric_detail::components_of_dual<NotATemplate>);
static_assert(!MetricComponents<NotConst> && auto_metric_detail::components_of_double_nonconst<NotConst>);
static_assert(!MetricComponents<NoHorizon>);
static_assert(MetricComponents<SchwarzschildComponents> && MetricComponents<EllisWormhole> &&
              MetricComponents<SchwarzschildDeSitter> && MetricComponents<ReissnerNordstrom> &&
              MetricComponents<EddingtonFinkelstein> && MetricComponents<MinkowskiComponents>);
static_assert(AutoSchwarzschild::active_count == 2 && AutoMinkowski::active_count == 4);
static_assert(MetricPolicy<AutoMetric<EllisWormhole>> && MetricPolicy<AutoMetric<SchwarzschildDeSitter>> &&
              MetricPolicy<AutoMetric<ReissnerNordstrom>> && MetricPolicy<AutoMetric<EddingtonFinkelstein>>);

// -----------------------------------------------------------------------------------------------------------
// Differentiated Christoffel symbols against the closed forms

template <class M>
Vec4 random_event(std::mt19937& rng, const M& metric) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if constexpr (M::chart == Chart::cartesian) {
    return Vec4(20.0 * u(rng) - 10.0, 20.0 * u(rng) - 10.0, 20.0 * u(rng) - 10.0, 20.0 * u(rng) - 10.0);
  } else {
    const double rh = metric.horizon_radius();
    const double r_lo = rh > 0.0 ? 1.05 * rh : 0.5, r_hi = rh > 0.0 ? 50.0 * rh : 50.0;
    return Vec4(100.0 * u(rng) - 50.0, r_lo + (r_hi - r_lo) * u(rng), 0.05 + (kPi - 0.1) * u(rng), 2.0 * kPi * u(rng));
  }
}

struct Mismatch {
  double christoffel = 0.0;   ///< worst |AD - closed| / |closed| over the nonzero symbols
  double zero_symbols = 0.0;  ///< worst |AD| / max|Gamma| over the symbols that vanish in closed form
  double acceleration = 0.0;  ///< worst |AD - closed| / sum |Gamma^mu_ab k^a k^b| terms, per component
  int nonzero = 0;
};

/// AD against closed form at `points` random events (and a random k at each).
template <class Closed, class Components>
Mismatch compare(const Closed& closed, const Components& components, std::uint32_t seed, int points = 200) {
  const AutoMetric<Components> automatic{components};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mismatch m;
  for (int p = 0; p < points; ++p) {
    const Vec4 x = random_event(rng, closed);
    const Christoffel exact = closed.christoffel(x), ad = automatic.christoffel(x);
    double largest = 0.0;
    for (const Mat4& G : exact) largest = std::max(largest, G.cwiseAbs().maxCoeff());
    for (std::size_t mu = 0; mu < 4; ++mu)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
          const double e = exact[mu](a, b), d = ad[mu](a, b);
          if (e != 0.0) {
            m.christoffel = std::max(m.christoffel, std::abs(d - e) / std::abs(e));
            ++m.nonzero;
          } else if (largest > 0.0) {
            m.zero_symbols = std::max(m.zero_symbols, std::abs(d) / largest);
          } else {
            m.zero_symbols = std::max(m.zero_symbols, std::abs(d));
          }
        }
    const Vec4 k(u(rng), u(rng), u(rng), u(rng));
    const Vec4 a_exact = closed.acceleration(x, k), a_ad = automatic.acceleration(x, k);
    for (std::size_t mu = 0; mu < 4; ++mu) {
      const double scale = k.cwiseAbs().dot(exact[mu].cwiseAbs() * k.cwiseAbs());
      const double diff = std::abs(a_ad[static_cast<int>(mu)] - a_exact[static_cast<int>(mu)]);
      m.acceleration = std::max(m.acceleration, scale > 0.0 ? diff / scale : diff);
    }
  }
  return m;
}

void expect_matches(const char* what, const Mismatch& m) {
  std::printf(
      "%s: worst relative Christoffel error %.3g (%d nonzero symbols), vanishing symbols %.3g, "
      "acceleration %.3g\n",
      what, m.christoffel, m.nonzero, m.zero_symbols, m.acceleration);
  EXPECT_LT(m.christoffel, 1e-13) << what;
  EXPECT_LT(m.zero_symbols, 1e-13) << what;
  EXPECT_LT(m.acceleration, 1e-13) << what;
}

TEST(AutoChristoffel, SchwarzschildEqualsTheClosedForm) {
  expect_matches("schwarzschild M=1", compare(SchwarzschildMetric{1.0}, SchwarzschildComponents{1.0}, 1u));
  expect_matches("schwarzschild M=2.5", compare(SchwarzschildMetric{2.5}, SchwarzschildComponents{2.5}, 2u));
}

TEST(AutoChristoffel, MinkowskiSphericalEqualsTheClosedForm) {
  expect_matches("minkowski-spherical", compare(MinkowskiSpherical{}, SchwarzschildComponents{0.0}, 3u));
}

TEST(AutoChristoffel, MinkowskiCartesianIsExactlyZero) {
  const Mismatch m = compare(MinkowskiMetric{}, MinkowskiComponents{}, 4u);
  expect_matches("minkowski", m);
  EXPECT_EQ(m.zero_symbols, 0.0);
  EXPECT_EQ(m.acceleration, 0.0);
}

TEST(AutoChristoffel, AccelerationIsMinusGammaKK) {
  // The contraction in acceleration() against the full table, for a non-diagonal metric (EF has g_vr).
  const AutoEddingtonFinkelstein ef{};
  std::mt19937 rng(5u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int p = 0; p < 200; ++p) {
    const Vec4 x(10.0 * u(rng), 1.5 + 20.0 * (u(rng) + 1.0), 1.5 + 1.4 * u(rng), 3.0 * u(rng));
    const Vec4 k(u(rng), u(rng), u(rng), u(rng));
    const Vec4 a = ef.acceleration(x, k), ref = acceleration_from_christoffel(ef.christoffel(x), k);
    worst = std::max(worst, (a - ref).cwiseAbs().maxCoeff() / (1.0 + ref.cwiseAbs().maxCoeff()));
  }
  std::printf("eddington-finkelstein: acceleration() against -Gamma(k, k) from the table: %.3g\n", worst);
  EXPECT_LT(worst, 1e-13);
}

TEST(AutoChristoffel, JetAndInverseAreConsistent) {
  const AutoSchwarzschild m{};
  const Vec4 x(0.0, 7.0, 1.0, 2.0);
  const MetricJet j = m.jet(x);
  EXPECT_EQ(j.g, m.metric(x));
  EXPECT_LT((j.g * m.inverse_metric(x) - Mat4::Identity()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_DOUBLE_EQ(j.dg[1](0, 0), 2.0 / 49.0);  // d_r (1 - 2/r) = 2 / r^2
  EXPECT_DOUBLE_EQ(j.dg[2](3, 3), -2.0 * 49.0 * std::sin(1.0) * std::cos(1.0));
}

// -----------------------------------------------------------------------------------------------------------
// Traced with GeodesicTracer: the same rays as the closed form

/// Total deflection of a photon of impact parameter b (the method of trace/deflection.hpp, for any tracer over a
/// Schwarzschild-like metric in Schwarzschild coordinates).
template <class Tracer>
double deflection(const Tracer& tracer, double b, TraceResult* out = nullptr) {
  const double r_s = std::max(50.0, 4.0 * b);
  TraceSettings s = tracer.settings();
  s.escape_radius = r_s * (1.0 + 1e-9);
  using Metric = std::remove_cvref_t<decltype(tracer.metric())>;
  const GeodesicTracer<Metric, DormandPrince54, PIController> local(tracer.metric(), s);
  const TraceResult r = local.trace(incoming_photon(b, r_s));
  if (out) *out = r;
  if (r.status != RayStatus::escaped) return std::numeric_limits<double>::quiet_NaN();
  const GeodesicState& y = r.step_end_state;
  return y[3] + exact::phi_from_infinity(b, 1.0 / r_s) + exact::phi_from_infinity(b, 1.0 / y[1]) - kPi;
}

TEST(AutoTrace, SchwarzschildDeflectionEqualsTheExactAndTheClosedFormTracers) {
  TraceSettings s;
  s.integrator.tolerance = {1e-11, 1e-13};
  const GeodesicTracer<AutoSchwarzschild, DormandPrince54, PIController> automatic(AutoSchwarzschild{}, s);
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> closed(SchwarzschildMetric{}, s);
  for (double b : {6.0, 10.0, 30.0}) {
    TraceResult ra, rc;
    const double da = deflection(automatic, b, &ra), dc = deflection(closed, b, &rc), de = exact::deflection_angle(b);
    std::printf("b = %4.1f: automatic %.15f, closed form %.15f, exact %.15f (steps %d / %d)\n", b, da, dc, de,
                ra.accepted, rc.accepted);
    EXPECT_NEAR(da, de, 1e-8) << "b = " << b;
    EXPECT_NEAR(da, dc, 1e-11) << "b = " << b;
    EXPECT_EQ(ra.accepted, rc.accepted) << "b = " << b;  // same right-hand side to rounding: same step sequence
    EXPECT_LT((ra.final_state - rc.final_state).cwiseAbs().maxCoeff(), 1e-9 * rc.final_state.cwiseAbs().maxCoeff());
  }
}

TEST(AutoTrace, PhotonBelowTheCriticalImpactParameterIsCaptured) {
  const GeodesicTracer<AutoSchwarzschild, DormandPrince54, PIController> tracer(AutoSchwarzschild{}, TraceSettings{});
  const TraceResult r = tracer.trace(incoming_photon(5.0, 50.0));
  EXPECT_EQ(r.status, RayStatus::captured);
}

// -----------------------------------------------------------------------------------------------------------
// The example metrics' physics

TEST(SchwarzschildDeSitter, HorizonsAreTheRootsOfTheCubic) {
  for (double lambda : {1e-6, 1e-3, 0.05, 0.1}) {
    const SchwarzschildDeSitter m{1.0, lambda};
    const double rb = m.black_hole_horizon_radius(), rc = m.cosmological_horizon_radius(), rn = m.cubic_root(2);
    const AutoSchwarzschildDeSitter a{m};
    auto gtt = [&](double r) { return a.metric(Vec4(0.0, r, 1.0, 0.0))(0, 0); };
    std::printf("Lambda = %g: r_b = %.15g, r_c = %.15g (sqrt(3/Lambda) = %.6g), g_tt(r_b) = %.3g, g_tt(r_c) = %.3g\n",
                lambda, rb, rc, std::sqrt(3.0 / lambda), gtt(rb), gtt(rc));
    EXPECT_LT(std::abs(gtt(rb)), 1e-14);
    EXPECT_LT(std::abs(gtt(rc)), 1e-14);
    // Vieta for Lambda r^3 / 3 - r + 2M: the roots sum to 0 and their product is -6M / Lambda.
    EXPECT_NEAR(rb + rc + rn, 0.0, 1e-12 * rc);
    EXPECT_NEAR(rb * rc * rn, -6.0 / lambda, 1e-12 * 6.0 / lambda);
    EXPECT_GT(rb, 2.0);
    EXPECT_LT(rb, 3.0);  // 9 Lambda M^2 < 1 keeps r_b below the extremal 3M
    EXPECT_GT(rc, 3.0);
    EXPECT_GT(gtt(0.5 * (rb + rc)), 0.0);  // static in between
    EXPECT_LT(gtt(0.99 * rb), 0.0);
    EXPECT_LT(gtt(1.01 * rc), 0.0);
    EXPECT_EQ(a.horizon_radius(), rb);
  }
  // Small Lambda: r_b -> 2M (1 + 4 Lambda M^2 / 3), r_c -> sqrt(3 / Lambda) - M.
  const SchwarzschildDeSitter small{1.0, 1e-8};
  EXPECT_NEAR(small.black_hole_horizon_radius(), 2.0 * (1.0 + 4e-8 / 3.0), 1e-13);
  EXPECT_NEAR(small.cosmological_horizon_radius(), std::sqrt(3e8) - 1.0, 1e-3);
}

TEST(ReissnerNordstrom, HorizonsAreWhereGttVanishes) {
  const ReissnerNordstrom m{1.0, 0.6};
  EXPECT_DOUBLE_EQ(m.horizon_radius(), 1.8);
  EXPECT_DOUBLE_EQ(m.inner_horizon_radius(), 0.2);
  const AutoReissnerNordstrom a{m};
  EXPECT_NEAR(a.metric(Vec4(0.0, 1.8, 1.0, 0.0))(0, 0), 0.0, 1e-15);
  EXPECT_NEAR(a.metric(Vec4(0.0, 0.2, 1.0, 0.0))(0, 0), 0.0, 1e-14);
  // Charge 0 is Schwarzschild, symbol for symbol.
  const Vec4 x(1.0, 4.0, 1.2, 0.3);
  const Christoffel rn = AutoReissnerNordstrom{{1.0, 0.0}}.christoffel(x), s = SchwarzschildMetric{1.0}.christoffel(x);
  for (std::size_t mu = 0; mu < 4; ++mu) EXPECT_LT((rn[mu] - s[mu]).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(EllisWormhole, RadialRayPassesTheThroatIntoTheOtherUniverse) {
  TraceSettings s;
  s.escape_radius = 30.0;
  const AutoEllisWormhole w{{1.0}};
  const GeodesicTracer<AutoEllisWormhole, DormandPrince54, PIController> tracer(w, s);
  // Radial, ingoing, null: k = (1, -1, 0, 0) in (t, l, theta, phi) (g = diag(1, -1, ...)).
  const TraceResult r = tracer.trace(make_state(Vec4(0.0, 20.0, kPi / 2.0, 0.0), Vec4(1.0, -1.0, 0.0, 0.0)));
  std::printf("radial ray from l = 20: %s at l = %.12g, t = %.12g after %d steps\n", to_string(r.status).data(),
              r.final_state[1], r.final_state[0], r.accepted);
  EXPECT_EQ(r.status, RayStatus::escaped);
  EXPECT_LT(r.final_state[1], 0.0);  // the other side
  EXPECT_NEAR(r.final_state[1], -std::sqrt(30.0 * 30.0 - 1.0), 1e-9);
  EXPECT_NEAR(r.final_state[0], 20.0 + std::sqrt(899.0), 1e-9);  // radial null: dt = |dl|
  // A ray with angular momentum above the throat's b0 is turned back to its own universe.
  const double L = 1.5;  // impact parameter L / E; the potential barrier is r(l) = b0 = 1 at the throat
  const TraceResult back = tracer.trace(
      make_state(Vec4(0.0, 20.0, kPi / 2.0, 0.0), Vec4(1.0, -std::sqrt(1.0 - L * L / 401.0), 0.0, L / 401.0)));
  EXPECT_EQ(back.status, RayStatus::escaped);
  EXPECT_GT(back.final_state[1], 0.0);
}

/// A photon of impact parameter b coming in from r = 40 in Schwarzschild coordinates, off the equator.
GeodesicState schwarzschild_photon(double b) {
  const double r = 40.0, f = 1.0 - 2.0 / r, theta = 1.1;
  // E = 1, L = b split between theta and phi; k^r from the null condition.
  const double kth = 0.6 * b / (r * r), kph = 0.8 * b / (r * r * std::sin(theta));
  const double kr = -std::sqrt(1.0 - f * b * b / (r * r));
  return make_state(Vec4(0.0, r, theta, 0.4), Vec4(1.0 / f, kr, kth, kph));
}

TEST(EddingtonFinkelstein, EscapingRayEndsInTheSameSkyDirectionAsInSchwarzschildCoordinates) {
  TraceSettings s;
  s.integrator.tolerance = {1e-11, 1e-13};
  s.escape_radius = 100.0;
  const EddingtonFinkelstein ef{};
  const GeodesicTracer<AutoEddingtonFinkelstein, DormandPrince54, PIController> in_ef(AutoEddingtonFinkelstein{ef}, s);
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> in_s(SchwarzschildMetric{}, s);
  for (double b : {5.5, 8.0, 20.0}) {
    const GeodesicState y0 = schwarzschild_photon(b);
    const TraceResult re = in_ef.trace(ef.from_schwarzschild(y0)), rs = in_s.trace(y0);
    ASSERT_EQ(re.status, RayStatus::escaped) << "b = " << b;
    ASSERT_EQ(rs.status, RayStatus::escaped) << "b = " << b;
    const auto de = exact::asymptotic_direction(ef.to_schwarzschild(re.final_state));
    const auto ds = exact::asymptotic_direction(rs.final_state);
    ASSERT_TRUE(de && ds);
    const double angle = exact::angular_distance(*de, *ds);
    std::printf(
        "b = %4.1f: EF sky (%.12f, %.12f), Schwarzschild sky (%.12f, %.12f), %.3g rad apart; "
        "t from EF %.10f vs %.10f\n",
        b, de->theta, de->phi, ds->theta, ds->phi, angle, ef.to_schwarzschild(re.final_state)[0], rs.final_state[0]);
    EXPECT_LT(angle, 1e-8) << "b = " << b;
    EXPECT_NEAR(ef.to_schwarzschild(re.final_state)[0], rs.final_state[0], 1e-6 * rs.final_state[0]);
    EXPECT_NEAR(ef.energy(re.final_state), 1.0, 1e-9);
  }
}

TEST(EddingtonFinkelstein, CapturedRayCrossesTheHorizonWithFixedStepRK4) {
  TraceSettings s;
  s.initial_step = 0.01;
  s.max_steps = 100000;
  const EddingtonFinkelstein ef{};
  const GeodesicTracer<AutoEddingtonFinkelstein, ClassicRK4, FixedStep> tracer(AutoEddingtonFinkelstein{ef}, s);
  double r_min_step = 1e300, kv_max = 0.0;
  int inside_steps = 0;
  auto observer = [&](const auto& integ, double /*theta*/) {
    const GeodesicState& y = integ.state();
    r_min_step = std::min(r_min_step, y[1]);
    kv_max = std::max(kv_max, std::abs(y[4]));
    if (y[1] < 2.0) ++inside_steps;
  };
  for (double b : {0.5, 3.0, 5.0}) {
    r_min_step = 1e300;
    kv_max = 0.0;
    inside_steps = 0;
    const TraceResult r = tracer.trace_observed(ef.from_schwarzschild(schwarzschild_photon(b)), observer);
    std::printf(
        "b = %.1f: %s at r = %.6f after %d fixed steps (%d inside r = 2M), |k^v| <= %.4g, "
        "g(k,k) drift %.3g, E = %.12f\n",
        b, to_string(r.status).data(), r.final_state[1], r.accepted, inside_steps, kv_max, r.constraint_drift,
        ef.energy(r.final_state));
    EXPECT_EQ(r.status, RayStatus::captured) << "b = " << b;
    EXPECT_NEAR(r.final_state[1], ef.capture_radius() * (1.0 + s.horizon_epsilon), 1e-9);
    EXPECT_GT(inside_steps, 5) << "the ray must be integrated inside r = 2M, not stopped at it";
    EXPECT_TRUE(r.final_state.allFinite());
    EXPECT_LT(std::abs(r.constraint_drift), 1e-4);  // h = 0.01 fixed; worst near the photon sphere (b = 5)
    EXPECT_NEAR(ef.energy(r.final_state), 1.0, 1e-4);
  }
  // The radial ingoing ray has k^v = 0 (v is constant along it) and g(k, k) has no nonzero term at all, so the
  // tracer's relative constraint guard divides 0 by 0 and calls the first step non_finite: switch the guard off.
  TraceSettings radial = s;
  radial.constraint_tolerance = 0.0;
  const GeodesicTracer<AutoEddingtonFinkelstein, ClassicRK4, FixedStep> radial_tracer(AutoEddingtonFinkelstein{ef},
                                                                                      radial);
  const TraceResult rr = radial_tracer.trace(ef.from_schwarzschild(schwarzschild_photon(0.0)));
  EXPECT_EQ(rr.status, RayStatus::captured);
  EXPECT_NEAR(rr.final_state[0], ef.from_schwarzschild(schwarzschild_photon(0.0))[0], 1e-12);  // v unchanged
  EXPECT_EQ(tracer.trace(ef.from_schwarzschild(schwarzschild_photon(0.0))).status, RayStatus::non_finite);
  // The same ray in Schwarzschild coordinates never gets inside: k^t blows up at r = 2M.
  const GeodesicTracer<SchwarzschildMetric, ClassicRK4, FixedStep> schwarzschild(SchwarzschildMetric{}, s);
  const TraceResult rs = schwarzschild.trace(schwarzschild_photon(3.0));
  std::printf("Schwarzschild coordinates, b = 3: %s at r = %.6f\n", to_string(rs.status).data(), rs.final_state[1]);
  EXPECT_GE(rs.final_state[1], 2.0);
}

TEST(EddingtonFinkelstein, OutgoingChartTakesPastDirectedCameraRaysThroughTheHorizon) {
  // A camera's rays are traced backwards (k past-directed, DESIGN.md). Those that "hit the hole" cross the PAST
  // horizon, which the outgoing chart u = t - r* covers: the time reverse of the ingoing case.
  TraceSettings s;
  s.initial_step = 0.01;
  const EddingtonFinkelstein out{1.0, 0.5, true};
  const GeodesicTracer<AutoEddingtonFinkelstein, ClassicRK4, FixedStep> tracer(AutoEddingtonFinkelstein{out}, s);
  const GeodesicTracer<AutoEddingtonFinkelstein, ClassicRK4, FixedStep> ingoing(AutoEddingtonFinkelstein{}, s);
  for (double b : {0.5, 3.0}) {
    GeodesicState y = schwarzschild_photon(b);
    y.tail<4>() = -y.tail<4>();  // past-directed: k^t < 0 ...
    y[5] = -std::abs(y[5]);      // ... and still heading inwards, for the hole
    const TraceResult r = tracer.trace(out.from_schwarzschild(y));
    std::printf("outgoing EF, past-directed b = %.1f: %s at r = %.6f after %d steps, g(k,k) drift %.3g\n", b,
                to_string(r.status).data(), r.final_state[1], r.accepted, r.constraint_drift);
    EXPECT_EQ(r.status, RayStatus::captured) << "b = " << b;
    EXPECT_LT(r.final_state[1], 2.0);
    EXPECT_LT(std::abs(r.constraint_drift), 1e-4);
    // The ingoing chart cannot take the same past-directed ray through r = 2M (v -> -infinity there).
    const TraceResult ri = ingoing.trace(EddingtonFinkelstein{}.from_schwarzschild(y));
    std::printf("  ingoing EF, same ray: %s at r = %.6f\n", to_string(ri.status).data(), ri.final_state[1]);
    EXPECT_NE(ri.status, RayStatus::captured);
  }
}

}  // namespace
}  // namespace grtrace
