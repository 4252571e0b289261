// grtrace/render/image.hpp
// What a render produces: one PixelSample per pixel, stored as planar float channels (the EXR layout).
// Row 0 is the top of the picture, column 0 the left.
//
// Channels (names are part of the grtrace-render contract, shared/DESIGN.md):
//   R, G, B     linear colour
//   object      0 sky, 1 horizon, 2 disk, ... (SceneObjectId)
//   status      RayStatus as a number (core/ray_status.hpp)
//   redshift    f_obs / f_src, NaN where undefined (e.g. failed rays)
//   sky_theta   asymptotic direction of escaped rays (radians), NaN otherwise
//   sky_phi
//   steps       accepted integration steps
// Extra channels (e.g. "error") can be added by name.
#pragma once

#include "grtrace/core/ray_status.hpp"

#include <array>
#include <cstddef>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace grtrace {

enum class SceneObjectId : int { sky = 0, horizon = 1, disk = 2, star = 3 };

struct PixelSample {
  static constexpr float nan = std::numeric_limits<float>::quiet_NaN();
  std::array<float, 3> rgb{0.0f, 0.0f, 0.0f};
  SceneObjectId object = SceneObjectId::sky;
  RayStatus status = RayStatus::max_steps;
  float redshift = nan;
  float sky_theta = nan;
  float sky_phi = nan;
  int steps = 0;
};

/// Planar float image with named channels, in a fixed channel order for the standard ones.
class Image {
 public:
  static constexpr std::array<const char*, 9> kStandardChannels = {"R",        "G",         "B",       "object", "status",
                                                                    "redshift", "sky_theta", "sky_phi", "steps"};

  Image(int width, int height) : width_(width), height_(height) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("image size must be positive");
    for (const char* name : kStandardChannels) add_channel(name);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t pixel_count() const { return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_); }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }

  /// Adds a channel filled with `fill` (no-op if it exists); returns its data.
  std::vector<float>& add_channel(const std::string& name, float fill = 0.0f) {
    auto [it, inserted] = channels_.try_emplace(name);
    if (inserted) {
      it->second.assign(pixel_count(), fill);
      order_.push_back(name);
    }
    return it->second;
  }
  bool has_channel(const std::string& name) const { return channels_.count(name) > 0; }
  std::vector<float>& channel(const std::string& name) { return channels_.at(name); }
  const std::vector<float>& channel(const std::string& name) const { return channels_.at(name); }
  const std::vector<std::string>& channel_names() const { return order_; }

  void set(int x, int y, const PixelSample& s) {
    const std::size_t i = index(x, y);
    channels_["R"][i] = s.rgb[0];
    channels_["G"][i] = s.rgb[1];
    channels_["B"][i] = s.rgb[2];
    channels_["object"][i] = static_cast<float>(static_cast<int>(s.object));
    channels_["status"][i] = static_cast<float>(static_cast<int>(s.status));
    channels_["redshift"][i] = s.redshift;
    channels_["sky_theta"][i] = s.sky_theta;
    channels_["sky_phi"][i] = s.sky_phi;
    channels_["steps"][i] = static_cast<float>(s.steps);
  }

  /// Free-form metadata (camera, metric, tableau, tolerances, render time): written as EXR header attributes.
  std::map<std::string, std::string> metadata;

 private:
  int width_, height_;
  std::map<std::string, std::vector<float>> channels_;
  std::vector<std::string> order_;
};

}  // namespace grtrace
