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
// Assumes: round-to-nearest, no -ffast-math reassociation (the kernels' order of operations matters).
#pragma once

#include "grtrace/core/mul_add.hpp"

#include <bit>
#include <cmath>
#include <cstdint>

namespace grtrace {

struct SinCos {
  double sin;
  double cos;
};

namespace sin_cos_detail {

/// The high 32 bits of |x| (fdlibm's `ix`): its comparisons are made on them.
inline std::uint32_t high_word(double x) {
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
inline double kernel_sin(double x, double y) {
  const double z = x * x, v = z * x;
  const double r = mul_add(z, mul_add(z, mul_add(z, mul_add(z, S6, S5), S4), S3), S2);
  return x - ((z * (0.5 * y - v * r) - y) - v * S1);
}

/// fdlibm __kernel_cos(x, y): cos(x + y) for |x| <= pi/4, |y| <= ulp(x) / 2.
inline double kernel_cos(double x, double y) {
  const double z = x * x;
  const double r = z * mul_add(z, mul_add(z, mul_add(z, mul_add(z, mul_add(z, C6, C5), C4), C3), C2), C1);
  const std::uint32_t ix = high_word(x);
  if (ix < 0x3fd33333U) return 1.0 - (0.5 * z - (z * r - x * y));  // |x| < 0.3
  // qx = |x| / 4 with the low 32 bits cleared (exact), or 0.28125 beyond 0.78125.
  const double qx = ix > 0x3fe90000U ? 0.28125 : std::bit_cast<double>(std::uint64_t{ix - 0x00200000U} << 32);
  const double hz = (0.5 * z - qx), a = 1.0 - qx;
  return a - (hz - (z * r - x * y));
}

/// The reduction's second and third iterations (x within ~2^-16 of a multiple of pi/2: rare, kept out of line).
/// Takes r = x - fn pio2_1 and w = fn pio2_1t with y0 = r - w; updates r, w and y0 (fdlibm __ieee754_rem_pio2).
[[gnu::noinline]] inline void reduce_further(double fn, int j, double& r, double& w, double& y0) {
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

[[gnu::noinline]] inline SinCos sin_cos_libm(double x) { return {std::sin(x), std::cos(x)}; }

}  // namespace sin_cos_detail

/// Forced inline (GCC and Clang): it is called once per right-hand side, and a call costs as much as the kernels.
[[gnu::always_inline]] inline SinCos sin_cos(double x) {
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
/// path for theta in [pi/4, 3pi/4], where a ray spends most of its steps.
/// Why: the sine and cosine of theta are the longest link of the right-hand side's chain, and a step is six or more
/// right-hand sides in a row. sin_cos reduces theta by the nearest multiple of pi/2 (a rounding, two products) and
/// its kernels carry the reduction's tail through a sequence of dependent corrections (fdlibm's order, for < 1 ulp).
/// Here the multiple is known (pi/2), p = theta - pi/2 is one exact subtraction and one rounded one (pi/2 in two
/// parts, Cody-Waite), and sin theta = cos p, cos theta = -sin p come from fdlibm's minimax polynomials evaluated by
/// Estrin's scheme (powers of z = p^2 alongside pairs of coefficients), without the tail: 10 against 19 ns of latency
/// on the machine of docs/benchmarks.md.
/// Takes:   any double theta.
/// Returns: {sin theta, cos theta}, within 2 ulp for theta in [pi/4, 3pi/4] (tests/sin_cos_test.cpp), except within
///          2^-16 of pi/2, where p = theta - pi/2 cancels too many bits of the two-part pi/2: there, and outside
///          [pi/4, 3pi/4], sin_cos(theta) (below 1 ulp).
[[gnu::always_inline]] inline SinCos polar_sin_cos(double theta) {
  using namespace sin_cos_detail;
  if (theta >= 0.78539816339744828 && theta <= 2.3561944901923448) {
    const double p = (theta - pio2_1) - pio2_1t;  // the first subtraction is exact (Sterbenz)
    if (high_word(p) >= 0x3ef00000U) {             // |p| >= 2^-16
      const double z = p * p, z2 = z * z, z4 = z2 * z2;
      const double s = mul_add(mul_add(S6, z, S5), z4, mul_add(mul_add(S4, z, S3), z2, mul_add(S2, z, S1)));
      const double c = mul_add(mul_add(C6, z, C5), z4, mul_add(mul_add(C4, z, C3), z2, mul_add(C2, z, C1)));
      return {mul_add(z2, c, mul_add(-0.5, z, 1.0)), -mul_add(p * z, s, p)};
    }
  }
  return sin_cos(theta);
}

}  // namespace grtrace
