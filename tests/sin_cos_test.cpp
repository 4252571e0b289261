// tests/sin_cos_test.cpp
// core/sin_cos.hpp (the metrics' inline sincos) against long double sinl/cosl: below 1 ulp over the polar angles
// a ray meets and far beyond, exact at the special points, libm's answer for NaN, infinities and huge arguments;
// polar_sin_cos within 2 ulp on its own path ([0, pi] but within 2^-16 of pi/2 and of pi: the short path taken in
// each of its three ranges) and sin_cos's bits everywhere else.
#include "grtrace/core/sin_cos.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
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

constexpr long double pi_l = 3.141592653589793238462643383279502884L;

/// Where polar_sin_cos must take its short path (1), must hand over to sin_cos (0), or may do either (-1: theta
/// within 1e-15 of a hand-over at 2^-16 from pi/2 or pi, where the rounding of the reduced argument decides).
int expected_path(double theta) {
  if (std::isnan(theta) || std::signbit(theta) || theta > std::numbers::pi) return 0;
  const long double from_half_pi = std::abs(static_cast<long double>(theta) - pi_l / 2);
  const long double from_pi = pi_l - static_cast<long double>(theta);
  const long double d = theta > 2.3 ? from_pi : theta > 0.8 ? from_half_pi : 1.0L;
  if (std::abs(d - 0x1p-16L) < 1e-15L) return -1;
  return d >= 0x1p-16L ? 1 : 0;
}

/// Checks polar_sin_cos(theta) against long double (every theta in [0, pi]: both paths are within 2 ulp) and
/// against sin_cos's bits where the short path must not be taken; counts per range (0: [0, pi/4), 1: [pi/4, 3pi/4],
/// 2: (3pi/4, pi]) where the result is not sin_cos's bits, which shows the short path taken there (its polynomials,
/// without the tail, differ from sin_cos in some last bits).
struct PolarChecker {
  double worst = 0.0;
  double worst_theta = 0.0;
  std::array<int, 3> short_path{};
  int off_path_mismatches = 0;
  int fast_expected_but_sin_cos = 0;
  void operator()(double theta) {
    const grtrace::SinCos sc = polar_sin_cos(theta), reference = sin_cos(theta);
    const bool is_sin_cos = std::bit_cast<std::uint64_t>(sc.sin) == std::bit_cast<std::uint64_t>(reference.sin) &&
                            std::bit_cast<std::uint64_t>(sc.cos) == std::bit_cast<std::uint64_t>(reference.cos);
    const int path = expected_path(theta);
    if (theta >= 0.0 && theta <= std::numbers::pi) {
      const long double tl = theta;
      const double e = std::max(ulps(sc.sin, std::sin(tl)), ulps(sc.cos, std::cos(tl)));
      if (e > worst) {
        worst = e;
        worst_theta = theta;
      }
    }
    if (path == 0) off_path_mismatches += !is_sin_cos;
    if (path == 1 && !is_sin_cos) {
      ++short_path[theta < std::numbers::pi / 4 ? 0 : theta <= 3 * std::numbers::pi / 4 ? 1 : 2];
    }
  }
};

// The short path: random theta in [0, pi], and grids of step 1e-9 (and of single ulps) through 0, pi/4, pi/2,
// 3pi/4, pi and the hand-overs to sin_cos at 2^-16 from pi/2 and from pi; within 2 ulp of long double everywhere in
// [0, pi], sin_cos's bits where the short path must hand over, and the short path taken in each of the three ranges.
TEST(PolarSinCos, WithinTwoUlpOnZeroToPi) {
  constexpr double pi = std::numbers::pi;
  std::mt19937_64 gen(12);
  std::uniform_real_distribution<double> dist(0.0, pi);
  PolarChecker check;
  for (int i = 0; i < 600000; ++i) check(dist(gen));
  for (const double center : {0.0, pi / 4, pi / 2, 3 * pi / 4, pi, pi / 2 - 0x1p-16, pi / 2 + 0x1p-16, pi - 0x1p-16}) {
    for (int i = -20000; i <= 20000; ++i) check(center + i * 1e-9);
    double up = center, down = center;
    for (int i = 0; i < 200; ++i) {
      check(up = std::nextafter(up, 4.0));
      check(down = std::nextafter(down, -1.0));
    }
  }
  EXPECT_LT(check.worst, 2.0) << "at theta = " << check.worst_theta;
  RecordProperty("worst_ulp", std::to_string(check.worst));
  EXPECT_EQ(check.off_path_mismatches, 0) << "within 2^-16 of pi/2 or pi, or outside [0, pi]: not sin_cos's bits";
  for (std::size_t range = 0; range < 3; ++range) {
    EXPECT_GT(check.short_path[range], 10000)
        << "range " << range << ": the short path was not taken: the test would only check sin_cos";
  }
}

// Near 0 the reduced argument is theta itself: no hand-over, and exact where sin theta rounds to theta.
TEST(PolarSinCos, ExactAtZeroAndForTinyAngles) {
  const grtrace::SinCos zero = polar_sin_cos(0.0);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(zero.sin), 0U) << "sin 0 must be +0";
  EXPECT_EQ(zero.cos, 1.0);
  for (const double t : {std::numeric_limits<double>::denorm_min(), 1e-310, std::numeric_limits<double>::min(),
                         1e-300, 1e-200, 1e-20, 0x1p-30}) {
    EXPECT_EQ(polar_sin_cos(t).sin, t) << t;
    EXPECT_EQ(polar_sin_cos(t).cos, 1.0) << t;
  }
  EXPECT_EQ(polar_sin_cos(1e-8).cos, 1.0 - 0.5e-16) << "cos 1e-8 = 1 - 5e-17 rounds down";
}

// Within 2^-16 of pi/2 and of pi, outside [0, pi] (-0.0 included), NaN and infinities: sin_cos's bits.
TEST(PolarSinCos, IsSinCosOffItsPath) {
  constexpr double pi = std::numbers::pi;
  const double inf = std::numeric_limits<double>::infinity();
  for (const double x : {pi / 2, pi / 2 + 1e-6, pi / 2 - 1e-6, pi / 2 + 0x1p-17, pi / 2 - 0x1.fffp-17, pi,
                         std::nextafter(pi, 0.0), pi - 1e-6, pi - 0x1.fffp-17, pi + 1e-9, 3.5, 7.0, -0.0, -1e-300,
                         -std::numeric_limits<double>::denorm_min(), -0.3, -1.0, 1e6}) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(polar_sin_cos(x).sin), std::bit_cast<std::uint64_t>(sin_cos(x).sin)) << x;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(polar_sin_cos(x).cos), std::bit_cast<std::uint64_t>(sin_cos(x).cos)) << x;
  }
  EXPECT_TRUE(std::signbit(polar_sin_cos(-0.0).sin));
  EXPECT_EQ(polar_sin_cos(pi / 2).sin, 1.0);
  EXPECT_EQ(polar_sin_cos(pi).cos, -1.0);
  for (const double x : {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::quiet_NaN(), inf,
                         -inf}) {
    EXPECT_TRUE(std::isnan(polar_sin_cos(x).sin)) << x;
    EXPECT_TRUE(std::isnan(polar_sin_cos(x).cos)) << x;
  }
}

}  // namespace
