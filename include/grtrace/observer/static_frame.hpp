// grtrace/observer/static_frame.hpp
// The local static orthonormal frame: hat e_t = d_t / sqrt(g_tt) and the chart's spatial axes orthonormalised
// against it (for a diagonal metric in (t, r, theta, phi): hat e_r = d_r / sqrt(-g_rr), and so on). Cameras are
// given their velocity, look and up directions in this frame (physicists think in it). It is the static case
// of ObserverFrame (observer/observers.hpp), which also has the ZAMO's frame.
#pragma once

#include "grtrace/observer/observers.hpp"

#include <stdexcept>

namespace grtrace {

struct StaticFrame : ObserverFrame {
  /// Takes g at the event; refuses g_tt <= 0 (at or inside a horizon, or inside an ergosphere).
  explicit StaticFrame(const Mat4& g) : ObserverFrame(g, checked_velocity(g)) {}

 private:
  static Vec4 checked_velocity(const Mat4& g) {
    if (auto u = static_velocity(g)) return *u;
    throw std::invalid_argument("static frame: g_tt <= 0 (at or inside a horizon)");
  }
};

}  // namespace grtrace
