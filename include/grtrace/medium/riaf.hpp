// grtrace/medium/riaf.hpp
// A radiatively inefficient accretion flow (RIAF): the hot, thick, optically thin-ish gas that the EHT images around
// M87* and Sgr A*, as an emitting medium (medium/emitting_medium.hpp) with physical units: its light is thermal
// synchrotron (medium/thermal_synchrotron.hpp), so a frame's intensity is in erg s^-1 cm^-2 Hz^-1 sr^-1 and its
// flux in janskys (core/physical_units.hpp).
//
// Takes:   a stationary axisymmetric metric in a spherical chart (Kerr in Boyer-Lindquist coordinates,
//          Schwarzschild), and RiafParameters: the hole's mass in solar masses, the accretion rate, the electron
//          temperature at r = M, the two power laws, the flow's thickness h, the plasma beta, the outer radius.
// Returns: at an event x = (t, r, theta, phi), with z = r cos(theta), rho = r sin(theta) and r in units of M
//          (the semi-analytic model of Broderick & Loeb 2006, ApJ 636 L109, in the form of Gold et al. 2020, ApJ 897
//          148, section 3):
//              n_e = n_0 r^-density_power exp(-z^2 / (2 h^2 rho^2))           (electrons cm^-3)
//              T_e = T_0 r^-temperature_power                                  (K)
//              B   = sqrt(8 pi n_e m_p c^2 / (6 beta r))                        (gauss: the gas's virial pressure,
//                                                                               n m_p c^2 / 6r, over beta)
//          the field toroidal (along d/dphi, made orthogonal to the gas's velocity), and j_nu, alpha_nu of thermal
//          synchrotron at the angle between the field and the ray in the gas's frame, per M (cgs times r_g).
//          The density's scale n_0 follows from the accretion rate: the mass flux of the flow's angular profile
//          through the sphere r = 2M at the radial speed v = inflow_speed c there (default 0.1: a RIAF falls at
//          about alpha times the free-fall speed, alpha ~ 0.1 its viscosity parameter, Narayan & Yi 1995; the free
//          fall from rest at infinity reaches c at 2M), Mdot = m_p n_e(2M, equator) v (2 r_g)^2 S(h), S(h) the
//          integral of exp(-cot^2 theta / 2h^2) over the sphere. Since n_e falls as r^-1.1, more slowly than
//          continuity would have it, the flow loses mass outwards, as RIAFs with winds do (Yuan, Quataert & Narayan
//          2003); Mdot is the rate at the hole. With the defaults, 230 GHz, a = 0.9 and 17 degrees, M87* at
//          5e-4 solar masses a year shines 0.3 Jy and Sgr A* at 1e-8 2.3 Jy: the order the EHT measures (0.5 and
//          2.4 Jy), at accretion rates within the ranges its models give.
//          The gas's velocity (Gold et al. 2020): on circular orbits of the equator's Keplerian angular velocity
//          Omega(r) outside the innermost stable circular orbit (ISCO), plunging inside it with the ISCO's energy
//          and angular momentum (u_t, u_phi kept, u_theta = 0, u_r from g(u, u) = 1); where neither is timelike,
//          the zero angular momentum observer.
// Assumes: the hole's sense of rotation is +phi (the gas's orbits are prograde); the metric is reflection-symmetric
//          about the equator. The emission ends at outer (a boundary the tracer stops its steps on).
#pragma once

#include "grtrace/core/golden_section.hpp"
#include "grtrace/core/host_device.hpp"
#include "grtrace/core/physical_units.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/core/uniform_table.hpp"
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/medium/thermal_synchrotron.hpp"
#include "grtrace/metric/circular_orbits.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grtrace {

/// The parameters of RiafFlow (see the top of riaf.hpp); defaults: Broderick & Loeb's shape around M87*.
/// RiafParameters::m87() and sgr_a() give each source's mass and an accretion rate that shines as it does.
struct RiafParameters {
  double mass_solar = 6.5e9;        ///< M in solar masses: lengths in cm, the density from the accretion rate
  double accretion_rate = 5e-4;     ///< Mdot at the hole, solar masses per year
  double temperature = 2e11;        ///< T_e at r = M, kelvin
  double inflow_speed = 0.1;        ///< the radial speed at r = 2M that carries Mdot, in units of c
  double density_power = 1.1;       ///< n_e ~ r^-density_power
  double temperature_power = 0.84;  ///< T_e ~ r^-temperature_power
  double thickness = 1.0;           ///< h: n_e ~ exp(-z^2 / (2 h^2 rho^2))
  double beta = 10.0;               ///< the gas's virial pressure over the field's
  double outer = 1000.0;            ///< no emission beyond this radius (M)

  static RiafParameters m87() {
    RiafParameters p;
    p.mass_solar = SourceScale::m87().mass_solar;
    p.accretion_rate = 5e-4;
    return p;
  }
  static RiafParameters sgr_a() {
    RiafParameters p;
    p.mass_solar = SourceScale::sgr_a().mass_solar;
    p.accretion_rate = 1e-8;
    return p;
  }

  /// The first parameter out of range, named as a user writes it, or empty.
  std::string problem() const {
    if (!(mass_solar > 0.0 && std::isfinite(mass_solar))) return "mass_solar must be finite and > 0";
    if (!(accretion_rate >= 0.0 && std::isfinite(accretion_rate))) return "accretion_rate must be finite and >= 0";
    if (!(temperature > 0.0 && std::isfinite(temperature))) return "temperature must be finite and > 0";
    if (!(inflow_speed > 0.0 && inflow_speed <= 1.0)) return "inflow_speed must be in (0, 1] (a fraction of c)";
    if (!(std::isfinite(density_power) && std::isfinite(temperature_power))) return "the power laws must be finite";
    if (!(thickness > 0.0 && std::isfinite(thickness))) return "thickness must be finite and > 0";
    if (!(beta > 0.0 && std::isfinite(beta))) return "beta must be finite and > 0";
    if (!(outer > 2.0 && std::isfinite(outer))) return "outer must be finite and > 2 M";
    return {};
  }
};

template <MetricPolicy Metric>
class RiafFlow {
  static_assert(Metric::chart == Chart::spherical,
                "RiafFlow: the flow is stated in a spherical chart (t, r, theta, phi) of a stationary axisymmetric "
                "metric (Kerr in Boyer-Lindquist coordinates, Schwarzschild)");

 public:
  static constexpr std::string_view kind = "riaf";
  static constexpr bool stationary = true;
  static constexpr bool axisymmetric = true;
  static constexpr bool equator_mirror_symmetric = true;

  /// std::invalid_argument naming the parameter when one is out of range, or when the metric has no stable
  /// circular orbit (no ISCO found between its photon orbit and 1e4 M).
  RiafFlow(const Metric& metric, const RiafParameters& p) : metric_(metric), p_(p) {
    if (const std::string problem = p.problem(); !problem.empty()) throw std::invalid_argument("RiafFlow: " + problem);
    r_g_ = p.mass_solar * cgs::solar_gravitational_radius;
    // n_e at r = 2M on the equator from Mdot (see the top of this file); n_0 is its value continued to r = M.
    const double mdot = p.accretion_rate * cgs::solar_mass / cgs::year;
    const double v = p.inflow_speed * cgs::speed_of_light;
    const double n_2 = mdot / (cgs::proton_mass * v * 4.0 * r_g_ * r_g_ * solid_angle_factor(p.thickness));
    n_0_ = n_2 * std::pow(2.0, p.density_power);
    find_isco();
  }

  const RiafParameters& parameters() const { return p_; }
  double isco() const { return r_isco_; }
  /// n_e (cm^-3), T_e as Theta_e = k T_e / m_e c^2, and B (gauss) at x.
  double density(const Vec4& x) const {
    const double r = x[1], c = std::cos(x[2]), s = std::sin(x[2]);
    const double cot2 = s > 0.0 ? c * c / (s * s) : std::numeric_limits<double>::infinity();
    return n_0_ * std::pow(r, -p_.density_power) * std::exp(-cot2 / (2.0 * p_.thickness * p_.thickness));
  }
  double electron_theta(const Vec4& x) const {
    const double me_c2 = cgs::electron_mass * cgs::speed_of_light * cgs::speed_of_light;
    return p_.temperature * std::pow(x[1], -p_.temperature_power) * cgs::boltzmann / me_c2;
  }
  double field_gauss(double n_e, double r) const {
    const double c = cgs::speed_of_light;
    return std::sqrt(8.0 * std::numbers::pi * n_e * cgs::proton_mass * c * c / (6.0 * p_.beta * r));
  }

  double outer_radius() const { return p_.outer; }
  template <MetricPolicy M>
  double boundary(const M&, const Vec4& x) const {
    return x[1] - p_.outer;
  }

  /// j_nu and alpha_nu per M (cgs per cm times r_g) for the ray k leaving the gas u at x, nu in Hz in its frame.
  template <MetricPolicy M>
  MediumCoefficients coefficients(const M& metric, const Vec4& x, const Vec4& k, const Vec4& u, double nu) const {
    return coefficients(metric, x, k, u, std::array<double, 1>{nu})[0];
  }

  /// The same at several frequencies: the gas's density, temperature, field and angle to the ray computed once.
  template <MetricPolicy M, std::size_t N>
  std::array<MediumCoefficients, N> coefficients(const M&, const Vec4& x, const Vec4& k, const Vec4& u,
                                                 const std::array<double, N>& nu) const {
    std::array<MediumCoefficients, N> out{};
    const double n_e = density(x);
    if (!(n_e > 0.0)) return out;
    const double theta_e = electron_theta(x);
    if (!(theta_e >= min_synchrotron_temperature)) return out;
    const Mat4 g = metric_.metric(x);
    // The field along d/dphi, made orthogonal to u; the ray's direction n in the gas's frame: k = E (u + n).
    Vec4 b = Vec4::Zero();
    b[3] = 1.0;
    b -= (u.dot(g * b)) * u;
    const double b2 = -b.dot(g * b);
    const double e = u.dot(g * k);
    double sin_theta = 1.0;
    if (b2 > 0.0 && e != 0.0) {
      const double cos_theta = -(k.dot(g * b)) / (e * std::sqrt(b2));
      sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    }
    const ThermalSynchrotronPlasma plasma(n_e, theta_e, field_gauss(n_e, x[1]), sin_theta);
    for (std::size_t i = 0; i < N; ++i) {
      const MediumCoefficients c = plasma.at(nu[i]);
      out[i] = {c.emission * r_g_, c.absorption * r_g_};
    }
    return out;
  }

  /// The gas's 4-velocity at x (see the top of this file).
  template <MetricPolicy M>
  Vec4 fluid_velocity(const M&, const Vec4& x) const {
    const Mat4 g = metric_.metric(x);
    const double r = x[1];
    if (r >= r_isco_) {
      const double omega = r <= table_end_ ? keplerian_(std::log(r)) : keplerian_omega(r);
      const double norm = g(0, 0) + 2.0 * omega * g(0, 3) + omega * omega * g(3, 3);
      if (norm > 0.0) return Vec4(1.0, 0.0, 0.0, omega) / std::sqrt(norm);
    } else {
      const Mat4 gi = g.inverse();
      const double k = gi(0, 0) * u_t_ * u_t_ + 2.0 * gi(0, 3) * u_t_ * u_phi_ + gi(3, 3) * u_phi_ * u_phi_;
      // g^rr < 0 outside the horizon: u_r^2 = (1 - K) / g^rr; u_r > 0 makes u^r = g^rr u_r < 0 (inwards).
      const double u_r = std::sqrt(std::max(0.0, (1.0 - k) / gi(1, 1)));
      Vec4 lowered(u_t_, u_r, 0.0, u_phi_);
      Vec4 u = gi * lowered;
      const double norm = u.dot(g * u);
      if (norm > 0.0 && u[0] > 0.0) return u / std::sqrt(norm);
    }
    const double omega = -g(0, 3) / g(3, 3);  // the zero angular momentum observer
    return Vec4(1.0, 0.0, 0.0, omega) / std::sqrt(g(0, 0) + omega * g(0, 3));
  }

  /// S(h) = integral over the sphere of exp(-cot^2 theta / (2 h^2)) (midpoint rule in cos theta on 4000 nodes: the
  /// integrand is smooth and vanishes with all its derivatives at the poles).
  static double solid_angle_factor(double h) {
    constexpr int n = 4000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double mu = -1.0 + (i + 0.5) * 2.0 / n;
      sum += std::exp(-mu * mu / ((1.0 - mu * mu) * 2.0 * h * h));
    }
    return 2.0 * std::numbers::pi * sum * 2.0 / n;
  }

 private:
  /// Omega of the prograde equatorial circular orbit at r (NaN where there is none).
  double keplerian_omega(double r) const {
    const auto u = circular_orbit_velocity(metric_, r, +1);
    return u ? (*u)[3] / (*u)[0] : std::numeric_limits<double>::quiet_NaN();
  }

  /// The energy u_t (signature +, -, -, -) of the prograde circular orbit at r, or NaN where there is none.
  double orbit_energy(double r) const {
    const auto u = circular_orbit_velocity(metric_, r, +1);
    if (!u) return std::numeric_limits<double>::quiet_NaN();
    return (metric_.metric(Vec4(0.0, r, std::numbers::pi / 2.0, 0.0)) * *u)[0];
  }

  /// The ISCO: the minimum of the circular orbits' energy (bracketed walking in from 1e4 M, then golden section).
  void find_isco() {
    double hi = 1e4, mid = hi / 1.05, e_mid = orbit_energy(mid);
    double lo = mid / 1.05, e_lo = orbit_energy(lo);
    while (e_lo < e_mid) {
      hi = mid;
      mid = lo;
      e_mid = e_lo;
      lo = mid / 1.05;
      e_lo = orbit_energy(lo);
      if (!(lo > metric_.horizon_radius())) break;
    }
    if (!(e_lo >= e_mid) && !std::isnan(e_lo))
      throw std::invalid_argument("RiafFlow: the metric has no innermost stable circular orbit");
    r_isco_ = golden_section_minimum([&](double r) { return orbit_energy(r); }, lo, hi, {1e-12, 0.0}).x;
    const auto u = circular_orbit_velocity(metric_, r_isco_, +1);
    if (!u) throw std::invalid_argument("RiafFlow: no circular orbit at the ISCO found");
    const Vec4 lowered = metric_.metric(Vec4(0.0, r_isco_, std::numbers::pi / 2.0, 0.0)) * *u;
    u_t_ = lowered[0];
    u_phi_ = lowered[3];
    // Omega(r) from the ISCO to the outer radius, on ln r: the circular orbit from the Christoffel symbols costs
    // 0.75 us, the table 10 ns, and the gas's velocity is asked at every stage (core/uniform_table.hpp: 2e-12
    // relative, Omega ~ e^(-3 ln r / 2)).
    if (p_.outer > 1.01 * r_isco_) {
      keplerian_ = UniformTable(std::log(r_isco_), std::log(p_.outer), 4097,
                                [this](double s) { return keplerian_omega(std::exp(s)); });
      table_end_ = p_.outer;
    }
  }

  Metric metric_;
  RiafParameters p_;
  double r_g_ = 0.0, n_0_ = 0.0;
  double r_isco_ = 6.0, u_t_ = 1.0, u_phi_ = 0.0;
  UniformTable keplerian_;  ///< Omega(r) of the prograde circular orbits on ln r in [ln r_isco, ln table_end_]
  double table_end_ = 0.0;
};

}  // namespace grtrace
