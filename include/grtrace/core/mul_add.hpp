// grtrace/core/mul_add.hpp
// a * b + c for the hot loops, rounded once where the processor fuses the two (one instruction), and as the two
// separately rounded operations everywhere else.
//
// Why: a step of the general tracer is a chain of dependent multiply-then-add operations (a stage's y + h sum, the
// polynomial kernels of sin_cos, the metrics' accelerations), and the chain's latency, not the number of
// operations, is what a step costs. A fused multiply-add has the latency of the multiplication alone (4 cycles
// against 4 + 3 on the machines we measure), so each link of the chain gets shorter. It is no help where the
// products are ready early and only the additions chain (a sum of many earlier stages: there a chain of fused
// operations is longer, 4 cycles a link against 3), so it is used only where a measurement showed a gain.
// Why not let the compiler contract a * b + c itself (-ffp-contract=fast): it fuses where its pattern matching
// finds the chance, which depends on what was inlined around the expression, so the same formula can round
// differently in two code paths, and the library promises that some paths are the same bit for bit (the batched
// and the scalar Runge-Kutta steppers, the planar table's full and ends-only builds). Written out here, every
// path that calls mul_add rounds the same way (the build compiles grtrace's programs with -ffp-contract=off).
//
// Takes:   any doubles a, b, c.
// Returns: fma(a, b, c) (one rounding) when the build targets a processor with fused multiply-add (__FMA__:
//          x86-64-v3 and later, e.g. -march=x86-64-v3 or -march=native on a recent x86; __ARM_FEATURE_FMA:
//          AArch64), else a * b + c (two roundings: the same bits as the plain expression).
// Assumes: nothing; on a processor without the instruction std::fma would be a slow library call, so it is used
//          only where the instruction exists (compile-time test, no run-time dispatch).
#pragma once

#include "grtrace/core/host_device.hpp"

#include <cmath>

namespace grtrace {

/// True when mul_add rounds once (the build has a fused multiply-add instruction).
inline constexpr bool fused_mul_add =
#if defined(__FMA__) || defined(__ARM_FEATURE_FMA) || defined(__CUDA_ARCH__)  // every CUDA GPU fuses
    true;
#else
    false;
#endif

[[gnu::always_inline]] inline GRTRACE_HD double mul_add(double a, double b, double c) {
  if constexpr (fused_mul_add) return std::fma(a, b, c);
  else return a * b + c;
}

}  // namespace grtrace
