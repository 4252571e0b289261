// grtrace/exact/kerr_null_geodesic.hpp
// A light ray of the Kerr exterior in closed form: from a state (x, k) in Boyer-Lindquist coordinates, where it
// crosses the equatorial plane (every order n = 0, 1, 2, ...), where it ends (the sky sphere or the horizon guard),
// its direction at infinity, and its state at any Mino time, with no integration.
//
// Takes:   a KerrMetric (any mass, |a| < M), a null state y0 in Boyer-Lindquist coordinates outside r_+ (a camera's
//          pixel: k past-directed or not, any normalisation), the radius of the sky sphere and of the horizon guard
//          (the integrating tracers' TraceSettings::escape_radius and (1 + horizon_epsilon) r_+).
// Returns: supported() false for the rays this form does not cover (below); otherwise the ray's end (escaped or
//          captured), its Mino time there, the Mino times and states of its equatorial crossings before the end,
//          and state_at(tau) for any Mino time up to the end: Boyer-Lindquist (x, k) with k in the scale of y0 and
//          t not followed (NaN), theta in [0, pi], phi continuous (not reduced).
// Method:  Gralla & Lupsasca, "Null geodesics of the Kerr exterior", Phys. Rev. D 101, 044032 (2020), written for
//          a camera at any radius. With lambda = L / E, eta = Q / E^2 and Mino time tau (d tau = |E| d(affine) /
//          Sigma): (dr/dtau)^2 = R(r) = r^4 + (a^2 - eta - lambda^2) r^2 + 2M (eta + (lambda - a)^2) r - a^2 eta and
//          (d cos(theta) / dtau)^2 = a^2 (u+ - cos^2)(cos^2 - u-).
//   Polar:  cos(theta) = sqrt(u+) sn(Y | m), Y = Y_o + nu sqrt(A) tau, A = -a^2 u- (> 0; eta + lambda^2 at a = 0),
//           m = u+ / u- <= 0: the equator is crossed at Y = 2 j K(m), so crossing n is at a Mino time known at
//           once, and int dtau / sin^2(theta) = Pi(u+; am Y | m) / sqrt(A) (GL eq. 29-31, 67).
//   Radial: the roots r1..r4 of R (GL eq. 95). Four real roots, r > r4: T(r) = 2 / sqrt(r31 r42) [F(asin sqrt(r31 /
//           r41)) - F(asin sqrt(r31 (r - r4) / (r41 (r - r3))))], modulus k = r32 r41 / (r31 r42), and r(T) by sn^2
//           (GL eq. B35-B37, Byrd & Friedman 258.00); r3, r4 complex: the same with cn (GL eq. B57-B58, B&F
//           260.00). T is the Mino time from infinity on the ingoing leg; the camera's T_o fixes the ray on it,
//           T = T_o - sign(dr/dtau at the camera) tau, and the turning point r4 is T = J (the first form is even in
//           T - J). The radial part of phi, int a (2 M r - a lambda) / Delta dtau, splits in 1 / (r - r_+-), which
//           are Pi(n; am | k) (four real roots: a Moebius function of sn^2) and R1 (complex roots: of cn;
//           core/jacobi_elliptic.hpp).
// Cost:    the constructor's polar means (the arithmetic-geometric mean of the polar parameter, kept: K and every
//          Jacobi function of the polar phase read them), the potential's roots, and four integrals in one loop of
//          four lanes (carlson_rf_rj_lanes: the start's polar phase with phi's polar start Pi, the radial half-period,
//          the Mino times from infinity to the camera and to the end). The direction at infinity: three more in one
//          such loop (the radial primitive at infinity, the leg from the camera to infinity by Carlson's addition
//          theorem, the polar Pi there). phi at a finite radius computes the radial primitive at the camera the first
//          time it is asked for and keeps it (as it keeps the radial means, built at the first radius asked for), so
//          an object is one ray's, read by one thread at a time (its const functions fill that cache).
// Not covered (supported() false: a tracer integrates these): eta <= 0 (vortical rays, which never cross the
//          equator, and the rays along it), all four roots complex (only for eta < 0), a camera inside the
//          potential's barrier (four real roots, r_o < r4) or on the axis, a radial or polar speed of exactly zero at
//          the start, a camera at or beyond the sky sphere.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/jacobi_elliptic.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/kerr.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace grtrace {

/// How a ray's radial potential factors (Gralla & Lupsasca's cases): four real roots with the largest outside the
/// horizon (the ray turns there), four real roots inside it, or two real and a complex pair.
enum class KerrRadialCase { turning, real_inside, complex_pair, unsupported };

class KerrNullGeodesic {
 public:
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  /// Rays that pass the axis closer than this fraction of their polar reach are the ray with L = 0 through it,
  /// as for the Mino-time tracer (trace/kerr_mino_system.hpp).
  static constexpr double kThroughAxis = 1e-8;

  GRTRACE_HD KerrNullGeodesic(const KerrMetric& metric, const GeodesicState& y0, double escape_radius,
                              double guard_radius)
      : mass_(metric.mass), a_(metric.spin), r_escape_(escape_radius), r_guard_(guard_radius) {
    const KerrMetric::ConstantsOfMotion constants = metric.constants_of_motion(y0);
    energy_ = constants.energy;
    const double l = constants.angular_momentum, q = constants.carter;
    lambda_ = l / energy_;
    eta_ = q / (energy_ * energy_);
    r_o_ = y0[1];
    theta_o_ = y0[2];
    phi_o_ = y0[3];
    const double sr = y0[5];
    k_theta_o_ = y0[6];
    if (!(eta_ > 0.0) || !(energy_ != 0.0) || sr == 0.0 || !(r_o_ < r_escape_) || !(r_o_ > r_guard_) ||
        !(std::sin(theta_o_) > 1e-6))
      return;
    s_r_ = sr > 0.0 ? 1.0 : -1.0;
    if (!setup_polar() || !setup_radial() || !setup_integrals()) return;
    supported_ = true;
  }

  GRTRACE_HD bool supported() const { return supported_; }
  GRTRACE_HD KerrRadialCase radial_case() const { return case_; }
  GRTRACE_HD bool escapes() const { return escapes_; }
  /// lambda = L / E and eta = Q / E^2 of the ray.
  GRTRACE_HD double lambda() const { return lambda_; }
  GRTRACE_HD double eta() const { return eta_; }
  /// E = p_t of y0's k (its scale: what the redshifts are measured against).
  GRTRACE_HD double energy() const { return energy_; }
  /// The Mino time at which the ray reaches the sky sphere (escapes) or the horizon guard.
  GRTRACE_HD double end_mino_time() const { return tau_end_; }
  /// The Mino time to infinity of an escaping ray (past the sky sphere).
  GRTRACE_HD double infinity_mino_time() const { return tau_infinity_; }
  /// The least radius the ray reaches before its end: the camera's for a ray that starts outwards, the turning
  /// point r4 for an inward ray that turns, the horizon guard's for one that falls in.
  GRTRACE_HD double least_radius() const {
    if (s_r_ > 0.0) return r_o_;
    return case_ == KerrRadialCase::turning ? r4_ : r_guard_;
  }
  /// The Mino time at which a ray that starts inwards first reaches the radius r (its least radius < r <= the
  /// camera's); NaN for a ray that starts outwards.
  GRTRACE_HD double ingoing_mino_time_to(double r) const { return s_r_ < 0.0 ? t_of_radius(r) - t_o_ : nan; }

  /// The Mino time of the n-th equatorial crossing (n = 0 the first after the start); it lies before the end
  /// when crossing_mino_time(n) < end_mino_time().
  GRTRACE_HD double crossing_mino_time(int n) const { return (2.0 * k_theta_ * (n + j0_) - y_sign_) / sqrt_a_; }
  /// The Mino time of the polar turning point after the n-th equatorial crossing (|cos theta| largest: half way to
  /// the next crossing).
  GRTRACE_HD double turning_mino_time_after(int n) const { return crossing_mino_time(n) + k_theta_ / sqrt_a_; }
  /// The equatorial crossings before Mino time tau.
  GRTRACE_HD int crossings_before(double tau) const {
    int n = 0;
    while (crossing_mino_time(n) < tau) ++n;
    return n;
  }

  /// The radius at Mino time tau (0 <= tau, up to the end; beyond the turning point as well).
  GRTRACE_HD double radius_at(double tau) const { return radius_at_t(t_o_ - s_r_ * tau); }

  /// The state at Mino time tau: (NaN, r, theta, phi, k) with k in y0's scale.
  GRTRACE_HD GeodesicState state_at(double tau) const {
    const double y = y_o_ + nu_ * sqrt_a_ * tau;
    const JacobiValues j = polar_jacobi_.operator()<false>(y);
    const PolarPhase polar = polar_phase(y, j);
    return make_state(tau, j.sn, j.cn, j.dn, &polar);
  }

  /// The state at the n-th equatorial crossing (theta = pi / 2 exactly; no Jacobi function needed there).
  GRTRACE_HD GeodesicState crossing_state(int n) const {
    GeodesicState y = crossing_state_without_phi(n);
    y[3] = crossing_phi(n, y[1]);
    return y;
  }

  /// The same with phi NaN: all of it but the azimuth's two Pi integrals (what a test of where the ray crosses an
  /// axisymmetric object needs; crossing_phi(n, y[1]) completes it).
  GRTRACE_HD GeodesicState crossing_state_without_phi(int n) const {
    const int j = n + j0_;  // Y = nu * 2 j K: sn = 0, cn = (-1)^j
    return make_state(crossing_mino_time(n), 0.0, (j % 2 == 0) ? 1.0 : -1.0, 1.0, nullptr);
  }

  /// phi at the n-th equatorial crossing (continuous, not reduced), whose radius r is known (crossing_state's or
  /// radius_at's; the one-argument form finds it).
  GRTRACE_HD double crossing_phi(int n, double r) const {
    const double tau = crossing_mino_time(n);
    const int j = n + j0_;
    // am Y = nu j pi exactly: j half turns and t = 0.
    return phi_at(tau, PolarPhase{nu_ * 2.0 * j * k_theta_, nu_ * j, 0.0, 1.0},
                  radial_amplitude(r, x_of_t(t_o_ - s_r_ * tau)));
  }
  GRTRACE_HD double crossing_phi(int n) const { return crossing_phi(n, radius_at(crossing_mino_time(n))); }

  /// The direction at infinity (theta, phi; phi continuous) of an escaping ray.
  GRTRACE_HD void direction_at_infinity(double& theta, double& phi) const {
    const double y = y_o_ + nu_ * sqrt_a_ * tau_infinity_;
    const JacobiValues j = polar_jacobi_.operator()<false>(y);
    theta = std::acos(std::clamp(sqrt_u_plus_ * j.sn, -1.0, 1.0));
    const PolarPhase phase = polar_phase(y, j);
    if (case_ != KerrRadialCase::complex_pair && a_ != 0.0 && !through_axis_) {
      // The three integrals phi needs here, H(F_inf), the leg's change D (radial_phi_to_infinity) and the polar Pi at
      // infinity, are unrelated: one duplication loop runs them side by side (carlson_rf_rj_lanes), where one after
      // another each waited on its own chain of square roots (a third less time for the three).
      const LegToInfinity leg = leg_to_infinity();
      const double s2 = leg.r31 / leg.r41, s = std::sqrt(s2), c2 = leg.r43 / leg.r41;  // am_inf's sine and cosine
      const double n_plus = leg.q * (r3_ - r_plus_) / leg.r4p, n_minus = leg.q * (r3_ - r_minus_) / leg.r4m;
      const double polar_s2 = phase.sin * phase.sin;
      if (detail::pi_away_from_pole(n_plus, s2) && detail::pi_away_from_pole(n_minus, s2) &&
          detail::pi_away_from_pole(u_plus_, polar_s2)) {
        using A4 = Eigen::Array4d;
        const A4 x(c2, leg.bx + leg.mu, phase.cos * phase.cos, 1.0);
        const A4 yy(1.0 - k_r_ * s2, leg.by + leg.mu, 1.0 - m_theta_ * polar_s2, 1.0);
        const A4 z(1.0, leg.bz + leg.mu, 1.0, 1.0);
        const double p_polar = 1.0 - u_plus_ * polar_s2;
        const A4 p[2] = {A4(1.0 - n_plus * s2, leg.p_plus + leg.mu, p_polar, 1.0),
                         A4(1.0 - n_minus * s2, leg.p_minus + leg.mu, p_polar, 1.0)};
        A4 rf, rj[2];
        carlson_rf_rj_lanes<2>(x, yy, z, p, rf, rj);
        const double h_inf = radial_h(f_inf_, legendre_pi_pair_of(n_plus, n_minus, s, s2, rf[0], rj[0][0], rj[1][0]));
        const double d = leg_change(leg, rf[1], rj[0][1], rj[1][1]);
        const double pi_polar = legendre_pi_of(u_plus_, phase.sin, polar_s2, rf[2], rj[0][2]);
        phi = phi_from(lambda_ * polar_phi_integral_of(phase.turns, pi_polar), s_r_ > 0.0 ? -d : 2.0 * h_inf - d);
        return;
      }
    }
    phi = phi_of(phase, radial_phi_to_infinity());
  }

  /// cos(theta) at Mino time tau (one Jacobi function: what the sky sphere's redshift needs of the state there).
  GRTRACE_HD double cos_theta_at(double tau) const {
    return std::clamp(sqrt_u_plus_ * polar_jacobi_.operator()<false>(y_o_ + nu_ * sqrt_a_ * tau).sn, -1.0, 1.0);
  }
  /// theta at Mino time tau.
  GRTRACE_HD double theta_at(double tau) const { return std::acos(cos_theta_at(tau)); }

 private:
  /// An amplitude in [-pi/2, pi/2] by its sine and cosine (cos >= 0).
  struct Amplitude {
    double sin = 0.0, cos = 1.0;
  };

  /// The polar phase Y and its amplitude am Y = turns pi + t by the half turns and sin t, cos t (|t| <= pi / 2):
  /// what phi's polar Pi takes, straight from the Jacobi functions (no arctangent, no sine and cosine of am).
  struct PolarPhase {
    double y, turns, sin, cos;
  };
  GRTRACE_HD static PolarPhase polar_phase(double y, const JacobiValues& j) {
    const double turn = std::fmod(j.turns, 2.0) == 0.0 ? 1.0 : -1.0;
    return {y, j.turns, turn * j.sn, turn * j.cn};
  }

  // ---- polar motion ----------------------------------------------------------------------------------------
  // The polar motion's constants and the start's phase (sin_o_, cos_o_), from the start's polar speed k_theta.
  GRTRACE_HD bool setup_polar() {
    const double a2 = a_ * a_, l2 = lambda_ * lambda_;
    // u+- = Delta_theta +- sqrt(Delta_theta^2 + eta / a^2), Delta_theta = (1 - (eta + lambda^2) / a^2) / 2, written
    // without dividing by a: A = -a^2 u- = (s + sqrt(s^2 + 4 a^2 eta)) / 2, s = eta + lambda^2 - a^2; u+ = eta / A.
    const double s = eta_ + l2 - a2, root = std::sqrt(s * s + 4.0 * a2 * eta_);
    const double big_a = s >= 0.0 ? 0.5 * (s + root) : 2.0 * a2 * eta_ / (root - s);
    if (!(big_a > 0.0)) return false;
    through_axis_ = l2 <= kThroughAxis * kThroughAxis * (eta_ + l2 + a2);
    u_plus_ = through_axis_ ? 1.0 : std::min(1.0, eta_ / big_a);
    sqrt_u_plus_ = std::sqrt(u_plus_);
    m_theta_ = -a2 * eta_ / (big_a * big_a);
    sqrt_a_ = std::sqrt(big_a);
    polar_jacobi_ = JacobiParameter(m_theta_);
    k_theta_ = polar_jacobi_.complete_f();
    // The start's phase: sn = cos(theta_o) / sqrt(u+), and cn from the start's own polar speed, (d cos / dtau)^2 =
    // (u+ - cos^2)(a^2 cos^2 + A): near the ray's polar turning point u+ - cos^2 from eta and lambda is a difference
    // of nearly equal numbers (a camera looking along a parallel), and asin(sn) would magnify its rounding there.
    const double c = std::cos(theta_o_), s_o = std::sin(theta_o_), sigma = r_o_ * r_o_ + a2 * c * c;
    const double dcos = s_o * sigma * k_theta_o_ / std::abs(energy_);
    const double x = std::clamp(c / sqrt_u_plus_, -1.0, 1.0);
    const double cn = through_axis_ ? std::sqrt(std::max(0.0, 1.0 - x * x))
                                    : std::sqrt(dcos * dcos / ((a2 * c * c + big_a) * u_plus_));
    const double norm = std::sqrt(x * x + cn * cn);  // both of order one: hypot's guard against overflow not needed
    sin_o_ = norm > 0.0 ? x / norm : 0.0;
    cos_o_ = norm > 0.0 ? cn / norm : 1.0;
    return std::isfinite(k_theta_);
  }

  // The ray's elliptic integrals that the setup needs, in one duplication loop of four lanes
  // (carlson_rf_rj_lanes): the start's polar phase F(am Y_o) = s R_F(c^2, 1 - m s^2, 1) (cos_o_ >= 0) with phi's
  // polar start Pi(u+; am Y_o) = s R_F + (u+ / 3) s^3 R_J of the same three arguments; the radial phase's F_inf; the
  // Mino times from infinity to the camera and to the end (the sky sphere, or the horizon guard for a ray that falls
  // in). Four unrelated chains of square roots, each of which waited on the last, overlap. Then the ends.
  GRTRACE_HD bool setup_integrals() {
    using A4 = Eigen::Array4d;
    const double s2 = sin_o_ * sin_o_;
    const bool polar_pi = !through_axis_ && detail::pi_away_from_pole(u_plus_, s2);
    escapes_ = s_r_ > 0.0 || case_ == KerrRadialCase::turning;
    const RadialFArgs f_inf = f_inf_args(), t_o = t_of_radius_args(r_o_),
                      t_end = t_of_radius_args(escapes_ ? r_escape_ : r_guard_);
    const A4 x(cos_o_ * cos_o_, f_inf.x, t_o.x, t_end.x), y(1.0 - m_theta_ * s2, f_inf.y, t_o.y, t_end.y),
        z(1.0, f_inf.z, t_o.z, t_end.z);
    // The R_F lanes' p is their z (an R_J not read, which meets its rule with theirs).
    const A4 p[1] = {A4(polar_pi ? 1.0 - u_plus_ * s2 : 1.0, f_inf.z, t_o.z, t_end.z)};
    A4 rf, rj[1];
    carlson_rf_rj_lanes<1>(x, y, z, p, rf, rj);
    y_o_ = sin_o_ * rf[0];
    if (polar_pi) polar_start_ = legendre_pi_of(u_plus_, sin_o_, s2, rf[0], rj[0][0]);
    else if (!through_axis_) polar_start_ = legendre_pi_sc(u_plus_, sin_o_, cos_o_, m_theta_);
    // d cos(theta)/dtau = -sin(theta) dtheta/dtau = sqrt(u+ A) cn dn nu: nu = -sign(k^theta); at a turning point
    // (k^theta = 0) the ray heads for the equator.
    nu_ = k_theta_o_ != 0.0 ? (k_theta_o_ > 0.0 ? -1.0 : 1.0) : (y_o_ > 0.0 ? -1.0 : 1.0);
    y_sign_ = nu_ * y_o_;
    j0_ = static_cast<int>(std::floor(y_sign_ / (2.0 * k_theta_))) + 1;
    f_inf_ = legendre_f_of(f_inf, rf[1]);
    j_r_ = g_r_ * f_inf_;
    t_o_ = t_of_radius_from(t_o, rf[2]);
    const double t_end_radius = t_of_radius_from(t_end, rf[3]);
    // The end: an inward ray turns at r4 (T = J) and leaves through the sky sphere at T = 2 J - T(R); without a
    // turning point it reaches the guard. An outward ray leaves at T = T(R).
    if (s_r_ > 0.0) {
      tau_end_ = t_o_ - t_end_radius;
      tau_infinity_ = t_o_;
    } else if (case_ == KerrRadialCase::turning) {
      tau_end_ = 2.0 * j_r_ - t_end_radius - t_o_;
      tau_infinity_ = 2.0 * j_r_ - t_o_;
    } else {
      tau_end_ = t_end_radius - t_o_;
      tau_infinity_ = nan;
    }
    return std::isfinite(y_o_) && std::isfinite(t_o_) && std::isfinite(tau_end_) && tau_end_ > 0.0;
  }

  // int_0^tau dtau' / sin^2(theta) = nu (Pi(u+; am Y) - Pi(u+; am Y_o)) / sqrt(A); Pi(u+; am Y_o) is the start's
  // (phi_at), the complete Pi(u+) computed once a ray, where a crossing first needs it.
  GRTRACE_HD double polar_phi_integral(const PolarPhase& am) const {
    return polar_phi_integral_of(am.turns, legendre_pi_sc(u_plus_, am.sin, am.cos, m_theta_));
  }
  // The same from Pi(u+; t) of am = turns pi + t, |t| <= pi / 2.
  GRTRACE_HD double polar_phi_integral_of(double turns, double pi_t) const {
    if (turns != 0.0 && std::isnan(pi_complete_)) pi_complete_ = complete_pi(u_plus_, m_theta_);
    return nu_ * (legendre_pi_turns_of(turns, pi_t, pi_complete_) - polar_start_) / sqrt_a_;
  }

  // Passes by the axis (sn = +-1: Y = (2 j + 1) K) between Y_o and Y, for a ray through it: each adds pi to phi.
  GRTRACE_HD int axis_passes(double y) const {
    const double lo = std::min(y, y_o_), hi = std::max(y, y_o_);
    const double first = std::ceil((lo / k_theta_ - 1.0) / 2.0), last = std::floor((hi / k_theta_ - 1.0) / 2.0);
    return static_cast<int>(std::max(0.0, last - first + 1.0));
  }

  // ---- radial motion ---------------------------------------------------------------------------------------
  GRTRACE_HD bool setup_radial() {
    const double a2 = a_ * a_, m = mass_;
    ca_ = a2 - eta_ - lambda_ * lambda_;
    cb_ = 2.0 * m * (eta_ + (lambda_ - a_) * (lambda_ - a_));
    const double ca = ca_, cb = cb_, cc = -a2 * eta_;
    // GL eq. 95: the resolvent cubic's root z^2 (the principal cube roots when its discriminant is negative).
    const double p = -ca * ca / 12.0 - cc, q = -ca / 3.0 * ((ca / 6.0) * (ca / 6.0) - cc) - cb * cb / 8.0;
    const double disc = (p / 3.0) * (p / 3.0) * (p / 3.0) + 0.25 * q * q;
    double sum = 0.0;
    if (disc >= 0.0) {
      sum = std::cbrt(-0.5 * q + std::sqrt(disc)) + std::cbrt(-0.5 * q - std::sqrt(disc));
    } else {
      sum = 2.0 * std::cbrt(std::sqrt(0.25 * q * q - disc)) * std::cos(std::atan2(std::sqrt(-disc), -0.5 * q) / 3.0);
    }
    const double z2 = 0.5 * sum - ca / 6.0;
    if (!(z2 > 0.0)) return false;
    const double z = std::sqrt(z2);
    const double inner = -0.5 * ca - z2 + cb / (4.0 * z), outer = -0.5 * ca - z2 - cb / (4.0 * z);
    if (!(inner >= 0.0)) return false;  // r1, r2 complex: all four are (eta < 0)
    r1_ = -z - std::sqrt(inner);
    r2_ = -z + std::sqrt(inner);
    r_plus_ = m + std::sqrt(m * m - a2);
    r_minus_ = m - std::sqrt(m * m - a2);
    if (outer >= 0.0) {
      r3_ = z - std::sqrt(outer);
      r4_ = z + std::sqrt(outer);
      polish(r4_);
      polish(r3_);
      case_ = r4_ > r_plus_ ? KerrRadialCase::turning : KerrRadialCase::real_inside;
      if (case_ == KerrRadialCase::turning && !(r_o_ > r4_)) return false;  // the camera inside the barrier
      const double r31 = r3_ - r1_, r41 = r4_ - r1_, r32 = r3_ - r2_, r42 = r4_ - r2_;
      k_r_ = r32 * r41 / (r31 * r42);
      g_r_ = 2.0 / std::sqrt(r31 * r42);
      if (!(k_r_ >= 0.0 && k_r_ < 1.0)) return false;
    } else {
      case_ = KerrRadialCase::complex_pair;
      const double im3 = std::sqrt(-outer);  // r3 = z - i im3, r4 = z + i im3
      ca3_ = std::hypot(z - r2_, im3);       // A = |r3 - r2|
      cb3_ = std::hypot(z - r1_, im3);       // B = |r3 - r1|
      const double r21 = r2_ - r1_;
      k_r_ = ((ca3_ + cb3_) * (ca3_ + cb3_) - r21 * r21) / (4.0 * ca3_ * cb3_);
      g_r_ = 1.0 / std::sqrt(ca3_ * cb3_);
      if (!(k_r_ >= 0.0 && k_r_ < 1.0)) return false;
      radial_jacobi_ = JacobiParameter(k_r_);
      radial_jacobi_ready_ = true;
      k_complete_r_ = radial_jacobi_.complete_f();
    }
    // phi's radial part: int a (2 M r - a lambda) / Delta dtau = sum c_+- int dtau / (r - r_+-).
    const double dr = r_plus_ - r_minus_;
    c_plus_ = dr > 0.0 ? a_ * (2.0 * m * r_plus_ - a_ * lambda_) / dr : 0.0;
    c_minus_ = dr > 0.0 ? -a_ * (2.0 * m * r_minus_ - a_ * lambda_) / dr : 0.0;
    return true;
  }

  // One Newton step towards a real root of R where it helps (the closed form loses digits near a double root).
  GRTRACE_HD void polish(double& r) const {
    const double d = (4.0 * r * r + 2.0 * ca_) * r + cb_;
    if (d == 0.0) return;
    const double next = r - radial_potential(r) / d;
    if (std::abs(radial_potential(next)) < std::abs(radial_potential(r))) r = next;
  }

  // R(r) = r^4 + ca r^2 + cb r - a^2 eta (E = 1).
  GRTRACE_HD double radial_potential(double r) const { return (((r * r + ca_) * r) + cb_) * r - a_ * a_ * eta_; }

  // The Mino time from infinity to r on the ingoing leg (r >= r4 with four real roots, r > r2 otherwise).
  // Four real roots: int_r^inf dr' / sqrt(R) in Carlson's symmetric form, 2 R_F(U12^2, U13^2, U14^2) with U_ij =
  // Y_i Y_j + Y_k Y_l, Y_i = sqrt(r - r_i) (DLMF 19.29.4 with its upper limit at infinity). Its three arguments
  // differ by O(r_i / r), so far from the hole R_F needs one or two duplications where g (F_inf - F(am(r))) needed
  // four and then lost digits in the difference (two at the camera of 50 M, three at a sky sphere of 1000 M).
  GRTRACE_HD double t_of_radius(double r) const {
    const RadialFArgs args = t_of_radius_args(r);
    return t_of_radius_from(args, carlson_rf(args.x, args.y, args.z));
  }

  // The R_F whose value gives T(r) (above) or F_inf, and how: Legendre's F(am) = s R_F(c^2, 1 - k s^2, 1) (2K less
  // it beyond pi / 2, c < 0) where `legendre`, else T = 2 R_F (Carlson's form).
  struct RadialFArgs {
    double x, y, z, s, c;
    bool legendre;
  };
  GRTRACE_HD RadialFArgs legendre_f_args(double s, double c) const {
    return {c * c, 1.0 - k_r_ * s * s, 1.0, s, c, true};
  }
  GRTRACE_HD double legendre_f_of(const RadialFArgs& args, double rf) const {
    const double f = args.s * rf;
    return args.c >= 0.0 ? f : 2.0 * k_complete_r_ - f;  // k_complete_r_ is read only for a complex pair (c < 0)
  }
  // F_inf = F(asin sqrt(r31 / r41)) for four real roots; for a complex pair the amplitude of cn = (A - B) / (A + B).
  GRTRACE_HD RadialFArgs f_inf_args() const {
    if (case_ == KerrRadialCase::complex_pair)
      return legendre_f_args(2.0 * std::sqrt(ca3_ * cb3_) / (ca3_ + cb3_), (ca3_ - cb3_) / (ca3_ + cb3_));
    const double r41 = r4_ - r1_;
    return legendre_f_args(std::sqrt((r3_ - r1_) / r41), std::sqrt((r4_ - r3_) / r41));
  }
  GRTRACE_HD RadialFArgs t_of_radius_args(double r) const {
    if (case_ == KerrRadialCase::complex_pair) {
      const double u = ca3_ * (r - r1_), v = cb3_ * (r - r2_);
      return legendre_f_args(2.0 * std::sqrt(u * v) / (u + v), (u - v) / (u + v));
    }
    const double y1 = std::sqrt(r - r1_), y2 = std::sqrt(r - r2_), y3 = std::sqrt(r - r3_);
    const double y4 = std::sqrt(std::max(0.0, r - r4_));
    const double u12 = y1 * y2 + y3 * y4, u13 = y1 * y3 + y2 * y4, u14 = y1 * y4 + y2 * y3;
    return {u12 * u12, u13 * u13, u14 * u14, 0.0, 0.0, false};
  }
  GRTRACE_HD double t_of_radius_from(const RadialFArgs& args, double rf) const {
    return args.legendre ? g_r_ * (f_inf_ - legendre_f_of(args, rf)) : 2.0 * rf;
  }

  GRTRACE_HD const JacobiParameter& radial_jacobi() const {
    if (!radial_jacobi_ready_) {
      radial_jacobi_ = JacobiParameter(k_r_);
      radial_jacobi_ready_ = true;
    }
    return radial_jacobi_;
  }

  GRTRACE_HD double x_of_t(double t) const { return t / g_r_ - f_inf_; }

  GRTRACE_HD double radius_at_t(double t) const {
    const double x = x_of_t(t);
    const JacobiValues j = radial_jacobi().operator()<false>(x);
    return radius_at_x(j.sn, j.cn);
  }

  GRTRACE_HD double radius_at_x(double sn, double cn) const {
    if (case_ == KerrRadialCase::complex_pair) {
      return ((cb3_ * r2_ - ca3_ * r1_) + (cb3_ * r2_ + ca3_ * r1_) * cn) / ((cb3_ - ca3_) + (cb3_ + ca3_) * cn);
    }
    const double r31 = r3_ - r1_, r41 = r4_ - r1_, s = sn * sn;
    return (r31 * r4_ - r41 * r3_ * s) / (r31 - r41 * s);
  }

  // H(X) = sum c_+- int_0^X dX' / (r(X') - r_+-), so that phi's radial part between X_a and X_b is
  // -sign(dr/dtau at the camera) g (H(X_b) - H(X_a)) (dtau = -s_r g dX).
  // am: the amplitude of X for four real roots (|X| < K there: am = asin(sn X), known from r at the ends).
  GRTRACE_HD double radial_phi_primitive(double x, Amplitude am) const {
    if (a_ == 0.0) return 0.0;
    if (case_ == KerrRadialCase::complex_pair) {
      double h = 0.0;
      const double b0 = cb3_ - ca3_, b1 = cb3_ + ca3_;
      const double a0 = cb3_ * r2_ - ca3_ * r1_, a1 = cb3_ * r2_ + ca3_ * r1_;
      const JacobiValues j = radial_jacobi().operator()<false>(x);  // one for both roots
      for (const auto& [c, rh] : {Pair{c_plus_, r_plus_}, Pair{c_minus_, r_minus_}}) {
        const double g0 = a0 - rh * b0, g1 = a1 - rh * b1;
        h += c * (b1 / g1 * x + (b0 * g1 - b1 * g0) / (g0 * g1) * jacobi_r1(g1 / g0, j, k_r_));
      }
      return h;
    }
    const double q = (r4_ - r1_) / (r3_ - r1_);
    const double n_plus = q * (r3_ - r_plus_) / (r4_ - r_plus_), n_minus = q * (r3_ - r_minus_) / (r4_ - r_minus_);
    return radial_h(x, legendre_pi_pair_sc(n_plus, n_minus, am.sin, am.cos, k_r_));
  }

  // H(X) for four real roots from Pi(n_+; am X) and Pi(n_-; am X).
  GRTRACE_HD double radial_h(double x, const PiPair& pi) const {
    const double q = (r4_ - r1_) / (r3_ - r1_);
    const double r4p = r4_ - r_plus_, r4m = r4_ - r_minus_;
    const double n_plus = q * (r3_ - r_plus_) / r4p, n_minus = q * (r3_ - r_minus_) / r4m;
    return c_plus_ / r4p * (q / n_plus * x + (1.0 - q / n_plus) * pi.first) +
           c_minus_ / r4m * (q / n_minus * x + (1.0 - q / n_minus) * pi.second);
  }

  struct Pair {
    double c, r;
  };

  // The amplitude of the radial phase X where the radius is r, for four real roots, by its sine and cosine: sin^2
  // am = r31 (r - r4) / (r41 (r - r3)) (|X| < K: am = asin(sn X), cos am >= 0), the sign of X's (negative on the
  // ingoing leg). Unread (zero) for a complex pair.
  GRTRACE_HD Amplitude radial_amplitude(double r, double x) const {
    if (case_ == KerrRadialCase::complex_pair) return {};
    const double s = std::clamp((r3_ - r1_) * (r - r4_) / ((r4_ - r1_) * (r - r3_)), 0.0, 1.0);
    return {x < 0.0 ? -std::sqrt(s) : std::sqrt(s), std::sqrt(1.0 - s)};
  }

  // phi at Mino time tau, the polar phase being Y there with amplitude am, the radial phase X with amplitude am_r
  // (read only for four real roots).
  GRTRACE_HD double phi_at(double tau, const PolarPhase& phase, Amplitude am_r) const {
    return phi_of(phase, radial_phi_primitive(x_of_t(t_o_ - s_r_ * tau), am_r) - radial_start());
  }

  // phi where the polar phase is `phase` and the radial primitive has moved by h_change = H(X) - H(X_o) since the
  // camera.
  GRTRACE_HD double phi_of(const PolarPhase& phase, double h_change) const {
    return phi_from(through_axis_ ? std::numbers::pi * axis_passes(phase.y) * (nu_ > 0.0 ? 1.0 : -1.0)
                                  : lambda_ * polar_phi_integral(phase),
                    h_change);
  }
  // phi from its polar term (lambda int dtau / sin^2, or the axis passes' pi) and the radial primitive's change.
  GRTRACE_HD double phi_from(double polar, double h_change) const {
    const double radial = -s_r_ * g_r_ * h_change;
    // d phi / dtau = sign(E) (a (2 M r - a lambda) / Delta + lambda / sin^2 theta) (k = dx / d(affine), E = p_t).
    return phi_o_ + (energy_ > 0.0 ? 1.0 : -1.0) * (radial + polar);
  }

  // H(X_o), the radial primitive at the camera: once a ray, and only for one whose phi at a finite radius is asked
  // for (a disk drawn by its light asks for none; the direction at infinity needs it only through
  // radial_phi_to_infinity's difference).
  GRTRACE_HD double radial_start() const {
    if (!phi_start_ready_) {
      const double x_o = x_of_t(t_o_);
      radial_start_ = radial_phi_primitive(x_o, radial_amplitude(r_o_, x_o));
      phi_start_ready_ = true;
    }
    return radial_start_;
  }

  // H(X_inf) - H(X_o): the radial primitive's change from the camera to infinity (X_inf = -+F_inf, whose amplitude
  // is asin sqrt(r31 / r41)).
  // Four real roots: X_o = -F(am_o) < 0 (T is measured on the ingoing leg), so with D = H(F_inf) - H(F(am_o)) the
  // change is -D for a ray that starts outwards (X_inf = -F_inf) and 2 H(F_inf) - D for one that turns at r4 (X_inf =
  // +F_inf; H is odd). D is the integral between the camera and infinity on one leg, which Carlson's addition
  // theorem (DLMF 19.26.9-19.26.12, tested here against the two primitives) gives as one Pi of a small amplitude:
  // with the amplitude's csc^2 written c, Pi(n; am) = R_F(c - 1, c - m, c) + (n / 3) R_J(.., c - n) (DLMF 19.25.5,
  // 19.25.14); B = (c_inf - 1, c_inf - m, c_inf), lambda = c_o - c_inf, and mu the larger root of (lambda mu - e2)^2
  // = 4 e3 (lambda + mu + e1) (e_k B's elementary symmetric functions):
  //   F_inf - F(am_o) = R_F(B + mu),
  //   Pi(n; am_inf) - Pi(n; am_o) = R_F(B + mu) + (n / 3) R_J(B + mu, p + mu) + n R_C(gamma - delta, gamma),
  //   p = c_inf - n, delta = (p - B_x)(p - B_y)(p - B_z), gamma = p (p + lambda)(p + mu).
  // mu grows as the camera recedes (~ 4 e3 / lambda^2, lambda ~ 1 / r_o): B + mu's arguments agree to ~1 / mu and
  // the duplication that took three or four levels takes one or none.
  GRTRACE_HD double radial_phi_to_infinity() const {
    const double x_inf = x_of_t(t_o_ - s_r_ * tau_infinity_);
    if (case_ == KerrRadialCase::complex_pair || a_ == 0.0) {
      return radial_phi_primitive(x_inf, Amplitude{}) - radial_start();
    }
    const LegToInfinity leg = leg_to_infinity();
    const double ps[2] = {leg.p_plus + leg.mu, leg.p_minus + leg.mu};
    double rj[2];
    const double rf = detail::carlson_rf_rj_n<2>(leg.bx + leg.mu, leg.by + leg.mu, leg.bz + leg.mu, ps, rj);
    const double d = leg_change(leg, rf, rj[0], rj[1]);
    const double h_inf =
        radial_phi_primitive(f_inf_, Amplitude{std::sqrt(leg.r31 / leg.r41), std::sqrt(leg.r43 / leg.r41)});
    return s_r_ > 0.0 ? -d : 2.0 * h_inf - d;
  }

  // The addition theorem's arguments for D (above); every one a product or quotient of the roots' positive
  // differences: no cancellation.
  struct LegToInfinity {
    double r31, r41, r43, q, bx, by, bz, lambda, mu, r4p, r4m, p_plus, p_minus;
  };
  GRTRACE_HD LegToInfinity leg_to_infinity() const {
    LegToInfinity g;
    g.r31 = r3_ - r1_;
    g.r41 = r4_ - r1_;
    g.r43 = r4_ - r3_;
    const double r42 = r4_ - r2_;
    g.q = g.r41 / g.r31;
    g.bx = g.r43 / g.r31;                   // c_inf - 1
    g.by = g.r41 * g.r43 / (g.r31 * r42);   // c_inf - m
    g.bz = g.q;                             // c_inf
    g.lambda = g.q * g.r43 / (r_o_ - r4_);  // c_o - c_inf
    const double e2 = g.bx * g.by + g.by * g.bz + g.bz * g.bx, e3 = g.bx * g.by * g.bz;
    // The larger root, written without a difference: (lambda mu - e2)^2 - 4 e3 (lambda + mu + e1) = 0 has
    // discriminant 4 e3 (lambda + B_x)(lambda + B_y)(lambda + B_z).
    g.mu =
        (g.lambda * e2 + 2.0 * e3 + 2.0 * std::sqrt(e3 * (g.lambda + g.bx) * (g.lambda + g.by) * (g.lambda + g.bz))) /
        (g.lambda * g.lambda);
    g.r4p = r4_ - r_plus_;
    g.r4m = r4_ - r_minus_;
    g.p_plus = g.q * g.r43 / g.r4p;  // c_inf - n, n = q (r3 - r_+-) / (r4 - r_+-)
    g.p_minus = g.q * g.r43 / g.r4m;
    return g;
  }

  // D from R_F(B + mu) and the two R_J(B + mu, p_+- + mu). Each root's term of H is c / (r4 - r_h) (q / n X + (1 -
  // q / n) Pi(n)); its change over the leg, with n - q = -p, is c / (r4 - r_h) (R_F - p (R_J / 3 + R_C)).
  GRTRACE_HD double leg_change(const LegToInfinity& g, double rf, double rj_plus, double rj_minus) const {
    const auto term = [&](double p, double rj_p) {
      const double delta = (p - g.bx) * (p - g.by) * (p - g.bz), gamma = p * (p + g.lambda) * (p + g.mu);
      return rf - p * (rj_p / 3.0 + carlson_rc(gamma - delta, gamma));
    };
    return c_plus_ / g.r4p * term(g.p_plus, rj_plus) + c_minus_ / g.r4m * term(g.p_minus, rj_minus);
  }

  // The state at Mino time tau from the polar phase's sn, cn, dn; polar = {Y, am Y} for phi, or null for phi NaN.
  GRTRACE_HD GeodesicState make_state(double tau, double sn, double cn, double dn, const PolarPhase* polar) const {
    const double t = t_o_ - s_r_ * tau, x = x_of_t(t);
    const JacobiValues jr = radial_jacobi().operator()<false>(x);
    const double r = radius_at_x(jr.sn, jr.cn);
    const double cos_t = std::clamp(sqrt_u_plus_ * sn, -1.0, 1.0), theta = std::acos(cos_t);
    const double sin2 = 1.0 - cos_t * cos_t, sin_t = std::sqrt(sin2);
    const double a2 = a_ * a_, sigma = r * r + a2 * cos_t * cos_t, delta = r * r - 2.0 * mass_ * r + a2;
    const double e = energy_, abs_e = std::abs(e);
    const double rr = std::max(0.0, radial_potential(r));
    // dr/dtau's sign: four real roots, r grows with |X| and T = T_o - s_r tau; otherwise r falls as T grows.
    const double radial_sign = case_ == KerrRadialCase::complex_pair ? s_r_ : -s_r_ * (x >= 0.0 ? 1.0 : -1.0);
    const double dcos = sqrt_u_plus_ * cn * dn * nu_ * sqrt_a_;  // d cos(theta) / dtau
    const double w = r * r + a2 - a_ * lambda_;
    GeodesicState out;
    out[0] = nan;
    out[1] = r;
    out[2] = theta;
    out[3] = polar ? phi_at(tau, *polar, radial_amplitude(r, x)) : nan;
    out[4] = e * ((r * r + a2) * w / delta - a_ * (a_ * sin2 - lambda_)) / sigma;
    out[5] = radial_sign * abs_e * std::sqrt(rr) / sigma;
    out[6] = -dcos / sin_t * abs_e / sigma;
    out[7] = e * (a_ * w / delta - a_ + lambda_ / sin2) / sigma;
    return out;
  }

  double mass_, a_, r_escape_, r_guard_;
  double energy_ = 0.0, lambda_ = 0.0, eta_ = 0.0, r_o_ = 0.0, theta_o_ = 0.0, phi_o_ = 0.0, s_r_ = 1.0;
  double k_theta_o_ = 0.0;  ///< the start's k^theta
  bool supported_ = false, escapes_ = false, through_axis_ = false;
  KerrRadialCase case_ = KerrRadialCase::unsupported;
  // polar
  double u_plus_ = 0.0, sqrt_u_plus_ = 0.0, m_theta_ = 0.0, sqrt_a_ = 1.0, k_theta_ = 1.0;
  JacobiParameter polar_jacobi_;  ///< the means of m_theta, computed once for every Jacobi function of the polar phase
  double sin_o_ = 0.0, cos_o_ = 1.0, y_o_ = 0.0, nu_ = 1.0, y_sign_ = 0.0;
  // phi's terms of the start (Pi(u+; am Y_o | m) and the radial primitive at the camera) and the complete Pi(u+ | m):
  // computed where a ray's phi is first asked for.
  mutable bool phi_start_ready_ = false;
  mutable double polar_start_ = 0.0, radial_start_ = 0.0, pi_complete_ = nan;
  int j0_ = 0;
  // radial
  double ca_ = 0.0, cb_ = 0.0;  ///< R's r^2 and r coefficients
  double r1_ = 0.0, r2_ = 0.0, r3_ = 0.0, r4_ = 0.0, ca3_ = 0.0, cb3_ = 0.0;
  double r_plus_ = 0.0, r_minus_ = 0.0, k_r_ = 0.0, k_complete_r_ = 0.0, g_r_ = 1.0, f_inf_ = 0.0, j_r_ = 0.0;
  // The means of k_r, for every Jacobi function of the radial phase: computed where one is first needed (a ray
  // that escapes without crossing the plane needs none).
  mutable JacobiParameter radial_jacobi_;
  mutable bool radial_jacobi_ready_ = false;
  double t_o_ = 0.0;
  double tau_end_ = nan, tau_infinity_ = nan, c_plus_ = 0.0, c_minus_ = 0.0;
};

}  // namespace grtrace
