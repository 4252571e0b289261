// grtrace/metric/dual.hpp
// Forward-mode dual numbers: Dual<N> carries a value and its gradient with respect to N chosen variables.
//
// Takes:   doubles (constants, derivative 0) or seeded variables (Dual<N>::variable(value, i): derivative e_i),
//          combined with + - * /, comparisons (on the value) and the elementary functions below.
// Returns: for every expression f built from them, f's value and its N partial derivatives, exact up to the
//          rounding of each operation (no truncation error: this is not a finite difference).
// Assumes: the functions are smooth where they are evaluated (abs at 0, sqrt at 0 ... give the one-sided or
//          infinite derivative an IEEE calculation gives).
//
// Why our own type rather than Eigen's AutoDiffScalar<Matrix<double, N, 1>>:
//   - speed: every operation is a short loop over a std::array<double, N> that the compiler unrolls and
//     vectorises; no expression templates to see through, and products with plain doubles have their own
//     overloads (x * 0.0 cannot be folded away by the compiler under IEEE rules, so a double must never be
//     promoted to a Dual with a zero gradient in the hot loop);
//   - no heap, trivially copyable, sizeof = 8 (N + 1) bytes (AutoDiffScalar with a fixed-size vector does not
//     allocate either, but its dynamic-size default does, and a wrong template argument silently does so);
//   - constexpr: the arithmetic works in constant expressions (tested with static_assert);
//   - compile time: one small header instead of unsupported/Eigen/AutoDiff and its expression machinery.
// Elementary functions are hidden friends found by argument-dependent lookup, so metric code written as
// `using std::sin; sin(theta)` works for double and for Dual alike. There is deliberately no conversion from
// Dual to double (it would silently drop the derivative); primal_value(s) reads the value of either (for branches
// in a metric).
#pragma once

#include "grtrace/core/host_device.hpp"

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace grtrace {

template <int N>
struct Dual {
  static_assert(N >= 1, "Dual<N>: N is the number of derivative directions and must be at least 1");
  static constexpr std::size_t size = static_cast<std::size_t>(N);

  double v = 0.0;                ///< the value
  std::array<double, size> d{};  ///< d[i] = d(value)/d(variable i)

  constexpr Dual() = default;
  /// A constant (every derivative 0). Implicit, so literals and doubles mix freely with Duals.
  GRTRACE_HD constexpr Dual(double value) : v(value) {}  // NOLINT(google-explicit-constructor)
  GRTRACE_HD constexpr Dual(double value, const std::array<double, size>& gradient) : v(value), d(gradient) {}

  /// The i-th independent variable at `value` (derivative e_i).
  static constexpr GRTRACE_HD Dual variable(double value, int i) {
    Dual x(value);
    x.d[static_cast<std::size_t>(i)] = 1.0;
    return x;
  }

  // ---- arithmetic ----------------------------------------------------------------------------------------
  friend constexpr GRTRACE_HD Dual operator+(const Dual& a) { return a; }
  friend constexpr GRTRACE_HD Dual operator-(const Dual& a) {
    Dual r(-a.v);
    for (std::size_t i = 0; i < size; ++i) r.d[i] = -a.d[i];
    return r;
  }
  friend constexpr GRTRACE_HD Dual operator+(const Dual& a, const Dual& b) {
    Dual r(a.v + b.v);
    for (std::size_t i = 0; i < size; ++i) r.d[i] = a.d[i] + b.d[i];
    return r;
  }
  friend constexpr GRTRACE_HD Dual operator-(const Dual& a, const Dual& b) {
    Dual r(a.v - b.v);
    for (std::size_t i = 0; i < size; ++i) r.d[i] = a.d[i] - b.d[i];
    return r;
  }
  friend constexpr GRTRACE_HD Dual operator*(const Dual& a, const Dual& b) {
    Dual r(a.v * b.v);
    for (std::size_t i = 0; i < size; ++i) r.d[i] = a.d[i] * b.v + a.v * b.d[i];
    return r;
  }
  friend constexpr GRTRACE_HD Dual operator/(const Dual& a, const Dual& b) {
    const double inv = 1.0 / b.v, q = a.v * inv;
    Dual r(q);
    for (std::size_t i = 0; i < size; ++i) r.d[i] = (a.d[i] - q * b.d[i]) * inv;
    return r;
  }
  // Mixed with double: the double is a constant, so its (zero) gradient is never multiplied out.
  friend constexpr GRTRACE_HD Dual operator+(const Dual& a, double b) { return Dual(a.v + b, a.d); }
  friend constexpr GRTRACE_HD Dual operator+(double a, const Dual& b) { return Dual(a + b.v, b.d); }
  friend constexpr GRTRACE_HD Dual operator-(const Dual& a, double b) { return Dual(a.v - b, a.d); }
  friend constexpr GRTRACE_HD Dual operator-(double a, const Dual& b) { return a + (-b); }
  friend constexpr GRTRACE_HD Dual operator*(const Dual& a, double b) {
    Dual r(a.v * b);
    for (std::size_t i = 0; i < size; ++i) r.d[i] = a.d[i] * b;
    return r;
  }
  friend constexpr GRTRACE_HD Dual operator*(double a, const Dual& b) { return b * a; }
  friend constexpr GRTRACE_HD Dual operator/(const Dual& a, double b) { return a * (1.0 / b); }
  friend constexpr GRTRACE_HD Dual operator/(double a, const Dual& b) {
    const double inv = 1.0 / b.v, q = a * inv;
    Dual r(q);
    for (std::size_t i = 0; i < size; ++i) r.d[i] = -q * inv * b.d[i];
    return r;
  }

  constexpr Dual& operator+=(const Dual& b) { return *this = *this + b; }
  constexpr Dual& operator-=(const Dual& b) { return *this = *this - b; }
  constexpr Dual& operator*=(const Dual& b) { return *this = *this * b; }
  constexpr Dual& operator/=(const Dual& b) { return *this = *this / b; }
  constexpr Dual& operator+=(double b) { return *this = *this + b; }
  constexpr Dual& operator-=(double b) { return *this = *this - b; }
  constexpr Dual& operator*=(double b) { return *this = *this * b; }
  constexpr Dual& operator/=(double b) { return *this = *this / b; }

  // ---- comparisons: on the value only (branches in a metric pick a formula; they are not differentiated) --
  friend constexpr bool operator==(const Dual& a, const Dual& b) { return a.v == b.v; }
  friend constexpr bool operator==(const Dual& a, double b) { return a.v == b; }
  friend constexpr auto operator<=>(const Dual& a, const Dual& b) { return a.v <=> b.v; }
  friend constexpr auto operator<=>(const Dual& a, double b) { return a.v <=> b; }

  // ---- elementary functions (chain rule: f(a) + f'(a) da) ------------------------------------------------
  /// f(a) with derivative fp = f'(a.v).
  friend constexpr GRTRACE_HD Dual chain(const Dual& a, double f, double fp) {
    Dual r(f);
    for (std::size_t i = 0; i < size; ++i) r.d[i] = fp * a.d[i];
    return r;
  }
  friend GRTRACE_HD Dual sqrt(const Dual& a) {
    const double s = std::sqrt(a.v);
    return chain(a, s, 0.5 / s);
  }
  friend GRTRACE_HD Dual cbrt(const Dual& a) {
    const double c = std::cbrt(a.v);
    return chain(a, c, 1.0 / (3.0 * c * c));
  }
  friend GRTRACE_HD Dual sin(const Dual& a) { return chain(a, std::sin(a.v), std::cos(a.v)); }
  friend GRTRACE_HD Dual cos(const Dual& a) { return chain(a, std::cos(a.v), -std::sin(a.v)); }
  friend GRTRACE_HD Dual tan(const Dual& a) {
    const double t = std::tan(a.v);
    return chain(a, t, 1.0 + t * t);
  }
  friend GRTRACE_HD Dual asin(const Dual& a) { return chain(a, std::asin(a.v), 1.0 / std::sqrt(1.0 - a.v * a.v)); }
  friend GRTRACE_HD Dual acos(const Dual& a) { return chain(a, std::acos(a.v), -1.0 / std::sqrt(1.0 - a.v * a.v)); }
  friend GRTRACE_HD Dual atan(const Dual& a) { return chain(a, std::atan(a.v), 1.0 / (1.0 + a.v * a.v)); }
  friend GRTRACE_HD Dual atan2(const Dual& y, const Dual& x) {
    const double inv = 1.0 / (x.v * x.v + y.v * y.v);
    Dual r(std::atan2(y.v, x.v));
    for (std::size_t i = 0; i < size; ++i) r.d[i] = (x.v * y.d[i] - y.v * x.d[i]) * inv;
    return r;
  }
  friend GRTRACE_HD Dual exp(const Dual& a) {
    const double e = std::exp(a.v);
    return chain(a, e, e);
  }
  friend GRTRACE_HD Dual log(const Dual& a) { return chain(a, std::log(a.v), 1.0 / a.v); }
  friend GRTRACE_HD Dual sinh(const Dual& a) { return chain(a, std::sinh(a.v), std::cosh(a.v)); }
  friend GRTRACE_HD Dual cosh(const Dual& a) { return chain(a, std::cosh(a.v), std::sinh(a.v)); }
  friend GRTRACE_HD Dual tanh(const Dual& a) {
    const double t = std::tanh(a.v);
    return chain(a, t, 1.0 - t * t);
  }
  friend GRTRACE_HD Dual pow(const Dual& a, double p) {
    const double ap = std::pow(a.v, p - 1.0);
    return chain(a, ap * a.v, p * ap);
  }
  friend GRTRACE_HD Dual pow(const Dual& a, const Dual& p) { return exp(p * log(a)); }
  friend constexpr GRTRACE_HD Dual abs(const Dual& a) { return a.v < 0.0 ? -a : a; }
  friend constexpr GRTRACE_HD Dual fabs(const Dual& a) { return abs(a); }
  friend GRTRACE_HD bool isfinite(const Dual& a) {
    bool ok = std::isfinite(a.v);
    for (double x : a.d) ok = ok && std::isfinite(x);
    return ok;
  }
};

/// The value of a number, Dual or plain (for branches and for code shared by both).
constexpr GRTRACE_HD double primal_value(double x) { return x; }
template <int N>
constexpr GRTRACE_HD double primal_value(const Dual<N>& x) {
  return x.v;
}

}  // namespace grtrace

// Eigen: Dual<N> as a matrix scalar (Matrix<Dual<4>, 4, 4>), mixing with double in products.
namespace Eigen {

template <int N>
struct NumTraits<grtrace::Dual<N>> : NumTraits<double> {
  using Real = grtrace::Dual<N>;
  using NonInteger = grtrace::Dual<N>;
  using Nested = grtrace::Dual<N>;
  using Literal = double;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = N + 1,
    AddCost = N + 1,
    MulCost = 2 * N + 1,
  };
  static inline GRTRACE_HD Real epsilon() { return Real(std::numeric_limits<double>::epsilon()); }
  static inline GRTRACE_HD Real dummy_precision() { return Real(NumTraits<double>::dummy_precision()); }
  static inline GRTRACE_HD Real highest() { return Real(std::numeric_limits<double>::max()); }
  static inline GRTRACE_HD Real lowest() { return Real(std::numeric_limits<double>::lowest()); }
};

template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<grtrace::Dual<N>, double, BinaryOp> {
  using ReturnType = grtrace::Dual<N>;
};
template <int N, typename BinaryOp>
struct ScalarBinaryOpTraits<double, grtrace::Dual<N>, BinaryOp> {
  using ReturnType = grtrace::Dual<N>;
};

}  // namespace Eigen
