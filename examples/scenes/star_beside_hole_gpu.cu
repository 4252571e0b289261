// examples/scenes/star_beside_hole_gpu.cu
// star_beside_hole on a GPU: the same user-written star (glowing_star.hpp, whose surface and motion are marked
// GRTRACE_HD so that a GPU thread can call them), the same view and tracer (star_beside_hole.hpp), each pixel's ray
// traced by one GPU thread (grtrace/gpu/gpu_frame.cuh); shading and the files are the host's, as on the CPU.
// Built when CMake finds a CUDA compiler (nvcc -std=c++20 --expt-relaxed-constexpr). Without a CUDA device it says
// so and traces the same frame on the CPU.
//   star_beside_hole_gpu [--out star-gpu.exr] [--size 512]       writes star-gpu.exr and star-gpu.png
#include "example_cli.hpp"
#include "star_beside_hole.hpp"

#include "grtrace/gpu/gpu_frame.cuh"
#include "grtrace/render/frame.hpp"
#include "grtrace/tableau/tsitouras54.hpp"

#include <iostream>

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("star_beside_hole_gpu", [&] {
    const ExampleArgs args = parse_example_args(argc, argv, {"star-gpu.exr", 512, {}});
    const auto [camera, tracer] = star_beside_hole_view<Tsitouras54>(args.size);
    const gpu::GpuDevice device = gpu::first_gpu();
    if (!device.present) {
      std::cerr << "star_beside_hole_gpu: no GPU (" << device.why_not << "); tracing on the CPU\n";
      write_example_frame(args, render_frame(camera, tracer));
      return;
    }
    write_example_frame(args, gpu::render_frame_on_gpu(camera, tracer));
  });
}
