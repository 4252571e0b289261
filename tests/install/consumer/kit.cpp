// A user's own test suite with the installed testing component (find_package(grtrace COMPONENTS testing),
// target grtrace::testing): a metric written as components only, checked with the kit.
#include <grtrace/metric/auto_metric.hpp>
#include <grtrace/metric/schwarzschild.hpp>
#include <grtrace/testing.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <string_view>

namespace {

/// Reissner-Nordstrom written by "the user": g only.
struct MyCharged {
  static constexpr std::string_view name = "my-charged-hole";
  static constexpr grtrace::Chart chart = grtrace::Chart::spherical;
  double mass = 1.0, charge = 0.4;
  template <class S>
  Eigen::Matrix<S, 4, 4> metric_components(const Eigen::Matrix<S, 4, 1>& x) const {
    using std::sin;
    const S r = x[1], f = 1.0 - 2.0 * mass / r + charge * charge / (r * r), rs = r * sin(x[2]);
    return grtrace::diagonal_metric<S>(f, -1.0 / f, -r * r, -rs * rs);
  }
  double radius(const grtrace::Vec4& x) const { return x[1]; }
  double horizon_radius() const { return mass + std::sqrt(mass * mass - charge * charge); }
};

TEST(ConsumerKit, MyMetricPassesTheKit) {
  const grtrace::AutoMetric<MyCharged> m{};
  grtrace::testing::MetricCheckOptions o;
  o.flat_radius = 1e8;
  GRTRACE_EXPECT_VALID_METRIC(m,
                              {{"energy",
                                [](const grtrace::GeodesicState& y) {
                                  const double r = y[1];
                                  return (1.0 - 2.0 / r + 0.16 / (r * r)) * y[4];
                                }}},
                              o);
}

/// Schwarzschild's g, the reference for the hand-written SchwarzschildMetric's Christoffel symbols.
struct Components {
  static constexpr std::string_view name = "schwarzschild-components";
  static constexpr grtrace::Chart chart = grtrace::Chart::spherical;
  template <class S>
  Eigen::Matrix<S, 4, 4> metric_components(const Eigen::Matrix<S, 4, 1>& x) const {
    using std::sin;
    const S r = x[1], f = 1.0 - 2.0 / r, rs = r * sin(x[2]);
    return grtrace::diagonal_metric<S>(f, -1.0 / f, -r * r, -rs * rs);
  }
  double radius(const grtrace::Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 2.0; }
};

TEST(ConsumerKit, HandWrittenSchwarzschildMatchesItsDifferentiatedG) {
  const grtrace::SchwarzschildMetric closed{1.0};
  const auto points = grtrace::testing::sample_events(closed, {}, 20);
  EXPECT_TRUE(grtrace::testing::christoffel_matches(closed, Components{}, points));
}

}  // namespace
