// grtrace/render/image.hpp
// What a render produces: one PixelSample (scene/pixel_sample.hpp) per pixel, stored as planar float channels
// (the EXR layout).
// Row 0 is the top of the picture, column 0 the left.
//
// Channels (names are part of the grtrace-render contract, shared/DESIGN.md):
//   R, G, B     linear colour
//   object      0 sky, 1 horizon, 2... the scene's objects in order (scene/object_ids.hpp; names in the
//               "object_names" metadata)
//   status      RayStatus as a number (core/ray_status.hpp)
//   redshift    f_obs / f_src, NaN where undefined (e.g. failed rays)
//   sky_theta   asymptotic direction of escaped rays (radians), NaN otherwise
//   sky_phi
//   steps       accepted integration steps
// Extra channels (e.g. "error") can be added by name.
//
// Threads: writing distinct pixels from several threads is safe through set(), a PixelWriter or raw channel
// pointers taken before the parallel loop; adding channels or metadata while other threads work is not.
//
// Included from here (no third-party dependency): output_file.hpp (write_file_atomically, OutputSet), which every
// image writer uses so that output files are created safely and written whole or not at all.
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/memory_limit.hpp"
#include "grtrace/scene/pixel_sample.hpp"
#include "grtrace/render/output_file.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace grtrace {

namespace detail {

/// Before the first touch of a large buffer of n floats: reserves it with 2 MB of slack and asks Linux to back it
/// with transparent huge pages (madvise MADV_HUGEPAGE; with the kernel's default "madvise" mode only advised memory
/// gets them), so that zeroing it costs a few 2 MB page faults instead of a thousand 4 kB ones (the main frame's ten
/// channels: ~6 ms less of a fresh process's ~10 ms, docs/benchmarks-archive.md). A hint only: small buffers, other
/// systems and a refusal (no huge pages free) leave the buffer as it is. The slack lets every 2 MB-aligned block that
/// holds data lie inside the advised range; it is virtual memory, never touched.
inline void advise_huge_pages([[maybe_unused]] std::vector<float>& v, [[maybe_unused]] std::size_t n) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::size_t huge = std::size_t{1} << 21, page = std::size_t{1} << 12;
  if (n * sizeof(float) < 2 * huge || !v.empty()) return;
  v.reserve(n + huge / sizeof(float));
  const auto begin = reinterpret_cast<std::uintptr_t>(v.data());
  const std::uintptr_t first = (begin + page - 1) & ~(page - 1);
  const std::uintptr_t last = (begin + v.capacity() * sizeof(float)) & ~(page - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
}

}  // namespace detail

/// Planar float image with named channels, in a fixed channel order for the standard ones.
class Image {
 public:
  static constexpr std::array<const char*, 10> kStandardChannels = {
      "R", "G", "B", "object", "status", "redshift", "sky_theta", "sky_phi", "steps", "order"};

  /// An image with the ten standard channels, all zero until set().
  /// Throws MemoryLimitError (before allocating) when the channels would exceed memory_limit_bytes().
  Image(int width, int height) : Image(width, height, NoChannels{}) {
    check_memory(image_bytes(width, height, kStandardChannels.size()),
                 "a " + std::to_string(width) + " x " + std::to_string(height) + " image with " +
                     std::to_string(kStandardChannels.size()) + " channels");
    // The first touch of a 1024 x 1024 frame's 36 MB (a page fault per 4 kB page, and zeroing) took 13 ms on one
    // thread, a tenth of the main frame (docs/benchmarks-archive.md). So the ten channels are zeroed on several
    // threads where OpenMP is on, and large channels ask Linux for 2 MB pages first (detail::advise_huge_pages).
    std::array<std::vector<float>*, kStandardChannels.size()> planes{};
    for (std::size_t c = 0; c < kStandardChannels.size(); ++c) {
      planes[c] = &channels_[kStandardChannels[c]];
      order_.push_back(kStandardChannels[c]);
    }
    const auto count = static_cast<int>(planes.size());
    [[maybe_unused]] const bool large = pixel_count() >= (std::size_t{1} << 16);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) if (large)
#endif
    for (int c = 0; c < count; ++c) {
      std::vector<float>& plane = *planes[static_cast<std::size_t>(c)];
      detail::advise_huge_pages(plane, pixel_count());
      plane.assign(pixel_count(), 0.0f);
    }
  }

  /// An image with exactly the named channels, in that order (duplicates ignored), each filled with `fill`.
  /// Used by read_exr() for files that are not grtrace renders (textures); set()/sample() need the standard
  /// channels and throw std::out_of_range without them.
  static Image with_channels(int width, int height, const std::vector<std::string>& names, float fill = 0.0f) {
    Image image(width, height, NoChannels{});
    check_memory(image_bytes(width, height, static_cast<double>(names.size())),
                 "a " + std::to_string(width) + " x " + std::to_string(height) + " image with " +
                     std::to_string(names.size()) + " channels");
    for (const auto& name : names) image.add_channel(name, fill);
    return image;
  }

  /// An image that takes `planes` as its channels: planes[i] holds channel names[i], width * height floats in row
  /// order. Used by read_exr(), which grows the planes as the file's pixels arrive instead of allocating what a
  /// header claims. Throws std::invalid_argument when the counts or sizes disagree or a name repeats.
  static Image from_planes(int width, int height, const std::vector<std::string>& names,
                           std::vector<std::vector<float>> planes) {
    Image image(width, height, NoChannels{});
    if (planes.size() != names.size())
      throw std::invalid_argument("Image::from_planes: " + std::to_string(names.size()) + " names but " +
                                  std::to_string(planes.size()) + " planes");
    for (std::size_t c = 0; c < names.size(); ++c) {
      if (planes[c].size() != image.pixel_count())
        throw std::invalid_argument("Image::from_planes: channel '" + names[c] + "' has " +
                                    std::to_string(planes[c].size()) + " values, not width * height = " +
                                    std::to_string(image.pixel_count()));
      if (!image.channels_.try_emplace(names[c], std::move(planes[c])).second)
        throw std::invalid_argument("Image::from_planes: channel '" + names[c] + "' named twice");
      image.order_.push_back(names[c]);
    }
    return image;
  }

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t pixel_count() const { return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_); }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x);
  }

  /// Adds a channel filled with `fill` (no-op if it exists); returns its data.
  std::vector<float>& add_channel(const std::string& name, float fill = 0.0f) {
    if (!has_channel(name))
      check_memory(image_bytes(width_, height_, static_cast<double>(order_.size() + 1)),
                   "a " + std::to_string(width_) + " x " + std::to_string(height_) + " image with " +
                       std::to_string(order_.size() + 1) + " channels");
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

  /// Raw pointers into the ten standard channels: writes a PixelSample by linear index without map look-ups.
  /// Take it before a parallel loop; it stays valid while the image lives (adding other channels does not move
  /// these). Distinct pixels may be written concurrently.
  class PixelWriter {
   public:
    void set(std::size_t i, const PixelSample& s) const {
      p_[0][i] = s.rgb[0];
      p_[1][i] = s.rgb[1];
      p_[2][i] = s.rgb[2];
      p_[3][i] = static_cast<float>(s.object);
      p_[4][i] = static_cast<float>(static_cast<int>(s.status));
      p_[5][i] = s.redshift;
      p_[6][i] = s.sky_theta;
      p_[7][i] = s.sky_phi;
      p_[8][i] = static_cast<float>(s.steps);
      p_[9][i] = static_cast<float>(s.order);
    }

   private:
    friend class Image;
    std::array<float*, kStandardChannels.size()> p_{};
  };

  /// Throws std::out_of_range if a standard channel is missing (only possible for with_channels() images).
  PixelWriter pixel_writer() {
    PixelWriter w;
    for (std::size_t c = 0; c < kStandardChannels.size(); ++c) w.p_[c] = channels_.at(kStandardChannels[c]).data();
    return w;
  }

  /// Safe to call concurrently for distinct pixels (no map insertion; at() only).
  void set(int x, int y, const PixelSample& s) { pixel_writer().set(index(x, y), s); }

  /// The sample stored at (x, y) (the inverse of set(): object, status, steps and order are rounded back to
  /// integers).
  PixelSample sample(int x, int y) const {
    const std::size_t i = index(x, y);
    auto at = [&](const char* name) { return channels_.at(name)[i]; };
    PixelSample s;
    s.rgb = {at("R"), at("G"), at("B")};
    s.object = static_cast<int>(at("object"));
    s.status = static_cast<RayStatus>(static_cast<int>(at("status")));
    s.redshift = at("redshift");
    s.sky_theta = at("sky_theta");
    s.sky_phi = at("sky_phi");
    s.steps = static_cast<int>(at("steps"));
    s.order = static_cast<int>(at("order"));
    return s;
  }

  /// Free-form metadata (camera, metric, tableau, tolerances, render time): written as EXR header attributes.
  std::map<std::string, std::string> metadata;

 private:
  struct NoChannels {};
  Image(int width, int height, NoChannels) : width_(width), height_(height) {
    if (width <= 0 || height <= 0) throw std::invalid_argument("image size must be positive");
  }

  int width_, height_;
  std::map<std::string, std::vector<float>> channels_;
  std::vector<std::string> order_;
};

}  // namespace grtrace
