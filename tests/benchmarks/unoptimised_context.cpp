// Linked into every benchmark of a build that compiles them at -O0 (GRTRACE_BENCHMARKS_UNOPTIMISED: the ci preset,
// which builds the benchmarks only to keep them compiling and never runs them): each report's context says so, so
// that no timing from such a build is mistaken for one (the bench and release presets compile them optimised).
#include <benchmark/benchmark.h>

namespace {

const bool kUnoptimisedNoted = [] {
  benchmark::AddCustomContext("grtrace_build",
                              "UNOPTIMISED (-O0, GRTRACE_BENCHMARKS_UNOPTIMISED): not timings; use the bench preset");
  return true;
}();

}  // namespace
