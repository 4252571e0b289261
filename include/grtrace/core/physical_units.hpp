// grtrace/core/physical_units.hpp
// From geometric units (G = c = 1, lengths in the hole's mass M) to what a telescope measures: the angle one M
// subtends at the source's distance, microarcseconds per pixel, janskys.
//
// Takes:   the hole's mass in solar masses and its distance in parsecs (SourceScale; the presets are the EHT's:
//          M87*, 6.5e9 at 16.8 Mpc, and Sgr A*, 4.0e6 at 8.15 kpc).
// Returns: the gravitational radius r_g = G M / c^2 in cm (the length a medium's coefficients per cm are multiplied
//          by to be per M), the angle theta_g = r_g / D (3.8 microarcseconds for M87*, 4.8 for Sgr A*: the EHT's
//          figures), a camera's pixel in microarcseconds, and a frame's flux density in janskys.
// Assumes: the camera is far from the hole and at rest there, so that the rays it sees reach a telescope at the
//          distance D with their angles scaled by r_cam / D and their intensity unchanged (I_nu / nu^3 is conserved
//          and a static observer at r_cam >> M measures the frequency a distant one does, to O(M / r_cam)).
//          Flux: F_nu = sum over pixels of I_nu dOmega_telescope = (r_cam / D)^2 sum of I_nu dOmega_camera, with
//          D in units of M, for I_nu in erg s^-1 cm^-2 Hz^-1 sr^-1 (cgs).
// Constants: CODATA 2018 (exact SI definitions where they are exact); the solar mass parameter G M_sun / c^2 from
//          IAU 2015 Resolution B3 (nominal G M_sun); the parsec from the IAU's astronomical unit.
#pragma once

#include <numbers>

namespace grtrace {

/// Physical constants in cgs units (see the top of this file for their sources).
namespace cgs {
inline constexpr double speed_of_light = 2.99792458e10;              ///< cm s^-1
inline constexpr double planck = 6.62607015e-27;                     ///< erg s
inline constexpr double boltzmann = 1.380649e-16;                    ///< erg K^-1
inline constexpr double electron_charge = 4.803204712570263e-10;     ///< esu (statcoulomb)
inline constexpr double electron_mass = 9.1093837015e-28;            ///< g
inline constexpr double proton_mass = 1.67262192369e-24;             ///< g
inline constexpr double solar_mass = 1.988409870698051e33;           ///< g (nominal G M_sun over CODATA G)
inline constexpr double solar_gravitational_radius = 1.476625038e5;  ///< G M_sun / c^2 in cm
inline constexpr double parsec = 3.0856775814913673e18;              ///< cm
inline constexpr double year = 3.15576e7;                            ///< s (Julian year)
inline constexpr double jansky = 1e-23;                              ///< erg s^-1 cm^-2 Hz^-1
inline constexpr double microarcsecond = std::numbers::pi / (180.0 * 3600.0 * 1e6);  ///< rad
}  // namespace cgs

/// The scale of a source: a hole of `mass_solar` solar masses at `distance_pc` parsecs.
struct SourceScale {
  double mass_solar = 6.5e9;
  double distance_pc = 16.8e6;

  /// M87* (EHT 2019, paper VI: 6.5e9 solar masses at 16.8 Mpc) and Sgr A* (EHT 2022, paper I: 4.0e6 at 8.15 kpc).
  static constexpr SourceScale m87() { return {6.5e9, 16.8e6}; }
  static constexpr SourceScale sgr_a() { return {4.0e6, 8.15e3}; }

  /// r_g = G M / c^2 in cm: one geometric length unit.
  constexpr double gravitational_radius_cm() const { return mass_solar * cgs::solar_gravitational_radius; }
  /// The distance in units of M.
  constexpr double distance_in_m() const { return distance_pc * cgs::parsec / gravitational_radius_cm(); }
  /// theta_g = r_g / D in microarcseconds: the angle one M subtends at the telescope.
  constexpr double microarcseconds_per_m() const { return 1.0 / (distance_in_m() * cgs::microarcsecond); }
  /// The angle a small angle `camera_radians` seen by a camera at radius `camera_radius` (in M) spans at the
  /// telescope, in microarcseconds (the camera far from the hole: see the top of this file).
  constexpr double microarcseconds_at_telescope(double camera_radians, double camera_radius) const {
    return camera_radians * camera_radius * microarcseconds_per_m();
  }
  /// A flux sum_pixels I_nu dOmega_camera (cgs intensity, the camera's solid angles) as janskys at the telescope.
  constexpr double janskys(double camera_flux, double camera_radius) const {
    const double ratio = camera_radius / distance_in_m();
    return camera_flux * ratio * ratio / cgs::jansky;
  }
};

}  // namespace grtrace
