// grtrace/integrate/event_locator.hpp
// Locates where a scalar event function first becomes <= 0 inside an accepted step, on the dense output,
// so that a surface is hit where it is and not one step late.
//
// Takes:   g(theta) (the event function composed with the step's interpolant), its values at both ends,
//          and how many interior samples to look at (to catch a surface entered and left within one step).
// Returns: the smallest theta in (0, 1] with g(theta) <= 0 to within `theta_tol`, or nothing.
// Method:  bracket by sampling, then the Illinois variant of regula falsi (Dowell & Jarratt 1971):
//          superlinear, and never leaves the bracket.
#pragma once

#include <cmath>
#include <optional>

namespace grtrace {

struct EventCrossing {
  double theta;  ///< step fraction of the crossing
  double value;  ///< g at theta (<= 0 up to the tolerance)
};

template <class G>
std::optional<EventCrossing> locate_first_crossing(const G& g, double g0, double g1, int interior_samples = 0,
                                                   double theta_tol = 1e-13) {
  if (!(g0 > 0.0)) return EventCrossing{0.0, g0};  // already inside at the start of the step
  double a = 0.0, ga = g0, b = 1.0, gb = g1;
  bool bracketed = false;
  const int pieces = interior_samples + 1;
  for (int j = 1; j <= pieces; ++j) {
    const double t = static_cast<double>(j) / pieces;
    const double gt = j == pieces ? g1 : g(t);
    if (gt <= 0.0 || !std::isfinite(gt)) {
      b = t;
      gb = gt;
      bracketed = true;
      break;
    }
    a = t;
    ga = gt;
  }
  if (!bracketed) return std::nullopt;
  if (!std::isfinite(gb)) {  // cannot interpolate through a non-finite value: bisect it away first
    for (int i = 0; i < 60 && !std::isfinite(gb); ++i) {
      const double m = 0.5 * (a + b);
      const double gm = g(m);
      if (std::isfinite(gm) && gm > 0.0) { a = m; ga = gm; }
      else { b = m; gb = gm; }
    }
    if (!std::isfinite(gb)) return EventCrossing{b, gb};
  }
  int side = 0;
  for (int it = 0; it < 100 && b - a > theta_tol; ++it) {
    double m = (a * gb - b * ga) / (gb - ga);
    if (!(m > a && m < b)) m = 0.5 * (a + b);
    const double gm = g(m);
    if (gm <= 0.0) {
      b = m;
      gb = gm;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = m;
      ga = gm;
      if (side == +1) gb *= 0.5;
      side = +1;
    }
    if (gm == 0.0) break;
  }
  return EventCrossing{b, gb};
}

}  // namespace grtrace
