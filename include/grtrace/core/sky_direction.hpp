// grtrace/core/sky_direction.hpp
// A direction on the celestial sphere, (theta, phi), in the Euclidean embedding of the metric's chart: where an
// escaped ray ends up, or where on a sphere a hit lies. Every tracer reports it the same way.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/spherical_chart.hpp"

#include <Eigen/Geometry>  // cross product in angular_distance

#include <cmath>
#include <numbers>

namespace grtrace {

struct SkyDirection {
  double theta;  ///< polar angle, [0, pi]
  double phi;    ///< azimuth, (-pi, pi]
};

/// An azimuth brought into (-pi, pi], the range of SkyDirection::phi (a spherical chart's phi keeps counting
/// turns; a reflection phi -> 2 phi_c - phi leaves the range by up to one turn). One turn is added or taken off
/// without std::remainder's cost, the usual case; anything farther out is reduced exactly by std::remainder.
inline GRTRACE_HD double azimuth_in_range(double phi) {
  constexpr double pi = std::numbers::pi;
  if (phi > pi) phi -= 2.0 * pi;
  else if (phi <= -pi) phi += 2.0 * pi;
  if (!(phi > -pi && phi <= pi)) {
    phi = std::remainder(phi, 2.0 * pi);
    if (phi == -pi) phi = pi;
  }
  return phi;
}

/// The sky direction of a nonzero Cartesian vector (a zero vector gives theta = NaN: callers never pass one).
inline GRTRACE_HD SkyDirection sky_direction_of(const Vec3& d) {
  SkyDirection s{};
  direction_angles(d, s.theta, s.phi);
  return s;
}

/// Unit Cartesian vector of a sky direction.
inline GRTRACE_HD Vec3 unit_vector_of(const SkyDirection& s) {
  const double st = std::sin(s.theta);
  return {st * std::cos(s.phi), st * std::sin(s.phi), std::cos(s.theta)};
}

/// Angle between two directions on the sky (radians), accurate for small angles (atan2 of |p x q| and p.q).
inline GRTRACE_HD double angular_distance(const SkyDirection& a, const SkyDirection& b) {
  const Vec3 p = unit_vector_of(a), q = unit_vector_of(b);
  return std::atan2(p.cross(q).norm(), p.dot(q));
}

}  // namespace grtrace
