// examples/scenes/star_beside_hole_gpu.cu
// star_beside_hole on a GPU: the same user-written star (glowing_star.hpp, whose surface and motion are marked
// GRTRACE_HD so that a GPU thread can call them), the same Schwarzschild hole and the same tracer, each pixel's ray
// traced by one GPU thread (grtrace/gpu/gpu_frame.cuh); shading and the files are the host's, as on the CPU.
// Built when CMake finds a CUDA compiler (nvcc -std=c++20 --expt-relaxed-constexpr). Without a CUDA device it says
// so and traces the same frame on the CPU.
//   star_beside_hole_gpu [--out star-gpu.exr] [--size 512]       writes star-gpu.exr and star-gpu.png
#include "example_cli.hpp"
#include "glowing_star.hpp"

#include "grtrace/gpu/gpu_frame.cuh"
#include "grtrace/grtrace.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/tableau/fehlberg78.hpp"

#include <iostream>

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("star_beside_hole_gpu", [&] {
    const ExampleArgs args = parse_example_args(argc, argv, {"star-gpu.exr", 512, {}});
    const SchwarzschildMetric metric{1.0};
    CameraSpec spec;  // static observer at r = 30 M, a little above the plane, looking at the hole
    spec.position = Vec4(0.0, 30.0, 1.48, 0.0);
    spec.width = spec.height = args.size;
    spec.fov_degrees = 60.0;
    const Camera camera = make_camera(metric, spec);
    const GlowingStar star;  // at (-12, 6, 0): behind the hole, off to one side
    check_star(metric, star, spec.position);

    TraceSettings settings;
    settings.integrator.tolerance = {1e-9, 1e-11};
    settings.escape_radius = 400.0;
    const auto tracer = make_general_tracer<Fehlberg78, IController>(metric, settings, AngleCorrection::exact,
                                                                     make_scene(StarFieldSky{}, HorizonPaint{}, star));
    const gpu::GpuDevice device = gpu::first_gpu();
    if (!device.present) {
      std::cerr << "star_beside_hole_gpu: no GPU (" << device.why_not << "); tracing on the CPU\n";
      write_example_frame(args, render_frame(camera, tracer));
      return;
    }
    write_example_frame(args, gpu::render_frame_on_gpu(camera, tracer));
  });
}
