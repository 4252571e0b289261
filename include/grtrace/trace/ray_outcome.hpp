// grtrace/trace/ray_outcome.hpp
// What every scene tracer reports for one camera ray, before shading: how it ended, where (sky direction after
// the chosen angle correction, or the point on the horizon / disk), and the redshift f_obs / f_src (seed eq. 9).
// The three tracers (general, symmetric-sky, straight-line) differ in how they get there, not in what they report.
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/render/image.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace grtrace {

enum class AngleCorrection {
  none,   ///< theta, phi where the ray meets the sky sphere (seed Fig. 4b)
  flat,   ///< the ray's Cartesian direction there, i.e. flat space beyond (seed eq. 7-8, Fig. 4a)
  exact,  ///< the exact Schwarzschild bending from there to infinity (elliptic integrals)
};

struct RayOutcome {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  RayStatus status = RayStatus::max_steps;
  SceneObjectId object = SceneObjectId::sky;
  exact::SkyDirection where{nan, nan};  ///< escaped: sky direction; captured / hit: (theta, phi) of the hit point
  double radius = nan;                  ///< r of the hit point (disk colour)
  double redshift = nan;                ///< f_obs / f_src; NaN for failed rays
  int steps = 0;
};

/// Where the state is on its sphere: (theta, phi) with phi reduced to (-pi, pi] (the chart's phi keeps counting turns).
inline exact::SkyDirection chart_angles(const GeodesicState& y) {
  return {y[2], std::remainder(y[3], 2.0 * std::numbers::pi)};
}

/// The sky direction of a ray that reached the sky sphere in state y, for each correction.
inline exact::SkyDirection corrected_sky_direction(const GeodesicState& y, AngleCorrection correction, double mass) {
  switch (correction) {
    case AngleCorrection::none: return chart_angles(y);
    case AngleCorrection::flat: return exact::flat_direction(y);
    case AngleCorrection::exact:
      if (auto d = exact::asymptotic_direction(y, mass)) return *d;
      return exact::flat_direction(y);  // cannot happen for a ray that left the sky sphere outward
  }
  return exact::flat_direction(y);
}

}  // namespace grtrace
