// grtrace/viz/frame_from_image.hpp
// A rendered grtrace::Image (or an EXR written by grtrace-render) as the 8-bit frame the viewer shows: exactly the
// colours of the renderer's PNG preview (grtrace/render/png_preview.hpp: linear * exposure, clamped, sRGB-encoded).
// Header-only; needs grtrace::render (OpenEXR, libpng) in addition to grtrace::viz.
#pragma once

#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/viz/frame_image.hpp"

#include <stdexcept>
#include <string>

namespace grtrace::viz {

inline Rgb8Image frame_from_image(const Image& image, float exposure = 1.0f) {
  for (const char* c : {"R", "G", "B"})
    if (!image.has_channel(c)) throw std::runtime_error(std::string("the frame has no '") + c + "' channel");
  Rgb8Image out(image.width(), image.height());
  const auto& r = image.channel("R");
  const auto& g = image.channel("G");
  const auto& b = image.channel("B");
  const double s = static_cast<double>(exposure);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const std::size_t i = image.index(x, y);
      out.set(x, y,
              {srgb_encode8(s * static_cast<double>(r[i])), srgb_encode8(s * static_cast<double>(g[i])),
               srgb_encode8(s * static_cast<double>(b[i]))});
    }
  return out;
}

inline Rgb8Image frame_from_exr(const std::string& path, float exposure = 1.0f) {
  return frame_from_image(read_exr(path), exposure);
}

}  // namespace grtrace::viz
