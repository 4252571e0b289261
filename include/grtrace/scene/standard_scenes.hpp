// grtrace/scene/standard_scenes.hpp
// The named scenes of the command-line tools (grtrace-render --scene, grtrace-view --scene), built from the
// library's parts so that every tool draws the same thing under the same name:
//   checker   theta-phi checkerboards on the sky and on the horizon (seed Fig. 4)
//   sky       a star field (or a texture) and a black horizon
//   redshift  every pixel coloured by f_obs / f_src (seed Fig. 5)
//   disk      a thin Keplerian disk (scene/thin_disk.hpp) in front of the star field (or texture)
// With far_side (for a wormhole chart, whose rays may end in the other universe at x^1 < 0) the other universe
// gets a sky of its own: a green-violet checkerboard for "checker", an orange-tinted star field (a different
// pattern) otherwise, so the throat shows the other side (scene/sky.hpp AnySky::far_side).
// A program of your own composes its scene directly with make_scene (scene/scene.hpp); these are presets.
#pragma once

#include "grtrace/scene/scene.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/scene/thin_disk.hpp"

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grtrace {

inline constexpr std::array<std::string_view, 4> kStandardSceneNames = {"checker", "sky", "redshift", "disk"};

struct StandardSceneSpec {
  std::string name = "checker";       ///< one of kStandardSceneNames
  int checker_squares = 18;           ///< checker: squares along theta on sky and horizon
  std::optional<TextureSky> texture;  ///< sky and disk: replaces the star field
  ThinDisk disk{};                    ///< disk
  bool far_side = false;              ///< a sky of its own for rays ending at x^1 < 0 (wormholes only)
};

using BackgroundScene = Scene<AnySky, HorizonPaint>;
using DiskScene = Scene<AnySky, HorizonPaint, ThinDisk>;

inline bool is_standard_scene(std::string_view name) {
  for (std::string_view n : kStandardSceneNames)
    if (n == name) return true;
  return false;
}

/// The sky and horizon of a preset (the disk preset's background). Throws std::invalid_argument for an unknown name.
inline BackgroundScene background_scene(const StandardSceneSpec& spec) {
  if (!is_standard_scene(spec.name))
    throw std::invalid_argument("unknown scene '" + spec.name + "'; choose checker, sky, redshift or disk");
  BackgroundScene scene;
  if (spec.name == "checker") {
    scene.sky.sky = CheckerSky{spec.checker_squares};
    scene.horizon.squares = spec.checker_squares;
  } else if (spec.texture) {
    scene.sky.sky = *spec.texture;
  }
  if (spec.far_side) {
    if (spec.name == "checker")
      scene.sky.far_side = CheckerSky{spec.checker_squares, {0.3f, 0.85f, 0.3f}, {0.3f, 0.05f, 0.35f}};
    else
      scene.sky.far_side = StarFieldSky{701, {1.7f, 0.85f, 0.35f}};
  }
  scene.colour_by_redshift = spec.name == "redshift";
  return scene;
}

inline DiskScene disk_scene(const StandardSceneSpec& spec) {
  const BackgroundScene b = background_scene(spec);
  return {b.sky, b.horizon, {spec.disk}, b.colour_by_redshift, b.failure};
}

/// Calls f(scene) with the preset's scene: a DiskScene for "disk", a BackgroundScene otherwise (two
/// instantiations of whatever f does, chosen at run time).
template <class F>
decltype(auto) with_standard_scene(const StandardSceneSpec& spec, F&& f) {
  if (spec.name == "disk") return f(disk_scene(spec));
  return f(background_scene(spec));
}

}  // namespace grtrace
