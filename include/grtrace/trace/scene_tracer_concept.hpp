// grtrace/trace/scene_tracer_concept.hpp
// What the frame pipeline (render/frame.hpp) needs of a scene tracer, whichever way it follows the light:
//   static constexpr const char* name            "general", "symmetric-sky", "straight-line", ... (image headers)
//   RayOutcome trace(const GeodesicState& y0) const   one camera ray, from the pixel's initial state; safe to call
//                                                from several threads at once (no mutable state)
//   const Scene& scene() const                   the scene it traces through: shade(outcome) -> PixelSample and
//                                                object_names() (scene/scene.hpp)
// May provide (detected at compile time):
//   using MetricType = ...; using SceneType = ...; const MetricType& metric() const;
//                                                the spacetime and scene it traces: render_frame then checks the
//                                                frame's mirror symmetries (render/mirror_symmetry.hpp) and traces
//                                                only the pixels it cannot reflect; without them every pixel is traced
//   void trace_many(std::span<const GeodesicState> y0, std::span<RayOutcome> out) const
//                                                out[i] = trace(y0[i]) for a group of rays, bit for bit, in less time
//                                                (GeneralSceneTracer: rays side by side, trace/batched_trace.hpp):
//                                                render_frame then traces each tile's pixels together (TracesMany)
// The library's tracers: GeneralSceneTracer (any metric, every pixel integrated, trace/scene_tracer.hpp),
// SymmetricSceneTracer (Schwarzschild sky and horizon from one table of rays), StraightLineTracer (flat space).
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/scene/pixel_sample.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <concepts>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace grtrace {

template <class T>
concept SceneTracer = requires(const T t, const GeodesicState y, const RayOutcome o) {
  { T::name } -> std::convertible_to<std::string_view>;
  { t.trace(y) } -> std::same_as<RayOutcome>;
  { t.scene().shade(o) } -> std::same_as<PixelSample>;
  { t.scene().object_names() } -> std::convertible_to<std::vector<std::string>>;
};

/// The optional trait above: a scene tracer that traces a group of rays in one call.
template <class T>
concept TracesMany =
    SceneTracer<T> && requires(const T t, std::span<const GeodesicState> y0, std::span<RayOutcome> out) {
                        t.trace_many(y0, out);
                      };

}  // namespace grtrace
