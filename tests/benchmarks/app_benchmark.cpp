// The application library's front door timed from C++ (grtrace/app/front_door.hpp): app::render of a typed request,
// the call the Python module's grtrace.render makes. python/benchmarks/render_overhead.py runs this program and the
// same requests from Python, alternated, to measure what the Python layer adds.
//   app_benchmark --benchmark_filter=front_door --benchmark_min_time=2
#include "grtrace/app/front_door.hpp"

#include <benchmark/benchmark.h>

#include <thread>

namespace {

using namespace grtrace;

/// The Kerr disk at a = 0.9 from 50 M, 80 degrees, 30 degrees across (the reduced Mino-time tracer), or the seed's
/// main frame (the planar tracer's table): `size` pixels square.
app::RenderRequest request(bool kerr, int size) {
  app::RenderRequest q;
  if (kerr) {
    q.metric.name = "kerr";
    q.metric.spin = 0.9;
    q.scene = "disk";
    q.camera.r = 50.0;
    q.camera.theta_degrees = 80.0;
    q.camera.fov_degrees = 30.0;
  }
  q.camera.width = q.camera.height = size;
  return q;
}

void front_door(benchmark::State& state, bool kerr) {
  const app::RenderRequest q = request(kerr, static_cast<int>(state.range(0)));
  app::RenderControl control;
  control.bar = ProgressMode::never;
  for (auto _ : state) {
    app::RenderResult r = app::render(q, control);
    benchmark::DoNotOptimize(r.image.channel("R").data());
  }
}

/// The same render on a thread of its own each time, as the Python module runs it (its OpenMP team is new each time).
void front_door_on_a_thread(benchmark::State& state, bool kerr) {
  const app::RenderRequest q = request(kerr, static_cast<int>(state.range(0)));
  app::RenderControl control;
  control.bar = ProgressMode::never;
  for (auto _ : state) {
    std::thread worker([&] {
      app::RenderResult r = app::render(q, control);
      benchmark::DoNotOptimize(r.image.channel("R").data());
    });
    worker.join();
  }
}

BENCHMARK_CAPTURE(front_door_on_a_thread, kerr_disk, true)->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(front_door, kerr_disk, true)->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(front_door, main_frame, false)->Arg(256)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
