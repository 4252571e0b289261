// grtrace/spectra/ring_image_output.hpp
// A ring image (spectra/ring_image.hpp) as a user looks at it: its channels with a colour picture, and its orders.
//
// ring_orders_picture: the orders side by side, n = 0 | n = 1 above, n = 2 | n >= 3 below, each panel at half the
//   image's resolution (2 x 2 pixels summed: its flux kept) and scaled to its own peak, (I / I_peak)^(1/2), its order
//   written in its corner (render/scale_bar.hpp's 3 x 5 digits; "3" for n >= 3), in the hot-gas colour map
//   (scene/colour_maps.hpp) sRGB-encoded as the PNG previews are.
// ring_image_channels: the image as EXR channels (render/image.hpp): I (all orders), I_n0, I_n1, I_n2, I_n3_up (the
//   mean intensity of each pixel, as ring_image gives it) and R, G, B: the total in the hot-gas colour map of
//   (I / I_peak)^(1/2) (the square root lifts the faint rings), linear RGB (the PNG preview encodes it).
#pragma once

#include "grtrace/render/image.hpp"
#include "grtrace/render/scale_bar.hpp"
#include "grtrace/scene/colour_maps.hpp"
#include "grtrace/spectra/line_profile_result.hpp"
#include "grtrace/spectra/ring_image_result.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace grtrace {

namespace ring_output_detail {

/// The sRGB transfer function (IEC 61966-2-1), linear [0, 1] -> byte.
inline std::uint8_t srgb_byte(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  return static_cast<std::uint8_t>(
      std::lround(255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055)));
}

/// Writes `plane` (w x h, top row first) into the picture at (x0, y0) in the hot-gas map of (v / peak)^(1/2).
inline void paint(LineChart& picture, const std::vector<double>& plane, int w, int h, int x0, int y0) {
  double peak = 0.0;
  for (double v : plane)
    if (std::isfinite(v)) peak = std::max(peak, v);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double v = plane[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
      const auto c = hot_gas_colour(peak > 0.0 && v > 0.0 ? std::sqrt(v / peak) : 0.0);
      const std::size_t at = 3 * (static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(picture.width) +
                                  static_cast<std::size_t>(x0 + x));
      for (std::size_t k = 0; k < 3; ++k) picture.rgb[at + k] = srgb_byte(c[k]);
    }
}

}  // namespace ring_output_detail

inline LineChart ring_orders_picture(const RingImage& image) {
  const int w = std::max(1, image.width / 2), h = std::max(1, image.height / 2);
  constexpr int kGap = 2;
  LineChart p{2 * w + kGap, 2 * h + kGap, {}};
  p.rgb.assign(3 * static_cast<std::size_t>(p.width) * static_cast<std::size_t>(p.height), 96);  // grey gaps
  for (std::size_t o = 0; o < RingImage::kOrderChannels; ++o) {
    std::vector<double> half(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0);
    for (int y = 0; y < 2 * h && y < image.height; ++y)
      for (int x = 0; x < 2 * w && x < image.width; ++x)
        half[static_cast<std::size_t>(y / 2) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x / 2)] +=
            image.intensity[o][static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                               static_cast<std::size_t>(x)];
    const int x0 = static_cast<int>(o % 2) * (w + kGap), y0 = static_cast<int>(o / 2) * (h + kGap);
    ring_output_detail::paint(p, half, w, h, x0, y0);
    // the order in the panel's corner, 3 x 5 pixels scaled by 2, white
    const auto g = scale_bar_detail::glyph(static_cast<char>('0' + o));
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (g[static_cast<std::size_t>(row)] & (4 >> col))
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
              const int px = x0 + 4 + 2 * col + dx, py = y0 + 4 + 2 * row + dy;
              if (px >= x0 + w || py >= y0 + h) continue;
              const std::size_t at =
                  3 * (static_cast<std::size_t>(py) * static_cast<std::size_t>(p.width) + static_cast<std::size_t>(px));
              p.rgb[at] = p.rgb[at + 1] = p.rgb[at + 2] = 255;
            }
  }
  return p;
}

inline Image ring_image_channels(const RingImage& ring) {
  Image image = Image::with_channels(ring.width, ring.height, {"R", "G", "B", "I", "I_n0", "I_n1", "I_n2", "I_n3_up"});
  const char* names[] = {"I_n0", "I_n1", "I_n2", "I_n3_up"};
  std::vector<float>& total = image.channel("I");
  for (std::size_t o = 0; o < RingImage::kOrderChannels; ++o) {
    std::vector<float>& plane = image.channel(names[o]);
    for (std::size_t i = 0; i < plane.size(); ++i) {
      plane[i] = static_cast<float>(ring.intensity[o][i]);
      total[i] += plane[i];
    }
  }
  float peak = 0.0f;
  for (float v : total) peak = std::max(peak, v);
  std::vector<float>&red = image.channel("R"), &green = image.channel("G"), &blue = image.channel("B");
  for (std::size_t i = 0; i < total.size(); ++i) {
    const auto c = hot_gas_colour(peak > 0.0f && total[i] > 0.0f ? std::sqrt(double{total[i]} / double{peak}) : 0.0);
    red[i] = c[0], green[i] = c[1], blue[i] = c[2];
  }
  return image;
}

}  // namespace grtrace
