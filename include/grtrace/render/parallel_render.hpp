// grtrace/render/parallel_render.hpp
// The OpenMP image loop: calls a pixel function once per pixel, stores the PixelSample, counts statuses.
//
//   // one tracer per thread (its buffers are scratch), no sharing:
//   grtrace::RenderStats stats = grtrace::render_image(
//       image,
//       [&] { return MyTracer(config); },                       // factory: called once per thread, serially
//       [&](int x, int y, MyTracer& tracer) { return tracer.trace_pixel(x, y); },
//       {.threads = 0});
//
//   // or, when the pixel function needs no per-thread state:
//   grtrace::render_image(image, [&](int x, int y) { return shade(x, y); });
//
// Guarantees
// - Work: the image is cut into tiles (tile_width x tile_height, row-major order) handed out with OpenMP
//   schedule(dynamic, 1), so uneven rays (the shadow edge, the photon ring) balance across threads.
// - Determinism: every pixel is computed by exactly one call pixel(x, y, scratch) and written to its own place,
//   and the statistics are integer sums, so the image and the counts are identical for any thread count and
//   tiling, provided the pixel function's result depends only on (x, y) (not on what the scratch object did
//   before: reset any state you keep in it).
// - Threads: the pixel function is called concurrently from several threads through a const reference; keep
//   per-thread mutable state in the scratch object, never in captured variables. Extra channels can be written
//   from the pixel function through a pointer taken before the call, e.g.
//   `float* err = image.add_channel("error").data();` then `err[image.index(x, y)] = ...` (distinct pixels).
// - No NaN in R, G, B: a pixel whose colour has a non-finite component gets RenderOptions::error_rgb (magenta)
//   instead, and, unless its status already reports a failed integration (max_steps, step_underflow,
//   non_finite), its status becomes RayStatus::non_finite, in the image's "status" channel and in the counts.
//   RenderStats::bad_colour counts these pixels. A status outside the RayStatus range is also stored and
//   counted as non_finite (and counted in bad_status). Other channels (redshift, sky_theta, ...) may hold NaN
//   by contract and are stored as given.
// - Exceptions: an exception thrown by the factory propagates before any pixel is traced. One thrown by the
//   pixel function does not terminate the program: the first one is captured, the remaining tiles are skipped,
//   the progress line is finished, and it is rethrown from render_image(); the image is then incomplete.
// - Progress: a ProgressBar on stderr (only when it is a terminal, unless RenderOptions::progress says otherwise);
//   RenderOptions::pixels_done counts finished pixels for a caller that reports progress its own way.
// - Cancelling: RenderOptions::cancel, set from another thread, skips the tiles not yet begun and ends the call
//   with RenderCancelled (within one tile's time per thread).
// Without OpenMP (_OPENMP undefined) the same code runs on one thread.
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/render/progress_bar.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

namespace grtrace {

struct RenderOptions {
  int threads = 0;       ///< number of threads; 0 = the OpenMP default (OMP_NUM_THREADS or all cores)
  int tile_width = 16;   ///< pixels per tile along x; 0 = whole rows
  int tile_height = 16;  ///< pixels per tile along y (>= 1)
  ProgressMode progress = ProgressMode::automatic;   ///< bar on stderr only if it is a terminal
  std::string progress_label = "render";             ///< first word of the progress line
  std::array<float, 3> error_rgb{1.0f, 0.0f, 1.0f};  ///< linear colour written where a pixel's colour was not finite
  /// A bar owned by the caller that this render advances instead of drawing its own (progress and progress_label
  /// are then unused): one bar over a sequence of frames (render/flight.hpp). Must outlive the call.
  ProgressBar* shared_progress = nullptr;
  /// render_frame (render/frame.hpp): copy mirror images instead of tracing them where the frame is mirror
  /// symmetric (render/mirror_symmetry.hpp); false traces every pixel (for comparisons).
  bool mirror_symmetry = true;
  /// Set (by another thread) to stop the render: the tiles not yet begun are skipped and the call throws
  /// RenderCancelled once the running tiles are done. Must outlive the call.
  const std::atomic<bool>* cancel = nullptr;
  /// Advanced by each tile's pixels as it finishes, for a caller that shows progress from another thread (the
  /// bar above draws on stderr). Must outlive the call.
  std::atomic<long>* pixels_done = nullptr;
};

/// A render stopped through RenderOptions::cancel: the image is incomplete and nothing was returned.
struct RenderCancelled : std::runtime_error {
  RenderCancelled() : std::runtime_error("render cancelled") {}
};

struct RenderStats {
  int width = 0;
  int height = 0;
  int threads = 0;                                    ///< threads that actually ran the loop
  long rays = 0;                                      ///< pixels rendered (= width * height)
  long traced_rays = 0;  ///< pixels whose pixel function ran: rays, or fewer where mirror images were copied
  std::array<long, kRayStatusCount> status_counts{};  ///< indexed by RayStatus; sums to `rays`
  long total_steps = 0;                               ///< sum of PixelSample::steps
  /// Pixels showing a scene object (status hit) by the image's order (PixelSample::order): n = 0 (direct),
  /// 1, 2 and 3 or more (photon rings); hits of unknown order are not counted.
  std::array<long, 4> hits_by_order{};
  long bad_colour = 0;                                ///< pixels whose R,G,B were non-finite and got error_rgb
  long bad_status = 0;                                ///< pixels whose status was outside the RayStatus range
  double seconds = 0.0;                               ///< wall time of the whole call
  double rays_per_second = 0.0;
  double mean_steps = 0.0;  ///< total_steps / rays

  long count(RayStatus s) const { return status_counts[static_cast<std::size_t>(s)]; }
  /// Rays whose integration failed (max_steps + step_underflow + non_finite).
  long failures() const {
    return count(RayStatus::max_steps) + count(RayStatus::step_underflow) + count(RayStatus::non_finite);
  }
};

namespace detail {

/// Holds one thread's scratch object, built in place from the factory's result (no copy or move needed).
template <class Scratch>
struct ScratchSlot {
  template <class Factory>
  explicit ScratchSlot(Factory& make) : value(make()) {}
  Scratch value;
};

/// One thread's counters, on their own cache line.
struct alignas(64) RenderTally {
  std::array<long, kRayStatusCount> status_counts{};
  std::array<long, 4> hits_by_order{};
  long steps = 0;
  long bad_colour = 0;
  long bad_status = 0;
};

/// Applies the no-NaN-colour and valid-status rules (see the top of this file) and counts the sample.
// Forced inline: once per pixel (out of line in grtrace-render's translation unit otherwise).
[[gnu::always_inline]] inline void sanitize_and_count(PixelSample& s, const RenderOptions& options,
                                                      RenderTally& tally) {
  auto status_index = static_cast<std::size_t>(s.status);
  if (status_index >= kRayStatusCount) {
    s.status = RayStatus::non_finite;
    status_index = static_cast<std::size_t>(RayStatus::non_finite);
    ++tally.bad_status;
  }
  if (!std::isfinite(s.rgb[0]) || !std::isfinite(s.rgb[1]) || !std::isfinite(s.rgb[2])) {
    s.rgb = options.error_rgb;
    ++tally.bad_colour;
    if (!is_failure(s.status)) {
      s.status = RayStatus::non_finite;
      status_index = static_cast<std::size_t>(RayStatus::non_finite);
    }
  }
  ++tally.status_counts[status_index];
  tally.steps += s.steps;
  if (s.status == RayStatus::hit && s.order >= 0) ++tally.hits_by_order[static_cast<std::size_t>(std::min(s.order, 3))];
}

inline int max_threads() {
#if defined(_OPENMP)
  return omp_get_max_threads();
#else
  return 1;
#endif
}

}  // namespace detail

/// The loop of render_image over a traced grid of traced_width x traced_height pixels (the image's top-left part),
/// where each call orbit(x, y, scratch, emit) delivers the samples of every image pixel that grid point stands for
/// by calling emit(col, row, PixelSample) once per pixel: itself and, in a mirror-symmetric frame, its mirror
/// images (render/frame.hpp). A scratch object with begin_tile(x0, y0, x1, y1) is told each tile (the traced
/// grid's pixels x0 <= x < x1, y0 <= y < y1) before its pixels. Every image pixel must be emitted exactly once over
/// the whole grid; emit applies the colour and status rules, counts the sample and advances the progress by one
/// pixel. Same guarantees and errors as render_image (of which it is the general form); RenderStats::traced_rays is
/// the traced grid's size.
template <class ScratchFactory, class OrbitFn>
requires std::invocable<ScratchFactory&>
RenderStats render_image_by_orbits(Image& image, int traced_width, int traced_height, ScratchFactory&& make_scratch,
                                   const OrbitFn& orbit, const RenderOptions& options = {}) {
  using Scratch = std::remove_cvref_t<std::invoke_result_t<ScratchFactory&>>;
  using Slot = detail::ScratchSlot<Scratch>;

  if (options.threads < 0) throw std::invalid_argument("render_image: threads must be >= 0 (0 = OpenMP default)");
  if (options.tile_width < 0) throw std::invalid_argument("render_image: tile_width must be >= 0 (0 = whole rows)");
  if (options.tile_height < 1) throw std::invalid_argument("render_image: tile_height must be >= 1");
  for (float c : options.error_rgb)
    if (!std::isfinite(c)) throw std::invalid_argument("render_image: error_rgb must be finite");
  if (traced_width < 1 || traced_width > image.width() || traced_height < 1 || traced_height > image.height())
    throw std::invalid_argument("render_image: the traced grid must lie inside the image");

  const auto start = std::chrono::steady_clock::now();
  const int width = traced_width;
  const int height = traced_height;
  const Image::PixelWriter writer = image.pixel_writer();

  const int tile_w = options.tile_width == 0 ? width : std::min(options.tile_width, width);
  const int tile_h = std::min(options.tile_height, height);
  const long tiles_x = (width + tile_w - 1) / tile_w;
  const long tiles_y = (height + tile_h - 1) / tile_h;
  const long tile_count = tiles_x * tiles_y;

  const int requested = options.threads > 0 ? options.threads : std::max(detail::max_threads(), 1);
  std::vector<std::unique_ptr<Slot>> slots;
  slots.reserve(static_cast<std::size_t>(requested));
  for (int t = 0; t < requested; ++t) slots.push_back(std::make_unique<Slot>(make_scratch));
  std::vector<detail::RenderTally> tallies(static_cast<std::size_t>(requested));

  ProgressBar own_progress(options.shared_progress ? 0L : static_cast<long>(image.pixel_count()),
                           options.progress_label, options.shared_progress ? ProgressMode::never : options.progress);
  ProgressBar& progress = options.shared_progress ? *options.shared_progress : own_progress;
  std::atomic<bool> failed{false};
  std::atomic<bool> cancelled{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  int team_size = 1;

#if defined(_OPENMP)
#pragma omp parallel num_threads(requested)
#endif
  {
#if defined(_OPENMP)
    const int thread = omp_get_thread_num();
    if (thread == 0) team_size = omp_get_num_threads();
#else
    const int thread = 0;
#endif
    Scratch& scratch = slots[static_cast<std::size_t>(thread)]->value;
    detail::RenderTally& tally = tallies[static_cast<std::size_t>(thread)];

#if defined(_OPENMP)
#pragma omp for schedule(dynamic, 1)
#endif
    for (long tile = 0; tile < tile_count; ++tile) {
      if (failed.load(std::memory_order_relaxed)) continue;
      if (options.cancel && options.cancel->load(std::memory_order_relaxed)) {
        cancelled.store(true, std::memory_order_relaxed);
        continue;
      }
      try {
        const int x0 = static_cast<int>(tile % tiles_x) * tile_w;
        const int y0 = static_cast<int>(tile / tiles_x) * tile_h;
        const int x1 = std::min(x0 + tile_w, width);
        const int y1 = std::min(y0 + tile_h, height);
        // Optional scratch trait: begin_tile(x0, y0, x1, y1) before the tile's pixels (render/frame.hpp traces a
        // tile's rays together with it, TileOutcomes).
        if constexpr (requires { scratch.begin_tile(x0, y0, x1, y1); }) scratch.begin_tile(x0, y0, x1, y1);
        long emitted = 0;
        const auto emit = [&](int col, int row, PixelSample s) {
          detail::sanitize_and_count(s, options, tally);
          writer.set(image.index(col, row), s);
          ++emitted;
        };
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x) orbit(x, y, scratch, emit);
        progress.advance(emitted);
        if (options.pixels_done) options.pixels_done->fetch_add(emitted, std::memory_order_relaxed);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed.store(true, std::memory_order_relaxed);
      }
    }
  }

  own_progress.finish();
  if (first_error) std::rethrow_exception(first_error);
  if (cancelled.load()) throw RenderCancelled();

  RenderStats stats;
  stats.width = image.width();
  stats.height = image.height();
  stats.threads = team_size;
  stats.rays = static_cast<long>(image.pixel_count());
  stats.traced_rays = static_cast<long>(traced_width) * static_cast<long>(traced_height);
  for (const auto& tally : tallies) {
    for (std::size_t i = 0; i < kRayStatusCount; ++i) stats.status_counts[i] += tally.status_counts[i];
    stats.total_steps += tally.steps;
    for (std::size_t n = 0; n < stats.hits_by_order.size(); ++n) stats.hits_by_order[n] += tally.hits_by_order[n];
    stats.bad_colour += tally.bad_colour;
    stats.bad_status += tally.bad_status;
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.rays_per_second = stats.seconds > 0.0 ? static_cast<double>(stats.rays) / stats.seconds : 0.0;
  stats.mean_steps = stats.rays > 0 ? static_cast<double>(stats.total_steps) / static_cast<double>(stats.rays) : 0.0;
  return stats;
}

/// Renders every pixel of `image` (its ten standard channels) with `pixel(x, y, scratch) -> PixelSample`,
/// where each thread owns the object `make_scratch()` returned (called serially, once per thread, before the
/// loop). See the top of this file for the guarantees. Throws std::invalid_argument for bad options (negative
/// threads, tile sizes out of range, a non-finite error colour) and whatever the factory or pixel function threw.
template <class ScratchFactory, class PixelFn>
requires std::invocable<ScratchFactory&> && std::invocable < const PixelFn&, int, int,
    std::remove_cvref_t<std::invoke_result_t<ScratchFactory&>>
& > &&std::convertible_to<
        std::invoke_result_t<const PixelFn&, int, int, std::remove_cvref_t<std::invoke_result_t<ScratchFactory&>>&>,
        PixelSample>
        RenderStats render_image(Image& image, ScratchFactory&& make_scratch, const PixelFn& pixel,
                                 const RenderOptions& options = {}) {
  return render_image_by_orbits(
      image, image.width(), image.height(), std::forward<ScratchFactory>(make_scratch),
      [&pixel](int x, int y, auto& scratch, const auto& emit) { emit(x, y, pixel(x, y, scratch)); }, options);
}

/// The same loop for a pixel function without per-thread state: pixel(x, y) -> PixelSample, called
/// concurrently (it must be safe to call from several threads at once).
template <class PixelFn>
requires std::invocable<const PixelFn&, int, int> &&
    std::convertible_to<std::invoke_result_t<const PixelFn&, int, int>, PixelSample>
        RenderStats render_image(Image& image, const PixelFn& pixel, const RenderOptions& options = {}) {
  struct NoScratch {};
  return render_image(
      image, [] { return NoScratch{}; }, [&pixel](int x, int y, NoScratch&) -> PixelSample { return pixel(x, y); },
      options);
}

/// Records the statistics of a render in the image's metadata (written as EXR header attributes):
/// render_seconds, rays_per_second, mean_steps, render_threads, traced_rays, status_counts as a JSON object
/// {"escaped":N,...} with every status name, and hits_by_order as a JSON array [n0,n1,n2,n3+]. Existing keys are
/// overwritten.
inline void record_render_stats(Image& image, const RenderStats& stats) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", stats.seconds);
  image.metadata["render_seconds"] = buffer;
  std::snprintf(buffer, sizeof buffer, "%.6g", stats.rays_per_second);
  image.metadata["rays_per_second"] = buffer;
  std::snprintf(buffer, sizeof buffer, "%.6g", stats.mean_steps);
  image.metadata["mean_steps"] = buffer;
  image.metadata["render_threads"] = std::to_string(stats.threads);
  image.metadata["traced_rays"] = std::to_string(stats.traced_rays);
  std::string counts = "{";
  for (std::size_t i = 0; i < kRayStatusCount; ++i) {
    if (i > 0) counts.push_back(',');
    counts.push_back('"');
    counts.append(kRayStatusNames[i]);
    counts.append("\":");
    counts.append(std::to_string(stats.status_counts[i]));
  }
  counts.push_back('}');
  image.metadata["status_counts"] = counts;
  const auto& o = stats.hits_by_order;
  image.metadata["hits_by_order"] = "[" + std::to_string(o[0]) + "," + std::to_string(o[1]) + "," +
                                    std::to_string(o[2]) + "," + std::to_string(o[3]) + "]";
}

}  // namespace grtrace
