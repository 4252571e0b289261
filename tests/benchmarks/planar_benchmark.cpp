// The planar-path tracer (issue 11) on the disk frame of the issue: camera r = 50 M, inclination 80 degrees,
// fov 60, static, Schwarzschild M = 1, disk 6 .. 20 M, tsit5 + I at grtrace-render's default tolerance: the table
// (its build, including the scan of the frame's angles), the per-pixel read-out, and the whole frame; against the
// general tracer on the same frame (every pixel integrated) for the ratio. Run, e.g.:
//   build/ci/tests/benchmarks/planar_benchmark --benchmark_filter='disk/(planar|general)/256'
//   build/ci/tests/benchmarks/planar_benchmark --benchmark_filter='disk/planar/1024'
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/trace/planar_scene_tracer.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <numbers>
#include <string>

namespace {

using namespace grtrace;

TraceSettings disk_settings() {
  TraceSettings s;
  s.integrator.tolerance = {2e-9, 2e-11};  // grtrace-render's default
  s.escape_radius = 400.0;
  return s;
}

Camera disk_camera(int n) {
  CameraSpec cs;
  cs.position = Vec4(0.0, 50.0, 80.0 * std::numbers::pi / 180.0, 0.0);
  cs.width = cs.height = n;
  cs.fov_degrees = 60.0;
  return make_camera(SchwarzschildMetric{1.0}, cs);
}

DiskScene disk() {
  StandardSceneSpec spec;
  spec.name = "disk";
  return disk_scene(spec);
}

RenderOptions quiet() {
  RenderOptions o;
  o.progress = ProgressMode::never;
  return o;
}

void disk_planar(benchmark::State& state, int n, int nodes) {
  const Camera cam = disk_camera(n);
  double table_s = 0.0, total_s = 0.0;
  long table_steps = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const PlanarSceneTracer<SchwarzschildMetric, Tsitouras54, IController, DiskScene> tracer(
        SchwarzschildMetric{1.0}, disk_settings(), cam, AngleCorrection::exact, disk(), nodes);
    const auto t1 = std::chrono::steady_clock::now();
    const Frame f = render_frame(cam, tracer, quiet());
    benchmark::DoNotOptimize(f.image.width());
    const auto t2 = std::chrono::steady_clock::now();
    table_s += std::chrono::duration<double>(t1 - t0).count();
    total_s += std::chrono::duration<double>(t2 - t0).count();
    table_steps = tracer.table().table_steps();
  }
  const double it = static_cast<double>(state.iterations());
  state.counters["table_ms"] = table_s / it * 1e3;
  state.counters["pixels_ms"] = (total_s - table_s) / it * 1e3;
  state.counters["table_steps"] = static_cast<double>(table_steps);
}

void disk_general(benchmark::State& state, int n) {
  const Camera cam = disk_camera(n);
  const auto tracer = make_general_tracer<Tsitouras54, IController>(SchwarzschildMetric{1.0}, disk_settings(),
                                                                    AngleCorrection::exact, disk());
  long steps = 0;
  for (auto _ : state) {
    const Frame f = render_frame(cam, tracer, quiet());
    steps = f.stats.total_steps;
  }
  state.counters["steps_per_ray"] = static_cast<double>(steps) / (static_cast<double>(n) * n);
}

const bool registered = [] {
  for (const int n : {256, 1024}) {
    benchmark::RegisterBenchmark(("disk/planar/" + std::to_string(n)).c_str(),
                                 [=](benchmark::State& s) { disk_planar(s, n, 2048); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("disk/general/" + std::to_string(n)).c_str(),
                                 [=](benchmark::State& s) { disk_general(s, n); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
