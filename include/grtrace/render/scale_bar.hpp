// grtrace/render/scale_bar.hpp
// A scale bar in a picture of a source in physical units: a white bar of a round length in microarcseconds near
// the bottom-left corner, its length written above it ("20 uas"), drawn into the image's R, G, B channels (the
// picture; the data channels are untouched).
//
// Takes:   an image with R, G, B channels and the width of its pixels in microarcseconds at the telescope
//          (core/physical_units.hpp, SourceScale::microarcseconds_at_telescope).
// Returns: the bar's length in microarcseconds, 1, 2 or 5 times a power of ten, the longest not over a quarter of
//          the image's width; also recorded in the image's metadata ("scale_bar_microarcseconds"). Nothing is
//          drawn (and 0 returned) where the image is too small for a bar of 4 pixels and its label (under 24 x 16
//          pixels) or the pixel's width is not a positive finite number.
// Method:  the label in a 3 x 5 pixel font (digits, '.', 'u', 'a', 's'), magnified by an integer factor that grows
//          with the image (one per 256 pixels of width), each glyph and the bar drawn on a black outline so that
//          they read on bright gas too.
#pragma once

#include "grtrace/core/number_text.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace grtrace {

namespace scale_bar_detail {

/// 3 x 5 glyphs, one row a byte (bit 2 the left column), for the characters of a label.
inline std::array<std::uint8_t, 5> glyph(char c) {
  switch (c) {
    case '0':
      return {7, 5, 5, 5, 7};
    case '1':
      return {2, 6, 2, 2, 7};
    case '2':
      return {7, 1, 7, 4, 7};
    case '3':
      return {7, 1, 7, 1, 7};
    case '4':
      return {5, 5, 7, 1, 1};
    case '5':
      return {7, 4, 7, 1, 7};
    case '6':
      return {7, 4, 7, 5, 7};
    case '7':
      return {7, 1, 1, 1, 1};
    case '8':
      return {7, 5, 7, 5, 7};
    case '9':
      return {7, 5, 7, 1, 7};
    case '.':
      return {0, 0, 0, 0, 2};
    case 'u':
      return {0, 5, 5, 5, 7};
    case 'a':
      return {0, 7, 1, 7, 7};
    case 's':
      return {0, 7, 6, 1, 7};
    default:
      return {0, 0, 0, 0, 0};
  }
}

inline bool inside(const Image& image, int x, int y) {
  return x >= 0 && y >= 0 && x < image.width() && y < image.height();
}

/// Paints the pixel (x, y) with value v in R, G, B if it lies in the image.
inline void paint(Image& image, int x, int y, float v) {
  if (!inside(image, x, y)) return;
  const std::size_t i = image.index(x, y);
  image.channel("R")[i] = image.channel("G")[i] = image.channel("B")[i] = v;
}

inline bool is_white(const Image& image, int x, int y) {
  const std::size_t i = image.index(x, y);
  return image.channel("R")[i] == 1.0f && image.channel("G")[i] == 1.0f && image.channel("B")[i] == 1.0f;
}

/// A white rectangle [x0, x1) x [y0, y1) on a black outline `outline` pixels wide; the outline does not cover
/// white already drawn (a neighbouring stroke).
inline void outlined_box(Image& image, int x0, int y0, int x1, int y1, int outline) {
  for (int y = y0 - outline; y < y1 + outline; ++y)
    for (int x = x0 - outline; x < x1 + outline; ++x) {
      const bool box = x >= x0 && x < x1 && y >= y0 && y < y1;
      if (!box && inside(image, x, y) && is_white(image, x, y)) continue;
      paint(image, x, y, box ? 1.0f : 0.0f);
    }
}

}  // namespace scale_bar_detail

/// The bar's length: 1, 2 or 5 x 10^k microarcseconds, the longest at most `longest`.
inline double round_scale_length(double longest) {
  const double decade = std::pow(10.0, std::floor(std::log10(longest)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * decade <= longest) return m * decade;
  return decade;
}

inline double draw_scale_bar(Image& image, double microarcseconds_per_pixel) {
  using namespace scale_bar_detail;
  const int w = image.width(), h = image.height();
  if (!(microarcseconds_per_pixel > 0.0 && std::isfinite(microarcseconds_per_pixel)) || w < 24 || h < 16) return 0.0;
  const double length = round_scale_length(0.25 * w * microarcseconds_per_pixel);
  const int pixels = static_cast<int>(std::lround(length / microarcseconds_per_pixel));
  if (pixels < 4) return 0.0;
  const int zoom = std::max(1, w / 256);
  const int margin = 3 * zoom, bar_height = 2 * zoom;
  const int bar_top = h - margin - bar_height;
  outlined_box(image, margin, bar_top, margin + pixels, bar_top + bar_height, zoom);
  const std::string label = shortest_number_text(length) + " uas";
  const int text_top = bar_top - 2 * zoom - 5 * zoom;
  int x = margin;
  for (const char c : label) {
    const std::array<std::uint8_t, 5> rows = glyph(c);
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (rows[static_cast<std::size_t>(row)] & (4 >> col))
          outlined_box(image, x + col * zoom, text_top + row * zoom, x + (col + 1) * zoom, text_top + (row + 1) * zoom,
                       zoom);
    x += 4 * zoom;
  }
  image.metadata["scale_bar_microarcseconds"] = exact_number(length);
  return length;
}

}  // namespace grtrace
