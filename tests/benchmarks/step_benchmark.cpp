// tests/benchmarks/step_benchmark.cpp
// The cost of the pieces of a ray, smallest first, so they can be compared with GPU codes' ~1 ns per photon
// per step:
//   rhs/acceleration      SchwarzschildMetric::acceleration (-Gamma k k in closed form)
//   rhs/acceleration_lanes/<W>  SchwarzschildMetric::acceleration_lanes<W>: W rays' accelerations at once in SIMD
//                         registers (core/lanes.hpp; W = 2, 4, 8), each lane acceleration()'s bits; counter
//                         ns_per_eval per ray (wall time / W), to compare with rhs/acceleration's
//   rhs/geodesic          the whole right-hand side d(x, k)/dlambda = (k, -Gamma k k)
//   step/<tableau>        one explicit Runge-Kutta step of every tableau (with the embedded error where there is
//                         one), state size 8; counters ns_per_step and ns_per_eval
//   ray/<method>/<kind>   one whole ray of the seed's main frame (static camera at r = 200 M, sky sphere at 400 M,
//                         exact continuation to infinity), for the candidate default methods; counters
//                         ns_per_step (wall time / accepted steps), steps, rejected, rhs_evals, error (rad,
//                         against exact::asymptotic_direction at the camera, continued from the sky-sphere
//                         crossing) and error_node (continued from the last accepted node)
//   lanes/<method>/<W>    the geodesic equation's integration alone (no events), W rays of the seed frame side by
//                         side in a BatchedIntegrator (integrate/batch_integrator.hpp: states lane-innermost, the
//                         right-hand side on all lanes at once with SchwarzschildMetric::acceleration_lanes), as
//                         the general tracer's frames integrate (trace/batched_trace.hpp); advance/<method> is
//                         one ray's ControlledIntegrator::advance. Counter ns_per_step: wall time per accepted
//                         step of one ray.
//   ad/<piece>/<metric>   automatic differentiation (metric/auto_metric.hpp) against the closed form, for
//                         Schwarzschild: acceleration() alone, one dopri5 step, and one whole ray (tsit5, I
//                         controller, rtol 2e-9: the render default) with counter ns_per_step per accepted step;
//                         <metric> is closed (SchwarzschildMetric), auto (AutoMetric<SchwarzschildComponents>,
//                         which declares depends_on = {r, theta}: Dual<2>) or auto_dual4 (the same g without
//                         depends_on: Dual<4>)
// Run: build-*/tests/benchmarks/step_benchmark --benchmark_min_time=0.2
//      build-*/tests/benchmarks/step_benchmark --benchmark_filter='^ad/' --benchmark_min_time=0.5
#include "grtrace/core/lanes.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/integrate/batch_integrator.hpp"
#include "grtrace/integrate/batch_stepper.hpp"
#include "grtrace/integrate/runge_kutta_stepper.hpp"
#include "grtrace/metric/examples/schwarzschild_components.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <optional>
#include <string>

namespace {

using namespace grtrace;
using Clock = std::chrono::steady_clock;

/// A photon state in the strong field (r = 10 M, off the equator), as stages see it mid-ray.
GeodesicState strong_field_state() {
  const double r = 10.0, f = 1.0 - 2.0 / r;
  const Vec4 x(0.0, r, 1.1, 0.3);
  const Vec4 k(1.0 / f, -0.6, 0.03, 0.05);
  return make_state(x, k);
}

/// Wall-clock nanoseconds per unit of work, measured around the whole benchmark loop.
class PerUnitTimer {
 public:
  PerUnitTimer() : start_(Clock::now()) {}
  double ns_per(double units_per_iteration, benchmark::IterationCount iterations) const {
    const double ns = std::chrono::duration<double, std::nano>(Clock::now() - start_).count();
    return ns / (units_per_iteration * static_cast<double>(iterations));
  }

 private:
  Clock::time_point start_;
};

// ---- right-hand side --------------------------------------------------------------------------------------

void rhs_acceleration(benchmark::State& state) {
  const SchwarzschildMetric metric{1.0};
  GeodesicState y = strong_field_state();
  Vec4 x = y.head<4>(), k = y.tail<4>();
  const PerUnitTimer timer;
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(k);
    Vec4 a = metric.acceleration(x, k);
    benchmark::DoNotOptimize(a);
  }
  state.counters["ns_per_eval"] = timer.ns_per(1.0, state.iterations());
}
BENCHMARK(rhs_acceleration);

/// W photons near strong_field_state's (r = 10 M + l / 4, theta = 1.1 + l / 100: every lane on polar_sin_cos's
/// short path, as rhs_acceleration's), through the same loop as rhs_acceleration.
template <int W>
void rhs_acceleration_lanes(benchmark::State& state) {
  const SchwarzschildMetric metric{1.0};
  std::array<Lanes<W>, 4> x{}, k{};
  for (std::size_t mu = 0; mu < 4; ++mu) {
    std::array<double, static_cast<std::size_t>(W)> xr{}, kr{};
    for (std::size_t l = 0; l < static_cast<std::size_t>(W); ++l) {
      const double r = 10.0 + 0.25 * static_cast<double>(l), f = 1.0 - 2.0 / r;
      const std::array<double, 4> xl = {0.0, r, 1.1 + 0.01 * static_cast<double>(l), 0.3};
      const std::array<double, 4> kl = {1.0 / f, -0.6, 0.03, 0.05};
      xr[l] = xl[mu];
      kr[l] = kl[mu];
    }
    x[mu] = load_lanes(xr);
    k[mu] = load_lanes(kr);
  }
  const PerUnitTimer timer;
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(k);
    std::array<Lanes<W>, 4> a = metric.acceleration_lanes<W>(x, k);
    benchmark::DoNotOptimize(a);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * W);
  state.counters["ns_per_eval"] = timer.ns_per(W, state.iterations());
}
BENCHMARK(rhs_acceleration_lanes<2>)->Name("rhs/acceleration_lanes/2");
BENCHMARK(rhs_acceleration_lanes<4>)->Name("rhs/acceleration_lanes/4");
BENCHMARK(rhs_acceleration_lanes<8>)->Name("rhs/acceleration_lanes/8");

void rhs_geodesic(benchmark::State& state) {
  const SchwarzschildMetric metric{1.0};
  const GeodesicEquation<SchwarzschildMetric> f{&metric};
  GeodesicState y = strong_field_state();
  const PerUnitTimer timer;
  for (auto _ : state) {
    benchmark::DoNotOptimize(y);
    GeodesicState dy = f(y);
    benchmark::DoNotOptimize(dy);
  }
  state.counters["ns_per_eval"] = timer.ns_per(1.0, state.iterations());
}
BENCHMARK(rhs_geodesic);

// ---- one step of each tableau -----------------------------------------------------------------------------

template <class T>
void one_step(benchmark::State& state) {
  const SchwarzschildMetric metric{1.0};
  const GeodesicEquation<SchwarzschildMetric> f{&metric};
  RungeKuttaStepper<T, 8> stepper;
  GeodesicState y = strong_field_state();
  const GeodesicState f0 = f(y);
  GeodesicState y_new, err;
  double h = 0.05;
  const PerUnitTimer timer;
  for (auto _ : state) {
    benchmark::DoNotOptimize(y);
    benchmark::DoNotOptimize(h);
    stepper.step(f, y, f0, h, y_new, err);
    benchmark::DoNotOptimize(y_new);
    benchmark::DoNotOptimize(err);
  }
  const double ns = timer.ns_per(1.0, state.iterations());
  constexpr int evals = RungeKuttaStepper<T, 8>::evals_per_step;  // stage 1 reuses f(y) from the last step
  state.counters["ns_per_step"] = ns;
  state.counters["evals"] = evals;
  if constexpr (evals > 0) state.counters["ns_per_eval"] = ns / evals;
}

// ---- one typical ray --------------------------------------------------------------------------------------

/// Pixel (px, py) of the seed's main frame: 1024 x 1024, fov 90, static camera at r = 200 M looking at the
/// hole (DESIGN.md pixel formula; same layout as grtrace-work-precision).
GeodesicState seed_frame_pixel(int px, int py) {
  const double r = 200.0, f = 1.0 - 2.0 / r, sf = std::sqrt(f), n_side = 1024.0;
  const double s = 2.0 * px / (n_side - 1.0) - 1.0, u = 2.0 * py / (n_side - 1.0) - 1.0;  // tan(45 deg) = 1
  const double n = std::sqrt(1.0 + u * u + s * s);
  return make_state(Vec4(0.0, r, std::numbers::pi / 2.0, 0.0), Vec4(-1.0 / sf, -sf / n, -u / (r * n), s / (r * n)));
}

/// Keeps the last accepted node of a ray (past the sky sphere), where the exact continuation may also start.
struct LastNode {
  GeodesicState* node;
  template <class Integrator>
  void operator()(const Integrator& integ, double /*theta_end*/) const {
    *node = integ.state();
  }
};

template <class T, class C>
void one_ray(benchmark::State& state, double rtol, int px, int py) {
  TraceSettings settings;
  settings.integrator.tolerance = {rtol, 1e-2 * rtol};
  settings.escape_radius = 400.0;
  const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{1.0}, settings);
  const GeodesicState y0 = seed_frame_pixel(px, py);
  const auto exact_dir = exact::asymptotic_direction(y0);
  TraceResult r;
  GeodesicState node = GeodesicState::Zero();
  const LastNode observer{&node};
  std::optional<exact::SkyDirection> dir;
  const PerUnitTimer timer;
  for (auto _ : state) {
    r = tracer.trace_observed(y0, observer);
    dir = r.status == RayStatus::escaped ? exact::asymptotic_direction(r.final_state) : std::nullopt;
    benchmark::DoNotOptimize(dir);
  }
  const auto dir_node = exact::asymptotic_direction(node);
  if (r.status != RayStatus::escaped || !dir || !dir_node || !exact_dir) {
    state.SkipWithError("the benchmark ray did not escape");
    return;
  }
  state.counters["ns_per_step"] = timer.ns_per(static_cast<double>(r.accepted), state.iterations());
  state.counters["steps"] = r.accepted;
  state.counters["rejected"] = r.rejected;
  state.counters["rhs_evals"] = static_cast<double>(r.rhs_evals);
  // error: exact continuation from the sky-sphere crossing the tracer reports (interpolated), as grtrace-render
  // does; error_node: from the last accepted node instead (see docs/benchmarks.md).
  state.counters["error"] = exact::angular_distance(*dir, *exact_dir);
  state.counters["error_node"] = exact::angular_distance(*dir_node, *exact_dir);
}

template <class T, class C>
void register_ray(const std::string& name, double rtol) {
  // typical: 30 degrees off the axis, weakly bent; near_ring: just outside the shadow edge (b ~ 5.2 M),
  // where the photon ring is and rays wind around the hole.
  benchmark::RegisterBenchmark(("ray/" + name + "/typical").c_str(), [rtol](benchmark::State& s) {
    one_ray<T, C>(s, rtol, 768, 640);
  })->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(("ray/" + name + "/near_ring").c_str(), [rtol](benchmark::State& s) {
    one_ray<T, C>(s, rtol, 525, 512);
  })->Unit(benchmark::kMicrosecond);
}

// ---- rays side by side (integration only) -------------------------------------------------------------------

/// Ray i of a fixed set of seed-frame pixels, 40 steps each (a typical ray takes 30 to 130), then the next.
constexpr int lane_steps = 40;
GeodesicState lane_start(int i) { return seed_frame_pixel(300 + 37 * (i % 16), 200 + 41 * (i / 16 % 16)); }

IntegratorSettings lane_settings(double rtol) { return IntegratorSettings{Tolerance{rtol, 1e-2 * rtol}}; }

template <class T, class C, int W>
void lanes(benchmark::State& state, double rtol) {
  const SchwarzschildMetric metric{1.0};
  const MetricGeodesicSystem<SchwarzschildMetric> system(metric, lane_start(0));  // its right-hand side: the metric's
  BatchedIntegrator<T, C, 8, W> batch(lane_settings(rtol));
  ControlledIntegrator<T, C, 8> starter(lane_settings(rtol));
  int next = 0;
  long accepted = 0;
  auto restart = [&](int l) {
    starter.start(system, lane_start(next++), 0.0);
    batch.load(l, starter);
  };
  for (int l = 0; l < W; ++l) restart(l);
  const PerUnitTimer timer;
  for (auto _ : state) {
    const auto verdict = batch.trial(system);
    for (int l = 0; l < W; ++l) {
      if (verdict[static_cast<std::size_t>(l)] != TrialVerdict::accepted) continue;
      batch.commit(l);
      ++accepted;
      if (batch.counters(l).accepted == lane_steps) restart(l);
    }
  }
  state.counters["ns_per_step"] = timer.ns_per(static_cast<double>(accepted) / static_cast<double>(state.iterations()),
                                               state.iterations());
}

template <class T, class C>
void advance_rays(benchmark::State& state, double rtol) {
  const SchwarzschildMetric metric{1.0};
  const GeodesicEquation<SchwarzschildMetric> f{&metric};
  ControlledIntegrator<T, C, 8> integ(lane_settings(rtol));
  int next = 0;
  integ.start(f, lane_start(next++), 0.0);
  const PerUnitTimer timer;
  for (auto _ : state) {
    benchmark::DoNotOptimize(integ.advance(f));
    if (integ.accepted() == lane_steps) integ.start(f, lane_start(next++), 0.0);
  }
  state.counters["ns_per_step"] = timer.ns_per(1.0, state.iterations());
}

template <class T, class C>
void register_lanes(const std::string& name, double rtol) {
  benchmark::RegisterBenchmark(("advance/" + name).c_str(),
                               [rtol](benchmark::State& s) { advance_rays<T, C>(s, rtol); });
  benchmark::RegisterBenchmark(("lanes/" + name + "/1").c_str(), [rtol](benchmark::State& s) { lanes<T, C, 1>(s, rtol); });
  benchmark::RegisterBenchmark(("lanes/" + name + "/2").c_str(), [rtol](benchmark::State& s) { lanes<T, C, 2>(s, rtol); });
  benchmark::RegisterBenchmark(("lanes/" + name + "/4").c_str(), [rtol](benchmark::State& s) { lanes<T, C, 4>(s, rtol); });
  benchmark::RegisterBenchmark(("lanes/" + name + "/8").c_str(), [rtol](benchmark::State& s) { lanes<T, C, 8>(s, rtol); });
}

// ---- automatic differentiation against the closed form ---------------------------------------------------

/// SchwarzschildComponents without depends_on: acceleration() differentiates along all four coordinates (Dual<4>).
struct SchwarzschildEveryCoordinate {
  static constexpr std::string_view name = "schwarzschild-auto-dual4";
  static constexpr Chart chart = Chart::spherical;
  double mass = 1.0;
  template <class S>
  Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    return SchwarzschildComponents{mass}.metric_components(x);
  }
  double radius(const Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 2.0 * mass; }
};
using AutoSchwarzschildDual4 = AutoMetric<SchwarzschildEveryCoordinate>;

template <class Metric>
void ad_acceleration(benchmark::State& state) {
  const Metric metric{};
  GeodesicState y = strong_field_state();
  Vec4 x = y.head<4>(), k = y.tail<4>();
  const PerUnitTimer timer;
  for (auto _ : state) {
    benchmark::DoNotOptimize(x);
    benchmark::DoNotOptimize(k);
    Vec4 a = metric.acceleration(x, k);
    benchmark::DoNotOptimize(a);
  }
  state.counters["ns_per_eval"] = timer.ns_per(1.0, state.iterations());
}

template <class Metric>
void ad_step(benchmark::State& state) {
  const Metric metric{};
  const GeodesicEquation<Metric> f{&metric};
  RungeKuttaStepper<DormandPrince54, 8> stepper;
  GeodesicState y = strong_field_state();
  const GeodesicState f0 = f(y);
  GeodesicState y_new, err;
  double h = 0.05;
  const PerUnitTimer timer;
  for (auto _ : state) {
    benchmark::DoNotOptimize(y);
    benchmark::DoNotOptimize(h);
    stepper.step(f, y, f0, h, y_new, err);
    benchmark::DoNotOptimize(y_new);
    benchmark::DoNotOptimize(err);
  }
  state.counters["ns_per_step"] = timer.ns_per(1.0, state.iterations());
}

template <class Metric>
void ad_ray(benchmark::State& state) {
  TraceSettings settings;
  settings.integrator.tolerance = {2e-9, 2e-11};
  settings.escape_radius = 400.0;
  const GeodesicTracer<Metric, Tsitouras54, IController> tracer(Metric{}, settings);
  const GeodesicState y0 = seed_frame_pixel(768, 640);
  TraceResult r;
  const PerUnitTimer timer;
  for (auto _ : state) {
    r = tracer.trace(y0);
    benchmark::DoNotOptimize(r);
  }
  if (r.status != RayStatus::escaped) {
    state.SkipWithError("the benchmark ray did not escape");
    return;
  }
  state.counters["ns_per_step"] = timer.ns_per(static_cast<double>(r.accepted), state.iterations());
  state.counters["steps"] = r.accepted;
}

BENCHMARK(ad_acceleration<SchwarzschildMetric>)->Name("ad/acceleration/closed");
BENCHMARK(ad_acceleration<AutoSchwarzschild>)->Name("ad/acceleration/auto");
BENCHMARK(ad_acceleration<AutoSchwarzschildDual4>)->Name("ad/acceleration/auto_dual4");
BENCHMARK(ad_step<SchwarzschildMetric>)->Name("ad/step_dopri5/closed");
BENCHMARK(ad_step<AutoSchwarzschild>)->Name("ad/step_dopri5/auto");
BENCHMARK(ad_step<AutoSchwarzschildDual4>)->Name("ad/step_dopri5/auto_dual4");
BENCHMARK(ad_ray<SchwarzschildMetric>)->Name("ad/ray_tsit5/closed")->Unit(benchmark::kMicrosecond);
BENCHMARK(ad_ray<AutoSchwarzschild>)->Name("ad/ray_tsit5/auto")->Unit(benchmark::kMicrosecond);
BENCHMARK(ad_ray<AutoSchwarzschildDual4>)->Name("ad/ray_tsit5/auto_dual4")->Unit(benchmark::kMicrosecond);

const bool registered = [] {
  for_each_tableau([](auto tag) {
    using T = typename decltype(tag)::type;
    benchmark::RegisterBenchmark(("step/" + std::string(T::name)).c_str(), one_step<T>);
  });
  // The defaults chosen from the work-precision chart (docs/benchmarks.md), grtrace-render's previous default,
  // the cheapest setting with the exit at the last node, and the seed's RK4 + step doubling.
  register_ray<Tsitouras54, IController>("tsit5/i/2e-9", 2e-9);
  register_ray<Tsitouras54, PIController>("tsit5/pi/3e-9", 3e-9);
  register_ray<DormandPrince54, PIController>("dopri5/pi/1e-10", 1e-10);
  register_ray<Fehlberg78, IController>("rkf78/i/1e-9", 1e-9);
  register_ray<ClassicRK4, StepDoubling>("rk4/doubling/1e-8", 1e-8);
  register_lanes<Fehlberg78, IController>("rkf78/i/1e-9", 1e-9);
  register_lanes<Tsitouras54, IController>("tsit5/i/2e-9", 2e-9);
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
