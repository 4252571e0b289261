// tests/testing_kit_test.cpp
// Tests of the GoogleTest kit for metrics (grtrace/testing.hpp): it passes on every metric grtrace ships (the
// closed forms against their automatic twins, and the example metrics of metric/examples/), and it catches
// deliberately broken metrics with messages that name the component, the event and both values: a sign error in
// g, an asymmetric g, a degenerate g, a wrong Christoffel symbol, an acceleration that disagrees with its own
// Christoffel table, a wrong depends_on, a quantity that is not conserved, a metric that is not flat far away.
#include "grtrace/metric/auto_metric.hpp"
#include "grtrace/metric/examples/eddington_finkelstein.hpp"
#include "grtrace/metric/examples/ellis_wormhole.hpp"
#include "grtrace/metric/examples/minkowski_components.hpp"
#include "grtrace/metric/examples/reissner_nordstrom.hpp"
#include "grtrace/metric/examples/schwarzschild_components.hpp"
#include "grtrace/metric/examples/schwarzschild_de_sitter.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/testing.hpp"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace grtrace {
namespace {

namespace kit = grtrace::testing;

/// The usual conserved pair of a static, axisymmetric metric that has energy(y) and angular_momentum(y).
template <class M>
std::vector<kit::Conserved> energy_and_lz(const M& m) {
  return {{"energy E", [m](const GeodesicState& y) { return m.energy(y); }},
          {"angular momentum L_z", [m](const GeodesicState& y) { return m.angular_momentum(y); }}};
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
std::string message_of(const ::testing::AssertionResult& r) { return r.message(); }

// -----------------------------------------------------------------------------------------------------------
// The kit passes on every shipped metric

TEST(KitPasses, SchwarzschildMetricAgainstItsComponents) {
  const SchwarzschildMetric m{1.0};
  kit::MetricCheckOptions o;
  o.flat_radius = 1e8;  // g_tt - 1 = 2M / R = 2e-8
  auto q = energy_and_lz(m);
  q.push_back({"total angular momentum |L|", [m](const GeodesicState& y) { return m.total_angular_momentum(y); }});
  GRTRACE_EXPECT_VALID_METRIC(m, SchwarzschildComponents{1.0}, q, o);
}

TEST(KitPasses, MinkowskiCartesianAndSpherical) {
  kit::MetricCheckOptions o;
  o.flat_radius = 10.0;
  GRTRACE_EXPECT_VALID_METRIC(MinkowskiMetric{}, MinkowskiComponents{}, {}, o);
  GRTRACE_EXPECT_VALID_METRIC(MinkowskiSpherical{}, SchwarzschildComponents{0.0}, energy_and_lz(MinkowskiSpherical{}),
                              o);
  GRTRACE_EXPECT_VALID_METRIC(AutoMinkowski{}, {}, o);
}

TEST(KitPasses, EveryExampleMetric) {
  kit::MetricCheckOptions o;
  o.flat_radius = 1e8;
  GRTRACE_EXPECT_VALID_METRIC(AutoSchwarzschild{}, energy_and_lz(AutoSchwarzschild{}), o);
  GRTRACE_EXPECT_VALID_METRIC(AutoReissnerNordstrom{{1.0, 0.7}}, energy_and_lz(AutoReissnerNordstrom{{1.0, 0.7}}), o);
  GRTRACE_EXPECT_VALID_METRIC(AutoEllisWormhole{{1.0}}, energy_and_lz(AutoEllisWormhole{{1.0}}), o);
  // Eddington-Finkelstein: flat far away means flat space in EF coordinates (the same chart with M = 0).
  const AutoEddingtonFinkelstein ef{};
  GRTRACE_EXPECT_VALID_METRIC(ef, energy_and_lz(ef));
  EXPECT_TRUE(kit::approaches_flat(ef, 1e8, 1e-6, AutoEddingtonFinkelstein{{0.0}}));
  // Schwarzschild-de Sitter is not flat far away (checked below); its rays must stay inside r_c = 171.7.
  kit::MetricCheckOptions sds;
  sds.points = {2.2, 150.0};
  sds.rays = {6.0, 60.0};
  sds.escape_radius = 150.0;
  const AutoSchwarzschildDeSitter dS{{1.0, 1e-4}};
  GRTRACE_EXPECT_VALID_METRIC(dS, energy_and_lz(dS), sds);
}

TEST(KitPasses, WormholeRaysFromBothSides) {
  kit::MetricCheckOptions o;
  o.rays = {-15.0, 15.0};
  const AutoEllisWormhole w{{2.0}};
  EXPECT_TRUE(kit::conserved_along_null_geodesics(w, energy_and_lz(w), o));
}

TEST(KitPasses, EddingtonFinkelsteinInsideTheHorizon) {
  // Pointwise checks where Schwarzschild coordinates fail: 1 < r < 2M is regular in EF.
  const AutoEddingtonFinkelstein ef{};
  const auto inside = kit::sample_events(ef, {1.05, 1.95}, 20);
  EXPECT_TRUE(kit::metric_is_lorentzian(ef, inside));
  EXPECT_TRUE(kit::inverse_is_consistent(ef, inside));
  EXPECT_TRUE(kit::christoffel_consistent(ef, inside));
}

// -----------------------------------------------------------------------------------------------------------
// Broken metrics, caught with precise messages

/// Schwarzschild with the classic typo: g_rr = +1/f.
struct SignError {
  static constexpr std::string_view name = "schwarzschild-sign-error";
  static constexpr Chart chart = Chart::spherical;
  template <class S>
  Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S r = x[1], f = 1.0 - 2.0 / r, rs = r * sin(x[2]);
    return diagonal_metric<S>(f, 1.0 / f, -r * r, -rs * rs);
  }
  double radius(const Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 2.0; }
};

TEST(KitCatches, ASignErrorInG) {
  const AutoMetric<SignError> m{};
  const std::vector<Vec4> at = {Vec4(0.0, 10.0, 1.0, 0.5)};
  const auto r = kit::metric_is_lorentzian(m, at);
  EXPECT_FALSE(r);
  const std::string msg = message_of(r);
  EXPECT_TRUE(contains(msg, "schwarzschild-sign-error: g is not Lorentzian (+,-,-,-) at x = (0, 10, 1, 0.5)")) << msg;
  EXPECT_TRUE(contains(msg, "(2 positive, 2 negative, 0 zero)")) << msg;
  EXPECT_TRUE(contains(msg, "g_{r r} = g(1, 1) = 1.25 should be negative")) << msg;
  EXPECT_NONFATAL_FAILURE(EXPECT_TRUE(kit::metric_is_lorentzian(m, at)), "g_{r r} = g(1, 1) = 1.25 should be negative");
}

/// g_tr written in one triangle only.
struct Asymmetric {
  static constexpr std::string_view name = "asymmetric";
  static constexpr Chart chart = Chart::spherical;
  template <class S>
  Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S r = x[1], rs = r * sin(x[2]);
    Mat4Of<S> g = diagonal_metric<S>(S(1.0), S(-1.0), -r * r, -rs * rs);
    g(0, 1) = S(0.25);
    return g;
  }
  double radius(const Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 0.0; }
};

TEST(KitCatches, AnAsymmetricG) {
  const std::vector<Vec4> at = {Vec4(1.0, 3.0, 1.0, 0.0)};
  const auto r = kit::metric_is_symmetric(AutoMetric<Asymmetric>{}, at);
  EXPECT_EQ(message_of(r),
            "asymmetric: g is not symmetric at x = (1, 3, 1, 0): g_{t r} = g(0, 1) is 0.25 but g_{r t} = g(1, 0) is 0 "
            "(difference 0.25 > 1e-12 of the largest component 9)");
}

/// g_thth forgotten (zero): degenerate.
struct Degenerate {
  static constexpr std::string_view name = "degenerate";
  static constexpr Chart chart = Chart::spherical;
  template <class S>
  Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S rs = x[1] * sin(x[2]);
    return diagonal_metric<S>(S(1.0), S(-1.0), S(0.0), -rs * rs);
  }
  double radius(const Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 0.0; }
};

TEST(KitCatches, ADegenerateG) {
  const AutoMetric<Degenerate> m{};
  const std::vector<Vec4> at = {Vec4(0.0, 2.0, 1.0, 0.0)};
  EXPECT_NONFATAL_FAILURE(EXPECT_TRUE(kit::metric_is_lorentzian(m, at)), "(1 positive, 2 negative, 1 zero)");
  const std::string msg = message_of(kit::inverse_is_consistent(m, at));
  EXPECT_TRUE(contains(msg, "degenerate: g g^-1 is not the identity at x = (0, 2, 1, 0)")) << msg;
  EXPECT_TRUE(contains(msg, "det g = 0, inverse from inverse_metric()")) << msg;
}

/// A hand-written Schwarzschild with a sign typo in Gamma^theta_phiphi, made consistently in christoffel() and
/// acceleration() (so only the comparison with the differentiated g sees it).
struct WrongChristoffel : SchwarzschildMetric {
  static constexpr std::string_view name = "schwarzschild-typo";
  Christoffel christoffel(const Vec4& x) const {
    Christoffel G = SchwarzschildMetric::christoffel(x);
    G[2](3, 3) = -G[2](3, 3);
    return G;
  }
  Vec4 acceleration(const Vec4& x, const Vec4& k) const {
    Vec4 a = SchwarzschildMetric::acceleration(x, k);
    a[2] -= 2.0 * std::sin(x[2]) * std::cos(x[2]) * k[3] * k[3];
    return a;
  }
};
static_assert(MetricPolicy<WrongChristoffel>);

TEST(KitCatches, AWrongChristoffelSymbol) {
  const WrongChristoffel m{};
  const std::vector<Vec4> at = {Vec4(0.0, 6.0, 1.0, 0.0)};
  EXPECT_TRUE(kit::christoffel_consistent(m, at));  // the typo is self-consistent
  const auto r = kit::christoffel_matches(m, SchwarzschildComponents{1.0}, at);
  const double s = std::sin(1.0) * std::cos(1.0);
  EXPECT_EQ(message_of(r),
            "schwarzschild-typo: Gamma^theta_{phi phi} = Gamma[2](3, 3) at x = (0, 6, 1, 0): "
            "christoffel() gives " +
                kit::detail::num(s) + " but differentiating the reference g gives " + kit::detail::num(-s) +
                " (relative difference 2 > 1e-11)");
  EXPECT_NONFATAL_FAILURE(EXPECT_TRUE(kit::christoffel_matches(m, SchwarzschildComponents{1.0}, at)),
                          "Gamma^theta_{phi phi} = Gamma[2](3, 3)");
}

/// acceleration() with a factor 2 missing in the phi equation (christoffel() is right).
struct WrongAcceleration : SchwarzschildMetric {
  static constexpr std::string_view name = "schwarzschild-acceleration-typo";
  Vec4 acceleration(const Vec4& x, const Vec4& k) const {
    Vec4 a = SchwarzschildMetric::acceleration(x, k);
    a[3] += k[1] * k[3] / x[1];  // -2/r k^r k^phi became -1/r k^r k^phi
    return a;
  }
};

TEST(KitCatches, AnAccelerationThatDisagreesWithItsChristoffels) {
  const WrongAcceleration m{};
  const std::vector<Vec4> at = kit::sample_events(m, {}, 5);
  const std::string msg = message_of(kit::christoffel_consistent(m, at));
  EXPECT_TRUE(contains(msg, "schwarzschild-acceleration-typo: acceleration^phi = acceleration(x, k)[3] at x = ("))
      << msg;
  EXPECT_TRUE(contains(msg, "-Gamma^phi_ab k^a k^b from christoffel() gives")) << msg;
  // Along rays the typo breaks L_z, and the conservation check names it.
  EXPECT_NONFATAL_FAILURE(EXPECT_TRUE(kit::conserved_along_null_geodesics(m, energy_and_lz(m))),
                          "angular momentum L_z not conserved along the null geodesic 1 from x = (");
}

/// SchwarzschildComponents claiming g depends on r only (theta forgotten).
struct WrongDependsOn : SchwarzschildComponents {
  static constexpr std::string_view name = "schwarzschild-depends-on-r-only";
  static constexpr std::array<int, 1> depends_on = {1};
};

TEST(KitCatches, AWrongDependsOn) {
  const AutoMetric<WrongDependsOn> m{};
  const std::vector<Vec4> at = {Vec4(0.0, 5.0, 1.0, 0.0)};
  EXPECT_NONFATAL_FAILURE(
      EXPECT_TRUE(kit::christoffel_consistent(m, at)),
      "schwarzschild-depends-on-r-only: acceleration^theta = acceleration(x, k)[2] at x = (0, 5, 1, 0)");
}

TEST(KitCatches, AQuantityThatIsNotConserved) {
  const SchwarzschildMetric m{};
  std::vector<kit::Conserved> q = energy_and_lz(m);
  EXPECT_TRUE(kit::conserved_along_null_geodesics(m, q));
  q.push_back({"k^t", [](const GeodesicState& y) { return y[4]; }});
  const auto r = kit::conserved_along_null_geodesics(m, q);
  const std::string msg = message_of(r);
  EXPECT_TRUE(contains(msg, "schwarzschild: k^t not conserved along the null geodesic 1 from x = (")) << msg;
  EXPECT_TRUE(contains(msg, " at the start, ")) << msg;
  EXPECT_TRUE(contains(msg, "|change| / (1 + |start|) = ")) << msg;
  EXPECT_NONFATAL_FAILURE(EXPECT_TRUE(kit::conserved_along_null_geodesics(m, q)), "k^t not conserved");
}

TEST(KitCatches, AMetricThatIsNotFlatFarAway) {
  const AutoSchwarzschildDeSitter m{{1.0, 1e-4}};
  const auto r = kit::approaches_flat(m, 100.0, 1e-6);
  // g_tt = 1 - 2/100 - 1e-4 * 100^2 / 3 = 0.64666...
  EXPECT_TRUE(contains(message_of(r),
                       "schwarzschild-de-sitter: not flat at radius 100: g_{t t} = g(0, 0) at "
                       "x = (0, 100, 0.4, 0.1) is 0.6466666667 but flat space (minkowski-spherical) "
                       "has 1"))
      << message_of(r);
}

// The whole-metric wrapper reports one failure per failed check, each with the caller's line in the trace.
TEST(KitCatches, TheWrapperReportsEachFailedCheckOnce) {
  ::testing::TestPartResultArray results;
  {
    const ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    const WrongChristoffel m{};
    GRTRACE_EXPECT_VALID_METRIC(m, SchwarzschildComponents{1.0}, energy_and_lz(m));
  }
  std::vector<std::string> messages;
  for (int i = 0; i < results.size(); ++i) messages.emplace_back(results.GetTestPartResult(i).message());
  for (const auto& msg : messages) std::printf("kit says: %s\n\n", msg.c_str());
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_TRUE(contains(messages[0], "schwarzschild-typo: ")) << messages[0];
  EXPECT_TRUE(contains(messages[0], " not conserved along the null geodesic")) << messages[0];
  EXPECT_TRUE(contains(messages[1], "Gamma^theta_{phi phi} = Gamma[2](3, 3)")) << messages[1];
  EXPECT_TRUE(contains(messages[1], "GRTRACE_EXPECT_VALID_METRIC(m, SchwarzschildComponents{1.0}, energy_and_lz(m))"))
      << messages[1];
}

// Fatal use: ASSERT_TRUE on a kit check inside a helper (EXPECT_FATAL_FAILURE's statement cannot see locals).
void assert_sign_error_is_lorentzian() {
  ASSERT_TRUE(kit::metric_is_lorentzian(AutoMetric<SignError>{}, {Vec4(0.0, 10.0, 1.0, 0.5)}));
}
TEST(KitCatches, WorksWithAssertAndExpectFatalFailure) {
  EXPECT_FATAL_FAILURE(assert_sign_error_is_lorentzian(), "g_{r r} = g(1, 1) = 1.25 should be negative");
}

}  // namespace
}  // namespace grtrace
