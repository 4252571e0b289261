// examples/scenes/glowing_star.hpp
// A scene object written by its user (grtrace/scene/scene_object.hpp lists what an object provides): a star,
// i.e. a sphere of given radius at rest at a fixed point of a static spacetime in a spherical chart, glowing like
// a blackbody whose colour and brightness follow the redshift of each ray that reaches it. Faint meridians and a
// bright equator band (in the star's own axes) show which part of it an image shows, so its secondary image,
// seen around the far side of the hole, is recognisable.
// Its surface and its matter's motion are marked GRTRACE_HD (grtrace/core/host_device.hpp): callable where the rays
// are traced, a CPU or a GPU (star_beside_hole_gpu.cu); its colour is the host's (shading happens there).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/spherical_chart.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/scene/colour_maps.hpp"
#include "grtrace/scene/scene_object.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <numbers>
#include <string_view>

struct GlowingStar {
  static constexpr std::string_view kind = "star";
  static constexpr int interior_samples = 4;  // small next to a step far from the hole: look inside each step
  grtrace::Vec3 centre{-12.0, 6.0, 0.0};      // Cartesian embedding of the chart (x, y, z), in units of M
  double radius = 1.5;
  double temperature = 6500.0;                 // kelvin, as emitted

  GRTRACE_HD double operator()(const grtrace::GeodesicState& y) const {
    return (grtrace::spherical_to_cartesian(y.head<4>()) - centre).norm() - radius;
  }

  /// The star is static: its matter moves along the Killing time (observer/observers.hpp).
  template <grtrace::MetricPolicy M>
  GRTRACE_HD grtrace::Vec4 emitter_velocity(const M& metric, const grtrace::Vec4& x) const {
    return grtrace::rest_emitter_velocity(metric, x);
  }

  grtrace::Rgb colour(const grtrace::SurfaceHit& hit) const {
    const grtrace::Vec3 n = (grtrace::spherical_to_cartesian(hit.position()) - centre).normalized();
    const double lon = std::atan2(n.y(), n.x()), lat = std::asin(std::clamp(n.z(), -1.0, 1.0));
    const bool line = std::abs(std::remainder(lon, std::numbers::pi / 6.0)) < 0.05 || std::abs(lat) < 0.08;
    const double g = hit.redshift;
    const auto shade = static_cast<float>((line ? 1.6 : 1.0) * std::min(1.5, 0.8 * g * g * g * g));
    const grtrace::Rgb c = grtrace::blackbody_colour(g * temperature);
    return {c[0] * shade, c[1] * shade, c[2] * shade};
  }
};

/// Refuses a star that cannot be drawn: non-finite numbers, radius <= 0, inside the horizon, around the camera.
template <grtrace::MetricPolicy M>
void check_star(const M& metric, const GlowingStar& star, const grtrace::Vec4& camera) {
  if (!star.centre.allFinite() || !std::isfinite(star.radius) || !std::isfinite(star.temperature))
    throw std::invalid_argument("star: centre, radius and temperature must be finite numbers");
  if (!(star.radius > 0.0)) throw std::invalid_argument("star: the radius must be > 0");
  if (!(star.centre.norm() - star.radius > metric.horizon_radius()))
    throw std::invalid_argument("star: it reaches into the horizon; move it out or make it smaller");
  if (!((grtrace::spherical_to_cartesian(camera) - star.centre).norm() > star.radius))
    throw std::invalid_argument("star: the camera is inside it; move the star or the camera");
}
