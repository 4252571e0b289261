// The tracing kernels alone, timed by CUDA events: the Kerr disk frame (kerr-mino) and the main frame (general
// tracer, Schwarzschild), each at 1024x1024 whole (no mirror), rkf78 + I at the tools' defaults (rtol 1e-9, atol
// 1e-11, sky sphere at 400). Prints one JSON line a frame: the kernel's milliseconds in each of four runs (the first
// pays the module load), the mean steps and the status counts; with --host, also how the outcomes compare with the
// host pass of the same source on this machine's cores, judged as gpu_frame_test judges them (outcome_comparison.hpp:
// statuses, objects, and the largest differences of redshift, sky direction or hit point, and hit radius).
// Built twice by cmake/gpu-check.sh pack: as is, and with GRTRACE_GPU_INLINE_ALL (everything inlined into the
// kernel, as the CPU inlines: core/host_device.hpp), so one run measures the one against the other.
#include "../common/quiet_trace.hpp"
#include "gpu_probe.cuh"  // probe_camera
#include "outcome_comparison.hpp"

#include "grtrace/gpu/gpu_frame.cuh"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

using namespace grtrace;

constexpr int kSize = 1024;

template <class Tracer>
void bench(const char* name, const Camera& c, const Tracer& tracer, bool host) {
  std::vector<double> ms;
  std::vector<RayOutcome> gpu;
  for (int run = 0; run < 4; ++run) {
    gpu::GpuTiming timing;
    gpu = gpu::trace_pixels(c, tracer, kSize, kSize, &timing);
    ms.push_back(1e3 * timing.trace);
  }
  long steps = 0;
  std::array<long, kRayStatusCount> status{};
  for (const RayOutcome& o : gpu) {
    steps += o.steps;
    ++status[static_cast<std::size_t>(o.status)];
  }
  std::printf("{\"kernel\":\"%s\",\"inline_all\":%s,\"kernel_ms\":[%.2f,%.2f,%.2f,%.2f],\"mean_steps\":%.3f,"
              "\"status_counts\":{",
              name, GRTRACE_BENCH_INLINE_ALL ? "true" : "false", ms[0], ms[1], ms[2], ms[3],
              static_cast<double>(steps) / static_cast<double>(gpu.size()));
  for (std::size_t s = 0; s < kRayStatusCount; ++s)
    std::printf("%s\"%s\":%ld", s > 0 ? "," : "", std::string(kRayStatusNames[s]).c_str(), status[s]);
  std::printf("}");
  if (host) {
    // Judged as gpu_frame_test judges them (outcome_comparison.hpp), here printed, not asserted.
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<RayOutcome> here = testing_support::trace_quietly_here(c, tracer, kSize, kSize);
    const double host_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const testing_support::OutcomeComparison r = testing_support::compare_outcomes(gpu, here);
    std::printf(",\"host_seconds\":%.3f,\"status_differ\":%ld,\"object_differ\":%ld,\"redshift_diff\":%.2e,"
                "\"where_rad\":%.2e,\"radius_rel\":%.2e",
                host_s, r.status_differs, r.silhouette, r.redshift, r.direction, r.radius);
  }
  std::printf("}\n");
}

}  // namespace

int main(int argc, char** argv) {
  const bool host = argc > 1 && std::strcmp(argv[1], "--host") == 0;
  if (const gpu::GpuDevice d = gpu::first_gpu(); !d.present) {
    std::fprintf(stderr, "gpu_kernel_benchmark: no GPU (%s)\n", d.why_not.c_str());
    return 1;
  }
  TraceSettings settings;
  settings.escape_radius = 400.0;                 // grtrace-render's --sky-radius
  settings.integrator.tolerance = {1e-9, 1e-11};  // and its --rtol, --atol
  StandardSceneSpec disk;
  disk.name = "disk";
  const KerrMetric kerr{1.0, 0.9};
  bench("kerr_disk_mino", gpu_probe::probe_camera(kerr, 50.0, 80.0, 60.0, kSize),
        make_kerr_mino_tracer<Fehlberg78, IController>(kerr, settings, AngleCorrection::exact, disk_scene(disk)), host);
  const SchwarzschildMetric schwarzschild{1.0};
  bench("main_general", gpu_probe::probe_camera(schwarzschild, 200.0, 90.0, 90.0, kSize),
        make_general_tracer<Fehlberg78, IController>(schwarzschild, settings, AngleCorrection::exact,
                                                     background_scene(StandardSceneSpec{})),
        host);
}
