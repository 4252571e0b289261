// grtrace/core/rounding.hpp
// floor and round-to-nearest as integers, inline. The build targets baseline x86-64 (SSE2), which has no rounding
// instruction, so std::floor and std::lround are calls into libm: about 5 ns each, several times per pixel (a sky's
// checkerboard cell, a table stencil's first node), a tenth of the main frame's pixel loop
// (docs/benchmarks-archive.md, "Table rays four at a time, and the pixel loop's stalls").
#pragma once

namespace grtrace {

/// floor(x) as a long, the same integer std::floor gives: exact for |x| < 2^63; assumes x is finite.
inline long floor_to_long(double x) {
  const long t = static_cast<long>(x);  // truncation towards zero
  return t - static_cast<long>(static_cast<double>(t) > x);
}

/// x rounded to the nearest integer, halves away from zero (std::lround) for x >= 0; assumes 0 <= x < 2^62.
inline long round_nonnegative_to_long(double x) {
  const long t = static_cast<long>(x);
  return t + static_cast<long>(x - static_cast<double>(t) >= 0.5);
}

}  // namespace grtrace
