// The tracers the CUDA backend runs, declared once (private to grtrace_app): the general tracer for every metric the
// tools integrate and the reduced Kerr tracer, each with the default method (rkf78 + I) and both preset scene types.
// frame_tracers_gpu_*.cu compile each one's kernel (trace_on_gpu); the frame tracer units, compiled by the C++
// compiler, ask gpu_traces<Tracer> and call trace_on_gpu across the boundary: the GPU units hold only kernels,
// while shading, mirrors and the frame's records stay in the CPU's one instantiation of render_frame.
#pragma once

#include "grtrace/app/front_door.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <type_traits>
#include <vector>

namespace grtrace::app {

/// True when this build has the CUDA backend (grtrace_app compiles frame_tracers_gpu_*.cu).
#if defined(GRTRACE_APP_CUDA)
inline constexpr bool kAppHasCuda = true;
#else
inline constexpr bool kAppHasCuda = false;
#endif

/// The one method the GPU runs: the tools' default.
using GpuTableau = Fehlberg78;
using GpuController = IController;
inline constexpr std::string_view kGpuTableau = "rkf78";
inline constexpr std::string_view kGpuControl = "i";

/// The metrics the GPU integrates: every metric the tools offer but flat space (drawn with straight lines).
template <class M>
inline constexpr bool gpu_metric =
    std::is_same_v<M, SchwarzschildMetric> || std::is_same_v<M, KerrMetric> || std::is_same_v<M, KerrSchildMetric> ||
    std::is_same_v<M, AutoReissnerNordstrom> || std::is_same_v<M, AutoSchwarzschildDeSitter> ||
    std::is_same_v<M, AutoEllisWormhole> || std::is_same_v<M, AutoEddingtonFinkelstein>;

template <class S>
inline constexpr bool gpu_scene = std::is_same_v<S, BackgroundScene> || std::is_same_v<S, DiskScene>;

/// True for the tracer types frame_tracers_gpu_*.cu instantiate trace_on_gpu for.
template <class Tracer>
inline constexpr bool gpu_traces = false;
template <class M, class S>
inline constexpr bool gpu_traces<GeneralSceneTracer<M, GpuTableau, GpuController, S>> = gpu_metric<M>&& gpu_scene<S>;
template <class S>
inline constexpr bool gpu_traces<KerrMinoSceneTracer<GpuTableau, GpuController, S>> = gpu_scene<S>;

/// What a frame's rays cost the GPU, in seconds (gpu::GpuTiming's trace and total, for the C++ units, which do not
/// read CUDA headers): the kernel's own time, and the whole call's (memory, copies and the kernel).
struct GpuSeconds {
  double kernel = 0.0, total = 0.0;
};

/// The outcomes of the camera's top-left width x height pixels, row by row, traced on the GPU
/// (gpu/gpu_frame.cuh, trace_pixels); *seconds (when given) receives what it cost. Defined for the tracers
/// gpu_traces lists, in the CUDA units only.
template <class Tracer>
std::vector<RayOutcome> trace_on_gpu(const Camera& camera, const Tracer& tracer, int width, int height,
                                     GpuSeconds* seconds);

}  // namespace grtrace::app
