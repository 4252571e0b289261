// tests/benchmarks/geodesic_benchmark.cpp
// Cost of one `grtrace-geodesic --impact 7` ray for every tableau at rtol 1e-8 (atol 1e-10, the CLI defaults):
// embedded pairs with the PI controller, the others with step doubling. Besides the time per ray it reports
// the right-hand-side evaluations, accepted and rejected steps, and the error of the total deflection against
// the exact elliptic-integral value. impact7_dense, disk_hit, disk_frame: the cost of refining event crossings on
// the step map (TraceSettings::refine_events), see below.
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/deflection.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

namespace {

using namespace grtrace;

constexpr double kImpact = 7.0;
constexpr double kRtol = 1e-8;
constexpr double kAtol = 1e-10;

template <class T>
void impact_ray(benchmark::State& state, bool refine) {
  using C = std::conditional_t<has_embedded_pair<T>, PIController, StepDoubling>;
  TraceSettings settings;
  settings.integrator.tolerance = {kRtol, kAtol};
  settings.refine_events = refine;
  const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{1.0}, settings);
  const double exact = exact::deflection_angle(kImpact);

  DeflectionResult result;
  for (auto _ : state) {
    result = measure_deflection(tracer, kImpact);
    benchmark::DoNotOptimize(result);
  }
  if (result.trace.status != RayStatus::escaped) state.SkipWithError("the b = 7 ray did not escape");
  state.counters["rhs_evals"] = static_cast<double>(result.trace.rhs_evals);
  state.counters["steps"] = static_cast<double>(result.trace.accepted);
  state.counters["rejected"] = static_cast<double>(result.trace.rejected);
  state.counters["error"] = std::abs(result.deflection - exact);
  state.SetLabel(std::string(C::name));
}

// ---- disk hits with and without refinement on the step map -----------------------------------------------
// disk_hit/<tableau>/<refined|dense>: one photon from r = 30, 0.4 rad above the equator, impact parameter 8,
// its orbital plane inclined, crossing the equatorial annulus 6 <= r <= 20 at r = 9.2645 (the first photon of
// tests/event_refinement_test.cpp); counters: rhs_evals, the right-hand sides spent on refinement, and the
// relative error of the hit radius against the exact 9.264495336375196.
// disk_frame/<tableau>/<refined|dense>: 16 x 16 such rays from 0.15 rad above the equator (impact parameters
// 0.25 ... 15, all directions of the orbital plane), through the same annulus: most cross the plane outside it
// once or twice (refined too, then refused) before they hit it, escape or fall in; the time is per ray.

struct DiskAnnulus {
  static constexpr bool two_sided = true;
  double operator()(const GeodesicState& y) const { return std::cos(y[2]); }
  bool accepts(const GeodesicState& y) const { return y[1] >= 6.0 && y[1] <= 20.0; }
};

/// A photon of energy 1 and impact parameter b at (r0, theta0, 0), moving inward, its angular motion alpha from
/// e_phi towards north.
GeodesicState inclined_photon(double b, double r0, double theta0, double alpha) {
  const double f = 1.0 - 2.0 / r0, w = b / (r0 * r0);
  const Vec4 x(0.0, r0, theta0, 0.0);
  const Vec4 k(1.0 / f, -std::sqrt(1.0 - f * b * b / (r0 * r0)), -w * std::sin(alpha),
               w * std::cos(alpha) / std::sin(theta0));
  GeodesicState y;
  y << x, k;
  return y;
}

template <class T>
void disk_hit(benchmark::State& state, bool refine) {
  using C = std::conditional_t<has_embedded_pair<T>, PIController, StepDoubling>;
  TraceSettings settings;
  settings.integrator.tolerance = {kRtol, kAtol};
  settings.refine_events = refine;
  const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{1.0}, settings);
  const GeodesicState y0 = inclined_photon(8.0, 30.0, std::numbers::pi / 2.0 - 0.4, -0.5);
  constexpr double exact_radius = 9.264495336375196;  // tests/event_refinement_test.cpp, ExactReference
  TraceResult r;
  for (auto _ : state) {
    r = tracer.trace(y0, DiskAnnulus{});
    benchmark::DoNotOptimize(r);
  }
  if (r.status != RayStatus::hit) state.SkipWithError("the photon did not hit the disk");
  state.counters["rhs_evals"] = static_cast<double>(r.rhs_evals);
  state.counters["refine_evals"] = static_cast<double>(r.refinement_evals);
  state.counters["radius_error"] = std::abs(r.final_state[1] / exact_radius - 1.0);
  state.SetLabel(std::string(C::name));
}

template <class T>
void disk_frame(benchmark::State& state, bool refine) {
  using C = std::conditional_t<has_embedded_pair<T>, PIController, StepDoubling>;
  TraceSettings settings;
  settings.integrator.tolerance = {kRtol, kAtol};
  settings.refine_events = refine;
  const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{1.0}, settings);
  std::vector<GeodesicState> rays;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j)
      rays.push_back(inclined_photon(0.25 + 0.98 * i, 30.0, std::numbers::pi / 2.0 - 0.15,
                                     2.0 * std::numbers::pi * j / 16.0));
  long evals = 0, refine_evals = 0;
  int hits = 0;
  for (auto _ : state) {
    evals = refine_evals = 0;
    hits = 0;
    for (const GeodesicState& y0 : rays) {
      const TraceResult r = tracer.trace(y0, DiskAnnulus{});
      evals += r.rhs_evals;
      refine_evals += r.refinement_evals;
      hits += r.status == RayStatus::hit;
    }
    benchmark::DoNotOptimize(evals);
  }
  const double n = static_cast<double>(rays.size());
  state.counters["rhs_evals_per_ray"] = static_cast<double>(evals) / n;
  state.counters["refine_evals_per_ray"] = static_cast<double>(refine_evals) / n;
  state.counters["hits"] = hits;
  state.counters["per_ray"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate |
                                                        benchmark::Counter::kInvert);
  state.SetLabel(std::string(C::name));
}

const bool registered = [] {
  for_each_tableau([](auto tag) {
    using T = typename decltype(tag)::type;
    benchmark::RegisterBenchmark(("impact7/" + std::string(T::name)).c_str(), impact_ray<T>, true)
        ->Unit(benchmark::kMicrosecond);
  });
  // The same escape located on the dense output only (TraceSettings::refine_events = false): the difference is
  // the cost of refining the sky-sphere crossing.
  for_each_tableau([](auto tag) {
    using T = typename decltype(tag)::type;
    benchmark::RegisterBenchmark(("impact7_dense/" + std::string(T::name)).c_str(), impact_ray<T>, false)
        ->Unit(benchmark::kMicrosecond);
  });
  for_each_tableau([](auto tag) {
    using T = typename decltype(tag)::type;
    if constexpr (T::order >= 4) {  // the low orders take 1e4+ steps per ray at rtol 1e-8
      for (const bool refine : {false, true}) {
        const std::string suffix = std::string(T::name) + (refine ? "/refined" : "/dense");
        benchmark::RegisterBenchmark(("disk_hit/" + suffix).c_str(), disk_hit<T>, refine)
            ->Unit(benchmark::kMicrosecond);
        benchmark::RegisterBenchmark(("disk_frame/" + suffix).c_str(), disk_frame<T>, refine)
            ->Unit(benchmark::kMillisecond);
      }
    }
  });
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
