// The planar-path tracer on the disk frame: camera r = 50 M, inclination 80 degrees,
// fov 60, static, Schwarzschild M = 1, disk 6 .. 20 M, tsit5 + I at grtrace-render's default tolerance: the table
// (its build, including the scan of the frame's angles), the per-pixel read-out, and the whole frame; against the
// general tracer on the same frame (every pixel integrated) for the ratio. Run, e.g.:
//   build/ci/tests/benchmarks/planar_benchmark --benchmark_filter='disk/(planar|general)/256'
//   build/ci/tests/benchmarks/planar_benchmark --benchmark_filter='disk/planar/1024'
//   OMP_NUM_THREADS=1 build/ci/tests/benchmarks/planar_benchmark --benchmark_filter='pixel/'
//   build/ci/tests/benchmarks/planar_benchmark --benchmark_filter='main/'
// main/planar/1024 is grtrace-render's default frame (r = 200 M, fov 90, checkerboard sky, rkf78 + I at 1e-9, sky
// sphere at 400 M, 2048 table rays per side: a table of ends, a quarter of the pixels traced): table_ms (its
// build) and pixels_ms (render_frame: the image's nine channels and every pixel), repeated in one process, so
// without a fresh process's first-touch and thread start-up costs (docs/benchmarks.md).
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
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

void main_frame(benchmark::State& state) {
  const SchwarzschildMetric metric{1.0};
  CameraSpec cs;
  cs.position = Vec4(0.0, 200.0, std::numbers::pi / 2, 0.0);
  cs.width = cs.height = 1024;
  cs.fov_degrees = 90.0;
  const Camera cam = make_camera(metric, cs);
  TraceSettings settings;
  settings.integrator.tolerance = {1e-9, 1e-11};
  settings.escape_radius = 400.0;
  const BackgroundScene scene = background_scene(StandardSceneSpec{});
  double table_s = 0.0, total_s = 0.0;
  long traced = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const PlanarSceneTracer<SchwarzschildMetric, Fehlberg78, IController, BackgroundScene> tracer(
        metric, settings, cam, AngleCorrection::exact, scene, 2048);
    const auto t1 = std::chrono::steady_clock::now();
    const Frame f = render_frame(cam, tracer, quiet());
    traced = f.stats.traced_rays;
    const auto t2 = std::chrono::steady_clock::now();
    table_s += std::chrono::duration<double>(t1 - t0).count();
    total_s += std::chrono::duration<double>(t2 - t0).count();
  }
  const double it = static_cast<double>(state.iterations());
  state.counters["table_ms"] = table_s / it * 1e3;
  state.counters["pixels_ms"] = (total_s - table_s) / it * 1e3;
  state.counters["traced_rays"] = static_cast<double>(traced);
}

// Where a pixel's time goes (one thread: run with OMP_NUM_THREADS=1 for the same numbers as the docs): the camera ray,
// then cumulatively the planar geometry, the table look-up, the sky direction, the whole trace (disk crossings
// included) and its shading; ns per pixel of a 512x512 frame at r = 100, inclination 80 degrees, fov 60 (the seed
// flight's kind of frame). Each stage's cost is its difference to the one before.
void pixel_parts(benchmark::State& state, int stage) {
  const SchwarzschildMetric metric{1.0};
  CameraSpec cs;
  cs.position = Vec4(0.0, 100.0, 80.0 * std::numbers::pi / 180.0, 0.0);
  cs.width = cs.height = 512;
  cs.fov_degrees = 60.0;
  const Camera cam = make_camera(metric, cs);
  TraceSettings settings = disk_settings();
  settings.escape_radius = 1000.0;
  const PlanarSceneTracer<SchwarzschildMetric, Tsitouras54, IController, DiskScene> tracer(
      metric, settings, cam, AngleCorrection::exact, disk(), 2048);
  const auto& table = tracer.table();
  const DiskScene scene = disk();
  const SphericalBasis basis = spherical_basis(cs.position[2], cs.position[3]);  // as the tracer: once per frame
  double sink = 0.0;
  for (auto _ : state) {
    for (int row = 0; row < cam.height(); ++row)
      for (int col = 0; col < cam.width(); ++col) {
        const GeodesicState y = cam.pixel_state(col, row);
        if (stage == 0) {
          sink += y[5];
        } else if (stage <= 3) {
          const PlanarGeometry g = planar_geometry(metric, y, basis);
          if (stage == 1) sink += g.delta;
          else if (stage == 2) sink += table.at(g.delta).sweep_end;
          else sink += rotate_in_plane(g, table.at(g.delta).sweep_end).phi;
        } else if (stage == 4) {
          sink += tracer.trace(y).where.phi;
        } else {
          sink += static_cast<double>(scene.shade(tracer.trace(y)).rgb[0]);
        }
      }
    benchmark::DoNotOptimize(sink);
  }
  state.counters["ns_per_pixel"] = benchmark::Counter(static_cast<double>(state.iterations()) * 512.0 * 512.0,
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

const bool registered = [] {
  const char* parts[] = {"camera_ray", "planar_geometry", "table_lookup", "sky_direction", "trace", "trace_shade"};
  for (int stage = 0; stage < 6; ++stage)
    benchmark::RegisterBenchmark((std::string("pixel/") + std::to_string(stage) + "_" + parts[stage]).c_str(),
                                 [=](benchmark::State& s) { pixel_parts(s, stage); })
        ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("main/planar/1024", main_frame)->Unit(benchmark::kMillisecond)->UseRealTime();
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
