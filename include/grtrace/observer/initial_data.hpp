// grtrace/observer/initial_data.hpp
// Initial states for single geodesics in spherical charts (t, r, theta, phi), for diagonal metrics.
// Cameras (pixel -> null momentum through a tetrad) live in observer/camera.hpp.
#pragma once

#include "grtrace/metric/schwarzschild_lapse.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/schwarzschild.hpp"

#include <cmath>
#include <numbers>
#include <optional>

namespace grtrace {

/// Solves g(k, k) = norm for k^t > 0 given the spatial components (diagonal metric).
/// norm = 0 gives a null vector, norm = 1 a timelike 4-velocity. Nothing when no real k^t exists
/// (e.g. a spatial velocity faster than light for norm = 1).
template <MetricPolicy M>
std::optional<Vec4> complete_time_component(const M& metric, const Vec4& x, const Vec4& k) {
  return complete_time_component(metric, x, k, 0.0);
}

template <MetricPolicy M>
std::optional<Vec4> complete_time_component(const M& metric, const Vec4& x, const Vec4& k_spatial, double norm) {
  const Mat4 g = metric.metric(x);
  Vec4 k = k_spatial;
  k[0] = 0.0;
  const double spatial = k.dot(g * k);  // <= 0 for signature (+,-,-,-)
  const double kt2 = (norm - spatial) / g(0, 0);
  if (!(g(0, 0) > 0.0) || !(kt2 >= 0.0) || !std::isfinite(kt2)) return std::nullopt;
  k[0] = std::sqrt(kt2);
  return k;
}

/// A photon with energy 1 and impact parameter b in the equatorial plane at radius r, moving inward,
/// starting at phi = 0. Schwarzschild (mass may be 0 for flat space).
/// Assumes the radius is outside any turning point (1 - (1 - 2M/r) b^2 / r^2 > 0).
inline GeodesicState incoming_photon(double b, double r, double mass = 1.0) {
  const double f = schwarzschild_f(r, mass);
  const Vec4 x(0.0, r, std::numbers::pi / 2.0, 0.0);
  const Vec4 k(1.0 / f, -std::sqrt(1.0 - f * b * b / (r * r)), 0.0, b / (r * r));
  return make_state(x, k);
}

}  // namespace grtrace
