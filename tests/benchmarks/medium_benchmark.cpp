// An emitting medium's frame: the spherically accreting Schwarzschild hole of examples/scenes/spherical_accretion
// (free fall, j ~ r^-2, a static camera at 1000 M, fov 1.2 degrees, rkf78 + I at rtol 1e-10) drawn from one table
// of rays (SphericalMediumTracer: its build and every pixel's look-up, through the image loop) against the general
// tracer, which integrates every pixel's ray with its light. Run, e.g.:
//   build/release/tests/benchmarks/medium_benchmark --benchmark_filter='table/1024'
//   build/release/tests/benchmarks/medium_benchmark --benchmark_filter='/128'
// table_ms is the table's build, pixels_ms the image loop; us_per_pixel is the whole frame over its pixels.
#include "grtrace/medium/spherical_accretion.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <benchmark/benchmark.h>

#include <chrono>
#include <numbers>

namespace {

using namespace grtrace;
using Table = SphericalMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SphericalAccretion>;
using General = GeneralMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SphericalAccretion>;

Camera camera_of(int n) {
  CameraSpec spec;
  spec.position = Vec4(0.0, 1000.0, std::numbers::pi / 2, 0.0);
  spec.spherical_position = true;
  spec.width = spec.height = n;
  spec.fov_degrees = 1.2;
  return make_camera(SchwarzschildMetric{1.0}, spec);
}

struct Scene {
  SchwarzschildMetric metric{1.0};
  SphericalAccretion gas;
  TraceSettings settings;
  Camera camera;
  RenderOptions options;
  explicit Scene(int n) : camera(camera_of(n)) {
    gas.outer = 1e6;
    settings.integrator.tolerance = {1e-10, 1e-12};
    settings.escape_radius = 2000.0;
    options.progress = ProgressMode::never;
  }
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void table(benchmark::State& state) {
  const Scene s(static_cast<int>(state.range(0)));
  double table_s = 0.0, pixels_s = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const Table tracer(s.metric, s.gas, s.settings, s.camera, 1.0);
    const auto t1 = std::chrono::steady_clock::now();
    const Frame frame = render_medium_frame(s.camera, tracer, s.options);
    pixels_s += seconds_since(t1);
    table_s += std::chrono::duration<double>(t1 - t0).count();
    benchmark::DoNotOptimize(frame.image.channel("intensity").data());
  }
  const double n = static_cast<double>(state.iterations()),
               pixels = static_cast<double>(state.range(0) * state.range(0));
  state.counters["table_ms"] = 1e3 * table_s / n;
  state.counters["pixels_ms"] = 1e3 * pixels_s / n;
  state.counters["us_per_pixel"] = 1e6 * (table_s + pixels_s) / n / pixels;
}

void general(benchmark::State& state) {
  const Scene s(static_cast<int>(state.range(0)));
  const General tracer(s.metric, s.gas, s.settings, s.camera.tetrad().e[0], 1.0);
  double total_s = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const Frame frame = render_medium_frame(s.camera, tracer, s.options);
    total_s += seconds_since(t0);
    benchmark::DoNotOptimize(frame.image.channel("intensity").data());
  }
  const double pixels = static_cast<double>(state.range(0) * state.range(0));
  state.counters["us_per_pixel"] = 1e6 * total_s / static_cast<double>(state.iterations()) / pixels;
}

BENCHMARK(table)->Name("accretion/table")->Arg(128)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(general)->Name("accretion/general")->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
