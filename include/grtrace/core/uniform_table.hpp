// grtrace/core/uniform_table.hpp
// A smooth function of one variable tabulated once on a uniform grid and read back by cubic interpolation: for
// the expensive functions a medium asks for at every stage of every step (a Bessel function, the angular velocity
// of circular orbits from the Christoffel symbols), where the function is smooth enough that 4 nodes carry it.
//
// Takes:   [x0, x1], the number of nodes n >= 4, and f (called n times, at construction).
// Returns: operator()(x): Lagrange's cubic through the 4 nodes around x (the middle interval's, or the first or
//          last three intervals' at the ends); outside [x0, x1] the end cubics extrapolate (callers keep to it).
// Error:   about h^4 max|f''''| / 24 inside (h the node spacing): 1e-12 relative for e^(-3s/2) with h = 2e-3.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace grtrace {

class UniformTable {
 public:
  UniformTable() = default;
  template <class F>
  UniformTable(double x0, double x1, int n, const F& f)
      : x0_(x0), step_((x1 - x0) / (n - 1)), values_(static_cast<std::size_t>(n)) {
    for (int i = 0; i < n; ++i) values_[static_cast<std::size_t>(i)] = f(x0 + i * step_);
  }

  double operator()(double x) const {
    const double s = (x - x0_) / step_;
    const int last = static_cast<int>(values_.size()) - 4;
    const int i = std::clamp(static_cast<int>(s) - 1, 0, last);
    const double t = s - i;  // in [1, 2) inside: the middle interval of the four nodes
    const double* f = &values_[static_cast<std::size_t>(i)];
    return -f[0] * (t - 1.0) * (t - 2.0) * (t - 3.0) / 6.0 + f[1] * t * (t - 2.0) * (t - 3.0) / 2.0 -
           f[2] * t * (t - 1.0) * (t - 3.0) / 2.0 + f[3] * t * (t - 1.0) * (t - 2.0) / 6.0;
  }

 private:
  double x0_ = 0.0, step_ = 1.0;
  std::vector<double> values_;
};

}  // namespace grtrace
