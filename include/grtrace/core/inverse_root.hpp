// grtrace/core/inverse_root.hpp
// x^(-1/k) for a small integer k, inline: the step controllers' law h_new = h * safety * err^(-1/k).
//
// Why: an adaptive step is one chain of dependent operations, and the controller sits on it: the next step's first
// stage waits for h_new, h_new for err^(-1/k), that for the error norm, the norm for the step's last stage. libm's
// pow is a general function (any base, any exponent, both logarithm and exponential to full precision) and measured
// ~80-100 cycles of latency in that chain; an integer root of a positive number needs neither logarithm nor
// exponential: its exponent part is integer arithmetic and its mantissa part a short series.
//
// Method (table-driven, as libm's own pow and cbrt): write x = 2^e m with 1 <= m < 2, and e = k q + s with
// 0 <= s < k (q = floor(e / k)). Then
//   x^(-1/k) = 2^-q * 2^(-s/k) * r_j^(1/k) * (m r_j)^(-1/k),
// where r_j ~ 1 / m is one of 128 reciprocals picked by m's leading 7 fraction bits, so that t = m r_j - 1 has
// |t| < 1/256 and (1 + t)^(-1/k) is its binomial series to degree 6 (truncation < 1e-17). 2^(-s/k) (k values) and
// r_j^(1/k) (128 values) are tables computed at compile time in long double; 2^-q is built from its bits. The chain
// from x is a table look-up, one multiply-add for t, four deep for the series (Estrin) and one product.
//
// Takes:   x > 0 finite and normal (the controllers' error norms). Anything else (0, subnormals, infinity, NaN,
//          negative numbers) goes to std::pow(x, -1.0 / k), which gives the same answer as for pow.
// Returns: x^(-1/k) within 4 ulp (tests/inline_math_test.cpp measures it against long double for k = 2..16).
//          Not always pow's bits: a step size can differ from pow's in its last bit, so step sequences agree
//          with pow's to round-off, not bit for bit.
// inverse_root(x, k) with k known only at run time picks the compile-time root for k = 2..16 (a switch that folds
// away where k is a constant after inlining, as in the integrators) and std::pow otherwise.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/mul_add.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace grtrace {

namespace inverse_root_detail {

/// a^(1/k) for 0 < a <= 1 in long double, by Newton's method from 1 (monotone for y^k - a, which is convex: every
/// iterate stays above the root), until it stops moving. Compile time only.
consteval long double root(long double a, int k) {
  long double y = 1.0L;
  for (int iteration = 0; iteration < 2000; ++iteration) {
    long double power = 1.0L;  // y^(k-1)
    for (int i = 1; i < k; ++i) power *= y;
    const long double next = y - (power * y - a) / (static_cast<long double>(k) * power);
    if (!(next < y)) break;  // converged: rounding would only make it oscillate
    y = next;
  }
  return y;
}

constexpr int fraction_bits = 7;  ///< m's leading fraction bits that pick r_j
constexpr std::size_t table_size = std::size_t{1} << fraction_bits;
constexpr int degree = 6;  ///< of the binomial series of (1 + t)^(-1/k), |t| < 1/256

template <int K>
struct Tables {
  std::array<double, table_size> reciprocal{};  ///< r_j ~ 1 / (1 + (j + 1/2) / 128), rounded to double
  std::array<double, table_size> root{};        ///< r_j^(1/k) of that rounded r_j
  std::array<double, static_cast<std::size_t>(K)> power{};             ///< 2^(-s/k), s = 0..k-1
  std::array<double, std::size_t{degree} + 1> series{};  ///< binom(-1/k, n), n = 0..degree
};

template <int K>
consteval Tables<K> make_tables() {
  Tables<K> t;
  for (std::size_t j = 0; j < table_size; ++j) {
    const double centre = 1.0 + (static_cast<double>(j) + 0.5) / static_cast<double>(table_size);
    t.reciprocal[j] = 1.0 / centre;
    t.root[j] = static_cast<double>(root(static_cast<long double>(t.reciprocal[j]), K));
  }
  const long double half_root = root(0.5L, K);  // 2^(-1/k)
  long double p = 1.0L;
  for (int s = 0; s < K; ++s, p *= half_root) t.power[static_cast<std::size_t>(s)] = static_cast<double>(p);
  long double c = 1.0L;
  for (int n = 0; n <= degree; ++n) {
    t.series[static_cast<std::size_t>(n)] = static_cast<double>(c);
    c *= (-1.0L / K - static_cast<long double>(n)) / static_cast<long double>(n + 1);
  }
  return t;
}

template <int K>
inline constexpr Tables<K> tables = make_tables<K>();

#if defined(__CUDACC__)
/// The same tables in the GPU's memory (a host variable cannot be read by device code).
template <int K>
__device__ constexpr Tables<K> device_tables = make_tables<K>();  // not inline: nvcc without -rdc
#endif

/// The tables of the pass being compiled: the host's, or their copy on the device.
template <int K>
GRTRACE_HD inline const Tables<K>& tables_here() {
#if GRTRACE_DEVICE_PASS
  return device_tables<K>;
#else
  return tables<K>;
#endif
}

}  // namespace inverse_root_detail

/// x^(-1/K) for 2 <= K <= 16 (see the top of this file).
template <int K>
[[gnu::always_inline]] inline GRTRACE_HD double inverse_root(double x) {
  static_assert(K >= 2 && K <= 16, "inverse_root<K>: K must be 2..16 (use std::pow for other exponents)");
  namespace d = inverse_root_detail;
  const d::Tables<K>& t = d::tables_here<K>();
  if (!(x >= 0x1p-1022 && x <= 0x1.fffffffffffffp+1023)) return std::pow(x, -1.0 / K);
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
  // e + offset >= 0 for every normal exponent e, with offset a multiple of K: e = K q + s without a signed division.
  constexpr int offset = K * ((1023 + K - 1) / K);
  const auto biased = static_cast<unsigned>(bits >> 52) - 1023U + static_cast<unsigned>(offset);
  const unsigned s = biased % static_cast<unsigned>(K);
  const int q = static_cast<int>(biased / static_cast<unsigned>(K)) - offset / K;
  const auto j = static_cast<std::size_t>((bits >> (52 - d::fraction_bits)) & (d::table_size - 1));
  const double m = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);
  const double two_to_minus_q = std::bit_cast<double>(static_cast<std::uint64_t>(1023 - q) << 52);
  const double scale = t.root[j] * t.power[s] * two_to_minus_q;  // off the chain: table values and bits
  const double u = mul_add(m, t.reciprocal[j], -1.0);
  // Estrin's scheme (pairs, then powers of u^2): three multiply-adds deep after u^2 where Horner's is six.
  static_assert(d::degree == 6, "the evaluation below is written out for degree 6");
  const auto& c = t.series;
  const double u2 = u * u;
  const double c01 = mul_add(c[1], u, c[0]), c23 = mul_add(c[3], u, c[2]), c45 = mul_add(c[5], u, c[4]);
  const double series = mul_add(mul_add(mul_add(c[6], u2, c45), u2, c23), u2, c01);
  return series * scale;
}

/// x^(-1/k) with k known at run time: inverse_root<k> for k = 2..16, std::pow(x, -1.0 / k) otherwise.
[[gnu::always_inline]] inline GRTRACE_HD double inverse_root(double x, int k) {
  switch (k) {
    case 2: return inverse_root<2>(x);
    case 3: return inverse_root<3>(x);
    case 4: return inverse_root<4>(x);
    case 5: return inverse_root<5>(x);
    case 6: return inverse_root<6>(x);
    case 7: return inverse_root<7>(x);
    case 8: return inverse_root<8>(x);
    case 9: return inverse_root<9>(x);
    case 10: return inverse_root<10>(x);
    case 11: return inverse_root<11>(x);
    case 12: return inverse_root<12>(x);
    case 13: return inverse_root<13>(x);
    case 14: return inverse_root<14>(x);
    case 15: return inverse_root<15>(x);
    case 16: return inverse_root<16>(x);
    default: return std::pow(x, -1.0 / k);
  }
}

}  // namespace grtrace
