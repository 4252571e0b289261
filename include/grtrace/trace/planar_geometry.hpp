// grtrace/trace/planar_geometry.hpp
// A ray of a static, spherically symmetric spacetime seen in its own orbital plane (metric/static_spherical.hpp):
// the plane through the centre spanned by the radial direction n of its start and its direction of travel t.
// Its path is r(psi) with psi the angle swept from n towards t; what happens to it depends only on delta, the angle
// between its direction of travel and n in the static frame at its start (aberration for a moving camera is
// already in the pixel's momentum).
#pragma once

#include "grtrace/core/rounding.hpp"
#include "grtrace/core/sin_cos.hpp"
#include "grtrace/core/sky_direction.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/spherical_chart.hpp"
#include "grtrace/metric/static_spherical.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace grtrace {

/// Where a ray from the camera goes, seen in its own orbital plane.
struct PlanarGeometry {
  Vec3 radial;      ///< unit vector from the centre to the start (Cartesian embedding)
  Vec3 tangential;  ///< unit vector in the orbital plane, perpendicular to radial, along the motion
  double delta;     ///< angle between the direction of travel and `radial`, in the static frame, [0, pi]
  double impact;    ///< b = L / E
  double angular_momentum;  ///< L = r^2 dpsi/dlambda (>= 0: psi grows along the ray)

  /// The embedding's unit vector at swept angle psi, and the unit vector along increasing psi there.
  Vec3 direction_at(double psi) const {
    const SinCos sc = sin_cos(psi);  // inline fdlibm: one per pixel of a table-traced frame
    return sc.cos * radial + sc.sin * tangential;
  }
  Vec3 sweep_direction_at(double psi) const {
    const SinCos sc = sin_cos(psi);
    return -sc.sin * radial + sc.cos * tangential;
  }
};

/// The static frame at radius r: A(r) = g_tt and the length sqrt(B(r)) = sqrt(-g_rr) of a unit of dr (the static
/// observer's radial component of k is sqrt(B) k^r). Shared by all the pixels of a frame (they start at the camera).
struct StaticRadialFrame {
  double lapse_squared;  ///< A(r)
  double radial_length;  ///< sqrt(B(r)) (1 / sqrt(A(r)) for f(r) metrics)
};

template <StaticSphericalMetric M>
StaticRadialFrame static_radial_frame(const M& metric, double r) {
  const double a = metric.lapse_squared(r);
  if constexpr (HasRadialScale<M>) return {a, std::sqrt(metric.radial_scale_squared(r))};
  else return {a, 1.0 / std::sqrt(a)};
}

/// Reads the planar geometry of a ray from its state (spherical chart, either time direction).
/// `e` is the spherical basis at the ray's start, spherical_basis(y[2], y[3]), and `f` the static frame at its
/// radius, static_radial_frame(metric, y[1]) (a frame's pixels share both).
inline PlanarGeometry planar_geometry(const GeodesicState& y, const SphericalBasis& e, const StaticRadialFrame& f) {
  const double r = y[1];
  const double a = f.lapse_squared;
  const Vec3 tangential = embedded_tangential_velocity(y, e);  // orthonormal-frame tangential part of dx/dl
  const double k_radial = f.radial_length * y[5];                // orthonormal radial part
  const double t_norm = tangential.norm();
  PlanarGeometry g;
  g.radial = e.r;
  g.tangential = t_norm > 0.0 ? Vec3(tangential / t_norm) : e.theta;
  g.delta = std::atan2(t_norm, k_radial);
  g.impact = std::abs(r * t_norm / (a * y[4]));
  g.angular_momentum = r * t_norm;
  return g;
}

template <StaticSphericalMetric M>
PlanarGeometry planar_geometry(const M& metric, const GeodesicState& y, const SphericalBasis& e) {
  return planar_geometry(y, e, static_radial_frame(metric, y[1]));
}

template <StaticSphericalMetric M>
PlanarGeometry planar_geometry(const M& metric, const GeodesicState& y) {
  return planar_geometry(metric, y, spherical_basis(y[2], y[3]));
}

/// The swept angle psi_0 in (0, pi] at which the ray first crosses the equatorial plane after its start; it crosses
/// again at psi_0 + k pi, since the plane's height z(psi) = n_z cos psi + t_z sin psi = R cos(psi - alpha) changes
/// sign every half turn. A start on the plane (within kOnEquatorialPlane: a camera in it) is not a crossing. NaN
/// when the ray's plane is the equatorial plane itself (it runs inside it: no crossing).
inline double first_equator_crossing(const PlanarGeometry& g) {
  constexpr double pi = std::numbers::pi;
  const double nz = g.radial.z(), tz = g.tangential.z();
  if (!(std::hypot(nz, tz) > 1e-12)) return std::numeric_limits<double>::quiet_NaN();
  double psi = std::atan2(tz, nz) + 0.5 * pi;
  psi -= pi * static_cast<double>(floor_to_long(psi / pi));  // the first zero in [0, pi)
  // The start itself is no crossing, nor is a zero within round-off of it (a camera in the plane).
  if (psi <= 0.0 || (std::abs(nz) <= kOnEquatorialPlane && psi < 0.5 * pi)) psi += pi;
  return psi;
}

/// The ray's crossings of the equatorial plane up to the swept angle `sweep`, where its direction in the embedding
/// is `seen` (g.direction_at(sweep), which the caller has: its sky direction): the plane's height along the ray,
/// z(psi) = R cos(psi - alpha), has one zero in each half turn, so floor(sweep / pi) of them, and one more where the
/// last, partial half turn ends on the other side, z(m pi) = (-1)^m n_z against seen.z(). No trigonometry (the
/// first crossing's atan2 would cost a table-traced sky frame a tenth of its time). A start on the plane is not a
/// crossing; a ray in the plane has none. The order of the image the ray ends on (RayOutcome::order).
inline int equator_crossings_to(const PlanarGeometry& g, double sweep, const Vec3& seen) {
  const double nz = g.radial.z(), tz = g.tangential.z();
  if (!(nz * nz + tz * tz > 1e-24)) return 0;
  const long m = floor_to_long(sweep / std::numbers::pi);
  const double start = std::abs(nz) > kOnEquatorialPlane ? (m % 2 == 0 ? nz : -nz) : 0.0;
  return static_cast<int>(m) + (start * seen.z() < 0.0 ? 1 : 0);
}

/// The direction at angle `sweep` from `radial` in the plane of the ray.
inline SkyDirection rotate_in_plane(const PlanarGeometry& g, double sweep) {
  return sky_direction_of(g.direction_at(sweep));
}

}  // namespace grtrace
