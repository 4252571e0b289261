// grtrace/scene/thin_disk.hpp
// A geometrically thin accretion disk in the equatorial plane, r_in <= r <= r_out, of emitters on circular
// geodesic (Keplerian) orbits of whatever metric it sits in (metric/circular_orbits.hpp: for Schwarzschild
// Omega = sqrt(M / r^3), u^t = 1 / sqrt(1 - 3M/r)), turning towards +phi (sense = +1) or -phi (sense = -1).
// A scene object (scene/scene_object.hpp) for metrics in a spherical chart: the two-sided surface g = cos(theta),
// accepted only between its radii, so it is hit where the ray crosses the plane, from above or below. The same disk
// in a Cartesian chart that names its spherical chart (metric/metric_traits.hpp HasSphericalChart: Kerr-Schild) is
// the plane z = 0 between the metric's radii, its matter on the circular orbits of the spherical chart pushed
// into this one (surface, accepts and emitter_velocity with the metric at hand).
// Colour: a Shakura-Sunyaev / Novikov-Thorne-like temperature profile T(r) ~ r^(-3/4) (1 - sqrt(r_in/r))^(1/4),
// shifted by the redshift g to T_obs = g T and dimmed with g (bolometric g^4 T^4, compressed for display),
// as a blackbody colour.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/circular_orbits.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/scene/colour_maps.hpp"
#include "grtrace/scene/scene_object.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grtrace {

struct ThinDisk {
  static constexpr std::string_view kind = "disk";
  static constexpr bool two_sided = true;
  static constexpr bool equatorial = true;  ///< lies in theta = pi / 2: the planar tracer can draw it
  static constexpr bool stationary = true;  ///< nothing depends on t: the reduced Kerr tracer can draw it
  static constexpr bool axisymmetric = true;  ///< an annulus: accepts() reads the radius alone
  /// The plane, the annulus and the orbits are unchanged by theta -> pi - theta (not by phi -> -phi: the gas
  /// orbits): mirror-symmetric frames trace half their rows (render/mirror_symmetry.hpp).
  static constexpr bool equator_mirror_symmetric = true;
  double r_in = 6.0, r_out = 20.0;
  double peak_temperature = 5000.0;  ///< kelvin, at the hottest radius (for the colour only)
  int sense = +1;                    ///< +1: the gas turns towards +phi; -1: towards -phi

  GRTRACE_HD double operator()(const GeodesicState& y) const { return std::cos(y[2]); }
  GRTRACE_HD bool accepts(const GeodesicState& y) const { return y[1] >= r_in && y[1] <= r_out; }

  /// The same with the metric at hand: in a Cartesian chart the equatorial plane is z = 0 (Kerr-Schild's
  /// z = r cos theta) and the radius is the metric's (Kerr-Schild's quadric r, not a coordinate).
  template <MetricPolicy M>
  GRTRACE_HD double surface(const M& /*metric*/, const GeodesicState& y) const {
    if constexpr (M::chart == Chart::spherical) return std::cos(y[2]);
    else return y[3];
  }
  template <MetricPolicy M>
  GRTRACE_HD bool accepts(const M& metric, const GeodesicState& y) const {
    const double r = metric.radius(y.template head<4>());
    return r >= r_in && r <= r_out;
  }

  /// The circular orbit's 4-velocity at the hit's radius (NaN where the metric has none: refused up front by
  /// check_disk_orbits, so a render never meets it). In a Cartesian chart: the orbit of its spherical chart at the
  /// hit's spherical event, pushed forward with d(chart)/d(spherical) (metric_traits.hpp jacobian_of_spherical).
  template <MetricPolicy M>
  requires(M::chart == Chart::spherical || HasSphericalChart<M>) GRTRACE_HD Vec4
      emitter_velocity(const M& metric, const Vec4& x)
  const {
    if constexpr (M::chart == Chart::spherical) {
      if (auto u = circular_orbit_velocity(metric, x[1], sense)) return *u;
    } else {
      const Vec4 xs = metric.spherical_event(x);
      if (auto u = circular_orbit_velocity(metric.spherical_chart(), xs[1], sense))
        return jacobian_of_spherical(metric, xs) * *u;
    }
    return Vec4::Constant(std::numeric_limits<double>::quiet_NaN());
  }

  /// The hit's radius (SurfaceHit::radius; a hit without one, in a spherical chart: x^1) and redshift.
  Rgb colour(const SurfaceHit& hit) const {
    return colour(std::isfinite(hit.radius) ? hit.radius : hit.state[1], hit.redshift);
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

/// Refuses (std::invalid_argument, saying what to change) radii that are not finite or not ordered, and a disk
/// whose inner edge (for Schwarzschild: r_in <= 3M) or outer edge (Schwarzschild-de Sitter: beyond the static
/// radius (3M / Lambda)^(1/3), where gravity no longer holds matter on a circle) has no timelike circular orbit in
/// the metric: its matter could not move there, and the rays hitting it would end as non_finite.
template <MetricPolicy M>
void check_disk_orbits(const M& metric, const ThinDisk& disk) {
  if constexpr (M::chart != Chart::spherical) {
    static_assert(HasSphericalChart<M>, "check_disk_orbits: a thin disk in a Cartesian chart needs the chart's "
                                        "spherical_chart() and spherical_event(x) (metric/metric_traits.hpp)");
    check_disk_orbits(metric.spherical_chart(), disk);  // the same radii, horizon and orbits
  } else {
    if (!(std::isfinite(disk.r_in) && std::isfinite(disk.r_out) && disk.r_in > 0.0 && disk.r_out > disk.r_in))
      throw std::invalid_argument("disk: radii must be finite with 0 < inner < outer");
    if (const double rh = metric.horizon_radius(); !(disk.r_in > rh))
      throw std::invalid_argument("disk: the inner radius " + std::to_string(disk.r_in) +
                                  " is inside the horizon; raise it");
    if (!circular_orbit_velocity(metric, disk.r_in, disk.sense))
      throw std::invalid_argument("disk: no timelike circular orbit exists at the inner radius r = " +
                                  std::to_string(disk.r_in) +
                                  " in this metric (Schwarzschild: circular orbits need r > 3M); raise the inner "
                                  "radius");
    if (!circular_orbit_velocity(metric, disk.r_out, disk.sense)) {
      // The last radius with an orbit, between the edges (the orbits of the metrics here fill one interval).
      double lo = disk.r_in, hi = disk.r_out;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (circular_orbit_velocity(metric, mid, disk.sense) ? lo : hi) = mid;
      }
      throw std::invalid_argument("disk: no timelike circular orbit exists at the outer radius r = " +
                                  std::to_string(disk.r_out) + " in this metric (they end near r = " +
                                  std::to_string(lo) + "); lower the outer radius below that");
    }
  }
}

}  // namespace grtrace
