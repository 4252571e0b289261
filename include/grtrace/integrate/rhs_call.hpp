// grtrace/integrate/rhs_call.hpp
// How the integrators call a right-hand side f (State -> State): evaluate_rhs(f, y) is f(y), inlined on the CPU;
// on the GPU one out-of-line call with the state in registers.
//
// Takes:   f, callable as f(const Vector<N>&) -> Vector<N>, and y.
// Returns: f(y), the same bits on either side (the device path only copies the values in and out).
// Assumes: nothing of f: it is inlined into the one out-of-line copy on the GPU.
// Why on the GPU: a Runge-Kutta step calls f once per stage (12 times for rkf78), the refinement of a crossing
// once per stage of each of its steps, and so on; inlined at every call, the right-hand side filled the kernel
// with dozens of copies of itself and the warps waited on instruction fetches (core/host_device.hpp). Called, an
// Eigen vector is passed by a hidden pointer (it is not trivially copyable), i.e. through the thread's stack in
// local memory; a std::array of the values is passed and returned in registers. Measured on an H200, one kernel
// benchmark run (docs/benchmarks.md, "GPU"): the main frame's general tracer 26.8 ms with the vector passed,
// 18.3 ms with the values.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"

#include <array>
#include <cstddef>

namespace grtrace {

namespace rhs_call_detail {

/// The N values of a state, trivially copyable (passed in registers).
template <int N>
using Values = std::array<double, static_cast<std::size_t>(N)>;

/// The state's values, and back: copies, the same bits.
template <int N>
GRTRACE_HD Values<N> values_of(const Vector<N>& x) {
  Values<N> v;
  for (int i = 0; i < N; ++i) v[static_cast<std::size_t>(i)] = x[i];
  return v;
}
template <int N>
GRTRACE_HD Vector<N> vector_of(const Values<N>& v) {
  Vector<N> x;
  for (int i = 0; i < N; ++i) x[i] = v[static_cast<std::size_t>(i)];
  return x;
}

/// f at the values y: the GPU's one copy of f for this Rhs and N.
template <class Rhs, int N>
GRTRACE_GPU_CALLED GRTRACE_HD Values<N> evaluate_values(const Rhs& f, Values<N> y) {
  return values_of<N>(f(vector_of<N>(y)));
}

}  // namespace rhs_call_detail

/// Forced inline: on the CPU it is f(y), wherever f(y) stood before (the same code).
template <class Rhs, int N>
[[gnu::always_inline]] inline GRTRACE_HD Vector<N> evaluate_rhs(const Rhs& f, const Vector<N>& y) {
#if GRTRACE_DEVICE_PASS && !defined(GRTRACE_GPU_INLINE_ALL)
  using namespace rhs_call_detail;
  return vector_of<N>(evaluate_values<Rhs, N>(f, values_of<N>(y)));
#else
  return f(y);
#endif
}

}  // namespace grtrace
