// grtrace/viz/pick.hpp
// Picking a pixel of the frame: where a window position falls in the frame, and that pixel's ray traced through
// a scene tracer, as drawn in the 3D view and as the tracer reports it. Header-only and VTK-free, so a pick can be
// made (and tested, and scripted: grtrace-view --pick COL,ROW) without a display.
//
// FrameFit    how the frame viewport places the frame (viz/frame_view.hpp: scaled uniformly to fit, centred):
//             pixel centre -> viewport position and back. FrameView keeps one; tests build one by hand.
// pick_ray    pixel -> RayPick: the path drawn (trace_pixels, the bundle's own path recorder, with the scene
//             tracer's integrator and the scene's objects as events) and the scene tracer's outcome for the same
//             initial state (status, object, end radius, redshift, accepted steps), with the object's name.
// describe    one line of text for a pick: pixel, status, object, hit radius, redshift, steps.
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/trace/ray_outcome.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/viz/bundles.hpp"
#include "grtrace/viz/frame_image.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace grtrace::viz {

/// A frame of frame_width x frame_height pixels shown in a viewport of viewport_width x viewport_height screen
/// pixels: scaled by scale() (the largest that fits) and centred. Viewport positions are continuous, origin at
/// the bottom-left corner (screen pixel (i, j) covers [i, i+1) x [j, j+1)); frame pixels are (column, row from the
/// top), pixel (x, y) covering [x - 1/2, x + 1/2) around its centre.
struct FrameFit {
  int frame_width = 0, frame_height = 0;
  int viewport_width = 1, viewport_height = 1;

  /// Takes nothing; returns screen pixels per frame pixel (0 for an empty frame or viewport).
  double scale() const {
    if (frame_width <= 0 || frame_height <= 0 || viewport_width <= 0 || viewport_height <= 0) return 0.0;
    return std::min(static_cast<double>(viewport_width) / frame_width,
                    static_cast<double>(viewport_height) / frame_height);
  }

  /// Takes a frame position (x = column, y = row from the top; integers are pixel centres); returns its viewport
  /// position. Assumes a non-empty frame.
  std::array<double, 2> to_viewport(double x, double y) const {
    const double s = scale();
    const double cx = 0.5 * (frame_width - 1.0), cy = 0.5 * (frame_height - 1.0);
    const double from_bottom = frame_height - 1.0 - y;
    return {0.5 * viewport_width + (x - cx) * s, 0.5 * viewport_height + (from_bottom - cy) * s};
  }

  /// Takes a viewport position; returns the frame pixel (column, row from the top) under it, or nothing when the
  /// position is outside the frame (on the letterbox margin, or outside the viewport) or the frame is empty.
  std::optional<std::array<int, 2>> pixel_at(double viewport_x, double viewport_y) const {
    const double s = scale();
    if (!(s > 0.0) || !std::isfinite(viewport_x) || !std::isfinite(viewport_y)) return std::nullopt;
    const double cx = 0.5 * (frame_width - 1.0), cy = 0.5 * (frame_height - 1.0);
    const double column = std::floor((viewport_x - 0.5 * viewport_width) / s + cx + 0.5);
    const double from_bottom = std::floor((viewport_y - 0.5 * viewport_height) / s + cy + 0.5);
    if (column < 0.0 || column >= frame_width || from_bottom < 0.0 || from_bottom >= frame_height) return std::nullopt;
    return std::array<int, 2>{static_cast<int>(column), frame_height - 1 - static_cast<int>(from_bottom)};
  }
};

/// One picked pixel: its ray as drawn and as the scene tracer reports it.
struct RayPick {
  std::array<int, 2> pixel{};  ///< (column, row from the top)
  TracedPath path;             ///< the drawn path (pixel and colour set as for bundle rays)
  RayOutcome outcome;          ///< the scene tracer's outcome for the pixel
  std::string object_name;     ///< the scene's name of outcome.object ("sky", "horizon", "disk", ...); "" if failed
  /// A medium's scene: the intensity the ray collects from the camera to each sample of its path
  /// (app::medium_light_along), which colours it in the 3D view; empty otherwise.
  std::vector<double> light;
};

/// Takes a scene tracer with tracer() (its GeodesicTracer), scene() (objects tuple, object_names()) and trace(y0)
/// (trace/scene_tracer.hpp's GeneralSceneTracer), pixel_state(x, y) -> the camera's initial state of a pixel, the
/// pixel, samples per accepted step, the observer's 4-velocity (the redshift along the path; nothing: none) and
/// optionally the frame (the path's colour). Returns the pick. Assumes the pixel lies in the camera's frame
/// (callers check it: a pixel outside gives a ray outside the field of view, not an error).
template <class SceneTracer, class PixelState>
RayPick pick_ray(const SceneTracer& scene_tracer, const PixelState& pixel_state, std::array<int, 2> pixel,
                 int samples_per_step, std::optional<Vec4> observer_velocity, const Rgb8Image* frame = nullptr) {
  RayPick pick;
  pick.pixel = pixel;
  const std::array<std::array<int, 2>, 1> one{pixel};
  std::vector<TracedPath> paths = std::apply(
      [&](const auto&... objects) {
        return trace_pixels(scene_tracer.tracer(), pixel_state, std::span<const std::array<int, 2>>(one),
                            samples_per_step, observer_velocity, frame,
                            bind_to_metric(objects, scene_tracer.tracer().metric())...);
      },
      scene_tracer.scene().objects);
  pick.path = std::move(paths.front());
  pick.outcome = scene_tracer.trace(pixel_state(pixel[0], pixel[1]));
  pick.object_name = outcome_object_name(pick.outcome, scene_tracer.scene().object_names());
  return pick;
}

/// Takes a pick; returns one line: "pixel (COL, ROW): STATUS, OBJECT at r = R M, redshift Z, N steps" (failed
/// rays: no object, radius or redshift; a NaN redshift, where no emitter can be, is written "n/a"), and for a
/// medium's scene ", light collected I" (the intensity the path collected).
inline std::string describe(const RayPick& pick) {
  char buf[256];
  const RayOutcome& o = pick.outcome;
  if (is_failure(o.status)) {
    std::snprintf(buf, sizeof buf, "pixel (%d, %d): %s, %d steps", pick.pixel[0], pick.pixel[1],
                  std::string(to_string(o.status)).c_str(), o.steps);
    return buf;
  }
  char redshift[32] = "n/a";
  if (std::isfinite(o.redshift)) std::snprintf(redshift, sizeof redshift, "%.6g", o.redshift);
  std::snprintf(buf, sizeof buf, "pixel (%d, %d): %s, %s at r = %.6g M, redshift %s, %d steps", pick.pixel[0],
                pick.pixel[1], std::string(to_string(o.status)).c_str(), pick.object_name.c_str(), o.radius, redshift,
                o.steps);
  if (pick.light.empty()) return buf;
  char light[64];
  std::snprintf(light, sizeof light, ", light collected %.6g", pick.light.back());
  return buf + std::string(light);
}

}  // namespace grtrace::viz
