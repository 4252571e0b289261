// grtrace/observer/tetrad.hpp
// An observer is an event plus a tetrad (vierbein) e_a^mu with g(e_a, e_b) = eta_ab = diag(1, -1, -1, -1):
// e_0 its 4-velocity, e_1 forward, e_2 up, e_3 right (seed sec. 2.2 and 3.1.1).
//
// make_tetrad takes the metric at the event, a future-directed timelike 4-velocity, a look direction and an up
// direction (coordinate vectors), and orthonormalises them by Gram-Schmidt in the metric: forward is look
// without its e_0 part, up is up without its e_0 and e_1 parts, and right is the coordinate basis vector with
// the largest remainder after removing all three (best conditioned), normalised, with its sign chosen so that
// det[e_0 e_1 e_2 e_3] > 0 (right-handed: right = forward x up in the observer's space).
// Refuses, with a message that says what to change: non-finite input, a 4-velocity that is not future-directed
// timelike, a look direction along the 4-velocity, and an up direction parallel to the look direction.
#pragma once

#include "grtrace/core/types.hpp"

#include <Eigen/LU>

#include <array>
#include <cmath>
#include <stdexcept>

namespace grtrace {

struct Tetrad {
  std::array<Vec4, 4> e;  ///< e[0] 4-velocity, e[1] forward, e[2] up, e[3] right
};

inline Tetrad make_tetrad(const Mat4& g, const Vec4& velocity, const Vec4& look, const Vec4& up) {
  if (!g.allFinite() || !velocity.allFinite() || !look.allFinite() || !up.allFinite())
    throw std::invalid_argument("observer: position, velocity, look and up must be finite numbers");
  auto dot = [&](const Vec4& a, const Vec4& b) { return a.dot(g * b); };
  if (look.isZero(0.0)) throw std::invalid_argument("observer: the look direction is zero; give a nonzero --look");
  if (up.isZero(0.0)) throw std::invalid_argument("observer: the up direction is zero; give a nonzero --up");
  const double uu = dot(velocity, velocity);
  const double size = velocity.cwiseAbs().dot(g.cwiseAbs() * velocity.cwiseAbs());
  if (!(uu > 1e-10 * size) || !(velocity[0] > 0.0))  // null within round-off counts as null
    throw std::invalid_argument("observer: the 4-velocity must be future-directed and timelike (|v| < c)");
  Tetrad t;
  t.e[0] = velocity / std::sqrt(uu);
  // Spacelike vectors have g(v, v) < 0; remove the parts along e_0 (g = +1) and along unit spacelike vectors (g = -1).
  auto remove = [&](Vec4 v, int upto) {
    v -= dot(v, t.e[0]) * t.e[0];
    for (int a = 1; a <= upto; ++a) v += dot(v, t.e[static_cast<std::size_t>(a)]) * t.e[static_cast<std::size_t>(a)];
    return v;
  };
  auto spatial_size = [&](const Vec4& v) { return std::sqrt(std::max(0.0, -dot(v, v))); };
  const Vec4 f = remove(look, 0);
  const double fn = spatial_size(f);
  if (!(fn > 1e-12 * std::max(1.0, spatial_size(remove(look, 0)) + std::abs(look.norm()))))
    throw std::invalid_argument("observer: the look direction has no spatial part in the observer's frame");
  t.e[1] = f / fn;
  const Vec4 w = remove(up, 1);
  const double wn = spatial_size(w);
  if (!(wn > 1e-9 * std::max(1.0, spatial_size(remove(up, 0)))))
    throw std::invalid_argument("observer: the up direction is parallel to the look direction; choose another --up");
  t.e[2] = w / wn;
  Vec4 best = Vec4::Zero();
  double best_size = -1.0;
  for (int i = 0; i < 4; ++i) {
    const Vec4 v = remove(Vec4::Unit(i), 2);
    if (const double s = spatial_size(v); s > best_size) {
      best_size = s;
      best = v;
    }
  }
  t.e[3] = best / best_size;
  Mat4 m;
  for (int a = 0; a < 4; ++a) m.col(a) = t.e[static_cast<std::size_t>(a)];
  if (m.determinant() < 0.0) t.e[3] = -t.e[3];
  return t;
}

/// g(e_a, e_b): eta_ab for a correct tetrad (tests).
inline Mat4 tetrad_gram(const Mat4& g, const Tetrad& t) {
  Mat4 m;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) m(a, b) = t.e[static_cast<std::size_t>(a)].dot(g * t.e[static_cast<std::size_t>(b)]);
  return m;
}

}  // namespace grtrace
