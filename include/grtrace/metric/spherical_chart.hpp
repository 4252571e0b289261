// grtrace/metric/spherical_chart.hpp
// Helpers shared by metrics written in spherical coordinates (t, r, theta, phi).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace grtrace {

/// Unit vectors of the spherical chart at (theta, phi), as Cartesian vectors of the Euclidean embedding.
struct SphericalBasis {
  Vec3 r, theta, phi;
  double sin_theta;
};

inline GRTRACE_HD SphericalBasis spherical_basis(double theta, double phi) {
  const double st = std::sin(theta), ct = std::cos(theta), sp = std::sin(phi), cp = std::cos(phi);
  return {Vec3(st * cp, st * sp, ct), Vec3(ct * cp, ct * sp, -st), Vec3(-sp, cp, 0.0), st};
}

/// The part of dx/dlambda across the radial direction, r k^theta e_theta + r sin(theta) k^phi e_phi, in the
/// embedding (its length times r is the total angular momentum r^2 |dOmega/dlambda|).
inline GRTRACE_HD Vec3 embedded_tangential_velocity(const GeodesicState& y, const SphericalBasis& e) {
  return y[1] * y[6] * e.theta + y[1] * e.sin_theta * y[7] * e.phi;
}

/// dx/dlambda of a state (t, r, theta, phi | k) as a Cartesian vector of the embedding (seed eq. 7).
inline GRTRACE_HD Vec3 embedded_velocity(const GeodesicState& y, const SphericalBasis& e) {
  return y[5] * e.r + embedded_tangential_velocity(y, e);
}

/// (theta, phi) of a nonzero Cartesian direction: theta in [0, pi], phi in (-pi, pi] (seed eq. 8).
inline GRTRACE_HD void direction_angles(const Vec3& d, double& theta, double& phi) {
  theta = std::acos(std::clamp(d.z() / d.norm(), -1.0, 1.0));
  phi = std::atan2(d.y(), d.x());
}

/// How far from the polar axis an observer asked for on it is placed: a spherical chart's theta and phi do not name a
/// direction there (d_phi vanishes, d_theta depends on phi), so no frame can be written on the axis in them. At 1e-9
/// rad the chart is regular to double precision, the frame is the continuous limit of those off the axis at the
/// given phi (look and up keep their meaning), and the camera moves by 1e-9 r: its rays' directions change by about
/// that angle, below every tolerance the tools offer (a test compares with a camera 1e-6 rad off the axis). Every ray
/// of such a camera passes the axis closer than the reduced Kerr tracer's 1e-8 rad, so that tracer draws the axis
/// camera itself (L_z = 0 for every ray).
inline constexpr double kAxisOffset = 1e-9;

/// theta moved off the polar axis by kAxisOffset where it lies on it or nearer (theta in [0, pi]).
inline GRTRACE_HD double off_axis(double theta) {
  // Compared by value (std::clamp takes references, which device code cannot form to a host constant).
  const double low = kAxisOffset, high = std::numbers::pi - kAxisOffset;
  return theta < low ? low : theta > high ? high : theta;
}

/// Euclidean embedding of (r, theta, phi): the point (r sin th cos ph, r sin th sin ph, r cos th).
inline GRTRACE_HD Vec3 spherical_to_cartesian(const Vec4& x) {
  const double r = x[1], st = std::sin(x[2]);
  return {r * st * std::cos(x[3]), r * st * std::sin(x[3]), r * std::cos(x[2])};
}

/// The state (t, r, theta, phi | k^t, k^r, k^theta, k^phi) of an event and tangent given in the Cartesian
/// embedding: the inverse of (spherical_to_cartesian, embedded_velocity). Assumes the point is off the polar axis.
inline GRTRACE_HD GeodesicState spherical_state_from_cartesian(double t, const Vec3& p, double kt, const Vec3& v) {
  const double r = p.norm();
  const double theta = std::acos(std::clamp(p.z() / r, -1.0, 1.0)), phi = std::atan2(p.y(), p.x());
  const SphericalBasis e = spherical_basis(theta, phi);
  GeodesicState y;
  y << t, r, theta, phi, kt, v.dot(e.r), v.dot(e.theta) / r, v.dot(e.phi) / (r * e.sin_theta);
  return y;
}

}  // namespace grtrace
