// grtrace/metric/spherical_chart.hpp
// Helpers shared by metrics written in spherical coordinates (t, r, theta, phi).
#pragma once

#include "grtrace/core/types.hpp"

#include <cmath>

namespace grtrace {

/// Euclidean embedding of (r, theta, phi): the point (r sin th cos ph, r sin th sin ph, r cos th).
inline Vec3 spherical_to_cartesian(const Vec4& x) {
  const double r = x[1], st = std::sin(x[2]);
  return {r * st * std::cos(x[3]), r * st * std::sin(x[3]), r * std::cos(x[2])};
}

}  // namespace grtrace
