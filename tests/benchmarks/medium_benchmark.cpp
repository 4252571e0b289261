// An emitting medium's frame: the spherically accreting Schwarzschild hole of examples/scenes/spherical_accretion
// (free fall, j ~ r^-2, a static camera at 1000 M, fov 1.2 degrees, vern6 + I at rtol 1e-10: the tools' method for
// media, whose error estimate sees the light) drawn from one table
// of rays (SphericalMediumTracer: its build and every pixel's look-up, through the image loop) against the general
// tracer, which integrates every pixel's ray with its light. Run, e.g.:
//   build/release/tests/benchmarks/medium_benchmark --benchmark_filter='table/1024'
//   build/release/tests/benchmarks/medium_benchmark --benchmark_filter='/128'
// table_ms is the table's build, pixels_ms the image loop; us_per_pixel is the whole frame over its pixels.
// riaf/kerr-mino: Sgr A*'s hot flow (medium/riaf.hpp) at 230 GHz around Kerr a = 0.9 from 1000 M at 17 degrees, a
// frame 40 M wide, vern6 + I at rtol 1e-8, every pixel integrated on Kerr's separated equations in Mino time;
// riaf/spectrum: the same frame at eight frequencies from 43 GHz to 1 THz, eight frames (one_pass:0) against one
// frame of eight bands (one_pass:1, each ray traced once, the flow asked for all eight at each stage).
#include "grtrace/medium/riaf.hpp"
#include "grtrace/medium/spherical_accretion.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace grtrace;
using Table = SphericalMediumTracer<SchwarzschildMetric, Verner65, IController, SphericalAccretion>;
using General = GeneralMediumTracer<SchwarzschildMetric, Verner65, IController, SphericalAccretion>;

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

/// Sgr A*'s frame of the riaf benchmarks (see the top of this file).
struct RiafScene {
  KerrMetric metric{1.0, 0.9};
  Camera camera;
  RiafFlow<KerrMetric> flow;
  TraceSettings settings;
  RenderOptions options;
  explicit RiafScene(int n)
      : camera([&] {
          CameraSpec spec;
          spec.position = Vec4(0.0, 1000.0, 17.0 * std::numbers::pi / 180.0, 0.0);
          spec.spherical_position = true;
          spec.width = spec.height = n;
          spec.fov_degrees = 2.0 * std::atan(20.0 / 1000.0) * 180.0 / std::numbers::pi;
          return make_camera(KerrMetric{1.0, 0.9}, spec);
        }()),
        flow(metric, [] {
          RiafParameters p = RiafParameters::sgr_a();
          p.outer = 2000.0;
          return p;
        }()) {
    settings.integrator.tolerance = {1e-8, 1e-10};
    settings.escape_radius = 2000.0;
    options.progress = ProgressMode::never;
  }
};

/// The eight frequencies of the spectrum benchmarks (examples/scenes/riaf_spectrum's), in Hz.
constexpr std::array<double, 8> kSpectrumHz{43e9, 86e9, 140e9, 230e9, 345e9, 490e9, 690e9, 1000e9};

template <class Tracer>
double frame_seconds(const RiafScene& s, const Tracer& tracer) {
  const auto t0 = std::chrono::steady_clock::now();
  const Frame frame = render_medium_frame(s.camera, tracer, s.options);
  benchmark::DoNotOptimize(frame.image.channel("intensity").data());
  return seconds_since(t0);
}

/// One frequency: 230 GHz.
void riaf(benchmark::State& state) {
  const RiafScene s(static_cast<int>(state.range(0)));
  const KerrMinoMediumTracer<Verner65, IController, RiafFlow<KerrMetric>> tracer(s.metric, s.flow, s.settings,
                                                                                 s.camera.tetrad().e[0], 230e9);
  double total_s = 0.0;
  for (auto _ : state) total_s += frame_seconds(s, tracer);
  const double pixels = static_cast<double>(state.range(0) * state.range(0));
  state.counters["us_per_pixel"] = 1e6 * total_s / static_cast<double>(state.iterations()) / pixels;
}

/// The spectrum at eight frequencies: one frame each (eight passes) against all eight in one pass.
void riaf_spectrum(benchmark::State& state) {
  const RiafScene s(static_cast<int>(state.range(0)));
  const bool one_pass = state.range(1) != 0;
  double total_s = 0.0;
  for (auto _ : state) {
    if (one_pass) {
      const KerrMinoMediumTracer<Verner65, IController, RiafFlow<KerrMetric>, kSpectrumHz.size()> tracer(
          s.metric, s.flow, s.settings, s.camera.tetrad().e[0], kSpectrumHz);
      std::vector<std::string> names(kSpectrumHz.size());
      for (std::size_t i = 0; i < names.size(); ++i) names[i] = std::to_string(i);
      const auto t0 = std::chrono::steady_clock::now();
      const Frame frame = render_medium_spectrum(s.camera, tracer, names, 3, s.options);
      benchmark::DoNotOptimize(frame.image.channel("intensity").data());
      total_s += seconds_since(t0);
    } else {
      for (const double nu : kSpectrumHz)
        total_s += frame_seconds(s, KerrMinoMediumTracer<Verner65, IController, RiafFlow<KerrMetric>>(
                                        s.metric, s.flow, s.settings, s.camera.tetrad().e[0], nu));
    }
  }
  const double pixels = static_cast<double>(state.range(0) * state.range(0));
  state.counters["us_per_pixel"] = 1e6 * total_s / static_cast<double>(state.iterations()) / pixels;
}

BENCHMARK(table)->Name("accretion/table")->Arg(128)->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(general)->Name("accretion/general")->Arg(128)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(riaf)->Name("riaf/kerr-mino")->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(riaf_spectrum)
    ->Name("riaf/spectrum")
    ->ArgNames({"n", "one_pass"})
    ->Args({64, 0})
    ->Args({64, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
