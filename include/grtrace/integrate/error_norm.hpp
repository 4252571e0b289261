// grtrace/integrate/error_norm.hpp
// Error norms for step control (Hairer, Norsett & Wanner I, eq. II.4.11).
// Each component of the local error estimate is scaled by sc_i = atol + rtol * max(|y_i|, |y_new_i|);
// a step is acceptable when the norm is <= 1.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/lanes.hpp"
#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/types.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace grtrace {

struct Tolerance {
  double rtol = 1e-8;
  double atol = 1e-10;
};

/// Root-mean-square of the scaled components (smooth, the usual choice).
struct RmsNorm {
  template <int N>
  GRTRACE_HD double operator()(const Vector<N>& err, const Vector<N>& y, const Vector<N>& y_new,
                               const Tolerance& tol) const {
    double sum = 0.0;
    for (int i = 0; i < N; ++i) {
      const double sc = tol.atol + tol.rtol * std::max(std::abs(y[i]), std::abs(y_new[i]));
      const double e = err[i] / sc;
      sum = mul_add(e, e, sum);
    }
    return std::sqrt(sum / N);
  }

  /// The same for W lanes at once (component-major, integrate/batch_stepper.hpp; W = 2, 4 or 8, one SIMD vector,
  /// core/lanes.hpp): lane l is operator() on lane l bit for bit (the same operations in the same order). In vector
  /// registers because the compiler leaves a loop over the lanes scalar; other widths are normed lane by lane
  /// (BatchedIntegrator does).
  template <std::size_t N, std::size_t W>
    requires(W == 2 || W == 4 || W == 8)
  std::array<double, W> operator()(const std::array<std::array<double, W>, N>& err,
                                   const std::array<std::array<double, W>, N>& y,
                                   const std::array<std::array<double, W>, N>& y_new, const Tolerance& tol) const {
    constexpr int w = static_cast<int>(W);
    const auto abs = [](const Lanes<w>& x) {  // std::abs: the sign bit cleared
      return std::bit_cast<Lanes<w>>(std::bit_cast<LaneMask<w>>(x) & std::numeric_limits<std::int64_t>::max());
    };
    const Lanes<w> atol = splat<w>(tol.atol), rtol = splat<w>(tol.rtol);
    Lanes<w> s = splat<w>(0.0);
    for (std::size_t i = 0; i < N; ++i) {
      const Lanes<w> a = abs(load_lanes(y[i])), b = abs(load_lanes(y_new[i]));
      const Lanes<w> sc = atol + rtol * (a < b ? b : a);  // std::max(a, b)
      const Lanes<w> e = load_lanes(err[i]) / sc;
      s = mul_add(e, e, s);
    }
    std::array<double, W> sum{};
    store_lanes(s, sum);
    for (std::size_t l = 0; l < W; ++l) sum[l] = std::sqrt(sum[l] / static_cast<int>(N));
    return sum;
  }
};

/// Largest scaled component (stricter: no component may exceed its tolerance).
struct MaxNorm {
  template <int N>
  GRTRACE_HD double operator()(const Vector<N>& err, const Vector<N>& y, const Vector<N>& y_new,
                               const Tolerance& tol) const {
    double worst = 0.0;
    for (int i = 0; i < N; ++i) {
      const double sc = tol.atol + tol.rtol * std::max(std::abs(y[i]), std::abs(y_new[i]));
      worst = std::max(worst, std::abs(err[i]) / sc);
    }
    return worst;
  }
};

}  // namespace grtrace
