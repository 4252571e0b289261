// grtrace/integrate/dense_output.hpp
// Cubic Hermite interpolation on one step: the continuous extension for tableaux without their own.
// Takes the step's end states and derivatives; order 3, C^1 across steps (Hairer, Norsett & Wanner I, II.6).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"

namespace grtrace {

template <int N>
GRTRACE_HD Vector<N> hermite_interpolate(const Vector<N>& y0, const Vector<N>& f0, const Vector<N>& y1,
                                         const Vector<N>& f1, double h, double theta) {
  const double t2 = theta * theta, t3 = t2 * theta;
  const double h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + theta, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
  return h00 * y0 + (h10 * h) * f0 + h01 * y1 + (h11 * h) * f1;
}

}  // namespace grtrace
