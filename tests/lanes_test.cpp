// tests/lanes_test.cpp
// core/lanes.hpp and the lane versions built on it: each lane must be the scalar function's bits, not merely close
// (a batched ray is promised to be the ray integrated alone), so every comparison is of bit patterns.
//   mul_add on Lanes<W> rounds as the scalar mul_add: once where the build fuses, twice elsewhere (a value where the
//   two differ shows which happened); loads, stores, splat, halves and joined, and the mask reductions.
//   polar_sin_cos on Lanes<W> (core/sin_cos.hpp) against the scalar polar_sin_cos, W = 2, 4, 8: random angles in
//   (0, pi) (lanes in all three of its ranges), and batches that mix lanes on and off the short path (its range
//   ends near pi/4 and 3pi/4, within 2^-16 of pi/2 and of pi and just outside, 0, -0, tiny and denormal angles,
//   beyond [0, pi], NaN, infinities).
//   SchwarzschildMetric::acceleration_lanes<W> against acceleration() per lane on random states with theta across
//   (0, pi), mixed batches included; and the trait HasLaneAcceleration.
#include "grtrace/core/lanes.hpp"
#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/sin_cos.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace grtrace {
namespace {

constexpr double pi = std::numbers::pi;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
constexpr double inf = std::numeric_limits<double>::infinity();

template <int W>
using Row = std::array<double, static_cast<std::size_t>(W)>;

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

/// Equal bit patterns, or both NaN (a NaN's payload is not part of the promise: libm's and the vector unit's
/// default NaNs may differ in sign).
bool same(double a, double b) { return bits(a) == bits(b) || (std::isnan(a) && std::isnan(b)); }

template <int W>
Row<W> to_row(const Lanes<W>& v) {
  Row<W> a{};
  store_lanes(v, a);
  return a;
}

// ---- core/lanes.hpp ---------------------------------------------------------------------------------------------

template <int W>
void check_mul_add() {
  // (1 + 2^-30)(1 - 2^-30) - 1 = -2^-60 exactly; the product rounded first is 1, and then the sum is 0.
  const double a = 1.0 + 0x1p-30, b = 1.0 - 0x1p-30, c = -1.0;
  ASSERT_NE(bits(std::fma(a, b, c)), bits(a * b + c)) << "the test value does not tell fused from unfused";
  Row<W> ra{}, rb{}, rc{};
  for (int l = 0; l < W; ++l) {  // lanes differ, so that a lane mix-up shows too
    const auto i = static_cast<std::size_t>(l);
    const double scale = std::ldexp(1.0, l);
    ra[i] = a * scale;
    rb[i] = l % 2 == 0 ? b : -b;
    rc[i] = l % 2 == 0 ? c * scale : -c * scale;
  }
  const Row<W> r = to_row<W>(mul_add(load_lanes<W>(ra), load_lanes<W>(rb), load_lanes<W>(rc)));
  for (std::size_t i = 0; i < static_cast<std::size_t>(W); ++i) {
    const double expected = grtrace::mul_add(ra[i], rb[i], rc[i]);
    EXPECT_EQ(bits(r[i]), bits(expected)) << "W = " << W << ", lane " << i;
    if constexpr (fused_mul_add) EXPECT_NE(r[i], 0.0) << "fused: -2^-60 scaled, not the unfused 0";
    else EXPECT_EQ(r[i], 0.0) << "unfused: the rounded product cancels";
  }
}

TEST(Lanes, MulAddRoundsAsTheScalarMulAdd) {
  check_mul_add<2>();
  check_mul_add<4>();
  check_mul_add<8>();
}

template <int W>
void check_moves_and_masks() {
  Row<W> a{};
  for (int l = 0; l < W; ++l) a[static_cast<std::size_t>(l)] = 0.5 + l;
  const Lanes<W> v = load_lanes<W>(a);
  EXPECT_EQ(to_row<W>(v), a);
  for (int l = 0; l < W; ++l) EXPECT_EQ(v[l], 0.5 + l);
  EXPECT_EQ(bits(to_row<W>(splat<W>(-0.0))[static_cast<std::size_t>(W - 1)]), bits(-0.0));
  EXPECT_TRUE(all_of<W>(v > 0.0));
  EXPECT_TRUE(any_of<W>(v > 0.0));
  EXPECT_FALSE(any_of<W>(v < 0.0));
  if constexpr (W > 2) {  // halves and joined: the lanes in order, and back
    const auto h = halves<W>(v);
    for (int l = 0; l < W / 2; ++l) {
      EXPECT_EQ(h[0][l], v[l]);
      EXPECT_EQ(h[1][l], v[W / 2 + l]);
    }
    EXPECT_EQ(to_row<W>(joined<W / 2>(h[0], h[1])), a);
  }
  for (int l = 0; l < W; ++l) {  // exactly one lane false, then exactly one lane true
    EXPECT_FALSE(all_of<W>(v != 0.5 + l)) << "W = " << W << ", lane " << l;
    EXPECT_TRUE(any_of<W>(v == 0.5 + l)) << "W = " << W << ", lane " << l;
  }
}

TEST(Lanes, LoadStoreSplatAndMasks) {
  check_moves_and_masks<2>();
  check_moves_and_masks<4>();
  check_moves_and_masks<8>();
}

// ---- polar_sin_cos ----------------------------------------------------------------------------------------------

/// The lane polar_sin_cos of the batch theta against the scalar one lane by lane; false on the first difference.
template <int W>
::testing::AssertionResult lanes_match_scalar(const Row<W>& theta) {
  const LaneSinCos<W> sc = polar_sin_cos(load_lanes<W>(theta));
  const Row<W> s = to_row<W>(sc.sin), c = to_row<W>(sc.cos);
  for (std::size_t i = 0; i < static_cast<std::size_t>(W); ++i) {
    const SinCos one = polar_sin_cos(theta[i]);
    if (!same(s[i], one.sin) || !same(c[i], one.cos)) {
      return ::testing::AssertionFailure() << "W = " << W << ", lane " << i << ", theta = " << theta[i] << ": lanes ("
                                           << s[i] << ", " << c[i] << "), scalar (" << one.sin << ", " << one.cos
                                           << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

/// Angles where the scalar function changes range or path, or leaves it: the ends of its middle range, pi/2 and
/// pi within 2^-16 (and just outside), 0 and tiny angles, beyond [0, pi], NaN and infinities.
std::vector<double> path_edges() {
  std::vector<double> edges = {0.1, 3.0, nan, -nan, inf, -inf, 0.0, -0.0, -1.0, -1e-300, pi, 7.0, 3.5, pi / 2, 1.0,
                               2.0, 1e-300, 1e-310, std::numeric_limits<double>::denorm_min(), 0x1p-30,
                               std::nextafter(pi, 0.0), std::nextafter(pi, 4.0)};
  for (const double d : {0.0, 1e-9, -1e-9, 1e-12, -1e-12, 1e-6, -1e-6, 1.5e-5, -1.5e-5, 1.6e-5, -1.6e-5}) {
    edges.push_back(pi / 4 + d);
    edges.push_back(3 * pi / 4 + d);
    edges.push_back(pi / 2 + d);
    edges.push_back(pi - std::abs(d));
    edges.push_back(std::abs(d));
  }
  // |u| = 2^-16 exactly and its neighbours: the scalar's thresholds at pi/2 (both sides) and pi.
  for (const double t : {pi / 2 + 0x1p-16, pi / 2 - 0x1p-16, pi - 0x1p-16}) {
    edges.push_back(t);
    for (int i = 0; i < 3; ++i) {
      edges.push_back(std::nextafter(edges.back(), 0.0));
    }
    edges.push_back(std::nextafter(std::nextafter(t, 4.0), 4.0));
    edges.push_back(std::nextafter(t, 4.0));
  }
  edges.push_back(std::nextafter(sin_cos_detail::polar_low, 0.0));
  edges.push_back(sin_cos_detail::polar_low);
  edges.push_back(sin_cos_detail::polar_high);
  edges.push_back(std::nextafter(sin_cos_detail::polar_high, 4.0));
  return edges;
}

template <int W>
void check_polar_sin_cos() {
  std::mt19937_64 gen(21 + W);
  std::uniform_real_distribution<double> angle(0.0, pi);
  Row<W> theta{};
  for (int i = 0; i < 50000; ++i) {  // random (0, pi): lanes in all three ranges, the batch (nearly) all short
    for (auto& t : theta) t = angle(gen);
    ASSERT_TRUE(lanes_match_scalar<W>(theta));
  }
  std::uniform_int_distribution<int> which(0, 2);
  std::uniform_real_distribution<double> low(0.0, pi / 4), middle(pi / 4, 3 * pi / 4), high(3 * pi / 4, pi);
  for (int i = 0; i < 20000; ++i) {  // each lane's range drawn on its own: every combination of the three
    for (auto& t : theta) {
      const int r = which(gen);
      t = r == 0 ? low(gen) : r == 1 ? middle(gen) : high(gen);
    }
    ASSERT_TRUE(lanes_match_scalar<W>(theta));
  }
  const std::vector<double> edges = path_edges();
  std::uniform_int_distribution<std::size_t> pick(0, edges.size() - 1);
  int mixed = 0;
  for (int i = 0; i < 20000; ++i) {  // one to all lanes at an edge, the others on the short path in any range
    for (auto& t : theta) t = angle(gen);
    const int n = 1 + i % W;
    for (int j = 0; j < n; ++j) theta[std::uniform_int_distribution<std::size_t>(0, W - 1)(gen)] = edges[pick(gen)];
    ASSERT_TRUE(lanes_match_scalar<W>(theta));
    ++mixed;
  }
  for (const double e : edges) {  // each edge alone in every lane position
    for (std::size_t l = 0; l < static_cast<std::size_t>(W); ++l) {
      for (std::size_t j = 0; j < static_cast<std::size_t>(W); ++j) {  // the others in the three ranges
        theta[j] = j % 3 == 0 ? 0.4 : j % 3 == 1 ? 1.2 : 2.8;
      }
      theta[l] = e;
      ASSERT_TRUE(lanes_match_scalar<W>(theta));
    }
  }
  EXPECT_EQ(mixed, 20000);
}

TEST(LanePolarSinCos, EachLaneIsTheScalarPolarSinCos) {
  check_polar_sin_cos<2>();
  check_polar_sin_cos<4>();
  check_polar_sin_cos<8>();
}

// The all-short-path branch and the per-lane fallback both get exercised (else the test above could pass by
// sending every batch through sin_cos, or none).
TEST(LanePolarSinCos, BothPathsAreTaken) {
  const Row<4> on = {0.1, 1.2, 2.0, 3.0};  // the three ranges, all on the short path
  const Row<4> off = {0.1, pi / 2, 3.0, pi};
  EXPECT_TRUE(lanes_match_scalar<4>(on));
  EXPECT_TRUE(lanes_match_scalar<4>(off));
  // The short path and sin_cos differ in some last bits in each of the short path's three ranges: a lane on the
  // wrong path, or given another range's arithmetic, would show.
  for (const auto& [from, to] : {std::array{0.0, pi / 4}, std::array{pi / 4, 3 * pi / 4}, std::array{3 * pi / 4, pi}}) {
    int differ = 0;
    for (int i = 0; i < 1000; ++i) {
      const double t = from + (to - from) * i / 1000.0;
      differ +=
          bits(polar_sin_cos(t).sin) != bits(sin_cos(t).sin) || bits(polar_sin_cos(t).cos) != bits(sin_cos(t).cos);
    }
    EXPECT_GT(differ, 10) << "[" << from << ", " << to << "]: the short path is sin_cos's bits here: lanes on the "
                          << "wrong path would go unseen";
  }
}

// ---- SchwarzschildMetric::acceleration_lanes --------------------------------------------------------------------

static_assert(HasLaneAcceleration<SchwarzschildMetric, 2>);
static_assert(HasLaneAcceleration<SchwarzschildMetric, 4>);
static_assert(HasLaneAcceleration<SchwarzschildMetric, 8>);
static_assert(HasLaneAcceleration<MinkowskiSpherical, 4>);
static_assert(!HasLaneAcceleration<MinkowskiMetric, 4>);

template <int W>
void check_acceleration(const SchwarzschildMetric& metric, std::uint64_t seed) {
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> radius(2.1, 1000.0), polar(0.0, pi), azimuth(-pi, pi);
  std::uniform_real_distribution<double> component(-1.0, 1.0), magnitude(-3.0, 3.0);
  const std::vector<double> edges = path_edges();
  std::uniform_int_distribution<std::size_t> pick(0, edges.size() - 1);
  int compared = 0;
  for (int batch = 0; batch < 3000; ++batch) {
    std::array<Row<W>, 4> xs{}, ks{};
    for (std::size_t l = 0; l < static_cast<std::size_t>(W); ++l) {
      xs[0][l] = 100.0 * component(gen);
      xs[1][l] = radius(gen);
      // theta across (0, pi) (lanes in all three ranges of polar_sin_cos's short path); a third of the batches
      // with some lanes at the path's edges (those in (0, pi): the polar axis itself is no ray's state).
      double theta = polar(gen);
      if (theta == 0.0) theta = 0.5;
      if (batch % 3 == 2 && l % 2 == 0) {
        const double e = edges[pick(gen)];
        if (e > 0.0 && e < pi) theta = e;
      }
      xs[2][l] = theta;
      xs[3][l] = azimuth(gen);
      for (std::size_t mu = 0; mu < 4; ++mu) ks[mu][l] = std::ldexp(component(gen), static_cast<int>(magnitude(gen)));
    }
    std::array<Lanes<W>, 4> x{}, k{};
    for (std::size_t mu = 0; mu < 4; ++mu) {
      x[mu] = load_lanes<W>(xs[mu]);
      k[mu] = load_lanes<W>(ks[mu]);
    }
    const std::array<Lanes<W>, 4> a = metric.acceleration_lanes<W>(x, k);
    for (std::size_t l = 0; l < static_cast<std::size_t>(W); ++l) {
      const Vec4 xl(xs[0][l], xs[1][l], xs[2][l], xs[3][l]), kl(ks[0][l], ks[1][l], ks[2][l], ks[3][l]);
      const Vec4 expected = metric.acceleration(xl, kl);
      for (std::size_t mu = 0; mu < 4; ++mu) {
        const double lane = to_row<W>(a[mu])[l];
        ASSERT_EQ(bits(lane), bits(expected[static_cast<Eigen::Index>(mu)]))
            << "W = " << W << ", M = " << metric.mass << ", lane " << l << ", component " << mu << ": r = "
            << xs[1][l] << ", theta = " << xs[2][l] << ", lanes " << lane << " against "
            << expected[static_cast<Eigen::Index>(mu)];
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, 3000 * W);
}

TEST(LaneAcceleration, SchwarzschildLanesAreAccelerationBitForBit) {
  for (const double mass : {1.0, 0.37}) {
    check_acceleration<2>(SchwarzschildMetric{mass}, 31);
    check_acceleration<4>(SchwarzschildMetric{mass}, 32);
    check_acceleration<8>(SchwarzschildMetric{mass}, 33);
  }
  check_acceleration<4>(MinkowskiSpherical{}, 34);
}

}  // namespace
}  // namespace grtrace
