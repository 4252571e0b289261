// tests/benchmarks/kerr_benchmark.cpp
// Cost of one geodesic acceleration -Gamma(k, k) (closed form) for the Kerr metrics against Schwarzschild, at
// the same strong-field photon state (r = 10 M, off the equator), and of one whole Kerr ray:
//   accel/schwarzschild         SchwarzschildMetric::acceleration
//   accel/kerr_bl/<a>           KerrMetric::acceleration, a = 0 and a = 0.9 (same code path, the cost of Kerr at a = 0)
//   accel/kerr_schild/<a>       KerrSchildMetric::acceleration at the corresponding KS state
//   accel/kerr_bl_table         acceleration_from_christoffel(christoffel()) for comparison (not for the hot loop)
//   accel/kerr_mino/0.9         KerrMinoSystem's right-hand side (trace/kerr_mino_system.hpp: the separated equations
//                               in Mino time, five variables) at the same photon
//   ray/<metric>[/<a>]          one photon from r = 7 M to r = 200 M with DormandPrince54 + PI at rtol 1e-9;
//                               counter ns_per_step: CPU time per accepted step
//                               (ray/kerr_bl/0 is the same ray as ray/schwarzschild: the whole-ray cost of Kerr at a =
//                               0); ray/kerr_mino/0.9: the same ray on the separated equations (its steps are in
//                               Mino time: compare the counter us_per_ray as well)
// One call per iteration: read the CPU column (the machine is shared; wall time inflates under load). Run:
// build-*/tests/benchmarks/kerr_benchmark --benchmark_min_time=0.2
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"

#include <benchmark/benchmark.h>

namespace {

using namespace grtrace;

GeodesicState bl_state(double a) {
  const KerrMetric m{1.0, a};
  const Vec4 x(0.0, 10.0, 1.1, 0.3);
  const auto e = m.zamo_tetrad(x);
  return make_state(x, e[0] - 0.8 * e[1] + 0.36 * e[2] + 0.48 * e[3]);
}

template <class Metric>
void run_acceleration(benchmark::State& state, const Metric& metric, const GeodesicState& y) {
  Vec4 x = y.head<4>(), k = y.tail<4>();
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(k);
    Vec4 acc = metric.acceleration(x, k);
    benchmark::DoNotOptimize(acc);
  }
}

void accel_schwarzschild(benchmark::State& state) { run_acceleration(state, SchwarzschildMetric{1.0}, bl_state(0.0)); }
void accel_kerr_bl_0(benchmark::State& state) { run_acceleration(state, KerrMetric{1.0, 0.0}, bl_state(0.0)); }
void accel_kerr_bl_09(benchmark::State& state) { run_acceleration(state, KerrMetric{1.0, 0.9}, bl_state(0.9)); }
void accel_kerr_schild_0(benchmark::State& state) {
  const KerrSchildMetric ks{1.0, 0.0, KerrSchildSlicing::ingoing};
  run_acceleration(state, ks, bl_to_ks(ks, bl_state(0.0)));
}
void accel_kerr_schild_09(benchmark::State& state) {
  const KerrSchildMetric ks{1.0, 0.9, KerrSchildSlicing::ingoing};
  run_acceleration(state, ks, bl_to_ks(ks, bl_state(0.9)));
}
void accel_kerr_bl_table(benchmark::State& state) {
  const KerrMetric m{1.0, 0.9};
  const GeodesicState y = bl_state(0.9);
  Vec4 x = y.head<4>(), k = y.tail<4>();
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(k);
    Vec4 acc = acceleration_from_christoffel(m.christoffel(x), k);
    benchmark::DoNotOptimize(acc);
  }
}
void accel_kerr_mino(benchmark::State& state) {
  const KerrMetric m{1.0, 0.9};
  const GeodesicState y = bl_state(0.9);
  const KerrMinoSystem system(m, y);
  KerrMinoSystem::State z = system.initial_state(y);
  for (auto _ : state) {
    benchmark::DoNotOptimize(z);
    KerrMinoSystem::State dz = system(z);
    benchmark::DoNotOptimize(dz);
  }
}
BENCHMARK(accel_schwarzschild)->Name("accel/schwarzschild");
BENCHMARK(accel_kerr_bl_0)->Name("accel/kerr_bl/0");
BENCHMARK(accel_kerr_bl_09)->Name("accel/kerr_bl/0.9");
BENCHMARK(accel_kerr_schild_0)->Name("accel/kerr_schild/0");
BENCHMARK(accel_kerr_schild_09)->Name("accel/kerr_schild/0.9");
BENCHMARK(accel_kerr_bl_table)->Name("accel/kerr_bl_table/0.9");
BENCHMARK(accel_kerr_mino)->Name("accel/kerr_mino/0.9");

TraceSettings ray_settings() {
  TraceSettings s;
  s.integrator.tolerance = {1e-9, 1e-12};
  s.escape_radius = 200.0;
  return s;
}

/// Runs trace() (one ray -> TraceResult) and reports its steps, ns per step and microseconds per ray.
template <class Trace>
void run_traced(benchmark::State& state, Trace&& trace) {
  int steps = 0;
  for (auto _ : state) {
    const TraceResult r = trace();
    steps = r.accepted;
    benchmark::DoNotOptimize(r);
  }
  state.counters["steps"] = steps;
  state.counters["us_per_ray"] = benchmark::Counter(1e-6 * static_cast<double>(state.iterations()),
                                                    benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  // CPU time per accepted step (one core), the isolated counterpart of frame_benchmark's frame/metric/*.
  state.counters["ns_per_step"] = benchmark::Counter(static_cast<double>(steps) * static_cast<double>(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
GeodesicState ray_start(double a) {
  const KerrMetric m{1.0, a};
  const Vec4 x(0.0, 7.0, 1.1, 0.5);
  const auto e = m.zamo_tetrad(x);
  return make_state(x, e[0] - 0.5 * e[1] + 0.2 * e[2] + 0.8426149773 * e[3]);
}
template <class Metric>
void run_ray(benchmark::State& state, const Metric& metric, const GeodesicState& y0) {
  const GeodesicTracer<Metric, DormandPrince54, PIController> tracer(metric, ray_settings());
  run_traced(state, [&] { return tracer.trace(y0); });
}
void ray_schwarzschild(benchmark::State& state) { run_ray(state, SchwarzschildMetric{1.0}, ray_start(0.0)); }
void ray_kerr_bl_0(benchmark::State& state) { run_ray(state, KerrMetric{1.0, 0.0}, ray_start(0.0)); }
void ray_kerr_bl(benchmark::State& state) { run_ray(state, KerrMetric{1.0, 0.9}, ray_start(0.9)); }
void ray_kerr_schild(benchmark::State& state) {
  const KerrSchildMetric ks{1.0, 0.9, KerrSchildSlicing::ingoing};
  run_ray(state, ks, bl_to_ks(ks, ray_start(0.9)));
}
BENCHMARK(ray_schwarzschild)->Name("ray/schwarzschild");
BENCHMARK(ray_kerr_bl_0)->Name("ray/kerr_bl/0");
BENCHMARK(ray_kerr_bl)->Name("ray/kerr_bl/0.9");
void ray_kerr_mino(benchmark::State& state) {
  const KerrMetric m{1.0, 0.9};
  const GeodesicState y0 = ray_start(0.9);
  run_traced(state, [&] { return trace_kerr_mino<DormandPrince54>(m, ray_settings(), PIController{}, y0); });
}
BENCHMARK(ray_kerr_schild)->Name("ray/kerr_schild/0.9");
BENCHMARK(ray_kerr_mino)->Name("ray/kerr_mino/0.9");

}  // namespace

BENCHMARK_MAIN();
