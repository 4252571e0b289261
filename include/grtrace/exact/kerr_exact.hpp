// grtrace/exact/kerr_exact.hpp
// Closed forms (and one quadrature) for Kerr, the judges for the Kerr tests. G = c = 1, mass M, spin a (|a| < M).
//
// Takes:   the spin a (signed: a < 0 rotates towards -phi), the mass M (default 1), and an orbit sense.
//          Every function checks M > 0, |a| < M and finite arguments, and throws std::invalid_argument with a
//          message saying what to change.
// Returns: r_isco (Bardeen, Press & Teukolsky, ApJ 178, 347 (1972), eq. 2.21), equatorial circular photon orbit
//          radii (Bardeen 1973), Keplerian Omega and u^t of circular equatorial orbits (BPT eq. 2.16 and 2.12),
//          the redshift of light from such an emitter g = 1 / (u^t (1 - Omega xi)), the spherical photon orbit
//          constants xi(r) = L_z/E, eta(r) = Q/E^2 and the critical curve (alpha, beta) seen by a distant
//          observer at inclination i (Bardeen, "Timelike and null geodesics in the Kerr metric", Les Houches
//          1973), and the total deflection of an equatorial light ray (Iyer & Hansen, Phys. Rev. D 80, 124023
//          (2009); written out below in our notation), by quadrature.
// Orbit sense: Orbit::prograde = co-rotating with the hole. Signed results (Omega, xi) are with respect to +phi:
// for a < 0 a prograde orbit has Omega < 0. With the sense s = +-1 of the motion in phi, every formula is the
// M = 1 form of shared/reference/kerr.md with a -> s a, e.g. Omega = s M^1/2 / (r^3/2 + s a M^1/2).
//
// Equatorial deflection. A photon in the plane theta = pi/2 with E = 1 and L_z = b (b > 0: it moves towards +phi)
// obeys, with u = 1/r (derived from the Carter equations with Q = 0; a = 0 gives Darwin's equation):
//   (du/dphi)^2 = B(u) (1 - 2Mu + a^2 u^2)^2 / (b - 2M (b - a) u)^2,   B(u) = 1 + (a^2 - b^2) u^2 + 2M (b - a)^2 u^3,
// so the angle swept from infinity to the turning point u0 (the smallest positive root of B) is
//   Phi = int_0^u0 (b - 2M(b - a)u) / ((1 - 2Mu + a^2u^2) sqrt(B(u))) du,
// and the total deflection is 2 |Phi| - pi. B(u) = (u0 - u) C(u) with C(u) = -[c3 (u^2 + u u0 + u0^2) + c2 (u + u0)]
// (c2 = a^2 - b^2, c3 = 2M(b - a)^2) exactly, and u = u0 (1 - t^2) turns the integral into the smooth
//   Phi = int_0^1 2 sqrt(u0) (b - 2M(b - a)u) / ((1 - 2Mu + a^2 u^2) sqrt(C(u))) dt,
// integrated by composite Gauss-Legendre (no singular endpoint left; near the critical b, C(u0) -> 0 and more
// panels are needed: the result diverges logarithmically there).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace grtrace::exact {

enum class Orbit { prograde, retrograde };

namespace kerr_detail {

inline void check_hole(double spin, double mass, const char* who) {
  if (!std::isfinite(mass) || !(mass > 0.0))
    throw std::invalid_argument(std::string(who) + ": mass must be finite and > 0 (got " + std::to_string(mass) + ")");
  if (!std::isfinite(spin) || !(std::abs(spin) < mass))
    throw std::invalid_argument(std::string(who) + ": spin must be finite with |a| < M (got a = " +
                                std::to_string(spin) + ", M = " + std::to_string(mass) + "); pass a smaller |a|");
}

inline void check_finite(double v, const char* who, const char* what) {
  if (!std::isfinite(v)) throw std::invalid_argument(std::string(who) + ": " + what + " must be finite");
}

/// The sense (+1 or -1) of an orbit's motion in phi: prograde follows the hole's rotation (+phi when a = 0).
inline double sense(double spin, Orbit orbit) {
  const double hole = spin < 0.0 ? -1.0 : 1.0;
  return orbit == Orbit::prograde ? hole : -hole;
}

/// 10-point Gauss-Legendre nodes and weights on [-1, 1].
inline constexpr std::array<double, 5> kGLx = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244,
                                               0.8650633666889845, 0.9739065285171717};
inline constexpr std::array<double, 5> kGLw = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820,
                                               0.1494513491505806, 0.0666713443086881};

template <class F>
double gauss_legendre(const F& f, double lo, double hi, int panels) {
  const double h = (hi - lo) / panels;
  double sum = 0.0;
  for (int p = 0; p < panels; ++p) {
    const double mid = lo + (p + 0.5) * h;
    for (std::size_t i = 0; i < kGLx.size(); ++i)
      sum += kGLw[i] * (f(mid - 0.5 * h * kGLx[i]) + f(mid + 0.5 * h * kGLx[i]));
  }
  return 0.5 * h * sum;
}

}  // namespace kerr_detail

/// Outer and inner horizons r_+- = M +- sqrt(M^2 - a^2).
inline double outer_horizon(double spin, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "outer_horizon");
  return mass + std::sqrt(mass * mass - spin * spin);
}
inline double inner_horizon(double spin, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "inner_horizon");
  return mass - std::sqrt(mass * mass - spin * spin);
}

/// Innermost stable circular orbit (BPT 1972): r = M (3 + Z2 -+ sqrt((3 - Z1)(3 + Z1 + 2 Z2))), upper = prograde.
inline double isco_radius(double spin, Orbit orbit, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "isco_radius");
  const double chi = std::abs(spin) / mass;
  const double z1 = 1.0 + std::cbrt(1.0 - chi * chi) * (std::cbrt(1.0 + chi) + std::cbrt(1.0 - chi));
  const double z2 = std::sqrt(3.0 * chi * chi + z1 * z1);
  const double root = std::sqrt((3.0 - z1) * (3.0 + z1 + 2.0 * z2));
  // For a = 0 both senses are the same orbit (6M); the sign convention only matters for a != 0.
  const bool co = (orbit == Orbit::prograde);
  return mass * (3.0 + z2 + (co ? -root : root));
}

/// Circular equatorial photon orbit r_ph = 2M (1 + cos((2/3) arccos(-+ |a|/M))), upper = prograde (Bardeen 1973).
inline double photon_orbit_radius(double spin, Orbit orbit, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "photon_orbit_radius");
  const double chi = std::abs(spin) / mass;
  const double c = orbit == Orbit::prograde ? -chi : chi;
  return 2.0 * mass * (1.0 + std::cos(2.0 / 3.0 * std::acos(c)));
}

/// Angular velocity d phi/dt of a circular equatorial geodesic at r, Omega = s sqrt(M) / (r^3/2 + s a sqrt(M)).
inline double keplerian_omega(double r, double spin, Orbit orbit, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "keplerian_omega");
  kerr_detail::check_finite(r, "keplerian_omega", "r");
  const double s = kerr_detail::sense(spin, orbit), sm = std::sqrt(mass);
  return s * sm / (r * std::sqrt(r) + s * spin * sm);
}

/// u^t = (r^3/2 + s a sqrt M) / (r^3/4 sqrt(r^3/2 - 3 M r^1/2 + 2 s a sqrt M)) of that orbit (BPT eq. 2.12 / 2.16).
/// Throws when no timelike circular orbit exists at r (inside the photon orbit).
inline double keplerian_ut(double r, double spin, Orbit orbit, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "keplerian_ut");
  kerr_detail::check_finite(r, "keplerian_ut", "r");
  const double s = kerr_detail::sense(spin, orbit), sm = std::sqrt(mass), sr = std::sqrt(r);
  const double rad = r * sr - 3.0 * mass * sr + 2.0 * s * spin * sm;
  if (!(rad > 0.0) || !(r > 0.0))
    throw std::invalid_argument("keplerian_ut: no timelike circular orbit at r = " + std::to_string(r) +
                                " (it must lie outside the photon orbit " +
                                std::to_string(photon_orbit_radius(spin, orbit, mass)) + ")");
  return (r * sr + s * spin * sm) / (std::sqrt(sr) * sr * std::sqrt(rad));
}

/// g = f_obs / f_em = 1 / (u^t (1 - Omega xi)) for light with xi = L_z/E emitted by a Keplerian emitter at r and
/// received at infinity.
inline double keplerian_redshift(double r, double xi, double spin, Orbit orbit, double mass = 1.0) {
  kerr_detail::check_finite(xi, "keplerian_redshift", "xi");
  return 1.0 / (keplerian_ut(r, spin, orbit, mass) * (1.0 - keplerian_omega(r, spin, orbit, mass) * xi));
}

/// Spherical photon orbit constants at radius r (Bardeen 1973):
///   xi = L_z/E = [r^2 (3M - r) - a^2 (r + M)] / (a (r - M)),  eta = Q/E^2 = r^3 [4 a^2 M - r (r - 3M)^2] / (a^2 (r -
///   M)^2)
/// Needs a != 0 (for a = 0 every spherical photon orbit is at 3M with xi^2 + eta = 27 M^2).
inline std::pair<double, double> spherical_photon_orbit(double r, double spin, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "spherical_photon_orbit");
  kerr_detail::check_finite(r, "spherical_photon_orbit", "r");
  if (spin == 0.0)
    throw std::invalid_argument("spherical_photon_orbit: needs a != 0 (for a = 0 use r = 3M, xi^2 + eta = 27 M^2)");
  const double a = spin, m = mass, rm = r - m, r3 = r - 3.0 * m;
  const double xi = (r * r * (3.0 * m - r) - a * a * (r + m)) / (a * rm);
  const double eta = r * r * r * (4.0 * a * a * m - r * r3 * r3) / (a * a * rm * rm);
  return {xi, eta};
}

/// Takes the spin, a sense s (+1: L_z = b > 0, moving towards +phi; -1: the other way) and the mass; returns the
/// signed critical impact parameter b_c of equatorial photons moving in that sense (the xi of the circular photon
/// orbit of that sense; +-3 sqrt(3) M for a = 0). Photons with b beyond it (s b > s b_c) escape, the others are
/// captured; a = 0.9: b_c = +2.85 M (prograde), -6.83 M (retrograde).
inline double equatorial_critical_impact(double spin, double s, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "equatorial_critical_impact");
  if (spin == 0.0) return (s < 0.0 ? -1.0 : 1.0) * 3.0 * std::sqrt(3.0) * mass;
  const Orbit orbit = s * spin > 0.0 ? Orbit::prograde : Orbit::retrograde;
  return spherical_photon_orbit(photon_orbit_radius(spin, orbit, mass), spin, mass).first;
}

/// The Lyapunov exponent gamma of the spherical photon orbit at radius r: a ray that starts near the orbit departs
/// from it by e^gamma per half orbit (per crossing of the equator), so the (n+1)-th image of a source is e^-gamma
/// times as wide as the n-th where they lie near the critical curve point of that orbit (Johnson et al., Sci. Adv. 6,
/// eaaz1310 (2020), eq. 7; Gralla & Lupsasca, Phys. Rev. D 101, 044031 (2020)):
///   gamma = 4 r sqrt(chi) K(m) / sqrt(A),  chi = 1 - M Delta(r) / (r (r - M)^2),  A = -a^2 u- ,  m = u+ / u- <= 0,
/// with u+- = D +- sqrt(D^2 + eta / a^2), D = (1 - (eta + xi^2) / a^2) / 2 the roots of the polar potential of the
/// orbit's xi, eta (spherical_photon_orbit) and K the complete elliptic integral of the first kind (parameter m).
/// A and m are written without the 1 / a^2 that cancels (A = sqrt((a^2 D)^2 + a^2 eta) - a^2 D, m = -a^2 eta / A^2),
/// so a -> 0 is smooth: gamma = pi at r = 3M (A = 27 M^2, m = 0, chi = 3/4). Takes r in [r_ph,pro, r_ph,retro] (for
/// a = 0: r = 3M); throws std::invalid_argument outside.
inline double photon_orbit_lyapunov(double r, double spin, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "photon_orbit_lyapunov");
  kerr_detail::check_finite(r, "photon_orbit_lyapunov", "r");
  const double r_lo = photon_orbit_radius(spin, Orbit::prograde, mass);
  const double r_hi = photon_orbit_radius(spin, Orbit::retrograde, mass);
  const double slack = 1e-9 * mass;
  if (!(r >= std::min(r_lo, r_hi) - slack && r <= std::max(r_lo, r_hi) + slack))
    throw std::invalid_argument("photon_orbit_lyapunov: r = " + std::to_string(r) +
                                " is not a spherical photon orbit radius; give r in [" + std::to_string(r_lo) + ", " +
                                std::to_string(r_hi) + "] M");
  const double a2 = spin * spin;
  double eta = 27.0 * mass * mass, xi = 0.0;  // a = 0: xi^2 + eta = 27 M^2 (any split: only the sum enters)
  if (spin != 0.0) std::tie(xi, eta) = spherical_photon_orbit(r, spin, mass);
  eta = std::max(0.0, eta);  // the ends of the range, where eta = 0 up to rounding
  const double a2d = 0.5 * (a2 - eta - xi * xi);
  const double big_a = std::sqrt(a2d * a2d + a2 * eta) - a2d;
  const double m = -a2 * eta / (big_a * big_a);
  // K(m) = pi / (2 AGM(1, sqrt(1 - m))), for any m < 1
  double x = 1.0, y = std::sqrt(1.0 - m);
  for (int it = 0; it < 64 && std::abs(x - y) > 1e-16 * x; ++it) {
    const double xn = 0.5 * (x + y);
    y = std::sqrt(x * y);
    x = xn;
  }
  const double k = std::numbers::pi / (x + y);
  const double delta = r * r - 2.0 * mass * r + a2, rm = r - mass;
  const double chi = 1.0 - mass * delta / (r * rm * rm);
  return 4.0 * r * std::sqrt(chi) * k / std::sqrt(big_a);
}

struct CelestialPoint {
  double alpha, beta;
  double r;  ///< the spherical photon orbit this point of the curve belongs to (3M for a = 0)
};

/// The critical curve (edge of the shadow) seen by a distant observer at inclination i in (0, pi) from the spin
/// axis: alpha = -xi / sin i, beta = +- sqrt(eta + a^2 cos^2 i - xi^2 cot^2 i), over the spherical photon
/// orbits r in [r_ph,pro, r_ph,retro] where beta is real. `samples` radii; returns both signs of beta.
/// For a = 0 the circle of radius 3 sqrt(3) M.
inline std::vector<CelestialPoint> critical_curve(double spin, double inclination, int samples = 400,
                                                  double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "critical_curve");
  if (!std::isfinite(inclination) || !(inclination > 0.0) || !(inclination < std::numbers::pi))
    throw std::invalid_argument("critical_curve: inclination must be in (0, pi) radians");
  if (samples < 2) throw std::invalid_argument("critical_curve: samples must be >= 2");
  std::vector<CelestialPoint> out;
  if (spin == 0.0) {
    const double rc = 3.0 * std::sqrt(3.0) * mass;
    for (int i = 0; i < samples; ++i) {
      const double p = 2.0 * std::numbers::pi * i / samples;
      out.push_back({rc * std::cos(p), rc * std::sin(p), 3.0 * mass});
    }
    return out;
  }
  const double r_lo = photon_orbit_radius(spin, Orbit::prograde, mass);
  const double r_hi = photon_orbit_radius(spin, Orbit::retrograde, mass);
  const double si = std::sin(inclination), ci = std::cos(inclination), cot = ci / si;
  auto beta2 = [&](double r) {
    const auto [xi, eta] = spherical_photon_orbit(r, spin, mass);
    return eta + spin * spin * ci * ci - xi * xi * cot * cot;
  };
  // beta^2 >= 0 on one interval [r1, r2] inside [r_lo, r_hi]; find its ends by bisection from the radius
  // where beta^2 is largest on a coarse grid (at i = pi/2 the ends are r_lo and r_hi themselves).
  double r_best = 0.5 * (r_lo + r_hi), b_best = -std::numeric_limits<double>::infinity();
  for (int i = 0; i <= 200; ++i) {
    const double r = r_lo + (r_hi - r_lo) * i / 200.0;
    if (const double b = beta2(r); b > b_best) {
      b_best = b;
      r_best = r;
    }
  }
  auto edge = [&](double inside, double outside) {
    if (beta2(outside) >= 0.0) return outside;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (inside + outside);
      (beta2(mid) >= 0.0 ? inside : outside) = mid;
    }
    return inside;
  };
  const double r1 = edge(r_best, r_lo), r2 = edge(r_best, r_hi);
  for (int i = 0; i < samples; ++i) {
    // Cosine spacing crowds the samples at the ends, where beta changes fastest.
    const double r = r1 + (r2 - r1) * 0.5 * (1.0 - std::cos(std::numbers::pi * i / (samples - 1)));
    const auto [xi, eta] = spherical_photon_orbit(r, spin, mass);
    const double b = std::sqrt(std::max(0.0, beta2(r)));
    out.push_back({-xi / si, b, r});
    out.push_back({-xi / si, -b, r});
  }
  return out;
}

/// Radial potential of a null geodesic with E = 1, L_z = xi, Q = eta (Carter): R(r) = (r^2 + a^2 - a xi)^2 -
/// Delta (eta + (xi - a)^2), with Sigma dr/dlambda = +- sqrt(R). Its double roots are the spherical photon orbits.
inline double radial_potential(double r, double xi, double eta, double spin, double mass = 1.0) {
  const double p = r * r + spin * spin - spin * xi, delta = r * r - 2.0 * mass * r + spin * spin;
  return p * p - delta * (eta + (xi - spin) * (xi - spin));
}

/// Turning point of an equatorial photon with E = 1, L_z = b: u0 = 1/r0, the smallest positive root of
/// B(u) = 1 + (a^2 - b^2) u^2 + 2M (b - a)^2 u^3. Throws when there is none (the photon is captured).
inline double equatorial_turning_point_u(double b, double spin, double mass = 1.0) {
  kerr_detail::check_hole(spin, mass, "equatorial_turning_point_u");
  kerr_detail::check_finite(b, "equatorial_turning_point_u", "b");
  const double c2 = spin * spin - b * b, c3 = 2.0 * mass * (b - spin) * (b - spin);
  auto B = [&](double u) { return 1.0 + u * u * (c2 + c3 * u); };
  // B falls from 1 to its minimum at u_m = -2 c2 / (3 c3) (needs c2 < 0); a root before it is the turning point.
  if (!(c2 < 0.0) || !(c3 > 0.0) || !(B(-2.0 * c2 / (3.0 * c3)) < 0.0))
    throw std::invalid_argument("equatorial deflection: b = " + std::to_string(b) +
                                " has no turning point (the photon is captured); use a larger |b|");
  double lo = 0.0, hi = -2.0 * c2 / (3.0 * c3);
  for (int it = 0; it < 200 && hi - lo > 1e-17 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (B(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Signed angle swept by the equatorial photon (E = 1, L_z = b) between u = 1/r = 0 and u (no turning point in
/// between; u <= u0): int_0^u (b - 2M(b - a)v) / ((1 - 2Mv + a^2 v^2) sqrt(B(v))) dv. Plain quadrature: for the
/// leg up to the turning point use equatorial_phi_to_turning_point.
inline double equatorial_phi_from_infinity(double b, double u, double spin, double mass = 1.0, int panels = 64) {
  kerr_detail::check_hole(spin, mass, "equatorial_phi_from_infinity");
  kerr_detail::check_finite(b, "equatorial_phi_from_infinity", "b");
  const double c2 = spin * spin - b * b, c3 = 2.0 * mass * (b - spin) * (b - spin);
  auto f = [&](double v) {
    return (b - 2.0 * mass * (b - spin) * v) /
           ((1.0 - 2.0 * mass * v + spin * spin * v * v) * std::sqrt(1.0 + v * v * (c2 + c3 * v)));
  };
  return kerr_detail::gauss_legendre(f, 0.0, u, panels);
}

/// Signed angle from infinity to the turning point, with u = u0 (1 - t^2) removing the square-root endpoint.
inline double equatorial_phi_to_turning_point(double b, double spin, double mass = 1.0, int panels = 64) {
  const double u0 = equatorial_turning_point_u(b, spin, mass);
  const double c2 = spin * spin - b * b, c3 = 2.0 * mass * (b - spin) * (b - spin);
  auto f = [&](double t) {
    const double u = u0 * (1.0 - t * t);
    const double c = -(c3 * (u * u + u * u0 + u0 * u0) + c2 * (u + u0));
    return 2.0 * std::sqrt(u0) * (b - 2.0 * mass * (b - spin) * u) /
           ((1.0 - 2.0 * mass * u + spin * spin * u * u) * std::sqrt(c));
  };
  return kerr_detail::gauss_legendre(f, 0.0, 1.0, panels);
}

/// Total deflection 2 |Phi| - pi of an equatorial light ray from infinity to infinity (Iyer & Hansen 2009).
/// b > 0 moves towards +phi: prograde for a > 0. |b| must exceed the critical impact parameter of that sense.
inline double equatorial_deflection(double b, double spin, double mass = 1.0, int panels = 64) {
  return 2.0 * std::abs(equatorial_phi_to_turning_point(b, spin, mass, panels)) - std::numbers::pi;
}

}  // namespace grtrace::exact
