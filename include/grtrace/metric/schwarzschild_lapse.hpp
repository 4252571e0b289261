// grtrace/metric/schwarzschild_lapse.hpp
// f(r) = 1 - 2M/r, the one function of Schwarzschild spacetime: g_tt = f, g_rr = -1/f, the squared lapse of the
// static observers, zero on the horizon r = 2M. Every place that needs it calls this, in any scalar type (double,
// or the dual numbers of metric/dual.hpp for automatic differentiation).
#pragma once

#include "grtrace/core/host_device.hpp"

namespace grtrace {

template <class S>
constexpr GRTRACE_HD S schwarzschild_f(const S& r, double mass) {
  return 1.0 - 2.0 * mass / r;
}

}  // namespace grtrace
