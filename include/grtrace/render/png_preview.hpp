// grtrace/render/png_preview.hpp
// 8-bit PNG output and input through libpng (link grtrace::render, which carries PNG::PNG): written with its full
// API ("up" filter, zlib level 3: fast; see png_write_rows), read with its simplified API.
//
//   grtrace::write_png_preview("frame.png", image);          // sRGB preview of the linear R, G, B channels
//   grtrace::write_png_rgb8("map.png", w, h, rgb);           // any 8-bit RGB picture (heat maps, status maps)
//   grtrace::PngRgb8 png = grtrace::read_png_rgb8("map.png"); // for tests and tools
//
// - Encoding: linear value * exposure, clamped to [0, 1], then the sRGB transfer function (IEC 61966-2-1:
//   12.92 v below 0.0031308, else 1.055 v^(1/2.4) - 0.055), rounded to the nearest of 0..255. So 0 -> 0,
//   1 -> 255, 0.5 -> 188, 0.18 -> 118. NaN and negative values give 0.
// - The files carry an sRGB chunk (rendering intent perceptual), so viewers show them as intended.
// - Row 0 is the top of the picture, as in Image; pixels are RGB triplets, row-major, no padding.
// - Encoded in memory, written to an exclusively created temporary sibling and renamed (output_file.hpp): whole
//   or not at all. The overloads taking an OutputSet& write into a set committed together.
//   Failures throw std::runtime_error naming the file; bad arguments throw std::invalid_argument.
#pragma once

#include "grtrace/render/image.hpp"

#include <png.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
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

namespace detail {

/// The 255 thresholds of srgb_encode8: thresholds[k - 1] is the smallest double x with srgb_encode8(x) >= k, found
/// by bisection over the bit patterns of the positive doubles (srgb_encode8 is non-decreasing). So, for every x,
/// srgb_encode8(x) == the number of thresholds <= x: the preview encodes a pixel with a binary search (8 comparisons)
/// instead of a pow, and gives the same bytes.
inline const std::array<double, 255>& srgb_encode8_thresholds() {
  static const std::array<double, 255> table = [] {
    std::array<double, 255> t{};
    for (int k = 1; k <= 255; ++k) {
      std::uint64_t lo = 0;                                   // +0.0: encodes to 0 < k
      std::uint64_t hi = std::bit_cast<std::uint64_t>(1.0);   // 1.0: encodes to 255 >= k
      while (hi - lo > 1) {
        const std::uint64_t mid = lo + (hi - lo) / 2;
        (srgb_encode8(std::bit_cast<double>(mid)) >= k ? hi : lo) = mid;
      }
      t[static_cast<std::size_t>(k - 1)] = std::bit_cast<double>(hi);
    }
    return t;
  }();
  return table;
}

/// srgb_encode8(linear), bit for bit, without pow (see srgb_encode8_thresholds).
inline std::uint8_t srgb_encode8_fast(double linear, const std::array<double, 255>& thresholds) {
  if (!(linear > 0.0)) return 0;  // also NaN
  if (linear >= 1.0) return 255;
  return static_cast<std::uint8_t>(std::upper_bound(thresholds.begin(), thresholds.end(), linear) - thresholds.begin());
}

}  // namespace detail

/// The inverse transfer function: an 8-bit sRGB code to its linear value in [0, 1].
inline double srgb_decode8(std::uint8_t code) {
  const double v = static_cast<double>(code) / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

namespace detail {

/// Where libpng's writer puts the file (png_set_write_fn) and its error message (png_set_error_fn).
struct PngMemorySink {
  std::vector<std::uint8_t> bytes;
  bool out_of_memory = false;
  char message[256] = {};
};

extern "C" inline void grtrace_png_write_to_memory(png_structp png, png_bytep data, png_size_t size) {
  auto* sink = static_cast<PngMemorySink*>(png_get_io_ptr(png));
  if (sink->out_of_memory) return;
  try {
    sink->bytes.insert(sink->bytes.end(), data, data + size);
  } catch (...) {  // no exception may cross libpng (C); noted and reported after png_write_end
    sink->out_of_memory = true;
  }
}
extern "C" inline void grtrace_png_flush_memory(png_structp) {}
extern "C" inline void grtrace_png_error(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngMemorySink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message ? message : "libpng error");
  png_longjmp(png, 1);
}
extern "C" inline void grtrace_png_warning(png_structp, png_const_charp) {}

/// libpng's write calls behind its setjmp (only libpng's own state lives across it). False after a libpng error.
inline bool png_write_rows(png_structp png, png_infop info, png_uint_32 width, png_uint_32 height,
                           const std::uint8_t* rgb) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);  // the sRGB chunk, as libpng's simplified writer adds
  // The "up" filter at zlib level 3: about 8x faster than libpng's adaptive filters at level 6 on grtrace's frames
  // (a preview; the data is in the EXR), for files about twice as large (docs/benchmarks.md).
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_UP);
  png_set_compression_level(png, 3);
  png_write_info(png, info);
  const std::size_t stride = 3u * static_cast<std::size_t>(width);
  for (png_uint_32 y = 0; y < height; ++y) png_write_row(png, rgb + stride * y);
  png_write_end(png, info);
  return true;
}

/// The PNG file (bytes) of an 8-bit RGB picture; `name` for messages.
inline std::vector<std::uint8_t> encode_png_rgb8(const std::string& name, int width, int height,
                                                 const std::vector<std::uint8_t>& rgb) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("write_png_rgb8: image size must be positive");
  const std::size_t expected = 3u * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (rgb.size() != expected)
    throw std::invalid_argument("write_png_rgb8: expected " + std::to_string(expected) + " bytes (3 * " +
                                std::to_string(width) + " * " + std::to_string(height) + "), got " +
                                std::to_string(rgb.size()));
  if (width > 1 << 30 || height > 1 << 30)  // PNG's limit is 2^31 - 1; far beyond any memory limit anyway
    throw std::invalid_argument("write_png_rgb8: image size too large for PNG");
  PngMemorySink sink;
  sink.bytes.reserve(expected / 8 + 1024);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, &grtrace_png_error, &grtrace_png_warning);
  if (!png) throw std::runtime_error("cannot write PNG '" + name + "': libpng could not start (out of memory?)");
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("cannot write PNG '" + name + "': libpng could not start (out of memory?)");
  }
  png_set_write_fn(png, &sink, &grtrace_png_write_to_memory, &grtrace_png_flush_memory);
  const bool ok = png_write_rows(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height),
                                 rgb.data());
  png_destroy_write_struct(&png, &info);
  if (!ok) throw std::runtime_error("cannot write PNG '" + name + "': " + sink.message);
  if (sink.out_of_memory) throw std::bad_alloc();
  return std::move(sink.bytes);
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
  const std::array<double, 255>& t = srgb_encode8_thresholds();
  std::vector<std::uint8_t> rgb(3 * image.pixel_count());
  for (std::size_t i = 0; i < image.pixel_count(); ++i) {
    rgb[3 * i + 0] = srgb_encode8_fast(scale * static_cast<double>(r[i]), t);
    rgb[3 * i + 1] = srgb_encode8_fast(scale * static_cast<double>(g[i]), t);
    rgb[3 * i + 2] = srgb_encode8_fast(scale * static_cast<double>(b[i]), t);
  }
  return rgb;
}

}  // namespace detail

/// The width and height of the PNG at `path` when its chunk structure is whole, else nothing: the signature, an
/// IHDR chunk first, then chunks (length, type, data, CRC) that lie inside the file, ending in IEND exactly at its
/// end. Reads the 8-byte chunk headers only (CRCs and pixels are not checked): a resumed flight tells a truncated
/// preview from a whole one without decoding it.
inline std::optional<std::array<int, 2>> whole_png_size(const std::filesystem::path& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return std::nullopt;
  struct Closer {
    std::FILE* f;
    ~Closer() { std::fclose(f); }
  } closer{f};
  auto be32 = [](const unsigned char* b) {
    return static_cast<std::uint32_t>(b[0]) << 24 | static_cast<std::uint32_t>(b[1]) << 16 |
           static_cast<std::uint32_t>(b[2]) << 8 | static_cast<std::uint32_t>(b[3]);
  };
  unsigned char start[8 + 8 + 8] = {};  // signature, IHDR's length and type, its width and height
  static constexpr unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (std::fread(start, 1, sizeof start, f) != sizeof start || std::memcmp(start, kSignature, 8) != 0 ||
      std::memcmp(start + 12, "IHDR", 4) != 0 || be32(start + 8) != 13)
    return std::nullopt;
  const std::uint32_t width = be32(start + 16), height = be32(start + 20);
  if (width == 0 || height == 0 || width > 0x7fffffffu || height > 0x7fffffffu) return std::nullopt;
  if (std::fseek(f, 8, SEEK_SET) != 0) return std::nullopt;
  for (;;) {  // each chunk: 4-byte length, 4-byte type, data, 4-byte CRC
    unsigned char head[8] = {};
    if (std::fread(head, 1, 8, f) != 8) return std::nullopt;  // ended without IEND
    const std::uint32_t length = be32(head);
    if (length > 0x7fffffffu) return std::nullopt;
    if (std::memcmp(head + 4, "IEND", 4) == 0) {
      if (length != 0 || std::fseek(f, 4, SEEK_CUR) != 0) return std::nullopt;
      const long end = std::ftell(f);
      if (std::fseek(f, 0, SEEK_END) != 0 || std::ftell(f) != end) return std::nullopt;  // IEND is the last byte
      return std::array<int, 2>{static_cast<int>(width), static_cast<int>(height)};
    }
    if (std::fseek(f, static_cast<long>(length) + 4, SEEK_CUR) != 0) return std::nullopt;
  }
}

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
