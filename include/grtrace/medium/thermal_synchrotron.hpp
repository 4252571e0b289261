// grtrace/medium/thermal_synchrotron.hpp
// The emission and absorption of electrons with a relativistic thermal (Maxwell-Juttner) distribution gyrating in a
// magnetic field: the light of the hot, thin plasma around M87* and Sgr A* at millimetre wavelengths.
//
// Takes:   the frequency nu (Hz) in the plasma's frame, the electron number density n_e (cm^-3), the dimensionless
//          electron temperature Theta_e = k T_e / (m_e c^2), the field strength B (gauss), and sin(theta) of the
//          angle between the field and the direction the light leaves in (the plasma's frame).
// Returns: j_nu (erg s^-1 cm^-3 Hz^-1 sr^-1) and alpha_nu (cm^-1), cgs.
// Method:  j_nu is the fit of Leung, Gammie & Noble 2011 (ApJ 737, 21, eq. 31), to the exact emissivity summed over
//          the harmonics:
//              j_nu = n_e sqrt(2) pi e^2 nu_s / (3 K_2(1 / Theta_e) c) (X^(1/2) + 2^(11/12) X^(1/6))^2 exp(-X^(1/3)),
//              X = nu / nu_s,  nu_s = (2/9) nu_c Theta_e^2 sin(theta),  nu_c = e B / (2 pi m_e c);
//          within 2.3 % of the ultrarelativistic emissivity (the synchrotron function F(x) integrated over the
//          distribution) for Theta_e >= 3 and 1 <= X <= 1e4 (tests/medium_riaf_test.cpp measures it).
//          alpha_nu = j_nu / B_nu(T_e) (Kirchhoff's law: the plasma is thermal), B_nu the Planck function.
//          K_2 comes from a table of ln K_2(1 / Theta) on a uniform grid of ln Theta (core/uniform_table.hpp;
//          relative error below 1e-9 against std::cyl_bessel_k): the library's Bessel function costs about 0.4 us
//          a call, the table 70 ns, and the transfer asks for it at every stage of every step.
// Assumes: Theta_e >= 0.01 (colder electrons emit nothing here: the fit is made for relativistic ones, and at
//          230 GHz their emission is below exp(-40) of the warm gas's); nu, n_e, B >= 0.
#pragma once

#include "grtrace/core/physical_units.hpp"
#include "grtrace/core/uniform_table.hpp"
#include "grtrace/medium/emitting_medium.hpp"

#include <cmath>
#include <numbers>

namespace grtrace {

namespace synchrotron_detail {

/// ln K_2(1 / Theta) on ln Theta in [ln 0.01, ln 1e3] (4097 nodes); beyond 1e3, K_2(x) = 2 / x^2 - 1 / 2 (x = 1 /
/// Theta: its next term is of order x^2 ln x, below 1e-12 relative there).
class BesselK2Table {
 public:
  static constexpr double theta_min = 0.01, theta_max = 1e3;

  BesselK2Table()
      : log_k2_(std::log(theta_min), std::log(theta_max), 4097,
                [](double s) { return std::log(std::cyl_bessel_k(2.0, std::exp(-s))); }) {}

  /// K_2(1 / theta) for theta in [theta_min, inf).
  double operator()(double theta) const {
    if (theta >= theta_max) return 2.0 * theta * theta - 0.5;
    return std::exp(log_k2_(std::log(theta)));
  }

 private:
  UniformTable log_k2_;
};

inline const BesselK2Table& bessel_k2_table() {
  static const BesselK2Table table;
  return table;
}

}  // namespace synchrotron_detail

/// K_2(1 / Theta_e), the Maxwell-Juttner distribution's normalisation (see the top of this file).
inline double maxwell_juttner_k2(double theta_e) { return synchrotron_detail::bessel_k2_table()(theta_e); }

/// The Planck function B_nu(T) in erg s^-1 cm^-2 Hz^-1 sr^-1, for nu in Hz and k T = Theta_e m_e c^2.
inline double planck_intensity(double nu, double theta_e) {
  const double c = cgs::speed_of_light;
  const double kt = theta_e * cgs::electron_mass * c * c;
  return 2.0 * cgs::planck * nu * nu * nu / (c * c) / std::expm1(cgs::planck * nu / kt);
}

/// The minimum dimensionless temperature that emits (see the top of this file).
inline constexpr double min_synchrotron_temperature = 0.01;

/// The thermal synchrotron light of one plasma (n_e, Theta_e, B, sin theta) at any frequency (see the top of this
/// file), what does not depend on nu computed once: for a ray traced at several frequencies.
class ThermalSynchrotronPlasma {
 public:
  ThermalSynchrotronPlasma(double n_e, double theta_e, double b_gauss, double sin_theta) : theta_e_(theta_e) {
    if (!(theta_e >= min_synchrotron_temperature) || !(n_e > 0.0) || !(b_gauss > 0.0) || !(sin_theta > 0.0)) return;
    const double e = cgs::electron_charge, c = cgs::speed_of_light;
    const double nu_c = e * b_gauss / (2.0 * std::numbers::pi * cgs::electron_mass * c);
    nu_s_ = (2.0 / 9.0) * nu_c * theta_e * theta_e * sin_theta;
    scale_ = n_e * std::numbers::sqrt2 * std::numbers::pi * e * e * nu_s_ / (3.0 * maxwell_juttner_k2(theta_e) * c);
  }

  /// j_nu and alpha_nu at nu (Hz), cgs.
  MediumCoefficients at(double nu) const {
    if (!(scale_ > 0.0) || !(nu > 0.0)) return {};
    const double x = nu / nu_s_;
    const double cbrt_x = std::cbrt(x), sixth_x = std::sqrt(cbrt_x);           // X^(1/3), X^(1/6)
    const double shape = cbrt_x * sixth_x + std::exp2(11.0 / 12.0) * sixth_x;  // X^(1/2) + 2^(11/12) X^(1/6)
    const double j = scale_ * shape * shape * std::exp(-cbrt_x);
    if (!(j > 0.0)) return {};
    return {j, j / planck_intensity(nu, theta_e_)};
  }

 private:
  double theta_e_;
  double nu_s_ = 0.0;
  double scale_ = 0.0;  ///< j_nu's factor before the shape in X (0: the plasma does not emit)
};

/// j_nu and alpha_nu of thermal synchrotron light, cgs (see the top of this file).
inline MediumCoefficients thermal_synchrotron(double nu, double n_e, double theta_e, double b_gauss, double sin_theta) {
  return ThermalSynchrotronPlasma(n_e, theta_e, b_gauss, sin_theta).at(nu);
}

}  // namespace grtrace
