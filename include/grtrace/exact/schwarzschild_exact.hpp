// grtrace/exact/schwarzschild_exact.hpp
// Exact answers for null geodesics of Schwarzschild, from elliptic integrals: the judge for every test,
// for the exact angle correction of escaping rays, and for the error maps.
//
// With u = 1/r and b = L/E the orbit obeys (du/dphi)^2 = P(u) = 1/b^2 - u^2 + 2 M u^3 (Darwin 1959;
// Chandrasekhar, "Mathematical Theory of Black Holes", sec. 20). The angle swept between u = 0 (infinity)
// and u on a branch without turning point is Phi(u) = int_0^u dv / sqrt(P(v)):
//   * b > b_c = 3 sqrt(3) M: three real roots u1 < 0 < u2 <= u3 (u2 = 1/periapsis) and, for 0 <= u <= u2,
//       Phi(u) = 2 / sqrt(2M (u3 - u1)) [F(psi(u), k) - F(psi(0), k)],
//       sin^2 psi(u) = (u - u1)/(u2 - u1),  k^2 = (u2 - u1)/(u3 - u1)            (Byrd & Friedman 233.00)
//   * b < b_c: one real root u1 < 0 and a complex pair m +- i n; with A = sqrt((m - u1)^2 + n^2),
//       Phi(u) = 1 / sqrt(2M A) [F(phi(u), k) - F(phi(0), k)],
//       cos phi(u) = (A - (u - u1)) / (A + (u - u1)),  k^2 = (A + m - u1) / (2A)   (Byrd & Friedman 239.00)
// The total deflection from infinity to infinity is alpha(b) = 2 Phi(1/r0) - pi.
// F is core/elliptic.hpp's elliptic_f(psi, k) (modulus k, not k^2; callable on a GPU); Darwin's closed form below
// uses the standard library's std::ellint_1, an independent implementation for the tests.
#pragma once

#include "grtrace/core/elliptic.hpp"
#include "grtrace/core/host_device.hpp"
#include "grtrace/core/sky_direction.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/schwarzschild_lapse.hpp"
#include "grtrace/metric/spherical_chart.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace grtrace::exact {

inline GRTRACE_HD double critical_impact_parameter(double mass = 1.0) { return 3.0 * std::sqrt(3.0) * mass; }

/// Closest approach r0 of a photon with impact parameter b > b_c (largest root of r^3 - b^2 r + 2 M b^2).
inline GRTRACE_HD double periapsis_from_impact(double b, double mass = 1.0) {
  return 2.0 * b / std::sqrt(3.0) * std::cos(std::acos(-critical_impact_parameter(mass) / b) / 3.0);
}

/// Impact parameter of the photon whose closest approach is r0 (> 3M).
inline GRTRACE_HD double impact_from_periapsis(double r0, double mass = 1.0) {
  return r0 / std::sqrt(schwarzschild_f(r0, mass));
}

namespace detail {
/// Phi(u) for b > b_c, given u2 = 1/periapsis (passed in: near b_c, u2 is better computed from r0 than from b).
inline GRTRACE_HD double phi_three_real_roots(double b, double u2, double u, double M) {
  // The other two roots of 2M u^3 - u^2 + 1/b^2 from Vieta: u1 + u3 = 1/(2M) - u2, u1 u3 = -1/(2M b^2 u2).
  const double s = 1.0 / (2.0 * M) - u2, p = -1.0 / (2.0 * M * b * b * u2);
  const double disc = std::sqrt(std::max(0.0, s * s - 4.0 * p));
  const double u3 = 0.5 * (s + disc), u1 = p / u3;
  const double k = std::sqrt((u2 - u1) / (u3 - u1));
  auto psi = [&](double v) { return std::asin(std::sqrt(std::clamp((v - u1) / (u2 - u1), 0.0, 1.0))); };
  return 2.0 / std::sqrt(2.0 * M * (u3 - u1)) * (elliptic_f(psi(u), k) - elliptic_f(psi(0.0), k));
}
}  // namespace detail

/// Angle swept between infinity and u = 1/r on a branch with no turning point in between.
/// Assumes 0 <= u and, for b > b_c, u <= 1/periapsis.
inline GRTRACE_HD double phi_from_infinity(double b, double u, double mass = 1.0) {
  if (mass == 0.0) return std::asin(std::min(1.0, b * u));
  const double M = mass;
  if (b > critical_impact_parameter(M)) return detail::phi_three_real_roots(b, 1.0 / periapsis_from_impact(b, M), u, M);
  // One real root u1 < 0 (Cardano), complex pair m +- i n from the quotient polynomial.
  const double a2 = -1.0 / (2.0 * M), a0 = 1.0 / (2.0 * M * b * b);  // monic: u^3 + a2 u^2 + a0
  const double q = -a2 * a2 / 9.0, r = -(a2 * a2 * a2) / 27.0 - a0 / 2.0;  // depressed cubic, shifted by -a2/3
  const double D = q * q * q + r * r;
  const double sq = std::sqrt(std::max(0.0, D));
  const double u1 = std::cbrt(r + sq) + std::cbrt(r - sq) - a2 / 3.0;
  const double m = -(a2 + u1) / 2.0;              // sum of the pair = -a2 - u1
  const double n2 = std::max(0.0, -a0 / u1 - m * m);  // product of the pair = -a0 / u1 = m^2 + n^2
  const double A = std::sqrt((m - u1) * (m - u1) + n2);
  const double k = std::sqrt(std::clamp((A + m - u1) / (2.0 * A), 0.0, 1.0));
  auto phi = [&](double v) { return std::acos(std::clamp((A - (v - u1)) / (A + (v - u1)), -1.0, 1.0)); };
  return (elliptic_f(phi(u), k) - elliptic_f(phi(0.0), k)) / std::sqrt(2.0 * M * A);
}

/// Total deflection of a photon from infinity to infinity (radians); NaN when b <= b_c (captured).
inline GRTRACE_HD double deflection_angle(double b, double mass = 1.0) {
  if (mass == 0.0) return 0.0;
  if (!(b > critical_impact_parameter(mass))) return std::numeric_limits<double>::quiet_NaN();
  return 2.0 * phi_from_infinity(b, 1.0 / periapsis_from_impact(b, mass), mass) - std::numbers::pi;
}

/// Total deflection of the photon whose closest approach is r0 > 3M (well conditioned even as r0 -> 3M).
inline GRTRACE_HD double deflection_angle_from_periapsis(double r0, double mass = 1.0) {
  const double b = impact_from_periapsis(r0, mass);
  return 2.0 * detail::phi_three_real_roots(b, 1.0 / r0, 1.0 / r0, mass) - std::numbers::pi;
}

/// The same deflection from Darwin's closed form in the periapsis r0 (the form quoted in
/// shared/reference/schwarzschild.md); an independent check on deflection_angle.
inline double deflection_angle_darwin(double r0, double mass = 1.0) {
  const double x = r0 / mass;
  const double Q = std::sqrt((x - 2.0) * (x + 6.0));
  const double k = std::sqrt((Q - x + 6.0) / (2.0 * Q));
  const double psi = std::asin(std::sqrt((Q - x + 2.0) / (Q - x + 6.0)));
  return -std::numbers::pi + 4.0 * std::sqrt(x / Q) * (std::comp_ellint_1(k) - std::ellint_1(k, psi));
}

/// Where a photon at radius r, moving outward (outward = true) or inward with impact parameter b, ends up:
/// nothing if it falls into the hole, else the angle it still sweeps in its orbital plane until infinity.
/// Assumes r > 2M.
inline GRTRACE_HD std::optional<double> remaining_sweep(double b, double r, bool outward, double mass = 1.0) {
  const double u = 1.0 / r;
  if (mass == 0.0) {
    const double base = std::asin(std::min(1.0, b * u));
    return outward ? base : std::numbers::pi - base;
  }
  const double bc = critical_impact_parameter(mass);
  const bool inside_photon_sphere = r < 3.0 * mass;
  if (b < bc) {
    if (!outward) return std::nullopt;
    return phi_from_infinity(b, u, mass);
  }
  if (inside_photon_sphere) return std::nullopt;  // b >= b_c below r = 3M: the barrier turns it back inward
  if (b == bc) return std::nullopt;               // the unstable circular orbit: never leaves
  const double u2 = 1.0 / periapsis_from_impact(b, mass);
  const double here = phi_from_infinity(b, std::min(u, u2), mass);
  return outward ? here : 2.0 * phi_from_infinity(b, u2, mass) - here;
}

// The sky-direction type and helpers live in core/sky_direction.hpp; these names keep exact:: spellings working.
using grtrace::SkyDirection;
using grtrace::sky_direction_of;
using grtrace::angular_distance;

/// Exact asymptotic direction of a null ray in Schwarzschild coordinates (t, r, theta, phi | k^mu), traced
/// forward in its affine parameter from the state y to infinity; nothing if it is captured.
/// Used at the camera (the exact answer for a whole ray) and at the escape sphere (exact angle correction).
/// Input that is not a ray also gives nothing (never a NaN direction), so callers must not read nullopt as
/// "captured" unless they know the state is valid: a non-finite state or mass, mass < 0, r <= 2M (or r <= 0),
/// zero momentum (k = 0) or k^t = 0 (E = 0: no impact parameter). A state on the polar axis (theta = 0 or pi) is
/// valid: the basis there is the limit along phi.
inline GRTRACE_HD std::optional<SkyDirection> asymptotic_direction(const GeodesicState& y, double mass = 1.0) {
  if (!all_finite(y) || !std::isfinite(mass) || mass < 0.0) return std::nullopt;
  if (!(y[1] > 2.0 * mass && y[1] > 0.0)) return std::nullopt;
  if (y.tail<4>().isZero(0.0) || y[4] == 0.0) return std::nullopt;
  const double r = y[1];
  const SphericalBasis e = spherical_basis(y[2], y[3]);
  const double E = schwarzschild_f(r, mass) * y[4];
  const Vec3 tangential = embedded_tangential_velocity(y, e);  // r dOmega/dlambda in the embedding
  const double L = r * tangential.norm();                      // total angular momentum r^2 |dOmega|
  const double b = std::abs(L / E);
  const bool outward = y[5] > 0.0;
  const auto sweep = remaining_sweep(b, r, outward, mass);
  if (!sweep) return std::nullopt;
  Vec3 dir = e.r;
  if (tangential.norm() > 0.0) dir = std::cos(*sweep) * e.r + std::sin(*sweep) * tangential.normalized();
  return sky_direction_of(dir);
}

/// The seed's angle correction (eq. 7-8): the direction of the ray's Cartesian velocity at its last point,
/// i.e. flat space beyond that point.
inline GRTRACE_HD SkyDirection flat_direction(const GeodesicState& y) {
  return sky_direction_of(embedded_velocity(y, spherical_basis(y[2], y[3])));
}

}  // namespace grtrace::exact
