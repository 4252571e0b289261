// grtrace/trace/sky_continuation_kind.hpp
// The names of the ways a tracer continues escaped rays to the sky (trace/sky_continuation.hpp says how each runs),
// apart from their code so that a frame's header and a tracer's report can name them without it.
#pragma once

namespace grtrace {

/// Which continuation a tracer applies to its escaped rays (recorded in a frame's header as sky_continuation).
enum class SkyContinuation {
  sky_sphere,      ///< AngleCorrection::none: the point on the sky sphere
  flat,            ///< the straight line from the sky sphere (approximate: flat_continuation_error)
  straight_line,   ///< a flat metric: the straight line is the ray (exact)
  exact_elliptic,  ///< the metric's asymptotic_direction (Schwarzschild: the elliptic integral)
  exact_mino,      ///< Kerr: the Mino-time system integrated to u = 1/r = 0
};

inline const char* sky_continuation_name(SkyContinuation c) {
  switch (c) {
    case SkyContinuation::sky_sphere: return "none (the point on the sky sphere)";
    case SkyContinuation::flat: return "flat (straight line from the sky sphere)";
    case SkyContinuation::straight_line: return "exact (flat metric: straight line)";
    case SkyContinuation::exact_elliptic: return "exact (the metric's asymptotic direction)";
    case SkyContinuation::exact_mino: return "exact (Kerr: Mino-time system to u = 1/r = 0)";
  }
  return "?";
}

}  // namespace grtrace
