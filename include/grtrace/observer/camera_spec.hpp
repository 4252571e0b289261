// grtrace/observer/camera_spec.hpp
// A camera for any metric from what a person states: where it is, which observer carries it (static or ZAMO,
// observer/observers.hpp), how fast it moves through that observer's frame, where it looks, which way is up,
// and the picture's size and field of view.
//
// Takes:   a metric policy and a CameraSpec: the position in the metric's chart, or (with spherical_position) in
//          spherical / Boyer-Lindquist coordinates (t, r, theta, phi) for any chart; velocity, look and up as
//          components along the observer's spatial axes, which are the chart's axes ((r, theta, phi) in a
//          spherical chart, (x, y, z) in a Cartesian one), or (r, theta, phi) when spherical_position is set.
//          With spherical_position the observer is also defined in the spherical chart (the static observer of its
//          t, the ZAMO normal to its t = const slices), so the same spec gives the same camera in every chart; theta
//          may be 0 or pi (on the axis: the camera is placed kAxisOffset = 1e-9 rad off it, where its frame is the
//          limit of those off the axis at its phi: metric/spherical_chart.hpp off_axis).
// Returns: the Camera (observer/camera.hpp), whose tetrad is built by Gram-Schmidt in the metric (tetrad.hpp).
// Refuses, with std::invalid_argument saying what to change and before any work: a non-finite position, a
//          camera on or inside the horizon, an observer that cannot exist there (static inside an ergosphere),
//          |velocity| >= 1, a zero look or up, up parallel to look, a size below one pixel, fov outside (0, 180).
#pragma once

#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/metric/spherical_chart.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/observer/tetrad.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace grtrace {

struct CameraSpec {
  Vec4 position{0.0, 200.0, 1.5707963267948966, 0.0};  ///< event in the metric's chart (default: r = 200 M)
  ObserverKind observer = ObserverKind::static_observer;
  Vec3 velocity = Vec3::Zero();  ///< 3-velocity (fraction of c) in the observer's frame
  Vec3 look{-1.0, 0.0, 0.0};     ///< in the observer's frame (default: radially inward, at the hole)
  Vec3 up{0.0, -1.0, 0.0};       ///< in the observer's frame (default: towards theta = 0, the north pole)
  int width = 1024, height = 1024;
  double fov_degrees = 90.0;
  /// true: `position` is (t, r, theta, phi) and the axes are r, theta, phi whatever the metric's chart (mapped
  /// through metric/metric_traits.hpp event_from_spherical / spherical_axes; Kerr-Schild cameras are placed so).
  bool spherical_position = false;
};

template <MetricPolicy M>
Camera make_camera(const M& metric, const CameraSpec& spec) {
  if (!spec.position.allFinite()) throw std::invalid_argument("camera: the position must be finite numbers");
  // A camera on the polar axis (theta = 0 or pi) is placed kAxisOffset off it (metric/spherical_chart.hpp).
  Vec4 spherical = spec.position;
  if (spec.spherical_position) spherical[2] = off_axis(spherical[2]);
  const Vec4 x = spec.spherical_position ? event_from_spherical(metric, spherical) : spec.position;
  if (const double rh = metric.horizon_radius(); rh > 0.0 && !(metric.radius(x) > rh))
    throw std::invalid_argument("camera: the position r = " + std::to_string(metric.radius(x)) +
                                " is on or inside the horizon (r = " + std::to_string(rh) + "); move the camera out");
  const ObserverFrame frame = spec.spherical_position
                                  ? observer_frame(metric, x, spec.observer, spherical_axes(metric, spherical),
                                                   jacobian_of_spherical(metric, spherical))
                                  : observer_frame(metric, x, spec.observer);
  const Tetrad tetrad =
      make_tetrad(metric.metric(x), frame.velocity(spec.velocity), frame.spatial(spec.look), frame.spatial(spec.up));
  return Camera(x, tetrad, spec.width, spec.height, spec.fov_degrees);
}

}  // namespace grtrace

namespace grtrace {

/// The look rule of a camera carried by a given 4-velocity (a flight along a worldline, observer/worldline.hpp):
/// look and up are components along the radial, polar and azimuthal axes (flight_look_axes) as the moving observer
/// sees them (each axis with its part along u removed, then orthonormalised: ObserverFrame(g, u, axes)), so "look at
/// the hole" (-1, 0, 0) stays at the hole all along the path while aberration and Doppler come from u itself.
struct CameraView {
  Vec3 look{-1.0, 0.0, 0.0};
  Vec3 up{0.0, -1.0, 0.0};
  int width = 1024, height = 1024;
  double fov_degrees = 90.0;
};

/// The axes a flight camera's look and up are read along, at the event x: in a spherical chart its coordinate
/// vectors d_r, d_theta, d_phi; in a Cartesian chart the embedding's unit radial, polar and azimuthal vectors at
/// the event's direction (spatial: no t part). The latter are regular through a horizon (a Kerr-Schild camera falls
/// through it), where the Boyer-Lindquist basis mapped into the chart is not (its d_r has a t part 2Mr/Delta). For
/// a radial fall the two give the same frame outside the horizon (the radial axis lies in the plane of d_t, d_r and
/// u either way; tests/render/flight_test.cpp).
template <MetricPolicy M>
std::array<Vec4, 3> flight_look_axes(const M& metric, const Vec4& x) {
  if constexpr (M::chart == Chart::spherical) {
    return {Vec4::Unit(1), Vec4::Unit(2), Vec4::Unit(3)};
  } else {
    double theta = 0.0, phi = 0.0;
    direction_angles(metric.to_cartesian(x), theta, phi);
    const SphericalBasis e = spherical_basis(theta, phi);
    auto spatial = [](const Vec3& v) { return Vec4(0.0, v[0], v[1], v[2]); };
    return {spatial(e.r), spatial(e.theta), spatial(e.phi)};
  }
}

/// The camera at event x moving with the future-directed unit timelike u, pointed by `view`.
/// Look and up are read along the moving observer's own axes. Where they have no component along the motion this
/// is make_camera's static observer boosted to u (make_camera reads look/up in the static frame; the two readings
/// differ only in a component along the motion, by the Lorentz factor): tests/render/flight_test.cpp checks both.
/// Throws std::invalid_argument (what to change) for a u that is not timelike and future-directed, a position on
/// or inside the metric's capture radius (horizon_radius(): the horizon itself in Schwarzschild-type charts, inside
/// it in Kerr-Schild, where a camera can look out from inside the black hole), a zero or degenerate look/up.
template <MetricPolicy M>
Camera make_moving_camera(const M& metric, const Vec4& x, const Vec4& u, const CameraView& view) {
  if (!x.allFinite() || !u.allFinite()) throw std::invalid_argument("camera: position and 4-velocity must be finite");
  if (const double rh = metric.horizon_radius(); rh > 0.0 && !(metric.radius(x) > rh))
    throw std::invalid_argument("camera: the position r = " + std::to_string(metric.radius(x)) +
                                " is on or inside the horizon (r = " + std::to_string(rh) + "); move the camera out");
  const Mat4 g = metric.metric(x);
  const ObserverFrame frame(g, u, flight_look_axes(metric, x));
  const Tetrad tetrad = make_tetrad(g, frame.e[0], frame.spatial(view.look), frame.spatial(view.up));
  return Camera(x, tetrad, view.width, view.height, view.fov_degrees);
}

}  // namespace grtrace
