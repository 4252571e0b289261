// grtrace/core/sin_cos.hpp
// sin x and cos x together, inline, for the metrics' right-hand sides (one per evaluation of a spherical chart's
// geodesic equation; the profile of a ray showed libm's out-of-line sincos as a quarter of every step).
//
// Takes:   any double x.
// Returns: {sin x, cos x}. For |x| < 2^19 pi/2 (about 8e5: every polar angle a ray meets) fdlibm's method
//          (Sun Microsystems, 1993; also glibc's and musl's): x = n pi/2 + (y + yy) with pi/2 in three parts
//          (Cody-Waite, with the second correction fdlibm applies when the first cancels), then the degree-13/14
//          minimax kernels __kernel_sin and __kernel_cos with the reduction's tail yy. Error below 1 ulp, like
//          libm's; the two may differ in the last bit (tests/sin_cos_test.cpp measures it against long double).
//          The kernels' Horner polynomials use mul_add (core/mul_add.hpp): fused where the processor has the
//          instruction (a shorter dependency chain, and no less accurate), fdlibm's own operations elsewhere.
//          Elsewhere, and for NaN and infinities, std::sin and std::cos.
//          polar_sin_cos(theta) (below) has a shorter path for polar angles, also for W angles at once in a
//          Lanes<W> (core/lanes.hpp), each lane the scalar polar_sin_cos's bits.
// Assumes: round-to-nearest, no -ffast-math reassociation (the kernels' order of operations matters).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/lanes.hpp"
#include "grtrace/core/mul_add.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

namespace grtrace {

struct SinCos {
  double sin;
  double cos;
};

/// sin and cos of W angles (lane l: angle l), from the lane polar_sin_cos.
template <int W>
struct LaneSinCos {
  Lanes<W> sin;
  Lanes<W> cos;
};

namespace sin_cos_detail {

/// The high 32 bits of |x| (fdlibm's `ix`): its comparisons are made on them.
inline GRTRACE_HD std::uint32_t high_word(double x) {
  return static_cast<std::uint32_t>(std::bit_cast<std::uint64_t>(x) >> 32) & 0x7fffffffU;
}

/// fdlibm's minimax coefficients: sin x = x + x z (S1 + S2 z + ... + S6 z^5), cos x = 1 - z / 2 + z^2 (C1 + C2 z + ...
/// + C6 z^5), z = x^2, |x| <= pi/4.
constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                 S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                 S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                 C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                 C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
/// pi/2 in two parts (Cody-Waite): pio2_1 has 33 significant bits, so n pio2_1 is exact for the n sin_cos meets.
constexpr double pio2_1 = 1.57079632673412561417e+00, pio2_1t = 6.07710050650619224932e-11;

/// fdlibm __kernel_sin(x, y, 1): sin(x + y) for |x| <= pi/4, |y| <= ulp(x) / 2.
inline GRTRACE_HD double kernel_sin(double x, double y) {
  const double z = x * x, v = z * x;
  const double r = mul_add(z, mul_add(z, mul_add(z, mul_add(z, S6, S5), S4), S3), S2);
  return x - ((z * (0.5 * y - v * r) - y) - v * S1);
}

/// fdlibm __kernel_cos(x, y): cos(x + y) for |x| <= pi/4, |y| <= ulp(x) / 2.
inline GRTRACE_HD double kernel_cos(double x, double y) {
  const double z = x * x;
  const double r = z * mul_add(z, mul_add(z, mul_add(z, mul_add(z, mul_add(z, C6, C5), C4), C3), C2), C1);
  const std::uint32_t ix = high_word(x);
  if (ix < 0x3fd33333U) return 1.0 - (0.5 * z - (z * r - x * y));  // |x| < 0.3
  // qx = |x| / 4 with the low 32 bits cleared (exact), or 0.28125 beyond 0.78125.
  const double qx = ix > 0x3fe90000U ? 0.28125 : std::bit_cast<double>(std::uint64_t{ix - 0x00200000U} << 32);
  const double hz = (0.5 * z - qx), a = 1.0 - qx;
  return a - (hz - (z * r - x * y));
}

/// fdlibm's polynomials without the tail, by Estrin's scheme (powers of z = u^2 alongside pairs of coefficients):
/// sin u and cos u for |u| <= pi/4 (a hair beyond at polar_sin_cos's range ends). Written once for double and
/// Lanes<W>, so that a lane of the lane polar_sin_cos cannot differ from the scalar one.
template <class S>
[[gnu::always_inline]] inline GRTRACE_HD void polar_polynomials(const S& u, S& sin_u, S& cos_u) {
  // The coefficients as S: mul_add's operands are of one type (for Lanes<W>, every lane the same constant).
  const S s1 = broadcast<S>(S1), s2 = broadcast<S>(S2), s3 = broadcast<S>(S3), s4 = broadcast<S>(S4),
          s5 = broadcast<S>(S5), s6 = broadcast<S>(S6);
  const S c1 = broadcast<S>(C1), c2 = broadcast<S>(C2), c3 = broadcast<S>(C3), c4 = broadcast<S>(C4),
          c5 = broadcast<S>(C5), c6 = broadcast<S>(C6);
  const S minus_half = broadcast<S>(-0.5), one = broadcast<S>(1.0);
  const S z = u * u, z2 = z * z, z4 = z2 * z2;
  const S s = mul_add(mul_add(s6, z, s5), z4, mul_add(mul_add(s4, z, s3), z2, mul_add(s2, z, s1)));
  const S c = mul_add(mul_add(c6, z, c5), z4, mul_add(mul_add(c4, z, c3), z2, mul_add(c2, z, c1)));
  sin_u = mul_add(u * z, s, u);
  cos_u = mul_add(z2, c, mul_add(minus_half, z, one));
}

/// polar_sin_cos's reduced arguments, written once for double and Lanes<W> (the same roundings in every lane):
/// u = theta - pi/2 (the middle range) and u = pi - theta (the high range), with pi/2 = pio2_1 + pio2_1t and
/// pi = 2 pio2_1 + 2 pio2_1t (doubling is exact). The first operation is exact in both (Sterbenz: theta within a
/// factor 2 of pio2_1, resp. of 2 pio2_1), the second rounds once. pio2_1t is pi/2 - pio2_1 to 53 bits: the
/// two-part pi/2 is off by 3.5e-27 (2^-87.9), pi by twice that; relative to |u| >= 2^-16, below 2^-70.
template <class S>
[[gnu::always_inline]] inline GRTRACE_HD S polar_middle_u(const S& theta) {
  return (theta - pio2_1) - pio2_1t;
}
template <class S>
[[gnu::always_inline]] inline GRTRACE_HD S polar_high_u(const S& theta) {
  constexpr double pi_1 = 2.0 * pio2_1, pi_1t = 2.0 * pio2_1t;
  return (pi_1 - theta) + pi_1t;
}

/// The ends of polar_sin_cos's middle range, [pi/4, 3pi/4] rounded inwards: below polar_low theta is the reduced
/// argument itself, above polar_high pi - theta.
constexpr double polar_low = 0.78539816339744828, polar_high = 2.3561944901923448;
/// polar_sin_cos's hand-overs to sin_cos, as bounds on theta (tested alongside the reduction, not after it):
/// theta strictly between polar_gap_low and polar_gap_high (|u| < 2^-16 in the middle range, to an ulp of theta) or
/// above polar_max (u < 2^-16 in the high range, and beyond pi). pi/2 and pi are the doubles nearest them.
constexpr double polar_gap_low = 1.5707963267948966 - 0x1p-16, polar_gap_high = 1.5707963267948966 + 0x1p-16;
constexpr double polar_max = 3.141592653589793 - 0x1p-16;

/// The reduction's second and third iterations (x within ~2^-16 of a multiple of pi/2: rare, kept out of line).
/// Takes r = x - fn pio2_1 and w = fn pio2_1t with y0 = r - w; updates r, w and y0 (fdlibm __ieee754_rem_pio2).
[[gnu::noinline]] inline GRTRACE_HD void reduce_further(double fn, int j, double& r, double& w, double& y0) {
  constexpr double pio2_2 = 6.07710050630396597660e-11, pio2_2t = 2.02226624879595063154e-21;
  constexpr double pio2_3 = 2.02226624871116645580e-21, pio2_3t = 8.47842766036889956997e-32;
  double t = r;  // 2nd iteration: good to 118 bits
  w = fn * pio2_2;
  r = t - w;
  w = fn * pio2_2t - ((t - r) - w);
  y0 = r - w;
  if (j - static_cast<int>(high_word(y0) >> 20) > 49) {  // 3rd iteration: 151 bits
    t = r;
    w = fn * pio2_3;
    r = t - w;
    w = fn * pio2_3t - ((t - r) - w);
    y0 = r - w;
  }
}

[[gnu::noinline]] inline GRTRACE_HD SinCos sin_cos_libm(double x) { return {std::sin(x), std::cos(x)}; }

}  // namespace sin_cos_detail

/// Forced inline (GCC and Clang): it is called once per right-hand side, and a call costs as much as the kernels.
[[gnu::always_inline]] inline GRTRACE_HD SinCos sin_cos(double x) {
  using namespace sin_cos_detail;
  const std::uint32_t ix = high_word(x);
  if (ix <= 0x3fe921fbU) return {kernel_sin(x, 0.0), kernel_cos(x, 0.0)};  // |x| ~<= pi/4
  if (ix > 0x413921fbU) return sin_cos_libm(x);                             // |x| ~> 2^19 pi/2; NaN, inf
  // fdlibm __ieee754_rem_pio2, medium range: n = nearest integer to x 2/pi, x - n pi/2 in three parts.
  constexpr double invpio2 = 6.36619772367581382433e-01;
  constexpr double round_magic = 6755399441055744.0;  // 1.5 * 2^52: (v + it) - it rounds v to an integer, inline
  const double fn = (x * invpio2 + round_magic) - round_magic;
  const int n = static_cast<int>(fn);
  double r = x - fn * pio2_1;
  double w = fn * pio2_1t;
  double y0 = r - w;
  const int j = static_cast<int>(ix >> 20);
  if (j - static_cast<int>(high_word(y0) >> 20) > 16) reduce_further(fn, j, r, w, y0);
  const double y1 = (r - y0) - w;
  const double s = kernel_sin(y0, y1), c = kernel_cos(y0, y1);
  switch (n & 3) {
    case 0: return {s, c};
    case 1: return {c, -s};
    case 2: return {-s, -c};
    default: return {-c, s};
  }
}

/// sin and cos of a polar angle, for the metrics' right-hand sides (Schwarzschild, Kerr): sin_cos with a shorter
/// path for theta in [0, pi], every polar angle a ray meets, except near pi/2 and pi.
/// Why: the sine and cosine of theta are the longest link of the right-hand side's chain, and a step is six or more
/// right-hand sides in a row. sin_cos reduces theta by the nearest multiple of pi/2 (a rounding, two products) and
/// its kernels carry the reduction's tail through a sequence of dependent corrections (fdlibm's order, for < 1 ulp).
/// Here the multiple is known from three ranges of theta, and the reduced argument u (|u| <= pi/4) is at most one
/// exact subtraction and one rounded one (pi/2 in two parts, Cody-Waite; polar_middle_u, polar_high_u):
///   [0, pi/4):     u = theta,         sin theta = sin u, cos theta =  cos u;
///   [pi/4, 3pi/4]: u = theta - pi/2,  sin theta = cos u, cos theta = -sin u;
///   (3pi/4, pi]:   u = pi - theta,    sin theta = sin u, cos theta = -cos u.
/// sin u and cos u are fdlibm's minimax polynomials by Estrin's scheme, without the tail (polar_polynomials): 10
/// against 19 ns of latency on the machine of docs/benchmarks.md. The lane version computes both polynomials on
/// every lane and selects (rays over a pole share a vector with rays that are not): the ranges are for the lanes
/// the same arithmetic as here.
/// Takes:   any double theta.
/// Returns: {sin theta, cos theta}, within 2 ulp for theta in [0, pi] (tests/sin_cos_test.cpp), sin 0 = 0 and
///          cos 0 = 1 exactly, except near pi/2 and pi, where u goes to 0 and the two-part pi/2's error (2^-88)
///          grows relative to it (at pi itself u would be 1.2e-16): |theta - pi/2| < 2^-16 and pi - theta < 2^-16
///          (fdlibm's margin; polar_gap_low, polar_gap_high, polar_max: bounds on theta, so that the test needs no
///          u). There, for theta outside [0, pi] (-0.0 included), NaN and infinities: sin_cos(theta) (below 1 ulp).
///          No hand-over near 0: there u = theta exactly.
[[gnu::always_inline]] inline GRTRACE_HD SinCos polar_sin_cos(double theta) {
  using namespace sin_cos_detail;
  // The short path: theta in [+0, polar_max] (false for NaN) and not in the gap around pi/2.
  if (!std::signbit(theta) && theta <= polar_max && (theta <= polar_gap_low || theta >= polar_gap_high)) {
    double sin_u, cos_u;
    if (theta < polar_low) {
      polar_polynomials(theta, sin_u, cos_u);
      return {sin_u, cos_u};
    }
    if (theta <= polar_high) {
      polar_polynomials(polar_middle_u(theta), sin_u, cos_u);
      return {cos_u, -sin_u};
    }
    polar_polynomials(polar_high_u(theta), sin_u, cos_u);
    return {sin_u, -cos_u};
  }
  return sin_cos(theta);
}

namespace sin_cos_detail {

/// Per lane, whether the scalar polar_sin_cos takes its short path (its test, on theta alone: NaN compares false;
/// -0.0 and negative theta by the sign bit).
template <int W>
[[gnu::always_inline]] inline LaneMask<W> polar_lanes_fast(const Lanes<W>& theta) {
  const LaneMask<W> positive = std::bit_cast<LaneMask<W>>(theta) > -1;  // the sign bit clear
  return positive & (theta <= polar_max) & ((theta <= polar_gap_low) | (theta >= polar_gap_high));
}

/// The lane polar_sin_cos's short path on every lane, branch-free: the three ranges' reduced arguments selected per
/// lane, both polynomials on it, and the results selected and signed per lane (a sign flip by xor is the scalar's
/// negation); each lane the scalar polar_sin_cos's arithmetic for its range.
template <int W>
[[gnu::always_inline]] inline LaneSinCos<W> polar_lanes_short(const Lanes<W>& theta) {
  const LaneMask<W> low = theta < polar_low, high = theta > polar_high, outer = low | high;
  const LaneMask<W> flip = ~low & std::bit_cast<LaneMask<W>>(splat<W>(-0.0));  // cos theta = -(...) but in low
  const Lanes<W> u = low ? theta : high ? polar_high_u(theta) : polar_middle_u(theta);
  Lanes<W> sin_u, cos_u;
  polar_polynomials(u, sin_u, cos_u);
  LaneSinCos<W> sc;
  sc.sin = outer ? sin_u : cos_u;
  sc.cos = std::bit_cast<Lanes<W>>(std::bit_cast<LaneMask<W>>(outer ? cos_u : sin_u) ^ flip);
  return sc;
}

/// polar_sin_cos of a batch with a lane off the short path: the short path on all lanes, then the lanes off it
/// replaced by sin_cos. Out of line: such batches are rare (a ray within 2^-16 of pi/2 or of the pole at pi), and
/// sin_cos inlined W times would crowd the caller's loop. It returns the whole result, so that the common path's
/// values stay in registers (results patched through a reference were kept in memory on both paths).
template <int W>
[[gnu::noinline]] inline LaneSinCos<W> polar_lanes_mixed(const Lanes<W>& theta) {
  const LaneMask<W> fast = polar_lanes_fast<W>(theta);
  LaneSinCos<W> sc = polar_lanes_short<W>(theta);
  for (int l = 0; l < W; ++l) {
    if (fast[l] == 0) {
      const SinCos one = sin_cos(theta[l]);
      sc.sin[l] = one.sin;
      sc.cos[l] = one.cos;
    }
  }
  return sc;
}

}  // namespace sin_cos_detail

/// polar_sin_cos of W angles at once: lane l is exactly polar_sin_cos(theta[l]) (tests/lanes_test.cpp).
/// When every lane is in the middle range (the common case: rays spend most steps between 45 and 135 degrees) only
/// its arithmetic; else every lane by the short path's arithmetic for its range (polar_lanes_short: no branch
/// between the ranges); when a lane is off the short path (within 2^-16 of pi/2 or of pi, outside [0, pi], NaN),
/// those lanes by sin_cos, one at a time. Measured in the batched integrator (step_benchmark lanes/<method>/4):
/// the middle-range branch makes rkf78 200-212 ns a step against 219-237 without it, tsit5 92-93 against 98-102. Vectors wider than the target's registers as two halves (core/lanes.hpp, native_lanes: GCC compares
/// and selects on them one lane at a time).
template <LaneVector V>
[[gnu::always_inline]] inline LaneSinCos<lanes_of<V>> polar_sin_cos(const V& theta) {
  using namespace sin_cos_detail;
  constexpr int W = lanes_of<V>;
  if constexpr (W > native_lanes) {
    const auto t = halves<W>(theta);
    const auto lo = polar_sin_cos(t[0]), hi = polar_sin_cos(t[1]);
    return {joined<W / 2>(lo.sin, hi.sin), joined<W / 2>(lo.cos, hi.cos)};
  } else {
    const LaneMask<W> fast = polar_lanes_fast<W>(theta);
    if (all_of<W>(fast & (theta >= polar_low) & (theta <= polar_high))) [[likely]] {
      LaneSinCos<W> sc;
      Lanes<W> sin_u, cos_u;
      polar_polynomials(polar_middle_u(theta), sin_u, cos_u);
      sc.sin = cos_u;
      sc.cos = -sin_u;
      return sc;
    }
    if (!all_of<W>(fast)) [[unlikely]] return polar_lanes_mixed<W>(theta);
    return polar_lanes_short<W>(theta);
  }
}

}  // namespace grtrace
