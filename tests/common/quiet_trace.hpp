// tests/common/quiet_trace.hpp
// What the GPU's threads compute for a frame (gpu/gpu_frame.cuh: one trace_quietly per pixel), computed on the host,
// for the tests that compare the GPU path's host side with the CPU's frame (tests/render/gpu_host_side_test.cpp,
// tests/gpu/gpu_frame_test.cu).
#pragma once

#include "grtrace/observer/camera.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <vector>

namespace grtrace::testing_support {

/// The outcomes of the camera's top-left width x height pixels, row by row, each by tracer.trace_quietly (which
/// changes nothing: the pixels are traced by the machine's cores side by side, each into its own slot).
template <class Tracer>
std::vector<RayOutcome> trace_quietly_here(const Camera& camera, const Tracer& tracer, int width, int height) {
  const long count = static_cast<long>(width) * height;
  std::vector<RayOutcome> outcomes(static_cast<std::size_t>(count > 0 ? count : 0));
#pragma omp parallel for schedule(dynamic, 64)
  for (long i = 0; i < count; ++i)
    outcomes[static_cast<std::size_t>(i)] =
        tracer.trace_quietly(camera.pixel_state(static_cast<int>(i % width), static_cast<int>(i / width)));
  return outcomes;
}

}  // namespace grtrace::testing_support
