// tests/benchmarks/geodesic_benchmark.cpp
// Cost of one `grtrace-geodesic --impact 7` ray for every tableau at rtol 1e-8 (atol 1e-10, the CLI defaults):
// embedded pairs with the PI controller, the others with step doubling. Besides the time per ray it reports
// the right-hand-side evaluations, accepted and rejected steps, and the error of the total deflection against
// the exact elliptic-integral value.
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/deflection.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <type_traits>

namespace {

using namespace grtrace;

constexpr double kImpact = 7.0;
constexpr double kRtol = 1e-8;
constexpr double kAtol = 1e-10;

template <class T>
void impact_ray(benchmark::State& state) {
  using C = std::conditional_t<has_embedded_pair<T>, PIController, StepDoubling>;
  TraceSettings settings;
  settings.integrator.tolerance = {kRtol, kAtol};
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

const bool registered = [] {
  for_each_tableau([](auto tag) {
    using T = typename decltype(tag)::type;
    benchmark::RegisterBenchmark(("impact7/" + std::string(T::name)).c_str(), impact_ray<T>)
        ->Unit(benchmark::kMicrosecond);
  });
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
