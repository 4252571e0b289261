// grtrace/core/jacobi_elliptic.hpp
// What Kerr's null geodesics in closed form need beyond core/elliptic.hpp: Carlson's R_C and R_J, Legendre's F and
// Pi for any real amplitude and a parameter m < 1 (negative included: Kerr's polar motion has m = u+ / u- < 0), the
// Jacobi functions sn, cn, dn and the amplitude am, and one integral of the Jacobi cn, R1 below.
//
// Takes:   the parameter m = k^2 (not the modulus), m < 1; amplitudes and arguments finite, any size.
// Returns: values to a few units in the last place (Carlson's series cut below 1e-17; the Jacobi functions by the
//          arithmetic-geometric mean to convergence), except near the singular points named at each function.
// Method:  R_C in closed form (arctan / artanh); R_J by Carlson's duplication with the R_C sum (B. C. Carlson,
//          "Numerical computation of real or complex elliptic integrals", Numer. Algorithms 10 (1995) 13-26, §2)
//          and the series to seventh order (DLMF 19.36.2). F(phi|m) = s R_F(c^2, 1 - m s^2, 1) and Pi(n; phi|m) = F +
//          (n/3) s^3 R_J(c^2, 1 - m s^2, 1, 1 - n s^2) (DLMF 19.25.5 and 19.25.14, s = sin phi, c = cos phi) on [-pi/2,
//          pi/2], extended by F(phi + j pi) = F(phi) + 2 j K. Pi with n > 1 is the Cauchy principal value (DLMF 19.7.9
//          with R_C's value for a negative second argument, DLMF 19.2.20). sn, cn, dn by Gauss's transformation (the
//          arithmetic-geometric mean, DLMF 22.7 and 22.20(ii), in Bulirsch's recursion), one sin and cos for all three;
//          the means of one parameter kept for many arguments (JacobiParameter). Several unrelated R_F and R_J in one
//          duplication loop of four lanes (carlson_rf_rj_lanes), where a caller needs them together.
// One source for the CPU and the GPU (no recursion, no library special functions).
#pragma once

#include "grtrace/core/elliptic.hpp"
#include "grtrace/core/host_device.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <type_traits>

namespace grtrace {

/// Carlson's R_C(x, y) = (1/2) int_0^inf dt / ((t + y) sqrt(t + x)), x >= 0, y != 0; for y < 0 the Cauchy
/// principal value (DLMF 19.2.20). Elementary (DLMF 19.2.18-19.2.19), in the arctangent forms: arctan(sqrt((y - x) /
/// x)) / sqrt(y - x) for x < y, artanh(sqrt((x - y) / x)) / sqrt(x - y) for y < x < 2y (arccosh beyond). The
/// arccos(sqrt(x / y)) and arccosh forms are the same numbers, but near x = y their argument's rounding is
/// magnified by 1 / sqrt(|1 - x / y|): 1e-13 relative at |1 - x / y| = 1e-3, which R_J's sum of R_C passed on.
/// A series where x and y agree to 1e-3.
inline GRTRACE_HD double carlson_rc(double x, double y) {
  if (y < 0.0) return std::sqrt(x / (x - y)) * carlson_rc(x - y, -y);  // one level: x - y > 0, -y > 0 below
  const double d = (x - y) / y;
  if (std::abs(d) < 1e-3) {
    // R_C(x, y) = y^-1/2 (1 - d/6 + 3 d^2 / 40 - 5 d^3 / 112 + 35 d^4 / 1152 - 63 d^5 / 2816 ...), d = (x - y) / y:
    // the series of (arctan sqrt(-d)) / sqrt(-d); six terms reach 1e-18 at |d| = 1e-3.
    return (1.0 + d * (-1.0 / 6.0 + d * (3.0 / 40.0 + d * (-5.0 / 112.0 + d * (35.0 / 1152.0 - d * 63.0 / 2816.0))))) /
           std::sqrt(y);
  }
  if (x < y) {
    const double w = std::sqrt(y - x);
    return std::atan(w / std::sqrt(x)) / w;  // x = 0: atan(inf) = pi / 2
  }
  const double w = std::sqrt(x - y);
  return (x < 2.0 * y ? std::atanh(w / std::sqrt(x)) : std::acosh(std::sqrt(x / y))) / w;
}

/// Carlson's R_J(x, y, z, p) = (3/2) int_0^inf dt / ((t + p) sqrt((t + x)(t + y)(t + z))), x, y, z >= 0 (at most one
/// zero), p > 0.
/// R_F(x, y, z) and R_J(x, y, z, p) together: the duplication of x, y and z is the same for both, so Legendre's Pi
/// (which needs both) pays for one loop.
struct CarlsonPair {
  double rf, rj;
};

namespace detail {
/// R_J's series about A (DLMF 19.36.2 to seventh order; E_k the elementary symmetric functions of X, Y, Z, P, P with
/// P = -(X + Y + Z) / 2) from the original arguments' deviations from A0 scaled by 4^-j / A_j (Carlson 1995 eq.
/// 2.17-2.18): for one value or a packet of lanes.
template <class T>
GRTRACE_HD T carlson_rj_polynomial(const T& X, const T& Y, const T& Z) {
  const T P = -0.5 * (X + Y + Z);
  const T e2 = X * Y + X * Z + Y * Z - 3.0 * P * P;
  const T e3 = X * Y * Z + 2.0 * e2 * P + 4.0 * P * P * P;
  const T e4 = (2.0 * X * Y * Z + e2 * P + 3.0 * P * P * P) * P;
  const T e5 = X * Y * Z * P * P;
  return 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 - 9.0 * e2 * e3 / 52.0 +
         3.0 * e5 / 26.0 - e2 * e2 * e2 / 16.0 + 3.0 * e2 * e4 / 20.0 + 3.0 * e3 * e3 / 40.0 +
         45.0 * e2 * e2 * e3 / 272.0 - 9.0 * (e2 * e5 + e3 * e4) / 68.0;
}

// One value or a packet of four lanes (Eigen::Array4d): what carlson_rf_rj_duplication reads its arguments as.
inline GRTRACE_HD double lane_sqrt(double v) { return std::sqrt(v); }
inline GRTRACE_HD double lane_abs(double v) { return std::abs(v); }
inline GRTRACE_HD double lane_max(double a, double b) { return std::max(a, b); }
inline GRTRACE_HD Eigen::Array4d lane_sqrt(const Eigen::Array4d& v) { return v.sqrt(); }
inline GRTRACE_HD Eigen::Array4d lane_abs(const Eigen::Array4d& v) { return v.abs(); }
inline GRTRACE_HD Eigen::Array4d lane_max(const Eigen::Array4d& a, const Eigen::Array4d& b) { return a.max(b); }
template <class Condition>
GRTRACE_HD bool every_lane(const Condition& c) {
  if constexpr (std::is_same_v<Condition, bool>) return c;
  else return c.all();
}

// R_C(1, 1 + e) = arctan(sqrt(e)) / sqrt(e): e falls by 64 a level, so after the first one or two it is small and
// its own series (1 - e/3 + e^2/5 - ..., six terms to 1e-19 at |e| = 1e-3) spares R_C's root and division.
template <class T>
GRTRACE_HD T rc_series(const T& e) {
  return 1.0 + e * (-1.0 / 3.0 + e * (1.0 / 5.0 + e * (-1.0 / 7.0 + e * (1.0 / 9.0 + e * (-1.0 / 11.0 + e / 13.0)))));
}
inline GRTRACE_HD double rc_one_plus(double e) {
  return std::abs(e) < 1e-3 ? rc_series(e) : carlson_rc(1.0, 1.0 + e);
}
inline GRTRACE_HD Eigen::Array4d rc_one_plus(const Eigen::Array4d& e) {
  Eigen::Array4d rc = rc_series<Eigen::Array4d>(e);
  if (!(e.abs() < 1e-3).all()) {  // beyond the series' range: the first level or two
    for (int l = 0; l < 4; ++l)
      if (!(std::abs(e[l]) < 1e-3)) rc[l] = carlson_rc(1.0, 1.0 + e[l]);
  }
  return rc;
}

/// R_F(x, y, z) and R_J(x, y, z, p_i) for N values p_i at once: one duplication of x, y and z for all (the i-th R_J
/// into rj[i]; returns R_F). T: double, or Eigen::Array4d for four independent argument sets side by side
/// (carlson_rf_rj_lanes), each lane's values as the double loop gives them (a lane that met its rule before the
/// slowest one is duplicated further: the same value, to its last bits or closer).
/// Flattened on the CPU: the lane helpers and R_C's series are called at every level (left out of line, the packet
/// series alone took a tenth of a closed-form ray).
template <class T, std::size_t N>
GRTRACE_FLATTEN_CPU GRTRACE_HD T carlson_rf_rj_duplication(T x, T y, T z, const T (&p_in)[N], T (&rj)[N]) {
  const T x0 = x, y0 = y, z0 = z;
  T p[N], a0[N], a[N], delta[N], sum[N];
  T q = 0.0 * x;  // x, y, z are finite
  for (std::size_t i = 0; i < N; ++i) {
    p[i] = p_in[i];
    a[i] = a0[i] = (x + y + z + 2.0 * p[i]) / 5.0;
    delta[i] = (p[i] - x) * (p[i] - y) * (p[i] - z);
    sum[i] = 0.0 * x;
    // Carlson's stopping rule: 4^-j Q < |A_j| with Q = c max |A0 - v|, i.e. every argument within A_j / c of the
    // mean. For the fifth-order series Carlson takes c = (4 / eps)^(1/6) = 860 (eps = 1e-17); the seventh-order
    // series below would allow (4 / eps)^(1/8) = 159, but c = 200 is taken so that x, y, z also meet R_F's own rule
    // (within 1e-2 of their mean: within 2 / c of each other): the same loop serves both. One Q for all (the
    // largest): each R_J is duplicated at least as far as its own rule asks.
    q = lane_max(q, 200.0 * lane_max(lane_max(lane_abs(a0[i] - x), lane_abs(a0[i] - y)),
                                     lane_max(lane_abs(a0[i] - z), lane_abs(a0[i] - p[i]))));
  }
  double scale = 1.0, cube = 1.0;  // scale = 4^-j, cube = 4^-3j
  auto converged = [&] {
    for (std::size_t i = 0; i < N; ++i)
      if (!every_lane(scale * q < lane_abs(a[i]))) return false;
    return true;
  };
  for (int j = 0; j < 64 && !converged(); ++j) {
    const T sx = lane_sqrt(x), sy = lane_sqrt(y), sz = lane_sqrt(z);
    const T lambda = sx * (sy + sz) + sy * sz;
    for (std::size_t i = 0; i < N; ++i) {
      const T sp = lane_sqrt(p[i]);
      const T inv_d = 1.0 / ((sp + sx) * (sp + sy) * (sp + sz));
      const T e = cube * delta[i] * inv_d * inv_d;
      sum[i] += scale * rc_one_plus(e) * inv_d;
      p[i] = 0.25 * (p[i] + lambda);
      a[i] = 0.25 * (a[i] + lambda);
    }
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    scale *= 0.25;
    cube *= 1.0 / 64.0;
  }
  for (std::size_t i = 0; i < N; ++i) {
    // The original arguments' deviations from A0 scaled by 4^-j / A_j (Carlson 1995 eq. 2.17-2.18), and the series.
    const T f = scale / a[i];
    const T series = carlson_rj_polynomial<T>((a0[i] - x0) * f, (a0[i] - y0) * f, (a0[i] - z0) * f);
    rj[i] = scale * series / (a[i] * lane_sqrt(a[i])) + 6.0 * sum[i];
  }
  // R_F from the same duplicated x, y, z: its own series about their mean; the loop above ran at least until R_F's
  // own rule (deviations below 1e-2 of the mean) was met, R_J's being the stricter.
  const T mean = (x + y + z) / 3.0;
  return carlson_rf_polynomial<T>(1.0 - x / mean, 1.0 - y / mean) / lane_sqrt(mean);
}

/// R_F(x, y, z) and R_J(x, y, z, p_i) for N values p_i at once (one duplication of x, y and z for all).
template <std::size_t N>
GRTRACE_HD double carlson_rf_rj_n(double x, double y, double z, const double (&p_in)[N], double (&rj)[N]) {
  return carlson_rf_rj_duplication<double, N>(x, y, z, p_in, rj);
}
}  // namespace detail

/// R_F(x, y, z) and R_J(x, y, z, p_i), i < N, of four independent argument sets (lanes) at once: carlson_rf_rj_n's
/// duplication and series, run on the four lanes side by side (Eigen's packets: one vector square root serves four
/// lanes on the CPU; a scalar loop on a GPU). Worth it where one ray needs several unrelated integrals at once: their
/// square-root chains, each waiting on the last, then overlap instead of following one another. The loop runs
/// until every lane meets its own rule. A lane not needed can be filled with ones (met at once).
template <std::size_t N>
GRTRACE_HD void carlson_rf_rj_lanes(const Eigen::Array4d& x, const Eigen::Array4d& y, const Eigen::Array4d& z,
                                    const Eigen::Array4d (&p)[N], Eigen::Array4d& rf, Eigen::Array4d (&rj)[N]) {
  rf = detail::carlson_rf_rj_duplication<Eigen::Array4d, N>(x, y, z, p, rj);
}

inline GRTRACE_HD CarlsonPair carlson_rf_rj(double x, double y, double z, double p) {
  const double ps[1] = {p};
  double rj[1];
  const double rf = detail::carlson_rf_rj_n<1>(x, y, z, ps, rj);
  return {rf, rj[0]};
}

inline GRTRACE_HD double carlson_rj(double x, double y, double z, double p) { return carlson_rf_rj(x, y, z, p).rj; }

/// Pi(n | m) = Pi(n; pi/2 | m) for m < 1; for n > 1 the Cauchy principal value K(m) - Pi(m / n | m) (DLMF 19.6.5).
/// For -1 <= n <= 0.9 (Kerr's polar motion: n = u+ in (0, 1)) by the arithmetic-geometric mean (DLMF 19.8.6): with
/// a_0 = 1, g_0 = sqrt(1 - m), p_0 = sqrt(1 - n), Q_0 = 1, Pi = pi / (4 M) (2 + n / (1 - n) sum Q_j), where
/// eps_j = (p_j^2 - a_j g_j) / (p_j^2 + a_j g_j), p_j+1 = (p_j^2 + a_j g_j) / (2 p_j), Q_j+1 = Q_j eps_j / 2: about a
/// third of R_J's time, within 1e-15 of it. Elsewhere by R_F and R_J: as n nears 1 the sum cancels (it falls as
/// sqrt(1 - n) while the factor grows as 1 / (1 - n)), and far below -1 p_j halves level by level before it converges.
inline GRTRACE_HD double complete_pi(double n, double m) {
  if (n > 1.0) return -m / (3.0 * n) * carlson_rj(0.0, 1.0 - m, 1.0, 1.0 - m / n);
  if (n < -1.0 || n > 0.9) {
    const CarlsonPair c = carlson_rf_rj(0.0, 1.0 - m, 1.0, 1.0 - n);
    return c.rf + n / 3.0 * c.rj;
  }
  double a = 1.0, g = std::sqrt(1.0 - m), p = std::sqrt(1.0 - n), q = 1.0, sum = 0.0;
  for (int i = 0; i < 24; ++i) {
    sum += q;
    const double ag = a * g, p2 = p * p;
    q *= 0.5 * (p2 - ag) / (p2 + ag);
    p = 0.5 * (p2 + ag) / p;
    const double mean = 0.5 * (a + g);
    g = std::sqrt(ag);
    a = mean;
    if (std::abs(q) <= 1e-17 * std::abs(sum) && std::abs(a - g) <= 1e-8 * a) break;
  }
  return std::numbers::pi / (2.0 * (a + g)) * (2.0 + n / (1.0 - n) * sum);
}

/// The half turns j of an amplitude phi = j pi + t, |t| <= pi / 2: where the integrals of any real amplitude add
/// 2 j times the complete one to that of t.
inline GRTRACE_HD double half_turns(double phi) { return std::floor(phi / std::numbers::pi + 0.5); }

/// Legendre's F(phi | m) = int_0^phi dt / sqrt(1 - m sin^2 t) for any real phi and m < 1.
inline GRTRACE_HD double legendre_f(double phi, double m) {
  const double j = half_turns(phi);
  const double t = phi - j * std::numbers::pi, s = std::sin(t), c = std::cos(t);
  const double f = s * carlson_rf(c * c, 1.0 - m * s * s, 1.0);
  return j == 0.0 ? f : f + 2.0 * j * complete_f(m);
}

/// F(phi | m) from sin(phi) = s and cos(phi) = c, for phi in [-pi/2, pi] (s >= 0 where c < 0), k = K(m) (read only
/// where c < 0): what a caller that knows the amplitude's sine and cosine calls instead of F(asin s) or F(acos c),
/// which would take them back through two more functions.
inline GRTRACE_HD double legendre_f_sc(double s, double c, double m, double k) {
  const double f = s * carlson_rf(c * c, 1.0 - m * s * s, 1.0);
  return c >= 0.0 ? f : 2.0 * k - f;  // beyond pi/2: F(phi) = 2K - F(pi - phi)
}

/// Pi(n; phi | m) from sin(phi) = s and cos(phi) = c >= 0 (|phi| <= pi/2), n < 1, or n > 1 as the Cauchy principal
/// value: what a caller that knows the amplitude's sine and cosine calls instead of Pi(n; asin s | m).
namespace detail {
/// Whether Pi(n; t) at sin^2 t = s2 is taken by its Carlson form (n < 1, or 1 - n s2 away from the pole of n > 1);
/// otherwise by DLMF 19.7.9's principal value.
inline GRTRACE_HD bool pi_away_from_pole(double n, double s2) { return n < 1.0 || 1.0 - n * s2 > 0.25; }
}  // namespace detail

/// Pi(n; t | m) = s R_F + (n / 3) s^3 R_J from R_F(c^2, 1 - m s^2, 1) and R_J(.., 1 - n s^2) computed elsewhere
/// (s = sin t, s2 = s^2; away from the pole: detail::pi_away_from_pole): what a caller that evaluates several
/// integrals in one loop (carlson_rf_rj_lanes) combines them with.
inline GRTRACE_HD double legendre_pi_of(double n, double s, double s2, double rf, double rj) {
  return s * rf + n / 3.0 * s * s2 * rj;
}

inline GRTRACE_HD double legendre_pi_sc(double n, double s, double c, double m) {
  const double s2 = s * s;
  if (detail::pi_away_from_pole(n, s2)) {
    const CarlsonPair cp = carlson_rf_rj(c * c, 1.0 - m * s2, 1.0, 1.0 - n * s2);
    return legendre_pi_of(n, s, s2, cp.rf, cp.rj);
  }
  // Near and beyond the pole: DLMF 19.7.9, Pi(n; t) = F(t) - Pi(m / n; t) + sqrt(cc) R_C((cc - 1)(cc - m),
  // (cc - n)(cc - m / n)), cc = 1 / sin^2 t, for 0 < |t| <= pi / 2 (odd in t).
  const double n2 = m / n, cc = 1.0 / s2;
  const CarlsonPair cp = carlson_rf_rj(c * c, 1.0 - m * s2, 1.0, 1.0 - n2 * s2);
  const double rf = cp.rf, pi2 = rf + n2 / 3.0 * s2 * cp.rj;  // Pi(n2; |t|) / |s|
  const double rc = std::sqrt(cc) * carlson_rc((cc - 1.0) * (cc - m), (cc - n) * (cc - n2));
  return s * rf - s * pi2 + (s < 0.0 ? -rc : rc);
}

/// Pi(n1; phi | m) and Pi(n2; phi | m) together, as legendre_pi_sc gives each: where neither is near its pole, one
/// duplication of R_F's arguments serves both (what a sum over the two roots of a radial integrand needs).
struct PiPair {
  double first, second;
};
/// The pair from R_F and the two R_J computed elsewhere (legendre_pi_of's pair).
inline GRTRACE_HD PiPair legendre_pi_pair_of(double n1, double n2, double s, double s2, double rf, double rj1,
                                             double rj2) {
  return {legendre_pi_of(n1, s, s2, rf, rj1), legendre_pi_of(n2, s, s2, rf, rj2)};
}

inline GRTRACE_HD PiPair legendre_pi_pair_sc(double n1, double n2, double s, double c, double m) {
  const double s2 = s * s;
  if (!(detail::pi_away_from_pole(n1, s2) && detail::pi_away_from_pole(n2, s2)))
    return {legendre_pi_sc(n1, s, c, m), legendre_pi_sc(n2, s, c, m)};
  const double ps[2] = {1.0 - n1 * s2, 1.0 - n2 * s2};
  double rj[2];
  const double rf = detail::carlson_rf_rj_n<2>(c * c, 1.0 - m * s2, 1.0, ps, rj);
  return legendre_pi_pair_of(n1, n2, s, s2, rf, rj[0], rj[1]);
}

/// Legendre's Pi(n; phi | m) = int_0^phi dt / ((1 - n sin^2 t) sqrt(1 - m sin^2 t)) for any real phi, m < 1, n < 1
/// (no pole), or n > 1 as the Cauchy principal value: an antiderivative on each interval between poles
/// (sin^2 phi = 1 / n), which is what a difference over a path that avoids them needs. `complete` is Pi(n | m)
/// (complete_pi), read only where half_turns(phi) != 0: a caller that evaluates many amplitudes of one n and m
/// computes it once.
inline GRTRACE_HD double legendre_pi(double n, double phi, double m, double complete) {
  const double j = half_turns(phi);
  const double t = phi - j * std::numbers::pi;
  const double v = legendre_pi_sc(n, std::sin(t), std::cos(t), m);
  return j == 0.0 ? v : v + 2.0 * j * complete;
}

inline GRTRACE_HD double legendre_pi(double n, double phi, double m) {
  return legendre_pi(n, phi, m, half_turns(phi) != 0.0 ? complete_pi(n, m) : 0.0);
}

/// sn, cn, dn of u for the parameter m < 1 (negative included), the amplitude am(u) (continuous in u: am(u + 2K) =
/// am(u) + pi), and its half turns: am = turns pi + t with |t| <= pi / 2, sin t = (-1)^turns sn and cos t =
/// (-1)^turns cn (what legendre_pi_turns takes in place of am).
struct JacobiValues {
  double sn, cn, dn, am, turns;
};

/// The Jacobi functions of one parameter m < 1 by Gauss's transformation (the arithmetic-geometric mean of 1 and
/// sqrt(1 - m), DLMF 22.7.1-22.7.5; R. Bulirsch, Numer. Math. 7 (1965) 78-90). The means depend on m alone, so
/// they are computed once here: a caller that evaluates many arguments of one parameter (a ray's polar phase at its
/// crossings, its end and infinity) keeps this object and pays, per argument, one sine and cosine and a division a
/// level. K(m) comes with the means (K = pi / (2 M)).
class JacobiParameter {
 public:
  /// m = 0: sn = sin, cn = cos, dn = 1, K = pi / 2.
  JacobiParameter() = default;
  GRTRACE_HD explicit JacobiParameter(double m) {
    // The mean converges quadratically: a relative gap of 1e-9 leaves the next mean within 1e-19; 8 levels reach
    // it from m = 1 - 1e-16, 6 from m = -1e4.
    double kc = 1.0 - m, a = 1.0;
    while (levels_ < kLevels) {
      mean_[levels_] = a;
      root_[levels_] = kc = std::sqrt(kc);
      ++levels_;
      limit_ = 0.5 * (a + kc);
      if (std::abs(a - kc) <= 1e-9 * a) break;
      kc *= a;
      a = limit_;
    }
  }

  /// K(m) = F(pi/2 | m) = pi / (2 M), M the means' limit (DLMF 19.8.5).
  GRTRACE_HD double complete_f() const { return std::numbers::pi / (2.0 * limit_); }

  /// sn, cn, dn of u: one sine and cosine of M u (sn vanishes where that is a multiple of pi, as K = pi / (2 M)),
  /// then back up the means with one division a level; am(u) = turns pi + atan2 of sn and cn turned to the half
  /// turn's sign (NaN where kAmplitude is false: a caller that needs sn, cn, dn and the half turns spares the
  /// arctangent).
  template <bool kAmplitude = true>
  GRTRACE_HD JacobiValues operator()(double u) const {
    double c = limit_;
    const double phase = u * c;
    double sn = std::sin(phase), cn = std::cos(phase), dn = 1.0;
    if (sn != 0.0) {
      // The ratio cn / sn of each level from the last one's (Bulirsch's recursion), then sn from it.
      double ratio = cn / sn;
      c *= ratio;
      for (int i = levels_ - 1; i >= 0; --i) {
        const double b = mean_[i];
        ratio *= c;
        c *= dn;
        dn = (root_[i] + ratio) / (b + ratio);
        ratio = c / b;
      }
      const double s = 1.0 / std::sqrt(c * c + 1.0);
      sn = sn >= 0.0 ? s : -s;
      cn = c * sn;
    }
    // am = j pi + t, |t| <= pi / 2: j counts the half-turns of the phase (am passes (j + 1/2) pi where u = (2 j + 1)
    // K), and (sin t, cos t) = (-1)^j (sn, cn).
    const double j = half_turns(phase);
    if constexpr (!kAmplitude) return {sn, cn, dn, std::numeric_limits<double>::quiet_NaN(), j};
    const double turn = std::fmod(j, 2.0) == 0.0 ? 1.0 : -1.0;
    return {sn, cn, dn, j * std::numbers::pi + std::atan2(turn * sn, turn * cn), j};
  }

 private:
  static constexpr int kLevels = 12;
  double mean_[kLevels] = {}, root_[kLevels] = {}, limit_ = 1.0;
  int levels_ = 0;
};

/// sn, cn, dn and am of u for the parameter m < 1 (JacobiParameter's, for one argument).
template <bool kAmplitude = true>
inline GRTRACE_HD JacobiValues jacobi(double u, double m) {
  return JacobiParameter(m).template operator()<kAmplitude>(u);
}

/// Pi(n; am | m) for am = turns pi + t, |t| <= pi / 2, from the half turns and sin t, cos t (JacobiValues' turns
/// and (-1)^turns (sn, cn)): what a caller holding the Jacobi functions calls instead of legendre_pi(n, am, m, ..),
/// sparing the arctangent that makes am and the sine and cosine that take it back. `complete` as there.
inline GRTRACE_HD double legendre_pi_turns_of(double turns, double pi_t, double complete) {
  return turns == 0.0 ? pi_t : pi_t + 2.0 * turns * complete;
}
inline GRTRACE_HD double legendre_pi_turns(double n, double turns, double s, double c, double m, double complete) {
  return legendre_pi_turns_of(turns, legendre_pi_sc(n, s, c, m), complete);
}

/// R1(alpha; u | m) = int_0^u dv / (1 + alpha cn(v | m)) for 0 <= m < 1 and any alpha with 1 + alpha cn != 0 on
/// [0, u] (the integral Kerr's radial motion needs when two roots of its potential are complex; Byrd & Friedman
/// 341.03, Gralla & Lupsasca 2020 appendix B). With c0 = 1 - alpha^2, n = alpha^2 / (alpha^2 - 1), w = sd(v):
///   1 / (1 + alpha cn) = (1 - alpha cn) / (c0 (1 - n sn^2)), and cn dv = d(sn) / dn, which w turns into
///   int cn dv / (c0 (1 - n sn^2)) = int dw / (c0 + D w^2), D = m + (1 - m) alpha^2;
/// so R1 = Pi(n; am u | m) / c0 - alpha * (arctan or log form of int dw / (c0 + D w^2)). For alpha^2 > 1, Pi is the
/// principal value: its logarithm at cn = 1 / alpha (no pole of the integrand) cancels the second term's.
/// j: the Jacobi functions of u for m (JacobiValues; its amplitude is not read): what a caller that needs R1 of
/// several alpha at one u (the two horizon roots) computes once.
inline GRTRACE_HD double jacobi_r1(double alpha, const JacobiValues& j, double m) {
  const double c0 = 1.0 - alpha * alpha, d = m + (1.0 - m) * alpha * alpha, w = j.sn / j.dn;
  double second = 0.0;
  if (c0 > 0.0) {
    second = std::atan(w * std::sqrt(d / c0)) / std::sqrt(c0 * d);
  } else {
    const double sc = std::sqrt(-c0), sd = std::sqrt(d);
    second = std::log(std::abs((sd * w - sc) / (sd * w + sc))) / (2.0 * sc * sd);
  }
  const double n = alpha * alpha / (alpha * alpha - 1.0), turn = std::fmod(j.turns, 2.0) == 0.0 ? 1.0 : -1.0;
  const double pi =
      legendre_pi_turns(n, j.turns, turn * j.sn, turn * j.cn, m, j.turns != 0.0 ? complete_pi(n, m) : 0.0);
  return pi / c0 - alpha * second;
}

/// The same at u, whose Jacobi functions of m it computes.
inline GRTRACE_HD double jacobi_r1(double alpha, double u, double m) {
  return jacobi_r1(alpha, jacobi<false>(u, m), m);
}

}  // namespace grtrace
