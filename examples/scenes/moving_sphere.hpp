// examples/scenes/moving_sphere.hpp
// A scene object for flat space written by its user: a sphere of rest-frame radius R whose centre moves with
// constant velocity v through Cartesian Minkowski coordinates (t, x, y, z), centre(t) = c0 + v t. Its surface is
// checkered in its own rest frame (longitude and latitude about its own axes), so the picture shows which side of
// it each pixel sees: light reaching the camera at one instant left different parts of a moving body at different
// times, and the sphere appears rotated, not flattened (Terrell 1959, Penrose 1959).
// Its function is the rest-frame distance from the centre minus R (the event boosted into the sphere's frame).
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/scene/colour_maps.hpp"
#include "grtrace/scene/scene_object.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string_view>

struct MovingSphere {
  static constexpr std::string_view kind = "sphere";
  grtrace::Vec3 centre_at_zero{10.0, 9.0, 0.0};  ///< c0: where the centre is at t = 0
  grtrace::Vec3 velocity{0.0, 0.9, 0.0};         ///< v, fraction of c
  double radius = 3.0;

  double gamma() const { return 1.0 / std::sqrt(1.0 - velocity.squaredNorm()); }

  /// The event x relative to the centre, in the sphere's rest frame (a pure boost along v).
  grtrace::Vec3 rest_frame_offset(const grtrace::Vec4& x) const {
    const grtrace::Vec3 d = x.tail<3>() - centre_at_zero;  // from the worldline's event at t = 0
    const double v = velocity.norm();
    if (v == 0.0) return d;
    const grtrace::Vec3 n = velocity / v;
    const double along = d.dot(n);
    return d + ((gamma() - 1.0) * along - gamma() * v * x[0]) * n;
  }

  double operator()(const grtrace::GeodesicState& y) const { return rest_frame_offset(y.head<4>()).norm() - radius; }

  template <class Metric>
  grtrace::Vec4 emitter_velocity(const Metric& /*flat, Cartesian*/, const grtrace::Vec4& /*x*/) const {
    grtrace::Vec4 u;
    u << 1.0, velocity;
    return gamma() * u;
  }

  /// 12 x 6 checkerboard in the rest frame, brightened by g^2 (relativistic beaming, compressed for display).
  grtrace::Rgb colour(const grtrace::SurfaceHit& hit) const {
    const grtrace::Vec3 n = rest_frame_offset(hit.position()).normalized();
    const double lon = std::atan2(n.y(), n.x()), lat = std::asin(std::clamp(n.z(), -1.0, 1.0));
    const long i = std::lround(std::floor(lon / (std::numbers::pi / 6.0))), j = std::lround(std::floor(lat / (std::numbers::pi / 6.0)));
    const grtrace::Rgb base = (i + j) % 2 == 0 ? grtrace::Rgb{0.95f, 0.9f, 0.8f} : grtrace::Rgb{0.9f, 0.35f, 0.1f};
    const auto b = static_cast<float>(std::clamp(hit.redshift * hit.redshift, 0.05, 2.0));
    return {base[0] * b, base[1] * b, base[2] * b};
  }

  /// Refuses |v| >= 1, a radius <= 0, non-finite numbers, and a camera at the origin inside the sphere at t = 0.
  void check() const {
    if (!centre_at_zero.allFinite() || !velocity.allFinite() || !std::isfinite(radius))
      throw std::invalid_argument("sphere: centre, velocity and radius must be finite numbers");
    if (!(velocity.norm() < 1.0)) throw std::invalid_argument("sphere: |velocity| must be below 1 (the speed of light)");
    if (!(radius > 0.0)) throw std::invalid_argument("sphere: the radius must be > 0");
    if (!(rest_frame_offset(grtrace::Vec4::Zero()).norm() > radius))
      throw std::invalid_argument("sphere: the camera at the origin is inside it; move the sphere");
  }
};
