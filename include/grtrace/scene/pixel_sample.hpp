// grtrace/scene/pixel_sample.hpp
// What a scene makes of one ray's outcome (Scene::shade, scene/scene.hpp): the pixel's colour and its data, the
// values render/image.hpp stores in its channels. A value type of the scene floor: scenes and tracers need it,
// and neither needs the image, its files or the render loop.
#pragma once

#include "grtrace/core/ray_status.hpp"

#include <array>
#include <limits>

namespace grtrace {

struct PixelSample {
  static constexpr float nan = std::numeric_limits<float>::quiet_NaN();
  std::array<float, 3> rgb{0.0f, 0.0f, 0.0f};
  int object = 0;  ///< position in the scene: 0 sky, 1 horizon, 2... objects (scene/object_ids.hpp)
  RayStatus status = RayStatus::max_steps;
  float redshift = nan;
  float sky_theta = nan;
  float sky_phi = nan;
  int steps = 0;
  int order = -1;  ///< the image's order n (RayOutcome::order): 0 direct, 1 the first photon ring, ...; -1 unknown
};

}  // namespace grtrace
