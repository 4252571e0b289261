// grtrace/scene/shading.hpp
// Turns a ray's outcome into a pixel: colour by scene, plus the data channels (object, status, redshift,
// sky direction, steps). The scenes of grtrace-render:
//   checker   theta-phi checkerboards on the sky and on the horizon (seed Fig. 4)
//   sky       a star field (or a texture) and a black horizon
//   redshift  every pixel coloured by f_obs / f_src (seed Fig. 5)
//   disk      a thin Keplerian disk in front of the star field, coloured by temperature and redshift
// A failed ray (max_steps, step_underflow, non_finite) gets a flat, visible colour and NaN data, never NaN colour.
#pragma once

#include "grtrace/render/image.hpp"
#include "grtrace/scene/colour_maps.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/scene/thin_disk.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <optional>
#include <string_view>
#include <variant>

namespace grtrace {

enum class SceneKind { checker, sky, redshift, disk };

inline std::optional<SceneKind> scene_kind_from_string(std::string_view s) {
  if (s == "checker") return SceneKind::checker;
  if (s == "sky") return SceneKind::sky;
  if (s == "redshift") return SceneKind::redshift;
  if (s == "disk") return SceneKind::disk;
  return std::nullopt;
}

struct Shading {
  SceneKind kind = SceneKind::checker;
  std::variant<CheckerSky, StarFieldSky, TextureSky> sky = CheckerSky{};
  int horizon_squares = 18;
  Rgb horizon_light{0.55f, 0.05f, 0.05f}, horizon_dark{0.05f, 0.0f, 0.0f};
  ThinDisk disk{};
  Rgb failure{1.0f, 0.0f, 1.0f};
};

inline PixelSample shade(const RayOutcome& o, const Shading& s) {
  PixelSample p;
  p.status = o.status;
  p.object = o.object;
  p.steps = o.steps;
  if (is_failure(o.status)) {
    p.rgb = s.failure;
    return p;
  }
  p.redshift = static_cast<float>(o.redshift);
  if (o.status == RayStatus::escaped) {
    p.sky_theta = static_cast<float>(o.where.theta);
    p.sky_phi = static_cast<float>(o.where.phi);
  }
  if (s.kind == SceneKind::redshift) {
    p.rgb = redshift_colour(o.redshift);
    return p;
  }
  switch (o.object) {
    case SceneObjectId::sky:
      p.rgb = std::visit([&](const auto& sky) { return sky(o.where.theta, o.where.phi); }, s.sky);
      break;
    case SceneObjectId::horizon:
      p.rgb = s.kind == SceneKind::checker
                  ? (checker_parity(o.where.theta, o.where.phi, s.horizon_squares) ? s.horizon_light : s.horizon_dark)
                  : Rgb{0.0f, 0.0f, 0.0f};
      break;
    case SceneObjectId::disk: p.rgb = s.disk.colour(o.radius, o.redshift); break;
    default: p.rgb = s.failure; break;
  }
  return p;
}

}  // namespace grtrace
