// grtrace/medium/spherical_accretion.hpp
// Optically thin gas falling onto (or resting around) a static spherically symmetric hole: an emitting medium
// (medium/emitting_medium.hpp) after Narayan, Johnson & Gammie 2019, "The shadow of a spherically accreting black
// hole" (ApJL 885 L33), whose image is the textbook check of a ray tracer's transfer.
//
// Takes:   the emissivity law j_nu = emissivity r^-power (frequency-independent; r in the metric's length unit,
//          the paper's power 2), no absorption, the gas at rest (static observers) or in free fall from rest at
//          infinity (u_t = 1 in signature (+, -, -, -)), between the metric's horizon and outer_radius.
// Returns: j, alpha = 0 and the gas's 4-velocity at an event of a static spherically symmetric metric in a
//          spherical chart with g_t_r = g_t_phi = 0 (Schwarzschild, Reissner-Nordstrom, Schwarzschild-de Sitter).
// Assumes: the event is outside the horizon (g_tt > 0). Free fall from infinity needs 1 / g_tt >= 1, which holds
//          wherever the metric is at most as deep as flat space (not beyond Schwarzschild-de Sitter's static
//          radius, where the infalling speed is set to 0).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace grtrace {

struct SphericalAccretion {
  static constexpr std::string_view kind = "spherical-accretion";
  static constexpr bool spherically_symmetric = true;
  static constexpr bool frequency_independent = true;

  enum class Gas { at_rest, free_fall };

  Gas gas = Gas::free_fall;
  double emissivity = 1.0;      ///< j_nu at r = 1
  double power = 2.0;           ///< j_nu = emissivity r^-power
  double outer = 1000.0;        ///< no gas beyond this radius

  GRTRACE_HD double outer_radius() const { return outer; }
  /// r - outer: the gas's edge, where j jumps to 0 (the tracer ends its steps there, and takes no light beyond).
  template <MetricPolicy M>
  GRTRACE_HD double boundary(const M& metric, const Vec4& x) const {
    return metric.radius(x) - outer;
  }

  template <MetricPolicy M>
  GRTRACE_HD MediumCoefficients coefficients(const M& metric, const Vec4& x, double /*nu*/) const {
    // Not cut at `outer`: the tracer takes the edge from boundary() and ends its steps there, and a step inside
    // needs the law continued smoothly a little way beyond it.
    return {emissivity * std::pow(metric.radius(x), -power), 0.0};
  }

  /// At rest: u = e_t / sqrt(g_tt). Free fall from rest at infinity: u^t = 1 / g_tt (energy u_t = 1), u^r from
  /// g(u, u) = 1, inwards.
  template <MetricPolicy M>
  GRTRACE_HD Vec4 fluid_velocity(const M& metric, const Vec4& x) const {
    static_assert(M::chart == Chart::spherical,
                  "SphericalAccretion: the gas's velocity is stated in a spherical chart (t, r, theta, phi) of a static "
                  "metric; use Schwarzschild-like coordinates");
    const Mat4 g = metric.metric(x);
    Vec4 u = Vec4::Zero();
    if (gas == Gas::at_rest) {
      u[0] = 1.0 / std::sqrt(g(0, 0));
      return u;
    }
    u[0] = 1.0 / g(0, 0);
    u[1] = -std::sqrt(std::max(0.0, (u[0] - 1.0) / -g(1, 1)));
    return u;
  }
};

}  // namespace grtrace
