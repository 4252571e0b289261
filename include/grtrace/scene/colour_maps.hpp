// grtrace/scene/colour_maps.hpp
// Colours for the scenes: checkerboards on (theta, phi) (seed sec. 3.1.4), a diverging redshift map, and an
// approximate blackbody colour for the disk. Linear RGB in [0, 1] (the PNG preview applies sRGB).
#pragma once

#include "grtrace/core/rounding.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace grtrace {

using Rgb = std::array<float, 3>;

/// Which square of an n_theta x (2 n_theta) checkerboard the direction (theta, phi) falls in: 0 or 1.
inline int checker_parity(double theta, double phi, int n_theta) {
  const double cell = std::numbers::pi / n_theta;
  const long i = floor_to_long(theta / cell);
  const long j = floor_to_long(phi / cell);
  return static_cast<int>(((i + j) % 2 + 2) % 2);
}

/// v in [0, 1] as black -> red -> yellow -> white (each colour rises in turn: a "hot gas" map, monotone in
/// brightness, readable without colour vision).
inline std::array<float, 3> hot_gas_colour(double v) {
  const double t = std::clamp(v, 0.0, 1.0);
  return {static_cast<float>(std::clamp(3.0 * t, 0.0, 1.0)), static_cast<float>(std::clamp(3.0 * t - 1.0, 0.0, 1.0)),
          static_cast<float>(std::clamp(3.0 * t - 2.0, 0.0, 1.0))};
}

/// f_obs / f_src as colour: red for redshift, blue for blueshift, white at 1; saturates at a factor `range`.
inline Rgb redshift_colour(double g, double range = 4.0) {
  if (!(g > 0.0) || !std::isfinite(g)) return {0.0f, 0.0f, 0.0f};
  const double t = std::clamp(std::log(g) / std::log(range), -1.0, 1.0);
  const double a = std::abs(t);
  if (t < 0) return {1.0f, static_cast<float>(1.0 - a), static_cast<float>(1.0 - a)};
  return {static_cast<float>(1.0 - a), static_cast<float>(1.0 - 0.5 * a), 1.0f};
}

/// Approximate chromaticity of a blackbody at temperature T (kelvin), 1000 K .. 40000 K, normalised to max 1
/// (a fit to the CIE colour-matching result; good enough for a picture, not for photometry).
inline Rgb blackbody_colour(double kelvin) {
  const double t = std::clamp(kelvin, 1000.0, 40000.0) / 100.0;
  double r = t <= 66 ? 255 : 329.698727446 * std::pow(t - 60, -0.1332047592);
  double g = t <= 66 ? 99.4708025861 * std::log(t) - 161.1195681661 : 288.1221695283 * std::pow(t - 60, -0.0755148492);
  double b = t >= 66 ? 255 : (t <= 19 ? 0 : 138.5177312231 * std::log(t - 10) - 305.0447927307);
  auto c = [](double v) { return static_cast<float>(std::clamp(v / 255.0, 0.0, 1.0)); };
  return {c(r), c(g), c(b)};
}

}  // namespace grtrace
