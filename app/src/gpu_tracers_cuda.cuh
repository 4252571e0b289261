// trace_on_gpu (gpu_tracers.hpp) for the tracers the CUDA units list: gpu::trace_pixels (gpu/gpu_frame.cuh), one
// explicit instantiation per tracer type, each checked against gpu_traces (a type the frame tracer units would never
// ask for, or one they ask for and no unit instantiates, is a compile or link error, not a silent CPU fallback).
#pragma once

#include "gpu_tracers.hpp"

#include "grtrace/gpu/gpu_frame.cuh"

namespace grtrace::app {

template <class Tracer>
std::vector<RayOutcome> trace_on_gpu(const Camera& camera, const Tracer& tracer, int width, int height,
                                     GpuSeconds* seconds) {
  static_assert(gpu_traces<Tracer>, "trace_on_gpu: add the tracer to gpu_traces (gpu_tracers.hpp) first");
  gpu::GpuTiming timing;
  std::vector<RayOutcome> outcomes = gpu::trace_pixels(camera, tracer, width, height, &timing);
  if (seconds) *seconds = {timing.trace, timing.total};
  return outcomes;
}

}  // namespace grtrace::app

/// The general tracer of Metric for both preset scene types.
#define GRTRACE_APP_GPU_GENERAL(Metric)                                                                           \
  template std::vector<RayOutcome> trace_on_gpu(                                                                 \
      const Camera&, const GeneralSceneTracer<Metric, GpuTableau, GpuController, BackgroundScene>&, int, int,   \
      GpuSeconds*);                                                                                               \
  template std::vector<RayOutcome> trace_on_gpu(                                                                 \
      const Camera&, const GeneralSceneTracer<Metric, GpuTableau, GpuController, DiskScene>&, int, int,         \
      GpuSeconds*);

/// The reduced Kerr tracer for both preset scene types.
#define GRTRACE_APP_GPU_KERR_MINO()                                                                               \
  template std::vector<RayOutcome> trace_on_gpu(                                                                 \
      const Camera&, const KerrMinoSceneTracer<GpuTableau, GpuController, BackgroundScene>&, int, int,          \
      GpuSeconds*);                                                                                               \
  template std::vector<RayOutcome> trace_on_gpu(                                                                 \
      const Camera&, const KerrMinoSceneTracer<GpuTableau, GpuController, DiskScene>&, int, int, GpuSeconds*);
