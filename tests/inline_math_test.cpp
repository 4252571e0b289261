// tests/inline_math_test.cpp
// The library's inline replacements for libm calls on the per-pixel path, against the standard library: floor and
// round (core/rounding.hpp) exactly; azimuth_in_range (core/sky_direction.hpp); and mul_add (core/mul_add.hpp), which
// must round once exactly when the build says it has the fused instruction, and exactly as a * b + c otherwise.
#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/rounding.hpp"
#include "grtrace/core/sky_direction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace {

using namespace grtrace;

TEST(Rounding, FloorAndRoundAgreeWithTheStandardLibrary) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> wide(-1e6, 1e6), unit(0.0, 1.0);
  std::vector<double> xs = {0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 1.5, 2.5, -2.5, 1e-300, -1e-300, 4503599627370495.5,
                            -4503599627370495.5, 9007199254740993.0, std::nextafter(1.0, 0.0), std::nextafter(-1.0, 0.0)};
  for (int i = 0; i < 100000; ++i) xs.push_back(i % 2 ? wide(rng) : unit(rng) * 7.0 - 3.0);
  for (const double x : xs) {
    EXPECT_EQ(floor_to_long(x), static_cast<long>(std::floor(x))) << x;
    if (x >= 0.0) {
      EXPECT_EQ(round_nonnegative_to_long(x), std::lround(x)) << x;
    }
  }
}

TEST(MulAdd, RoundsOnceWhereTheBuildFusesAndLikeTheExpressionElsewhere) {
  // (1 + 2^-30)(1 - 2^-30) - 1 = -2^-60 exactly; the product alone rounds to 1, so a * b + c gives 0.
  const double eps = std::ldexp(1.0, -30);
  volatile double a = 1.0 + eps, b = 1.0 - eps, c = -1.0;  // volatile: no folding at compile time
  const double fused = mul_add(a, b, c);
  if (fused_mul_add) {
    EXPECT_EQ(fused, -std::ldexp(1.0, -60));
  } else {
    EXPECT_EQ(fused, 0.0);
  }
  // Either way, as accurate as the two-rounding expression on ordinary arguments, and the same on exact ones.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  for (int i = 0; i < 10000; ++i) {
    const double x = u(rng), y = u(rng), z = u(rng);
    const long double exact = static_cast<long double>(x) * y + z;
    const double plain = x * y + z;
    // "exact" is itself rounded to long double's 64 bits: allow 1e-18 of the terms' size for that.
    const long double slack = 1e-18L * (std::abs(static_cast<long double>(x) * y) + std::abs(z));
    EXPECT_LE(std::abs(static_cast<long double>(mul_add(x, y, z)) - exact),
              std::abs(static_cast<long double>(plain) - exact) + slack)
        << x << " " << y << " " << z;
  }
  EXPECT_EQ(mul_add(3.0, 4.0, 5.0), 17.0);
}

TEST(AzimuthInRange, BringsAnyAngleIntoMinusPiPi) {
  constexpr double pi = std::numbers::pi;
  EXPECT_EQ(azimuth_in_range(-pi), pi);
  EXPECT_EQ(azimuth_in_range(pi), pi);
  EXPECT_EQ(azimuth_in_range(0.25), 0.25);
  EXPECT_EQ(azimuth_in_range(-3.0 * pi), pi);
  for (const double phi : {0.3, -2.9, 3.1, 1.5 * pi, -1.7 * pi, 40.0, -40.0, 7.5 * pi, 1e6}) {
    const double a = azimuth_in_range(phi);
    EXPECT_GT(a, -pi) << phi;
    EXPECT_LE(a, pi) << phi;
    EXPECT_NEAR(std::remainder(a - phi, 2.0 * pi), 0.0, 1e-12 * std::max(1.0, std::abs(phi))) << phi;
  }
  // Within one turn of the range the result is the exact difference (Sterbenz): the same as std::remainder.
  for (const double phi : {1.5 * pi, -1.5 * pi, 2.9 * pi, -2.9 * pi})
    EXPECT_EQ(azimuth_in_range(phi), std::remainder(phi, 2.0 * pi)) << phi;
}

}  // namespace
