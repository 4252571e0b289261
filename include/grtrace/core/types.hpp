// grtrace/core/types.hpp
// Fixed-size value types shared by every part of the library.
//
// Numerics use Eigen fixed-size vectors (stack allocated, no heap traffic in the hot loop).
// A geodesic state packs position x^mu and tangent k^mu = dx^mu/dlambda into eight numbers.
#pragma once

#include "grtrace/core/host_device.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstddef>

namespace grtrace {

template <int N>
using Vector = Eigen::Matrix<double, N, 1>;

using Vec3 = Vector<3>;
using Vec4 = Vector<4>;
using Mat4 = Eigen::Matrix<double, 4, 4>;

/// Minkowski's metric diag(1, -1, -1, -1), written out: Eigen's asDiagonal() assignment is not callable on a GPU
/// (nvcc compiles it into a call through a null pointer; see core/optional.hpp).
inline GRTRACE_HD Mat4 minkowski_eta() {
  Mat4 eta = Mat4::Zero();
  eta(0, 0) = 1.0;
  eta(1, 1) = eta(2, 2) = eta(3, 3) = -1.0;
  return eta;
}

/// y = (x^0..x^3, k^0..k^3): position and tangent of a geodesic.
using GeodesicState = Vector<8>;

inline GRTRACE_HD Vec4 position(const GeodesicState& y) { return y.head<4>(); }
inline GRTRACE_HD Vec4 momentum(const GeodesicState& y) { return y.tail<4>(); }

inline GRTRACE_HD GeodesicState make_state(const Vec4& x, const Vec4& k) {
  GeodesicState y;
  y << x, k;
  return y;
}

/// m.allFinite() as one branch-free pass (Eigen's allFinite is an out-of-line unrolled compare in the hot loop, and
/// is not callable on a GPU).
template <int Rows, int Cols>
inline GRTRACE_HD bool all_finite(const Eigen::Matrix<double, Rows, Cols>& m) {
  bool ok = true;
  for (int j = 0; j < Cols; ++j)
    for (int i = 0; i < Rows; ++i) ok &= std::isfinite(m(i, j));
  return ok;
}

}  // namespace grtrace
