// grtrace/core/elliptic.hpp
// Legendre's incomplete elliptic integral of the first kind F(phi, k) and the complete K(k), through Carlson's
// symmetric R_F by the duplication theorem (B. C. Carlson, "Numerical computation of real or complex elliptic
// integrals", Numer. Algorithms 10 (1995) 13-26; DLMF 19.25.5 and 19.36.1). One source for the CPU and the GPU:
// std::ellint_1 is a library function the GPU does not have.
//
// Takes:   the modulus k (not the parameter m = k^2), 0 <= k < 1, and the amplitude phi in [0, pi].
// Returns: F and K to a few units in the last place (the series after the duplications, to seventh order, is cut
//          where its next term is below 1e-17 relative: DLMF 19.36.1, once max |1 - x/A| <= 1e-2; K by the
//          arithmetic-geometric mean, complete_f, which also takes the parameter m = k^2 < 1, negative included).
// Assumes: finite arguments; k = 1 gives +inf at phi = pi/2 (as std::ellint_1 does).
#pragma once

#include "grtrace/core/host_device.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace grtrace {

namespace detail {
/// R_F's Taylor series about the arguments' mean A times sqrt(A), from their relative deviations dx = 1 - x / A,
/// dy = 1 - y / A (dz = -(dx + dy)): for one value or a packet of lanes (core/jacobi_elliptic.hpp).
template <class T>
GRTRACE_HD T carlson_rf_polynomial(const T& dx, const T& dy) {
  const T dz = -(dx + dy);
  const T e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
  // DLMF 19.36.1 to seventh order: 1 - E2/10 + E3/14 + E2^2/24 - 3 E2 E3/44 - 5 E2^3/208 + 3 E3^2/104 +
  // E2^2 E3/16: two more terms than the fifth order's spare one or two duplications (four square roots each).
  return 1.0 + e2 * (-0.1 + e2 * (1.0 / 24.0 - 5.0 / 208.0 * e2 + e3 / 16.0) - 3.0 * e3 / 44.0) +
         e3 * (1.0 / 14.0 + 3.0 / 104.0 * e3);
}

/// R_F(x, y, z) by its Taylor series about the arguments' mean A, once duplication has drawn them within 1e-2 of A.
inline GRTRACE_HD double carlson_rf_series(double x, double y, double z) {
  const double a = (x + y + z) / 3.0;
  return carlson_rf_polynomial(1.0 - x / a, 1.0 - y / a) / std::sqrt(a);
}
}  // namespace detail

/// Carlson's R_F(x, y, z) = (1/2) int_0^inf dt / sqrt((t + x)(t + y)(t + z)) for x, y, z >= 0, at most one zero.
inline GRTRACE_HD double carlson_rf(double x, double y, double z) {
  // Duplication: R_F(x, y, z) = R_F((x + l)/4, (y + l)/4, (z + l)/4), l = sqrt(xy) + sqrt(yz) + sqrt(zx), which
  // draws the three arguments together; then the seventh-order Taylor series about their mean A.
  for (int i = 0; i < 64; ++i) {
    const double a = (x + y + z) / 3.0;
    const double deviation = std::max(std::abs(a - x), std::max(std::abs(a - y), std::abs(a - z)));
    if (deviation <= 1e-2 * a) break;  // the series' first neglected term ~ deviation^8 / 10 < 1e-17
    const double sx = std::sqrt(x), sy = std::sqrt(y), sz = std::sqrt(z);
    const double l = sx * (sy + sz) + sy * sz;
    x = 0.25 * (x + l);
    y = 0.25 * (y + l);
    z = 0.25 * (z + l);
  }
  return detail::carlson_rf_series(x, y, z);
}

/// K(m) = F(pi/2 | m) for m < 1, by the arithmetic-geometric mean: K = pi / (2 M(1, sqrt(1 - m))) (DLMF 19.8.5).
/// The means converge quadratically, one square root a level (5-8 levels from m = -1e6 to 1 - 1e-16), where R_F's
/// duplication needs 4-5 levels of three: about a third of the time, to the same few ulps.
inline GRTRACE_HD double complete_f(double m) {
  double a = 1.0, g = std::sqrt(1.0 - m);
  // Once the two agree to 1e-8, their mean is M to 1e-17 (the gap squares each level).
  for (int i = 0; i < 24 && std::abs(a - g) > 1e-8 * a; ++i) {
    const double mean = 0.5 * (a + g);
    g = std::sqrt(a * g);
    a = mean;
  }
  return std::numbers::pi / (a + g);
}

/// K(k) = F(pi/2, k), the modulus k = sqrt(m).
inline GRTRACE_HD double complete_elliptic_f(double k) { return complete_f(k * k); }

/// F(phi, k) = int_0^phi dt / sqrt(1 - k^2 sin^2 t) for phi in [0, pi] (beyond pi/2 by F(phi) = 2K - F(pi - phi)).
inline GRTRACE_HD double elliptic_f(double phi, double k) {
  const bool beyond = phi > 0.5 * std::numbers::pi;  // no recursion: a GPU kernel's stack is sized at compile time
  const double t = beyond ? std::numbers::pi - phi : phi;
  const double s = std::sin(t), c = std::cos(t);
  const double f = s * carlson_rf(c * c, 1.0 - k * k * s * s, 1.0);
  return beyond ? 2.0 * complete_elliptic_f(k) - f : f;
}

}  // namespace grtrace
