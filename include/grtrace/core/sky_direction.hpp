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

/// Below this angle from the equatorial plane (radians) a point counts as on it, in the count of a ray's crossings
/// of the plane (RayOutcome::order): a hit located on a thin disk ends within round-off of the plane, on either
/// side, and a camera in the plane starts on it; neither is a crossing.
inline constexpr double kOnEquatorialPlane = 1e-9;

/// 1 when an escaped ray, last seen at `latitude_at_end` (radians above the equatorial plane: its end on the sky
/// sphere), is seen in a direction on the other side of the plane: it crossed the plane once more beyond the sphere,
/// where it runs nearly straight (at most once). 0 otherwise, and for an end on the plane. So a ray's order counts
/// its crossings up to where it is seen (the direction at infinity, or the sphere's point: AngleCorrection).
inline GRTRACE_HD int crossed_beyond_sphere(double latitude_at_end, const SkyDirection& seen) {
  constexpr double half_pi = 1.5707963267948966;
  return std::abs(latitude_at_end) > kOnEquatorialPlane && latitude_at_end * (half_pi - seen.theta) < 0.0 ? 1 : 0;
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
