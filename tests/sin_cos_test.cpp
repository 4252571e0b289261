// tests/sin_cos_test.cpp
// core/sin_cos.hpp (the metrics' inline sincos) against long double sinl/cosl: below 1 ulp over the polar angles
// a ray meets and far beyond, exact at the special points, libm's answer for NaN, infinities and huge arguments;
// polar_sin_cos within 2 ulp on its own path ([pi/4, 3pi/4]) and sin_cos's bits everywhere else.
#include "grtrace/core/sin_cos.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

namespace {

using grtrace::polar_sin_cos;
using grtrace::sin_cos;

/// |v - ref| in units of the last place of the double nearest to ref.
double ulps(double v, long double ref) {
  const double r = static_cast<double>(ref);
  const double ulp = std::nextafter(std::abs(r), std::numeric_limits<double>::infinity()) - std::abs(r);
  return static_cast<double>(std::abs(static_cast<long double>(v) - ref) / static_cast<long double>(ulp));
}

TEST(SinCos, BelowOneUlpAgainstLongDouble) {
  std::mt19937_64 gen(11);
  for (const double limit : {0.8, 4.0, 10.0, 1e3, 8e5}) {
    std::uniform_real_distribution<double> dist(-limit, limit);
    double worst = 0.0;
    for (int i = 0; i < 200000; ++i) {
      const double x = dist(gen);
      const auto sc = sin_cos(x);
      const long double xl = x;
      worst = std::max({worst, ulps(sc.sin, std::sin(xl)), ulps(sc.cos, std::cos(xl))});
    }
    EXPECT_LT(worst, 1.0) << "|x| < " << limit;
  }
}

TEST(SinCos, SpecialPoints) {
  constexpr double pi = std::numbers::pi;
  EXPECT_EQ(sin_cos(0.0).sin, 0.0);
  EXPECT_EQ(sin_cos(0.0).cos, 1.0);
  EXPECT_TRUE(std::signbit(sin_cos(-0.0).sin));
  EXPECT_EQ(sin_cos(1e-300).sin, 1e-300);
  EXPECT_EQ(sin_cos(pi / 2).sin, 1.0);
  EXPECT_EQ(sin_cos(pi).cos, -1.0);
  EXPECT_EQ(sin_cos(pi).sin, std::sin(pi));  // 1.2246e-16: the distance of the double pi from pi
  for (const double x : {pi / 4, pi / 2, 3 * pi / 4, pi, 1.5 * pi, 2 * pi, -pi / 3}) {
    EXPECT_NEAR(sin_cos(x).sin, std::sin(x), 1e-16) << x;
    EXPECT_NEAR(sin_cos(x).cos, std::cos(x), 1e-16) << x;
  }
}

TEST(SinCos, NonFiniteAndHugeArgumentsAreLibms) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const double x : {std::numeric_limits<double>::quiet_NaN(), inf, -inf}) {
    EXPECT_TRUE(std::isnan(sin_cos(x).sin));
    EXPECT_TRUE(std::isnan(sin_cos(x).cos));
  }
  for (const double x : {1e6, -3e7, 1e300}) {
    EXPECT_EQ(sin_cos(x).sin, std::sin(x));
    EXPECT_EQ(sin_cos(x).cos, std::cos(x));
  }
}

// The short path for polar angles: every theta in [pi/4, 3pi/4] (random, and a fine grid up to the ends and
// through pi/2, where it hands over to sin_cos within 2^-16), within 2 ulp of long double.
TEST(PolarSinCos, WithinTwoUlpBetweenAQuarterAndThreeQuartersOfPi) {
  constexpr double pi = std::numbers::pi;
  std::mt19937_64 gen(12);
  std::uniform_real_distribution<double> dist(pi / 4, 3 * pi / 4);
  double worst = 0.0;
  int short_path = 0;
  const auto check = [&](double theta) {
    const auto sc = polar_sin_cos(theta);
    const long double tl = theta;
    worst = std::max({worst, ulps(sc.sin, std::sin(tl)), ulps(sc.cos, std::cos(tl))});
    const auto reference = sin_cos(theta);
    short_path += sc.sin != reference.sin || sc.cos != reference.cos;
  };
  for (int i = 0; i < 400000; ++i) check(dist(gen));
  for (int i = -20000; i <= 20000; ++i) {
    check(pi / 2 + i * 1e-9);          // through the hand-over at |theta - pi/2| = 2^-16 ~ 1.5e-5
    check(pi / 4 + std::abs(i) * 1e-9);
    check(3 * pi / 4 - std::abs(i) * 1e-9);
  }
  EXPECT_LT(worst, 2.0);
  RecordProperty("worst_ulp", std::to_string(worst));
  EXPECT_GT(short_path, 100000) << "the short path was not taken: the test would only check sin_cos";
}

// Outside [pi/4, 3pi/4], at pi/2 within 2^-16, and for NaN, infinities and negative angles: sin_cos's bits.
TEST(PolarSinCos, IsSinCosOffItsPath) {
  constexpr double pi = std::numbers::pi;
  const double inf = std::numeric_limits<double>::infinity();
  for (const double x : {0.0, 0.3, pi / 4 - 1e-9, 3 * pi / 4 + 1e-9, 2.9, pi, -1.0, 7.0, pi / 2, pi / 2 + 1e-6, 1e6}) {
    EXPECT_EQ(polar_sin_cos(x).sin, sin_cos(x).sin) << x;
    EXPECT_EQ(polar_sin_cos(x).cos, sin_cos(x).cos) << x;
  }
  EXPECT_EQ(polar_sin_cos(pi / 2).sin, 1.0);
  for (const double x : {std::numeric_limits<double>::quiet_NaN(), inf, -inf}) {
    EXPECT_TRUE(std::isnan(polar_sin_cos(x).sin)) << x;
    EXPECT_TRUE(std::isnan(polar_sin_cos(x).cos)) << x;
  }
}

}  // namespace
