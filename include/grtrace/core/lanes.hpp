// grtrace/core/lanes.hpp
// W doubles in one SIMD register (W = 2, 4, 8), for evaluating the right-hand sides of W rays at once: the value
// type Lanes<W>, its loads and stores from the batched stepper's component rows, and the lane-wise mul_add.
//
// Why: the batched stepper (integrate/batch_stepper.hpp) keeps component i of its W rays side by side, so one
// instruction can do the same operation for every ray. The library promises that a batched lane is the ray
// integrated alone, bit for bit, so a lane version of a scalar formula must round every lane exactly as the scalar
// one. The way this is kept true: the formula is written once, as a template over the scalar type (double or
// Lanes<W>), and this header's operations round like their scalar counterparts. GCC and Clang's vector extension
// gives +, -, *, / and comparisons lane by lane with the scalar's IEEE rounding (one per operation; the build's
// -ffp-contract=off keeps a * b + c two roundings there as in scalar code), a scalar operand is broadcast to every
// lane, and lane l is v[l]. What it does not give is mul_add, which must fuse exactly where the scalar
// grtrace::mul_add does (core/mul_add.hpp): here by the FMA instructions themselves, not by W calls of std::fma.
//
// Takes/returns: Lanes<W> values (lane l of each argument is ray l); LaneMask<W> is the result of comparing two of
//                them (per lane all bits set for true, zero for false), reduced by all_of / any_of.
// Assumes: GCC 12 or later, or Clang (vector_size, __builtin_shufflevector). A vector wider than the target's
//          registers (Lanes<8> under AVX2, Lanes<4> without AVX) is correct but slower: see native_lanes and
//          in_halves. The functions are inline (always_inline): no call passes a vector in registers whose
//          convention depends on the target (the compilers' -Wpsabi warning, silenced below).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/mul_add.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <tuple>
#include <type_traits>

#if defined(__FMA__) || defined(__AVX__) || defined(__SSE2__)
#include <immintrin.h>
#endif

// -Wpsabi is silenced for every translation unit that includes this header (not popped at its end, on purpose).
// GCC and Clang warn (an error under -Werror) where a function takes or returns a vector wider than the target's
// registers (Lanes<8> without AVX-512, Lanes<4> without AVX) that such a call is passed differently on other
// targets. That matters only for a call between translation units compiled for different processors; the lane
// functions are inline templates, inlined in each unit, so there is none. A push/pop around the lane code cannot
// silence it: GCC reports it at the end of the calling function or of the unit (where it lowers the calls), so
// the setting must still hold there.
#if defined(__clang__)
#if __has_warning("-Wpsabi")
#pragma clang diagnostic ignored "-Wpsabi"
#endif
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace grtrace {

namespace lanes_detail {

/// The vector type, via a class template: an alias template cannot carry the attribute in every compiler.
template <int W>
struct LaneVector {
  static_assert(W == 2 || W == 4 || W == 8, "Lanes<W>: W is 2, 4 or 8 doubles (one SSE, AVX or AVX-512 register)");
  typedef double type __attribute__((vector_size(8 * W)));  // NOLINT(modernize-use-using): the attribute's place
};

template <class V>
inline constexpr int lane_count = 0;
template <>
inline constexpr int lane_count<LaneVector<2>::type> = 2;
template <>
inline constexpr int lane_count<LaneVector<4>::type> = 4;
template <>
inline constexpr int lane_count<LaneVector<8>::type> = 8;

}  // namespace lanes_detail

/// W doubles, one per ray, operated on together.
template <int W>
using Lanes = typename lanes_detail::LaneVector<W>::type;

/// Lanes<2>, Lanes<4> or Lanes<8> (their W cannot be deduced from an argument: the alias is not deducible, so the
/// lane functions below are constrained templates on the vector type instead).
template <class V>
concept LaneVector = lanes_detail::lane_count<std::remove_cvref_t<V>> > 0;

/// W of a lane vector type.
template <LaneVector V>
inline constexpr int lanes_of = lanes_detail::lane_count<std::remove_cvref_t<V>>;

/// The result of comparing two Lanes<W>: per lane an integer of all bits set (true) or zero (false).
template <int W>
using LaneMask = decltype(Lanes<W>{} < Lanes<W>{});

/// Lane l = a[l]: one unaligned load (the batched stepper's rows are plain arrays of doubles). W is deduced from
/// the array, or given: load_lanes<4>(row).
template <std::size_t W>
[[gnu::always_inline]] inline Lanes<static_cast<int>(W)> load_lanes(const std::array<double, W>& a) {
  Lanes<static_cast<int>(W)> v;
  std::memcpy(&v, a.data(), sizeof v);
  return v;
}

/// a[l] = lane l of v.
template <LaneVector V>
[[gnu::always_inline]] inline void store_lanes(const V& v, std::array<double, lanes_of<V>>& a) {
  std::memcpy(a.data(), &v, sizeof v);
}

/// The widest lane vector the target computes in one register: 8 with AVX-512, 4 with AVX, else 2 (SSE2).
/// Wider vectors are lowered by the compiler, in halves for arithmetic, but one lane at a time for comparisons
/// (GCC: 32 scalar comparisons for the four of polar_sin_cos on a Lanes<8> under AVX2): compare in halves().
inline constexpr int native_lanes =
#if defined(__AVX512F__)
    8;
#elif defined(__AVX__)
    4;
#else
    2;
#endif

/// Lanes 0 .. W/2 - 1 and W/2 .. W - 1 of v, as two vectors of half the width (register moves, no arithmetic).
/// By shuffles, not memcpy: GCC copies a memcpy'd 64-byte vector through the stack and general registers.
template <int W>
[[gnu::always_inline]] inline std::array<Lanes<W / 2>, 2> halves(const Lanes<W>& v) {
  static_assert(W == 4 || W == 8);
  if constexpr (W == 8) return {__builtin_shufflevector(v, v, 0, 1, 2, 3), __builtin_shufflevector(v, v, 4, 5, 6, 7)};
  else return {__builtin_shufflevector(v, v, 0, 1), __builtin_shufflevector(v, v, 2, 3)};
}

/// The vector of twice the width with lanes lo, then hi (the inverse of halves).
template <int W>
[[gnu::always_inline]] inline Lanes<2 * W> joined(const Lanes<W>& lo, const Lanes<W>& hi) {
  static_assert(W == 2 || W == 4);
  if constexpr (W == 4) return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
  else return __builtin_shufflevector(lo, hi, 0, 1, 2, 3);
}

/// f(x_half, k_half) on lanes 0 .. W/2 - 1 and on lanes W/2 .. W - 1 of two arrays of lane vectors, the results
/// joined: a kernel of W lanes run as two of W/2 where W is wider than the target's registers (Lanes<8> under
/// AVX2). GCC lowers the wide vector's arithmetic in halves itself, but keeps the values where two paths merge
/// (polar_sin_cos's mixed-batch branch) in memory, copied 16 bytes at a time; two narrow kernels keep them in
/// registers, and are two independent chains (rhs/acceleration_lanes/8's loop, GCC 12 on a 2-core AMD EPYC:
/// 22 ns -> 19-21 ns a batch; Clang, which keeps 512-bit vectors in register pairs, 18 ns without it). Each lane's
/// operations are the same.
template <int W, std::size_t N, class F>
[[gnu::always_inline]] inline auto in_halves(const std::array<Lanes<W>, N>& x, const std::array<Lanes<W>, N>& k,
                                             F f) {
  std::array<Lanes<W / 2>, N> x_lo, x_hi, k_lo, k_hi;
  for (std::size_t i = 0; i < N; ++i) {
    const auto xh = halves<W>(x[i]), kh = halves<W>(k[i]);
    x_lo[i] = xh[0];
    x_hi[i] = xh[1];
    k_lo[i] = kh[0];
    k_hi[i] = kh[1];
  }
  const auto lo = f(x_lo, k_lo), hi = f(x_hi, k_hi);
  std::array<Lanes<W>, std::tuple_size_v<std::remove_cvref_t<decltype(lo)>>> joined_result;
  for (std::size_t i = 0; i < joined_result.size(); ++i) joined_result[i] = joined<W / 2>(lo[i], hi[i]);
  return joined_result;
}

/// Every lane x (a broadcast).
template <int W>
[[gnu::always_inline]] inline Lanes<W> splat(double x) {
  Lanes<W> v;
  for (int l = 0; l < W; ++l) v[l] = x;
  return v;
}

/// The scalar type's value x: x itself for double, every lane x for a lane vector. For formulas written once over
/// both (constants that must be an operand of mul_add, where no broadcast happens by itself).
template <class S>
[[gnu::always_inline]] inline GRTRACE_HD S broadcast(double x) {
  if constexpr (std::is_same_v<S, double>) return x;
  else return splat<lanes_of<S>>(x);
}

/// a * b + c lane by lane, each lane rounded exactly as the scalar mul_add(a[l], b[l], c[l]) (core/mul_add.hpp):
/// once where fused_mul_add, by the processor's FMA instruction on the whole vector; else twice, as a * b + c.
template <LaneVector V>
[[gnu::always_inline]] inline V mul_add(const V& a, const V& b, const V& c) {
  constexpr int W = lanes_of<V>;
  if constexpr (!fused_mul_add) {
    return a * b + c;
  } else {
#if defined(__FMA__)
    if constexpr (W == 2) {
      return _mm_fmadd_pd(a, b, c);
    } else if constexpr (W == 4) {
      return _mm256_fmadd_pd(a, b, c);
    } else {
#if defined(__AVX512F__)
      return _mm512_fmadd_pd(a, b, c);
#else
      // Two 256-bit halves: x86-64-v3 has FMA but no 512-bit registers.
      const auto ah = halves<8>(a), bh = halves<8>(b), ch = halves<8>(c);
      return joined<4>(_mm256_fmadd_pd(ah[0], bh[0], ch[0]), _mm256_fmadd_pd(ah[1], bh[1], ch[1]));
#endif
    }
#else
    // A fused multiply-add without x86's intrinsics (AArch64): std::fma per lane, which the compiler maps to the
    // instruction (a vector one where it finds it); the same single rounding.
    V r;
    for (int l = 0; l < W; ++l) r[l] = std::fma(a[l], b[l], c[l]);
    return r;
#endif
  }
}

/// True when every lane of the mask is true. The sign bits in one instruction (movemask) where there is one: a
/// loop over the lanes compiles to W extractions and branches.
template <int W>
[[gnu::always_inline]] inline bool all_of(const LaneMask<W>& m) {
#if defined(__AVX__)
  if constexpr (W == 4) return _mm256_movemask_pd(std::bit_cast<__m256d>(m)) == 0xf;
  if constexpr (W == 8) {
    const LaneMask<4> both = __builtin_shufflevector(m, m, 0, 1, 2, 3) & __builtin_shufflevector(m, m, 4, 5, 6, 7);
    return _mm256_movemask_pd(std::bit_cast<__m256d>(both)) == 0xf;
  }
#endif
#if defined(__SSE2__)
  if constexpr (W == 2) return _mm_movemask_pd(std::bit_cast<__m128d>(m)) == 0x3;
#endif
  bool all = true;
  for (int l = 0; l < W; ++l) all = all && m[l] != 0;
  return all;
}

/// True when some lane of the mask is true.
template <int W>
[[gnu::always_inline]] inline bool any_of(const LaneMask<W>& m) {
  return !all_of<W>(m == 0);
}

}  // namespace grtrace

