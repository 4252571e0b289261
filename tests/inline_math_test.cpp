// tests/inline_math_test.cpp
// The library's inline replacements for libm calls on the per-pixel path, against the standard library: floor and
// round (core/rounding.hpp) exactly; azimuth_in_range (core/sky_direction.hpp); mul_add (core/mul_add.hpp), which
// must round once exactly when the build says it has the fused instruction, and exactly as a * b + c otherwise; and
// the step controllers' inverse_root (core/inverse_root.hpp) within 4 ulp of long double, std::pow's answer off its
// domain; and the one golden-section search (core/golden_section.hpp).
#include "grtrace/core/golden_section.hpp"
#include "grtrace/core/inverse_root.hpp"
#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/rounding.hpp"
#include "grtrace/core/sky_direction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

/// x^(-1/K) for every K the controllers can ask for, on a million positive normal x spread over the exponent range
/// (each residue of the exponent modulo K and every mantissa table cell are met), against long double's powl.
template <int K>
double worst_inverse_root_ulps() {
  std::mt19937_64 rng(K);
  std::uniform_real_distribution<double> exponent(-1000.0, 1000.0), mantissa(1.0, 2.0);
  double worst = 0.0;
  for (int i = 0; i < 1000000 / 16; ++i) {
    const double x = std::ldexp(mantissa(rng), static_cast<int>(exponent(rng)));
    const long double exact = std::pow(static_cast<long double>(x), -1.0L / K);
    const double nearest = static_cast<double>(exact);
    const double ulp = std::nextafter(nearest, std::numeric_limits<double>::infinity()) - nearest;
    worst = std::max(worst, static_cast<double>(std::abs(inverse_root<K>(x) - exact) / ulp));
  }
  return worst;
}

TEST(InverseRoot, WithinFourUlpOfLongDoubleForEveryExponent) {
  const double worst[] = {worst_inverse_root_ulps<2>(),  worst_inverse_root_ulps<3>(),  worst_inverse_root_ulps<4>(),
                          worst_inverse_root_ulps<5>(),  worst_inverse_root_ulps<6>(),  worst_inverse_root_ulps<7>(),
                          worst_inverse_root_ulps<8>(),  worst_inverse_root_ulps<9>(),  worst_inverse_root_ulps<10>(),
                          worst_inverse_root_ulps<11>(), worst_inverse_root_ulps<12>(), worst_inverse_root_ulps<13>(),
                          worst_inverse_root_ulps<14>(), worst_inverse_root_ulps<15>(), worst_inverse_root_ulps<16>()};
  for (int k = 2; k <= 16; ++k) EXPECT_LT(worst[k - 2], 4.0) << "k = " << k;
  // The extremes of the domain and exact powers: 2^-10 -> 2^2 (k = 5), 2^16 -> 2^-2 (k = 8).
  EXPECT_NEAR(inverse_root<5>(std::ldexp(1.0, -10)), 4.0, 4 * std::numeric_limits<double>::epsilon() * 4.0);
  EXPECT_NEAR(inverse_root<8>(65536.0), 0.25, 4 * std::numeric_limits<double>::epsilon() * 0.25);
  const double smallest = std::numeric_limits<double>::min(), largest = std::numeric_limits<double>::max();
  EXPECT_NEAR(inverse_root<5>(smallest), std::pow(smallest, -0.2), 1e-14 * std::pow(smallest, -0.2));
  EXPECT_NEAR(inverse_root<9>(largest), std::pow(largest, -1.0 / 9), 1e-14 * std::pow(largest, -1.0 / 9));
}

TEST(InverseRoot, OffItsDomainItIsStdPow) {
  const double inf = std::numeric_limits<double>::infinity();
  for (const double x : {0.0, -0.0, 1e-310, inf, -1.0}) {
    const double expected = std::pow(x, -1.0 / 5);
    const double got = inverse_root<5>(x);
    if (std::isnan(expected)) {
      EXPECT_TRUE(std::isnan(got)) << x;
    } else {
      EXPECT_EQ(got, expected) << x;
    }
  }
  EXPECT_TRUE(std::isnan(inverse_root<5>(std::numeric_limits<double>::quiet_NaN())));
  // The run-time form: the compile-time root for k = 2..16, std::pow beyond.
  EXPECT_EQ(inverse_root(0.3, 8), inverse_root<8>(0.3));
  EXPECT_EQ(inverse_root(0.3, 17), std::pow(0.3, -1.0 / 17));
}

}  // namespace

namespace {

TEST(GoldenSection, FindsTheExtremumWithOneEvaluationAStepAndAvoidsWhereFIsNaN) {
  // (x - 0.3)^2 + 1 on [0, 2]: the minimum to the square root of the rounding (the function is flat there), the
  // bracket 0.618 times narrower for each evaluation.
  int evaluations = 0;
  const GoldenSection m = golden_section_minimum(
      [&](double x) {
        ++evaluations;
        return (x - 0.3) * (x - 0.3) + 1.0;
      },
      0.0, 2.0, {0.0, 1e-6});
  EXPECT_FALSE(m.stopped);
  EXPECT_NEAR(m.x, 0.3, 1e-6);
  EXPECT_LE(evaluations,
            2 + static_cast<int>(std::ceil(std::log(1e-6 / 2.0) / std::log(0.5 * (std::sqrt(5.0) - 1.0)))));
  // No value below 0.5 (a horizon, say): the search moves away from there and finds the minimum at 1.
  const GoldenSection away = golden_section_minimum(
      [](double x) { return x < 0.5 ? std::numeric_limits<double>::quiet_NaN() : (x - 1.0) * (x - 1.0); }, 0.0, 3.0,
      {1e-12, 0.0});
  EXPECT_NEAR(away.x, 1.0, 1e-7);
  // Towards a maximum, stopping at the first probe above 0.99: that probe, and f there.
  const GoldenSection found = golden_section_maximum([](double x) { return 1.0 - (x - 0.7) * (x - 0.7); }, 0.0, 1.0,
                                                     {0.0, 1e-12}, 60, [](double, double v) { return v > 0.99; });
  ASSERT_TRUE(found.stopped);
  EXPECT_GT(found.value, 0.99);
  EXPECT_EQ(found.value, 1.0 - (found.x - 0.7) * (found.x - 0.7));
}

}  // namespace
