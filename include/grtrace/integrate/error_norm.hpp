// grtrace/integrate/error_norm.hpp
// Error norms for step control (Hairer, Norsett & Wanner I, eq. II.4.11).
// Each component of the local error estimate is scaled by sc_i = atol + rtol * max(|y_i|, |y_new_i|);
// a step is acceptable when the norm is <= 1.
#pragma once

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
  double operator()(const Vector<N>& err, const Vector<N>& y, const Vector<N>& y_new, const Tolerance& tol) const {
    double sum = 0.0;
    for (int i = 0; i < N; ++i) {
      const double sc = tol.atol + tol.rtol * std::max(std::abs(y[i]), std::abs(y_new[i]));
      const double e = err[i] / sc;
      sum = mul_add(e, e, sum);
    }
    return std::sqrt(sum / N);
  }

  /// The same for W lanes at once (component-major, integrate/batch_stepper.hpp): lane l is operator() on lane l
  /// bit for bit (the same operations in the same order), with the lanes side by side in vector registers.
  template <std::size_t N, std::size_t W>
  std::array<double, W> operator()(const std::array<std::array<double, W>, N>& err,
                                   const std::array<std::array<double, W>, N>& y,
                                   const std::array<std::array<double, W>, N>& y_new, const Tolerance& tol) const {
    std::array<double, W> sum{};
    if constexpr (W == 2 || W == 4 || W == 8) {
      // In vector registers (core/lanes.hpp): the compiler leaves the loop below scalar.
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
      store_lanes(s, sum);
    } else {
      for (std::size_t i = 0; i < N; ++i)
        for (std::size_t l = 0; l < W; ++l) {
          const double sc = tol.atol + tol.rtol * std::max(std::abs(y[i][l]), std::abs(y_new[i][l]));
          const double e = err[i][l] / sc;
          sum[l] = mul_add(e, e, sum[l]);
        }
    }
    for (std::size_t l = 0; l < W; ++l) sum[l] = std::sqrt(sum[l] / static_cast<int>(N));
    return sum;
  }
};

/// Largest scaled component (stricter: no component may exceed its tolerance).
struct MaxNorm {
  template <int N>
  double operator()(const Vector<N>& err, const Vector<N>& y, const Vector<N>& y_new, const Tolerance& tol) const {
    double worst = 0.0;
    for (int i = 0; i < N; ++i) {
      const double sc = tol.atol + tol.rtol * std::max(std::abs(y[i]), std::abs(y_new[i]));
      worst = std::max(worst, std::abs(err[i]) / sc);
    }
    return worst;
  }
};

}  // namespace grtrace
