// grtrace/core/optional.hpp
// A value or nothing, for the hot path that runs on the CPU and the GPU: a ray's end ("nothing: it goes on"), a
// crossing found in a step, a trial step size, the sky direction of an escaping Kerr ray.
//
// Why not std::optional: nvcc (CUDA 13 with libstdc++ 12, --expt-relaxed-constexpr) compiles the in-place
// constructor of std::optional<T>, for a T with a user-provided copy (one holding Eigen vectors: TraceResult,
// RefinedCrossing), into a call through a null function pointer in device code, without a diagnostic. Unoptimised,
// the GPU stops with "invalid program counter"; optimised, the call is dropped as unreachable and the trace loop
// never returns (every ray ran to the step cap or hung). Found in the PTX of tests/gpu/gpu_probe_unoptimised.cu;
// tests/gpu/device_code_test.cpp scans the application layer's kernels' PTX for such calls on every build with nvcc.
//
// Takes:   T default-constructible and copyable (the hot path's results are plain structs of numbers and
//          fixed-size Eigen vectors).
// Returns: std::optional's reading interface (has_value, operator bool, *, ->, value_or); an empty Optional holds a
//          default-constructed T that is never read.
// Assumes: nothing about the pass: no union, no placement new, every member callable on the host and the device.
#pragma once

#include "grtrace/core/host_device.hpp"

#include <type_traits>
#include <utility>

namespace grtrace {

/// The empty Optional's tag (std::nullopt's role): `return no_value;`.
struct NoValue {
  explicit constexpr NoValue(int) {}
};
inline constexpr NoValue no_value{0};

template <class T>
class Optional {
  static_assert(std::is_default_constructible_v<T> && std::is_copy_constructible_v<T>,
                "grtrace::Optional<T> holds a default-constructed T when empty: T needs a default constructor and a "
                "copy constructor (use std::optional off the hot path)");

 public:
  GRTRACE_HD constexpr Optional() {}
  GRTRACE_HD constexpr Optional(NoValue) {}
  GRTRACE_HD constexpr Optional(const T& value) : value_(value), engaged_(true) {}
  GRTRACE_HD constexpr Optional(T&& value) : value_(std::move(value)), engaged_(true) {}

  GRTRACE_HD constexpr bool has_value() const { return engaged_; }
  GRTRACE_HD constexpr explicit operator bool() const { return engaged_; }

  /// The value; reading an empty Optional's is a caller's error (as for std::optional), here a default T.
  GRTRACE_HD constexpr const T& operator*() const { return value_; }
  GRTRACE_HD constexpr T& operator*() { return value_; }
  GRTRACE_HD constexpr const T* operator->() const { return &value_; }
  GRTRACE_HD constexpr T* operator->() { return &value_; }

  GRTRACE_HD constexpr T value_or(const T& fallback) const { return engaged_ ? value_ : fallback; }

 private:
  T value_{};
  bool engaged_ = false;
};

}  // namespace grtrace
