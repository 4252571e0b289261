// grtrace/trace/kerr_mino_system.hpp
// Kerr's null geodesics reduced by their constants of motion: a geodesic system (trace/geodesic_system.hpp) of five
// variables in Mino time whose right-hand side is a few polynomials, in place of the eight-variable geodesic
// equation of KerrMetric (Boyer-Lindquist).
//
// Takes:   a KerrMetric and a null state (x, k) in Boyer-Lindquist coordinates, outside r_+ (on the axis only with
//          L_z = 0, which every ray from there has).
// Returns: the system for that ray and its initial state z0 = (u, theta, phi, u', theta'); its geodesic_state(z)
//          is the Boyer-Lindquist (x, k) again (k = dx/dlambda, affine), except t, which it does not follow (NaN:
//          a stationary scene does not depend on it; the scene tracer that uses this system refuses other scenes).
// Method:  Carter (1968): a null geodesic has the constants E = p_t, L = -p_phi (KerrMetric::energy,
//          angular_momentum) and Q (carter_constant); with Mino time, d lambda_M = d lambda / Sigma (Mino 2003),
//          the radial and polar motions separate: (dr/dlambda_M)^2 = R(r), (dtheta/dlambda_M)^2 = Theta(theta).
//          Their second-order forms, d^2 r/dlambda_M^2 = R'(r) / 2 and the same for theta, pass through the turning
//          points (where the square roots of the first-order forms change sign) without special treatment.
//          The radius is carried as u = 1/r: u^4 R(1/u) = R~(u) is a polynomial, regular at infinity, so a ray
//          leaving towards the sky sphere is a nearly straight line in (lambda_M, u) and not a pole at finite
//          Mino time as r is:
//            R~(u)     = P~^2 - K u^2 Delta~,    P~ = E + A u^2,  A = a (a E - L),  Delta~ = 1 - 2 M u + a^2 u^2,
//                        K = Q + (L - a E)^2
//            u''       = R~'(u) / 2 = 2 A u P~ - K u + 3 M K u^2 - 2 a^2 K u^3
//            Theta     = Q + a^2 E^2 cos^2 th - L^2 cot^2 th,   theta'' = Theta'/2 = cos th (L^2 / sin^3 th - a^2 E^2 sin th)
//            phi'      = a P~ / Delta~ - a E + L / sin^2 th
//          and back to the affine tangent: k^r = -r^2 u' / Sigma, k^th = theta' / Sigma, k^ph = phi' / Sigma,
//          k^t = ((r^2 + a^2) P~ / Delta~ - a (a E sin^2 th - L)) / Sigma (Sigma = r^2 + a^2 cos^2 th).
//          theta is kept (not cos theta) so that a ray through the axis is re-charted exactly as in the
//          geodesic equation (wrap_chart: theta -> -theta, phi -> phi + pi, theta' -> -theta'): in cos theta the
//          axis would be a turning point and a ray with L = 0 would miss its jump of pi in phi.
// Assumes: null rays (g(k, k) = 0: the camera's). The constraints the second-order forms do not enforce,
//          u'^2 = R~(u) and theta'^2 = Theta, are the tracer's guard (constraint_violation). A trial stage deep
//          inside the polar turning point, or across the axis for L_z != 0, is answered with NaN, so that the step
//          is shrunk until the pass by the axis is resolved (operator()); a pass closer than 1e-8 rad is taken as
//          the L_z = 0 ray's, through the axis (kThroughAxis).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/sin_cos.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/trace/geodesic_system.hpp"  // wrap_polar_axis

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace grtrace {

struct KerrMinoSystem {
  static constexpr int dimension = 5;
  using State = Vector<5>;  ///< (u = 1/r, theta, phi, du/dlambda_M, dtheta/dlambda_M)

  KerrMetric metric;
  double energy = 0.0, angular_momentum = 0.0, carter = 0.0;  ///< E, L_z, Q of the ray

  /// The system of the ray y0 (Boyer-Lindquist, null, outside r_+).
  GRTRACE_HD KerrMinoSystem(const KerrMetric& m, const GeodesicState& y0)
      : metric(m), energy(m.energy(y0)), angular_momentum(m.angular_momentum(y0)), carter(m.carter_constant(y0)) {
    // A ray that passes the axis closer than its turning point could be resolved (sin theta_min = |L| / sqrt(Q + L^2
    // + a^2 E^2 cos^2) below kThroughAxis) is traced as the ray with L = 0 through the axis, which it equals to
    // within that angle; one with L exactly 0 starts or passes on the axis.
    // reach = theta'^2 + L^2 / sin^2 theta + a^2 E^2 sin^2 theta >= 0; it is 0 for a ray along the axis, where its
    // round-off (of |Q| + a^2 E^2) may leave it negative and a round-off L != 0 (a camera's central pixel on the axis).
    const double a2e2 = m.spin * m.spin * energy * energy;
    const double reach =
        std::max(carter + angular_momentum * angular_momentum + a2e2, 1e-15 * (std::abs(carter) + a2e2));
    through_axis_ = angular_momentum * angular_momentum <= kThroughAxis * kThroughAxis * reach;
    // A ray that starts that close to the axis too (a camera on it) is not near its own start's meridian: its
    // L^2 / sin^2 theta is a part of its polar speed there. It becomes the L = 0 ray parallel to it (initial_state),
    // whose Carter constant takes in L^2 (Theta = Q + L^2 + a^2 E^2 cos^2 - L^2 / sin^2: the polar speed once off
    // the axis).
    if (through_axis_ && polar_sin_cos(y0[2]).sin < kNearAxisStart) {
      axis_start_l_ = angular_momentum;
      carter += angular_momentum * angular_momentum;
    }
    if (through_axis_) angular_momentum = 0.0;
    const double a = m.spin, e = energy, l = angular_momentum;
    a2_ = a * a;
    big_a_ = a * (a * e - l);
    k_ = carter + (l - a * e) * (l - a * e);
    a2e2_ = a2_ * e * e;
    l2_ = l * l;
    forbidden_ = 4.0 * (carter + l2_ + a2e2_);
    slowed_near_axis_ = !through_axis_ && l2_ < kSlowedNearAxis * kSlowedNearAxis * reach;
  }

  /// z0 of the ray y0 the system was built for: u = 1/r, u' = -Sigma k^r / r^2, theta' = Sigma k^theta.
  GRTRACE_HD State initial_state(const GeodesicState& y0) const {
    const double r = y0[1], c = polar_sin_cos(y0[2]).cos, sigma = r * r + a2_ * c * c;  // the GPU's bits too
    State z;
    z << 1.0 / r, y0[2], y0[3], -sigma * y0[5] / (r * r), sigma * y0[6];
    if (axis_start_l_ != 0.0) start_through_axis(z);
    return z;
  }

  /// dz/dlambda_M. Forced inline: a call costs as much as the polynomials (the stepper calls it once per stage).
  [[gnu::always_inline]] GRTRACE_HD State operator()(const State& z) const {
    const double u = z[0], u2 = u * u, m = metric.mass;
    const SinCos sc = polar_sin_cos(z[1]);
    // L = 0 (through_axis_): no L / sin^2 terms, which would be 0 * inf on the axis itself.
    const double s2 = sc.sin * sc.sin, inv_s2 = through_axis_ ? 0.0 : 1.0 / s2;
    // Not a state of the ray, but a trial stage of a step too long for the ray's pass by the axis: deep beyond
    // the polar turning point (see forbidden_), or across the axis, which a ray with L != 0 never reaches (the
    // chart is wrapped after every accepted step, so a step starts in [0, pi]). NaN makes the integrator shrink
    // the step (controlled_integrator.hpp) until the pass is resolved.
    if (l2_ * inv_s2 > forbidden_ || (!through_axis_ && !(z[1] >= 0.0 && z[1] <= std::numbers::pi)))
      return State::Constant(std::numeric_limits<double>::quiet_NaN());
    // Sums of products as mul_add (core/mul_add.hpp), in the formula's order of additions.
    const double p = mul_add(big_a_, u2, energy), delta = mul_add(a2_, u2, 1.0 - 2.0 * m * u);
    State dz;
    dz[0] = z[3];
    dz[1] = z[4];
    dz[2] = mul_add(angular_momentum, inv_s2, metric.spin * (p / delta - energy));
    dz[3] = u * mul_add(u * k_, mul_add(-2.0 * a2_, u, 3.0 * m), 2.0 * big_a_ * p - k_);
    dz[4] = sc.cos * sc.sin * (l2_ * inv_s2 * inv_s2 - a2e2_);
    if (slowed_near_axis_) dz *= sc.sin / (sc.sin + kSlowedNearAxis);  // time_scale(z), from the sine at hand
    return dz;
  }

  /// The Mino time from z to u = 0 along an outgoing leg (u' < 0; negative for a z beyond infinity, u < 0) in the
  /// radial potential cut after u^2, R~(u) ~ E^2 - K' u^2 with K' = K - 2 E A: asin(sqrt(K') u / |E|) / sqrt(K')
  /// (asinh for K' < 0). The first guess of trace/sky_continuation.hpp's iteration: unlike u / |u'| it stays on
  /// the ray's way out where u' is small (a ray near its periapsis), where R~'s higher terms are O(M u) smaller.
  GRTRACE_HD double mino_time_to_infinity(const State& z) const {
    const double k2 = k_ - 2.0 * energy * big_a_, x = z[0] / std::abs(energy);
    if (k2 > 0.0) {
      const double s = std::sqrt(k2);
      return std::asin(std::clamp(s * x, -1.0, 1.0)) / s;
    }
    if (k2 < 0.0) {
      const double s = std::sqrt(-k2);
      return std::asinh(s * x) / s;
    }
    return x;
  }

  GRTRACE_HD double radius(const State& z) const { return 1.0 / z[0]; }
  /// -u = -1/r: increasing in r and smooth through infinity (u = 0), which a step towards the sky may cross.
  GRTRACE_HD double radial_coordinate(const State& z) const { return -z[0]; }
  static GRTRACE_HD double radial_coordinate_at(double r) { return -1.0 / r; }

  /// (x, k) in Boyer-Lindquist coordinates, t = NaN (not followed).
  GRTRACE_HD GeodesicState geodesic_state(const State& z) const {
    const double u = z[0], r = 1.0 / z[0], u2 = u * u, a = metric.spin;
    const SinCos sc = sin_cos(z[1]);
    const double s2 = sc.sin * sc.sin, inv_sigma = 1.0 / (r * r + a2_ * sc.cos * sc.cos);
    const double l_over_s2 = through_axis_ ? 0.0 : angular_momentum / s2;
    const double p_over_delta = (energy + big_a_ * u2) / (1.0 - 2.0 * metric.mass * u + a2_ * u2);
    GeodesicState y;
    y << std::numeric_limits<double>::quiet_NaN(), r, z[1], z[2],
        ((r * r + a2_) * p_over_delta - a * (a * energy * s2 - angular_momentum)) * inv_sigma,
        -r * r * z[3] * inv_sigma, z[4] * inv_sigma,
        (a * (p_over_delta - energy) + l_over_s2) * inv_sigma;
    return y;
  }

  /// The larger of the relative residuals of u'^2 = R~(u) and theta'^2 = Theta(theta), each against the size of
  /// its terms (for Theta: Q, a^2 E^2 and L^2 / sin^2 theta, not their products with cos theta, which vanish on the
  /// equator, where an equatorial ray's Theta and theta' are both zero to round-off).
  GRTRACE_HD double constraint_violation(const State& z) const {
    const double u = z[0], u2 = u * u, p = energy + big_a_ * u2;
    const double delta = 1.0 - 2.0 * metric.mass * u + a2_ * u2;
    const double radial = std::abs(z[3] * z[3] - (p * p - k_ * u2 * delta)) / (z[3] * z[3] + p * p + std::abs(k_ * u2 * delta));
    const SinCos sc = sin_cos(z[1]);
    const double c2 = sc.cos * sc.cos, inv_s2 = through_axis_ ? 0.0 : 1.0 / (sc.sin * sc.sin);
    const double polar = std::abs(z[4] * z[4] - (carter + a2e2_ * c2 - l2_ * c2 * inv_s2)) /
                         (z[4] * z[4] + std::abs(carter) + a2e2_ + l2_ * inv_s2);
    const double v = std::max(radial, polar);
    return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
  }

  /// g(k, k) at z (the ray is null: 0 at the start).
  GRTRACE_HD double constraint_drift(const State& z) const {
    GeodesicState y = geodesic_state(z);
    y[0] = 0.0;  // the metric does not depend on t
    return inner_product(metric, y.head<4>(), y.tail<4>(), y.tail<4>());
  }

  /// d(Mino time) / d(system time) at z: 1, or sin theta / (sin theta + kSlowedNearAxis) for a ray slowed near the
  /// axis (see slowed_near_axis_): the factor operator() applies to dz/dlambda_M.
  GRTRACE_HD double time_scale(const State& z) const {
    if (!slowed_near_axis_) return 1.0;
    const double s = polar_sin_cos(z[1]).sin;
    return s / (s + kSlowedNearAxis);
  }

  /// d lambda / ds at z: the rate of the affine parameter lambda in the system's time s, Sigma = r^2 + a^2 cos^2
  /// theta (d lambda = Sigma d lambda_M) times time_scale(z). What a quantity integrated along the ray in lambda
  /// (a medium's light: trace/emission_system.hpp) is multiplied by to be integrated in s.
  GRTRACE_HD double affine_rate(const State& z) const {
    const double r = 1.0 / z[0];
    const SinCos sc = polar_sin_cos(z[1]);
    const double sigma = r * r + a2_ * sc.cos * sc.cos;
    return slowed_near_axis_ ? sigma * sc.sin / (sc.sin + kSlowedNearAxis) : sigma;  // times time_scale(z)
  }
  /// t is not followed (geodesic_state's t is NaN): what is integrated along the ray may not depend on it.
  static constexpr bool follows_time = false;

  /// The polar axis crossed: theta -> -theta (or 2 pi - theta), phi -> phi + pi, theta' -> -theta'.
  GRTRACE_HD bool wrap_chart(State& z) const { return wrap_polar_axis<1, 2, 4>(z); }
  /// pi/2 - theta: the side of the equatorial plane (trace/geodesic_system.hpp).
  GRTRACE_HD double equatorial_latitude(const State& z) const { return 0.5 * std::numbers::pi - z[1]; }

 private:
  /// The closest pass by the axis (sin theta_min) below which a ray is traced as the L = 0 ray through it: a pass
  /// that close needs steps near the floor of double precision in lambda (a ray with L = 1.6e-9, sin theta_min =
  /// 7e-11, ended as step_underflow); the direction it leaves in differs from the L = 0 ray's by about that angle.
  static constexpr double kThroughAxis = 1e-8;
  /// A start nearer the axis than this (sin theta) is where the L = 0 ray's start is moved onto that ray
  /// (start_through_axis); farther out the ray keeps its start, as L^2 / sin^2 theta is below 1e-8 of its polar
  /// speed there.
  static constexpr double kNearAxisStart = 1e-4;
  /// The closest pass by the axis (sin theta_min) below which a ray is slowed near the axis: 0.1, where L / sin^2
  /// theta reaches 100 times its value on the equator.
  static constexpr double kSlowedNearAxis = 0.1;
  bool through_axis_ = false;
  /// The system's time is tau, d tau = d lambda_M (sin theta + s0) / sin theta with s0 = kSlowedNearAxis, for a ray
  /// with L != 0 passing the axis closer than s0 (operator() multiplies dz/dlambda_M by time_scale). Near the axis
  /// the ray crosses the sphere on a nearly straight line, where in Mino time phi sweeps about pi within
  /// sin theta_min / |theta'| (phi' = L / sin^2 theta, a spike) and theta turns as sqrt(sin^2 theta_min + theta'^2
  /// lambda^2), a kink: a step across the pass that Fehlberg 7(8)'s four-stage error estimate accepted left the ray's
  /// direction wrong by 4e-3 rad (a camera 1e-6 rad from the axis, rtol 1e-9). In tau the distance from the axis
  /// goes as sin theta_min cosh(v tau / s0) and d phi / d tau ~ L / (s0 sin theta): both smooth on the scale of the
  /// pass, which the step control then resolves; away from the axis the two times differ by a factor of order one.
  /// (A factor sin^2 theta instead puts a pole in theta(tau) at the pass's ends, where vern6 lost accuracy.)
  bool slowed_near_axis_ = false;
  double axis_start_l_ = 0.0;  ///< L of a ray traced as the L = 0 ray from a start near the axis (0: none)

  /// Moves z0 of a ray that starts near the axis (sin theta < kNearAxisStart) with a pass closer than kThroughAxis
  /// onto the L = 0 ray parallel to it. Near the axis the sphere is a plane with polar coordinates (rho, phi),
  /// rho = theta (or pi - theta at the south pole); the ray crosses it on a straight line with velocity
  /// rho' e_rho + (L rho / sin^2 theta) e_phi in Mino time. The L = 0 ray is the line through the axis with that
  /// velocity; the start goes to the nearest point on it (a move of at most r sin theta_min: 1e-8 r) and its
  /// polar speed is sqrt(Theta) of the Carter constant Q + L^2 (the constructor), so the constraint holds at once.
  /// Without this a camera 1e-9 rad from the axis started every ray with a polar speed missing L^2 / sin^2 theta,
  /// a constraint violation of order one, and the guard ended them as non_finite.
  GRTRACE_HD void start_through_axis(State& z) const {
    const bool north = z[1] < std::numbers::pi / 2.0;
    const double rho = north ? z[1] : std::numbers::pi - z[1], rho_rate = north ? z[4] : -z[4];
    const double s = polar_sin_cos(z[1]).sin;
    const double across = s > 0.0 ? axis_start_l_ * rho / (s * s) : 0.0;
    const double cp = std::cos(z[2]), sp = std::sin(z[2]);
    const double vx = rho_rate * cp - across * sp, vy = rho_rate * sp + across * cp, speed = std::hypot(vx, vy);
    if (!(speed > 0.0)) return;
    const double along = rho * (cp * vx + sp * vy) / speed;  // the start's distance along the line from the axis
    const double rho_new = std::abs(along);
    const double theta_new = north ? rho_new : std::numbers::pi - rho_new;
    const double c = std::cos(theta_new);
    const double polar_speed = std::sqrt(std::max(0.0, carter + a2e2_ * c * c));
    const double rate = along >= 0.0 ? polar_speed : -polar_speed;  // away from the axis ahead of it, else towards
    z[1] = theta_new;
    z[2] = std::atan2(vy, vx) + (along >= 0.0 ? 0.0 : std::numbers::pi);
    z[4] = north ? rate : -rate;
  }
  double a2_ = 0.0, big_a_ = 0.0, k_ = 0.0, a2e2_ = 0.0, l2_ = 0.0;
  // Theta >= 0 on the ray means L^2 / sin^2 = Q + L^2 + a^2 E^2 cos^2 - theta'^2 <= Q + L^2 + a^2 E^2: the ray never
  // comes nearer the axis than its turning point. A trial stage far inside it (a step across a close pass by the
  // axis, where theta'' ~ L^2 / sin^3 theta explodes) is refused: beyond 4 x that bound (sin theta < half the
  // turning point's). Fehlberg 7(8)'s error estimate reads only stages 1, 11, 12 and 13, so it can accept such a
  // step (measured: theta = 2e8 after one step, then the constraint guard's non_finite).
  double forbidden_ = std::numeric_limits<double>::infinity();
};

}  // namespace grtrace
