// grtrace/integrate/error_norm.hpp
// Error norms for step control (Hairer, Norsett & Wanner I, eq. II.4.11).
// Each component of the local error estimate is scaled by sc_i = atol + rtol * max(|y_i|, |y_new_i|);
// a step is acceptable when the norm is <= 1.
#pragma once

#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/types.hpp"

#include <algorithm>
#include <cmath>

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
