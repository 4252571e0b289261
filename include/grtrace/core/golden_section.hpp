// grtrace/core/golden_section.hpp
// The library's one search for an extremum on a bracket: golden-section search (Kiefer 1953). Used for a static
// metric's photon sphere (the minimum of r^2 / A), a flow's ISCO (the minimum of the circular orbits' energy), a
// torus's cusp (the maximum of its potential on the equator), and the lowest point of a medium's boundary along a
// step (a layer thinner than the step, trace/emission_system.hpp).
//
// Takes:   f, a bracket [lo, hi] on which it is unimodal, when the bracket is narrow enough
//          (GoldenSectionWidth: hi - lo <= relative |hi| + absolute), at most max_steps steps, and optionally
//          `stop(x, value)`: the search ends at the first probe it accepts.
// Returns: GoldenSection: the probe `stop` accepted, or the final bracket's midpoint (f not evaluated there).
// Method:  two interior probes at the golden ratio's points; each step keeps the part of the bracket around the
//          better one and evaluates f once (the other probe is reused): the bracket shrinks by 0.618 a step. A NaN
//          value counts as worse than any number, so the bracket moves away from where f cannot be evaluated (inside
//          a horizon, beyond the last timelike circular orbit).
// Assumes: f unimodal on the bracket (else: a local extremum).
#pragma once

#include "grtrace/core/host_device.hpp"

#include <cmath>
#include <limits>

namespace grtrace {

/// When a golden-section bracket is narrow enough: hi - lo <= relative |hi| + absolute.
struct GoldenSectionWidth {
  double relative = 0.0;
  double absolute = 0.0;
};

/// Where a golden-section search ended.
struct GoldenSection {
  double x;      ///< the probe `stop` accepted, else the final bracket's midpoint
  double value;  ///< f at the accepted probe (NaN at the midpoint: not evaluated)
  bool stopped;  ///< `stop` accepted a probe
};

namespace golden_detail {
struct NeverStop {
  GRTRACE_HD bool operator()(double, double) const { return false; }
};
/// a better than b for a search towards the largest value (NaN is worse than anything).
GRTRACE_HD inline bool better(double a, double b) { return a > b || (std::isnan(b) && !std::isnan(a)); }
}  // namespace golden_detail

/// Towards the largest value of f on [lo, hi] (see the top of this file).
template <class F, class Stop = golden_detail::NeverStop>
GRTRACE_HD GoldenSection golden_section_maximum(const F& f, double lo, double hi, GoldenSectionWidth width,
                                                int max_steps = 200, const Stop& stop = {}) {
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double t1 = hi - golden * (hi - lo), t2 = lo + golden * (hi - lo), f1 = f(t1), f2 = f(t2);
  for (int i = 0; i < max_steps && hi - lo > width.relative * std::abs(hi) + width.absolute; ++i) {
    if (stop(t1, f1)) return {t1, f1, true};
    if (stop(t2, f2)) return {t2, f2, true};
    if (golden_detail::better(f1, f2)) {  // the largest lies in [lo, t2]
      hi = t2;
      t2 = t1;
      f2 = f1;
      t1 = hi - golden * (hi - lo);
      f1 = f(t1);
    } else {  // in [t1, hi]
      lo = t1;
      t1 = t2;
      f1 = f2;
      t2 = lo + golden * (hi - lo);
      f2 = f(t2);
    }
  }
  return {0.5 * (lo + hi), std::numeric_limits<double>::quiet_NaN(), false};
}

/// Towards the smallest value of f on [lo, hi]: golden_section_maximum of -f (NaN still the worst); the value
/// returned is f's.
template <class F>
GRTRACE_HD GoldenSection golden_section_minimum(const F& f, double lo, double hi, GoldenSectionWidth width,
                                                int max_steps = 200) {
  GoldenSection s = golden_section_maximum([&](double x) { return -f(x); }, lo, hi, width, max_steps);
  s.value = -s.value;
  return s;
}

}  // namespace grtrace
