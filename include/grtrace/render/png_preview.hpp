// grtrace/render/png_preview.hpp
// 8-bit PNG output and input through libpng's simplified API (link grtrace::render, which carries PNG::PNG).
//
//   grtrace::write_png_preview("frame.png", image);          // sRGB preview of the linear R, G, B channels
//   grtrace::write_png_rgb8("map.png", w, h, rgb);           // any 8-bit RGB picture (heat maps, status maps)
//   grtrace::PngRgb8 png = grtrace::read_png_rgb8("map.png"); // for tests and tools
//
// - Encoding: linear value * exposure, clamped to [0, 1], then the sRGB transfer function (IEC 61966-2-1:
//   12.92 v below 0.0031308, else 1.055 v^(1/2.4) - 0.055), rounded to the nearest of 0..255. So 0 -> 0,
//   1 -> 255, 0.5 -> 188, 0.18 -> 118. NaN and negative values give 0.
// - The files carry an sRGB chunk (libpng's simplified writer adds it), so viewers show them as intended.
// - Row 0 is the top of the picture, as in Image; pixels are RGB triplets, row-major, no padding.
// - Encoded in memory, written to an exclusively created temporary sibling and renamed (output_file.hpp): whole
//   or not at all. The overloads taking an OutputSet& write into a set committed together.
//   Failures throw std::runtime_error naming the file; bad arguments throw std::invalid_argument.
#pragma once

#include "grtrace/render/image.hpp"

#include <png.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace grtrace {

/// An 8-bit RGB picture: rgb.size() == 3 * width * height, row 0 at the top.
struct PngRgb8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

/// The sRGB encoding of one linear value, clamped to [0, 1] (NaN -> 0).
inline std::uint8_t srgb_encode8(double linear) {
  if (!(linear > 0.0)) return 0;  // also NaN
  if (linear >= 1.0) return 255;
  const double encoded = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  return static_cast<std::uint8_t>(std::lround(encoded * 255.0));
}

/// The inverse transfer function: an 8-bit sRGB code to its linear value in [0, 1].
inline double srgb_decode8(std::uint8_t code) {
  const double v = static_cast<double>(code) / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

namespace detail {

/// The PNG file (bytes) of an 8-bit RGB picture; `name` for messages.
inline std::vector<std::uint8_t> encode_png_rgb8(const std::string& name, int width, int height,
                                                 const std::vector<std::uint8_t>& rgb) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("write_png_rgb8: image size must be positive");
  const std::size_t expected = 3u * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (rgb.size() != expected)
    throw std::invalid_argument("write_png_rgb8: expected " + std::to_string(expected) + " bytes (3 * " +
                                std::to_string(width) + " * " + std::to_string(height) + "), got " +
                                std::to_string(rgb.size()));
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = PNG_FORMAT_RGB;
  const auto row_stride = static_cast<png_int_32>(3 * width);
  png_alloc_size_t size = 0;
  // First call: the size; second: the bytes (libpng's simplified in-memory writer).
  if (png_image_write_to_memory(&image, nullptr, &size, 0, rgb.data(), row_stride, nullptr) == 0) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error("cannot write PNG '" + name + "': " + message);
  }
  std::vector<std::uint8_t> bytes(size);
  if (png_image_write_to_memory(&image, bytes.data(), &size, 0, rgb.data(), row_stride, nullptr) == 0) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error("cannot write PNG '" + name + "': " + message);
  }
  bytes.resize(size);
  return bytes;
}

inline std::vector<std::uint8_t> preview_rgb8(const Image& image, float exposure) {
  if (!std::isfinite(exposure) || exposure < 0.0f)
    throw std::invalid_argument("write_png_preview: exposure must be finite and >= 0");
  for (const char* c : {"R", "G", "B"})
    if (!image.has_channel(c))
      throw std::invalid_argument(std::string("write_png_preview: the image has no '") + c + "' channel");
  const std::vector<float>& r = image.channel("R");
  const std::vector<float>& g = image.channel("G");
  const std::vector<float>& b = image.channel("B");
  const double scale = static_cast<double>(exposure);
  std::vector<std::uint8_t> rgb(3 * image.pixel_count());
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    rgb[3 * i + 0] = srgb_encode8(scale * static_cast<double>(r[i]));
    rgb[3 * i + 1] = srgb_encode8(scale * static_cast<double>(g[i]));
    rgb[3 * i + 2] = srgb_encode8(scale * static_cast<double>(b[i]));
  }
  return rgb;
}

}  // namespace detail

/// Writes an 8-bit RGB PNG (rgb: 3 * width * height bytes, row-major, top row first), whole or not at all.
inline void write_png_rgb8(const std::filesystem::path& path, int width, int height,
                           const std::vector<std::uint8_t>& rgb) {
  const std::vector<std::uint8_t> bytes = detail::encode_png_rgb8(path.string(), width, height, rgb);
  TemporaryOutput out(path);
  out.write(bytes.data(), bytes.size());
  out.commit();
}

/// The same as part of a set of outputs (written now, renamed into place by set.commit()).
inline void write_png_rgb8(OutputSet& set, const std::filesystem::path& path, int width, int height,
                           const std::vector<std::uint8_t>& rgb) {
  const std::vector<std::uint8_t> bytes = detail::encode_png_rgb8(path.string(), width, height, rgb);
  TemporaryOutput& out = set.add(path);
  out.write(bytes.data(), bytes.size());
  out.finish();
}

/// Writes an 8-bit sRGB PNG preview of the linear R, G, B channels of `image`, each multiplied by `exposure`
/// (a linear factor: 2 is one stop brighter) before encoding. Whole or not at all.
inline void write_png_preview(const std::filesystem::path& path, const Image& image, float exposure = 1.0f) {
  write_png_rgb8(path, image.width(), image.height(), detail::preview_rgb8(image, exposure));
}

/// The same as part of a set of outputs.
inline void write_png_preview(OutputSet& set, const std::filesystem::path& path, const Image& image,
                              float exposure = 1.0f) {
  write_png_rgb8(set, path, image.width(), image.height(), detail::preview_rgb8(image, exposure));
}

/// Reads any PNG as 8-bit sRGB RGB (libpng converts grey, palette and 16-bit; alpha is composited onto black).
/// Throws std::runtime_error naming the file.
inline PngRgb8 read_png_rgb8(const std::filesystem::path& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_file(&image, path.c_str()) == 0) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error("cannot read PNG '" + path.string() + "': " + message);
  }
  image.format = PNG_FORMAT_RGB;
  try {
    check_memory(3.0 * image.width * image.height,
                 "its " + std::to_string(image.width) + " x " + std::to_string(image.height) + " pixels");
  } catch (const MemoryLimitError& e) {
    png_image_free(&image);
    throw MemoryLimitError("cannot read PNG '" + path.string() + "': " + e.what());
  }
  const std::size_t bytes = 3u * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (bytes == 0 || image.width > 1u << 30 || image.height > 1u << 30) {
    png_image_free(&image);
    throw std::runtime_error("cannot read PNG '" + path.string() + "': unsupported size");
  }
  PngRgb8 out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.assign(bytes, std::uint8_t{0});
  const png_color black{0, 0, 0};
  if (png_image_finish_read(&image, &black, out.rgb.data(), 0, nullptr) == 0) {
    const std::string message = image.message;
    png_image_free(&image);
    throw std::runtime_error("cannot read PNG '" + path.string() + "': " + message);
  }
  return out;
}

}  // namespace grtrace
