// grtrace/observer/static_frame.hpp
// The local static orthonormal frame of a diagonal metric in spherical coordinates (t, r, theta, phi):
// hat e_t = d_t / sqrt(g_tt), hat e_r = d_r / sqrt(-g_rr), hat e_theta, hat e_phi likewise. Cameras are given
// their velocity, look and up directions in this frame (physicists think in it; it exists outside horizons).
#pragma once

#include "grtrace/core/types.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace grtrace {

struct StaticFrame {
  std::array<Vec4, 4> e;  ///< hat e_t, hat e_r, hat e_theta, hat e_phi as coordinate vectors

  /// Takes g at the event; assumes it is diagonal with g_tt > 0 (outside any horizon).
  explicit StaticFrame(const Mat4& g) {
    if (!(g(0, 0) > 0.0)) throw std::invalid_argument("static frame: g_tt <= 0 (at or inside a horizon)");
    for (int a = 0; a < 4; ++a) {
      e[static_cast<std::size_t>(a)] = Vec4::Zero();
      e[static_cast<std::size_t>(a)][a] = 1.0 / std::sqrt(std::abs(g(a, a)));
    }
  }

  /// Spatial vector with components (r, theta, phi) in this frame, as a coordinate vector.
  Vec4 spatial(const Vec3& v) const { return v[0] * e[1] + v[1] * e[2] + v[2] * e[3]; }

  /// 4-velocity of an observer moving with 3-velocity beta (fraction of c) through this frame.
  Vec4 velocity(const Vec3& beta) const {
    const double b2 = beta.squaredNorm();
    if (!(b2 < 1.0)) throw std::invalid_argument("velocity: |beta| must be below 1 (the speed of light)");
    const double gamma = 1.0 / std::sqrt(1.0 - b2);
    return gamma * (e[0] + spatial(beta));
  }
};

}  // namespace grtrace
