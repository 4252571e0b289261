// grtrace/viz/frame_image.hpp
// An 8-bit RGB picture as the frame viewport shows it: the rendered frame's preview colours.
// Row 0 is the top of the picture, column 0 the left (the same convention as grtrace::Image).
// VTK-free; the conversion from a float grtrace::Image uses the renderer's preview tone map (see the tool).
#pragma once

#include "grtrace/viz/traced_path.hpp"

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace grtrace::viz {

struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< width * height * 3 bytes, row-major from the top

  Rgb8Image() = default;
  Rgb8Image(int w, int h, Rgb8 fill = {0, 0, 0}) : width(w), height(h) {
    if (w <= 0 || h <= 0) throw std::invalid_argument("Rgb8Image: size must be positive");
    rgb.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3);
    for (std::size_t i = 0; i < rgb.size(); i += 3) {
      rgb[i] = fill[0];
      rgb[i + 1] = fill[1];
      rgb[i + 2] = fill[2];
    }
  }

  bool empty() const { return width <= 0 || height <= 0; }
  std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  }
  Rgb8 at(int x, int y) const {
    const std::size_t o = offset(x, y);
    return {rgb[o], rgb[o + 1], rgb[o + 2]};
  }
  void set(int x, int y, Rgb8 c) {
    const std::size_t o = offset(x, y);
    rgb[o] = c[0];
    rgb[o + 1] = c[1];
    rgb[o + 2] = c[2];
  }
};

}  // namespace grtrace::viz
