// grtrace/observer/timelike_start.hpp
// Where a massive body (a camera on a flight, a planet) starts: an event and a unit timelike 4-velocity
// (g(u, u) = 1, future-directed) in any metric policy. Positions and velocities are stated in spherical coordinates
// (t, r, theta, phi) (Boyer-Lindquist for Kerr) whatever the metric's chart, and mapped into it
// (metric/metric_traits.hpp event_from_spherical, jacobian_of_spherical: a Kerr-Schild camera falls through the
// horizon in its own chart). circular_orbit_start needs a spherical chart.
//
//   timelike_velocity      the 4-velocity with given dr/dtau, dtheta/dtau, dphi/dtau (solves for u^t, cross
//                          terms g_{t i} included, so Kerr's frame dragging is accounted for)
//   orbit_start            a body at (r, theta, phi) with dr/dtau and dphi/dtau given (dtheta/dtau = 0)
//   seed_orbit_start       the seed report's test orbit (sec. 3.2.1): r = 100 M, dphi/dtau = 0.00075 / M, at rest
//                          radially, equatorial: a precessing ellipse between ~39 M and 100 M
//   circular_orbit_start   the circular geodesic of radius r (metric/circular_orbits.hpp), either sense
//   radial_infall_start    released from rest (the static observer's 4-velocity) at (r, theta, phi)
// Each refuses, with std::invalid_argument saying what to change, a start where no such 4-velocity exists: inside
// an ergosphere or horizon (g_tt <= 0), a speed >= c, no circular orbit at that radius (inside the photon orbit).
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/metric/circular_orbits.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/metric/spherical_chart.hpp"

#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

namespace grtrace {

/// An event and a unit timelike 4-velocity: the (x, u) state a timelike geodesic is integrated from.
struct TimelikeStart {
  Vec4 x = Vec4::Zero();
  Vec4 u = Vec4::Zero();
  GeodesicState state() const { return make_state(x, u); }
};

/// The future-directed u with u^i = spatial^i and g(u, u) = 1 for the metric g at an event, or nothing where none
/// exists.
/// Takes:   g at the event, the spatial components (dx^i/dtau).
/// Method:  g_tt (u^t)^2 + 2 (g_ti u^i) u^t + g_ij u^i u^j = 1, the root with u^t > 0; assumes g_tt > 0 (outside
///          ergospheres and horizons, where d_t is timelike and the larger root is the future one).
inline std::optional<Vec4> timelike_velocity(const Mat4& g, const Vec3& spatial) {
  if (!g.allFinite() || !spatial.allFinite() || !(g(0, 0) > 0.0)) return std::nullopt;
  Vec4 v(0.0, spatial[0], spatial[1], spatial[2]);
  const double b = g.row(0).dot(v);   // g_ti u^i
  const double c = v.dot(g * v) - 1.0;  // g_ij u^i u^j - 1 (< 0 for every subluminal spatial part)
  const double disc = b * b - g(0, 0) * c;
  if (!(disc > 0.0)) return std::nullopt;
  v[0] = (-b + std::sqrt(disc)) / g(0, 0);
  if (!(v[0] > 0.0)) return std::nullopt;
  return v;
}

/// The same at the event x of a metric.
template <MetricPolicy M>
std::optional<Vec4> timelike_velocity(const M& metric, const Vec4& x, const Vec3& spatial) {
  return timelike_velocity(metric.metric(x), spatial);
}

/// A body at spherical (r, theta, phi) (radians) moving with dr/dtau and dphi/dtau; throws where no timelike u
/// exists. In a chart that is not spherical the event and u are mapped into it: u is found in the spherical chart's
/// metric J^T g J (J = d(chart)/d(spherical)) and pushed forward, u = J u_s.
template <MetricPolicy M>
TimelikeStart orbit_start(const M& metric, double r, double theta, double phi, double dr_dtau, double dphi_dtau) {
  // On the polar axis (theta = 0 or pi) the start is placed kAxisOffset off it (metric/spherical_chart.hpp).
  const Vec4 xs(0.0, r, std::isfinite(theta) ? off_axis(theta) : theta, phi);
  if (!xs.allFinite() || !std::isfinite(dr_dtau) || !std::isfinite(dphi_dtau))
    throw std::invalid_argument("timelike start: position and velocities must be finite numbers");
  const Vec4 x = event_from_spherical(metric, xs);
  if (const double rh = metric.horizon_radius(); rh > 0.0 && !(metric.radius(x) > rh))
    throw std::invalid_argument("timelike start: r = " + std::to_string(r) + " is on or inside the horizon (r = " +
                                std::to_string(rh) + "); start further out");
  std::optional<Vec4> u;
  if constexpr (M::chart == Chart::spherical) {
    u = timelike_velocity(metric, x, Vec3(dr_dtau, 0.0, dphi_dtau));
  } else {
    const Mat4 j = jacobian_of_spherical(metric, xs);
    if (auto us = timelike_velocity(Mat4(j.transpose() * metric.metric(x) * j), Vec3(dr_dtau, 0.0, dphi_dtau)))
      u = j * *us;
  }
  if (!u)
    throw std::invalid_argument("timelike start: no timelike 4-velocity with dr/dtau = " + std::to_string(dr_dtau) +
                                " and dphi/dtau = " + std::to_string(dphi_dtau) + " at r = " + std::to_string(r) +
                                " (faster than light there, or inside an ergosphere); lower the velocities");
  return {x, *u};
}

/// The seed report's orbit for a hole of the given mass: r = 100 M, equatorial, phi = 0, dphi/dtau = 0.00075 / M.
template <MetricPolicy M>
TimelikeStart seed_orbit_start(const M& metric, double mass = 1.0) {
  return orbit_start(metric, 100.0 * mass, std::numbers::pi / 2.0, 0.0, 0.0, 0.00075 / mass);
}

/// The circular geodesic through (r, pi/2, phi) turning towards +phi (sense +1) or -phi (-1).
template <MetricPolicy M>
  requires(M::chart == Chart::spherical)
TimelikeStart circular_orbit_start(const M& metric, double r, int sense = +1, double phi = 0.0) {
  const auto u = circular_orbit_velocity(metric, r, sense);
  if (!u)
    throw std::invalid_argument("circular orbit: no timelike circular orbit at r = " + std::to_string(r) +
                                " (inside the photon orbit, or no stationary observer there); choose a larger radius");
  return {Vec4(0.0, r, std::numbers::pi / 2.0, phi), *u};
}

/// Released from rest at (r, theta, phi): the static observer's 4-velocity; throws where g_tt <= 0.
template <MetricPolicy M>
TimelikeStart radial_infall_start(const M& metric, double r, double theta = std::numbers::pi / 2.0, double phi = 0.0) {
  return orbit_start(metric, r, theta, phi, 0.0, 0.0);
}

}  // namespace grtrace
