// grtrace/viz/bundles.hpp
// Bundles of rays to draw: initial states for a fan of parallel photons in the equatorial plane, and the
// subsampled pixel grids / fans of a camera's frame. Header-only and VTK-free.
//
// parallel_fan       `count` photons of a beam travelling along -x in the equatorial plane (the classic lensing
//                    diagram): impact parameters evenly spaced in [-b_max, b_max], starting on the sphere r = start.
// pixel_grid         a cols x rows grid of pixel centres spread evenly over a W x H frame (corners included when
//                    the grid has more than one column/row), as (x, y-from-top) pixels.
// pixel_row/column   `count` pixels along the middle row (a fan in the camera's horizontal plane) or the middle
//                    column (its vertical plane).
// trace_pixels       traces the rays of given pixels with any tracer (and the scene's events), recording each path;
//                    a path gets its pixel and, when a frame is given, the frame's colour of that pixel.
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/viz/frame_image.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

namespace grtrace::viz {

inline std::vector<GeodesicState> parallel_fan(double mass, int count, double b_max, double start_radius) {
  if (count < 1) throw std::invalid_argument("parallel_fan: count must be >= 1");
  if (!(b_max >= 0.0) || !(start_radius > b_max) || !(start_radius > 2.0 * mass))
    throw std::invalid_argument("parallel_fan: need 0 <= b_max < start radius, outside the horizon");
  std::vector<GeodesicState> out;
  for (int i = 0; i < count; ++i) {
    const double b = count == 1 ? 0.0 : -b_max + 2.0 * b_max * i / (count - 1);
    // incoming_photon starts at phi = 0; turning it by asin(b / r) makes its (flat, far-field) line parallel to -x.
    GeodesicState y = incoming_photon(std::abs(b), start_radius, mass);
    const double turn = std::asin(std::abs(b) / start_radius);
    if (b < 0.0) y[7] = -y[7];
    y[3] = b < 0.0 ? -turn : turn;
    out.push_back(y);
  }
  return out;
}

/// Pixel centres of a cols x rows grid over a width x height frame.
inline std::vector<std::array<int, 2>> pixel_grid(int width, int height, int cols, int rows) {
  if (width < 1 || height < 1 || cols < 1 || rows < 1) throw std::invalid_argument("pixel_grid: sizes must be >= 1");
  auto spread = [](int i, int n, int size) {
    if (n == 1) return (size - 1) / 2;
    return static_cast<int>(std::lround(static_cast<double>(i) * (size - 1) / (n - 1)));
  };
  std::vector<std::array<int, 2>> out;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) out.push_back({spread(c, cols, width), spread(r, rows, height)});
  return out;
}

inline std::vector<std::array<int, 2>> pixel_row(int width, int height, int count) {
  auto g = pixel_grid(width, 1, count, 1);
  for (auto& p : g) p[1] = (height - 1) / 2;
  return g;
}

inline std::vector<std::array<int, 2>> pixel_column(int width, int height, int count) {
  auto g = pixel_grid(1, height, 1, count);
  for (auto& p : g) p[0] = (width - 1) / 2;
  return g;
}

/// Takes a bundle ray's path, its frame pixel and the frame (or nothing); records the pixel on the path and gives it
/// the pixel's colour where the frame has one.
inline void mark_pixel(TracedPath& path, std::array<int, 2> p, const Rgb8Image* frame) {
  path.pixel_x = p[0];
  path.pixel_y = p[1];
  if (frame && !frame->empty() && p[0] >= 0 && p[1] >= 0 && p[0] < frame->width && p[1] < frame->height)
    path.color = frame->at(p[0], p[1]);
}

/// pixel_state(x, y) -> GeodesicState: the camera's initial state for pixel (x, y-from-top).
/// observer_velocity: the camera's 4-velocity e_0 (gives the redshift array). frame: colours for the paths.
template <class Tracer, class PixelState, class... Events>
std::vector<TracedPath> trace_pixels(const Tracer& tracer, const PixelState& pixel_state,
                                     std::span<const std::array<int, 2>> pixels, int samples_per_step,
                                     std::optional<Vec4> observer_velocity, const Rgb8Image* frame,
                                     const Events&... events) {
  std::vector<TracedPath> out;
  out.reserve(pixels.size());
  double held = 0.0;  // the bundle's paths together, under the memory limit as each one is (trace_path)
  for (const auto& p : pixels) {
    TracedPath path = trace_path(tracer, pixel_state(p[0], p[1]), samples_per_step, observer_velocity, events...);
    held += path_bytes(path.samples.capacity(), path.steps.capacity());
    check_memory(held, "the paths of " + std::to_string(out.size() + 1) + " of " + std::to_string(pixels.size()) +
                           " rays at " + std::to_string(samples_per_step) +
                           " samples a step (fewer rays or fewer samples a step)");
    mark_pixel(path, p, frame);
    out.push_back(std::move(path));
  }
  return out;
}

}  // namespace grtrace::viz
