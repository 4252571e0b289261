// grtrace/render/mirror_symmetry.hpp
// The mirror symmetries of a frame: when the spacetime, the scene and the camera are all unchanged by a reflection
// that maps the pixel grid onto itself, the pixels of one side are the mirror images of the other side's, and
// render_frame (render/frame.hpp) traces one half (or one quarter) of the frame and reflects the rest.
//
// Two reflections of a spherical chart (t, r, theta, phi) are used:
//   equator   theta -> pi - theta, k^theta -> -k^theta. The camera is on the equator (theta = pi / 2), its "up"
//             axis e_2 lies along d_theta and e_0, e_1, e_3 have no theta part: rows mirror, row <-> H - 1 - row.
//   meridian  phi -> 2 phi_c - phi, k^phi -> -k^phi (phi_c the camera's). Its "right" axis e_3 lies along d_phi
//             and e_0, e_1, e_2 have no phi part: columns mirror, col <-> W - 1 - col.
// Each is used only when it maps the metric to itself (metric traits equator_mirror_symmetric /
// meridian_mirror_symmetric, metric/metric_traits.hpp), every object of the scene (the object traits of the same
// names, scene/scene_object.hpp) and the camera (its event and tetrad up to e_a -> -e_a for the flipped axis,
// checked to 1e-12 of each component's size in the metric). The sky and horizon painters and the objects' colours
// need not be symmetric: only where the light goes is mirrored, each pixel is coloured at its own end.
//
// Why it is exact: the pixel (col, H - 1 - row) starts with the reflected momentum of (col, row) (the camera's
// pixel directions are symmetric about the centre up to one rounding of the pixel coordinate), and a reflection
// that maps the metric to itself maps geodesics to geodesics; so its ray is the reflection of the other's, and so
// is every event on it. The frame with mirrors equals the frame without them to the integration's tolerance
// (tests/render/mirror_symmetry_test.cpp).
#pragma once

#include "grtrace/core/sky_direction.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace grtrace {

/// Which reflections a frame has (see the top of this file).
struct FrameMirrors {
  bool equator = false;   ///< rows mirror: theta -> pi - theta
  bool meridian = false;  ///< columns mirror: phi -> 2 phi_c - phi
  double camera_phi = 0.0;  ///< phi_c, the plane of the meridian reflection

  bool any() const { return equator || meridian; }
  /// "equator", "meridian", "equator,meridian" or "none" (the image header's `mirrors`).
  std::string names() const {
    if (equator && meridian) return "equator,meridian";
    return equator ? "equator" : meridian ? "meridian" : "none";
  }
};

namespace detail {

/// True when the camera's tetrad maps to itself under the reflection of coordinate `axis` (2: theta, 3: phi), with
/// e_flipped -> -e_flipped and the other three unchanged: the reflected components of each vector, scaled by
/// sqrt|g_mu mu| at the camera, within 1e-12 of the expected ones.
template <MetricPolicy M>
bool tetrad_mirrors(const M& metric, const Camera& camera, int axis, int flipped) {
  const Mat4 g = metric.metric(camera.position());
  for (int a = 0; a < 4; ++a) {
    const Vec4& e = camera.tetrad().e[static_cast<std::size_t>(a)];
    const double sign = a == flipped ? -1.0 : 1.0;
    for (int mu = 0; mu < 4; ++mu) {
      const double reflected = mu == axis ? -e[mu] : e[mu];
      if (!(std::abs(reflected - sign * e[mu]) * std::sqrt(std::abs(g(mu, mu))) <= 1e-12)) return false;
    }
  }
  return true;
}

}  // namespace detail

/// The reflections of the frame a tracer of metric type M and scene type SceneT draws from `camera` (see the top
/// of this file). Takes the metric for the camera's check (its components at the camera).
template <MetricPolicy M, class SceneT>
FrameMirrors frame_mirrors(const M& metric, const Camera& camera) {
  FrameMirrors m;
  m.camera_phi = camera.position()[3];
  if constexpr (M::chart == Chart::spherical) {
    if constexpr (metric_is_equator_mirror_symmetric<M>() &&
                  every_object_of<SceneT>([]<class O>() { return object_is_equator_mirror_symmetric<O>(); }))
      m.equator = std::abs(camera.position()[2] - std::numbers::pi / 2) <= 1e-14 &&
                  detail::tetrad_mirrors(metric, camera, 2, 2);
    if constexpr (metric_is_meridian_mirror_symmetric<M>() &&
                  every_object_of<SceneT>([]<class O>() { return object_is_meridian_mirror_symmetric<O>(); }))
      m.meridian = detail::tetrad_mirrors(metric, camera, 3, 3);
  }
  return m;
}

/// Reflects an outcome in the equatorial plane, in place: direction and end state reflected, the rest equal.
inline void reflect_in_equator(RayOutcome& o) {
  o.where.theta = std::numbers::pi - o.where.theta;
  o.state[2] = std::numbers::pi - o.state[2];
  o.state[6] = -o.state[6];
}

/// Reflects an outcome in the meridian plane phi = phi_c, in place: phi -> 2 phi_c - phi (the direction's brought
/// back into (-pi, pi], as every tracer reports it), k^phi -> -k^phi.
inline void reflect_in_meridian(RayOutcome& o, double phi_c) {
  o.where.phi = azimuth_in_range(2.0 * phi_c - o.where.phi);
  o.state[3] = 2.0 * phi_c - o.state[3];
  o.state[7] = -o.state[7];
}

/// The outcome of the ray reflected in the equatorial plane (reflect_in_equator on a copy).
inline RayOutcome reflected_in_equator(RayOutcome o) {
  reflect_in_equator(o);
  return o;
}

/// The outcome of the ray reflected in the meridian plane phi = phi_c (reflect_in_meridian on a copy).
inline RayOutcome reflected_in_meridian(RayOutcome o, double phi_c) {
  reflect_in_meridian(o, phi_c);
  return o;
}

}  // namespace grtrace
