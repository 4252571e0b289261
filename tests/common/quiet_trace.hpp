// tests/common/quiet_trace.hpp
// What the GPU's threads compute for a frame (gpu/gpu_frame.cuh: one trace_quietly per pixel), computed on the host,
// for the tests that compare the GPU path's host side with the CPU's frame (tests/render/gpu_host_side_test.cpp,
// tests/gpu/gpu_frame_test.cu).
#pragma once

#include "grtrace/observer/camera.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <vector>

namespace grtrace::testing_support {

/// The outcomes of the camera's top-left width x height pixels, row by row, each by tracer.trace_quietly.
template <class Tracer>
std::vector<RayOutcome> trace_quietly_here(const Camera& camera, const Tracer& tracer, int width, int height) {
  std::vector<RayOutcome> outcomes;
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) outcomes.push_back(tracer.trace_quietly(camera.pixel_state(col, row)));
  return outcomes;
}

}  // namespace grtrace::testing_support
