// grtrace/scene/thin_disk.hpp
// A geometrically thin accretion disk in the equatorial plane, r_in <= r <= r_out, of emitters on circular
// Keplerian orbits: Omega = sqrt(M / r^3), u^t = 1 / sqrt(1 - 3M/r), u = u^t (1, 0, 0, Omega) (prograde, +phi).
// As a tracer event it is the two-sided surface g = cos(theta) = 0, accepted only between its radii, so it is
// hit where the ray crosses the plane (located on the dense output), from above or below.
// Colour: a Shakura-Sunyaev / Novikov-Thorne-like temperature profile T(r) ~ r^(-3/4) (1 - sqrt(r_in/r))^(1/4),
// shifted by the redshift g to T_obs = g T and dimmed with g (bolometric g^4 T^4, compressed for display),
// as a blackbody colour.
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/scene/colour_maps.hpp"

#include <algorithm>
#include <cmath>

namespace grtrace {

struct ThinDisk {
  static constexpr bool two_sided = true;
  static constexpr SceneObjectId id = SceneObjectId::disk;
  double mass = 1.0;
  double r_in = 6.0, r_out = 20.0;
  double peak_temperature = 5000.0;  ///< kelvin, at the hottest radius (for the colour only)

  double operator()(const GeodesicState& y) const { return std::cos(y[2]); }
  bool accepts(const GeodesicState& y) const { return y[1] >= r_in && y[1] <= r_out; }

  Vec4 emitter_velocity(double r) const {
    const double omega = std::sqrt(mass / (r * r * r));
    const double ut = 1.0 / std::sqrt(1.0 - 3.0 * mass / r);
    return Vec4(ut, 0.0, 0.0, ut * omega);
  }

  /// Linear RGB of the disk at radius r seen with redshift g = f_obs / f_src.
  Rgb colour(double r, double g) const {
    auto profile = [&](double x) { return std::pow(x, -0.75) * std::pow(std::max(0.0, 1.0 - std::sqrt(r_in / x)), 0.25); };
    const double peak = profile(r_in * 49.0 / 36.0);  // the profile's maximum
    const double t = peak_temperature * profile(r) / peak;
    const Rgb c = blackbody_colour(std::max(1000.0, g * t));
    // Bolometric g^4 T^4, square-rooted so that the display range shows both the hot inner edge and the dim rim.
    const double brightness = std::clamp(0.6 * std::pow(g, 2.0) * std::pow(t / peak_temperature, 2.0), 0.0, 1.5);
    const auto b = static_cast<float>(brightness);
    return {c[0] * b, c[1] * b, c[2] * b};
  }
};

}  // namespace grtrace
