// grtrace/metric/metric_traits.hpp
// What the layers above the tracer (scenes, cameras, renders) ask of a metric beyond MetricPolicy, in one place.
//
// Required (metric/metric_concept.hpp): name, chart, metric(x), christoffel(x), acceleration(x, k), radius(x),
// horizon_radius() (0 when there is none: no capture surface is traced), to_cartesian(x).
//
// Optional, detected at compile time (a metric that lacks one gets the generic answer named here):
//   std::optional<SkyDirection> asymptotic_direction(const GeodesicState& y) const
//       The exact sky direction of a ray continued from y to infinity, or nothing if it falls back in.
//       Used for AngleCorrection::exact. Generic answer: the flat continuation (the direction of the embedded
//       velocity at y, seed eq. 7-8), exact only where the metric is flat beyond y.
//   Vec4 event_from_spherical(const Vec4& x) const;  Mat4 jacobian_from_spherical(const Vec4& x) const;
//       For charts that are not spherical: the event with spherical (Boyer-Lindquist) coordinates x = (t, r, theta,
//       phi) in this chart, and the Jacobian d(chart)/d(spherical) there. Cameras and tools state positions and
//       directions in (r, theta, phi) for every chart (KerrSchildMetric). Generic answer: a spherical chart takes
//       x as it is; a Cartesian chart maps (r, theta, phi) to (x, y, z) by the flat embedding.
//   auto spherical_chart() const;  Vec4 spherical_event(const Vec4& x) const;
//       For charts that are not spherical: the same spacetime as a metric policy in its spherical chart
//       (Kerr-Schild -> KerrMetric, Boyer-Lindquist), and the spherical coordinates of an event of this chart (the
//       inverse of event_from_spherical, outside the horizon). Lets what is defined in (t, r, theta, phi) be used
//       in this chart: a thin disk's circular orbits (scene/thin_disk.hpp). No generic answer (HasSphericalChart).
//   double capture_radius(const GeodesicState& y0) const;  bool leaves_interior(const GeodesicState& y0) const;
//       For horizon-penetrating charts, where whether a ray can cross the horizon depends on its time direction
//       (KerrSchildMetric). capture_radius: the radius r_cap of the tracer's horizon guard r = (1 + eps) r_cap for
//       the ray that starts at y0 (inside the event horizon for a ray the chart carries across it, at it for a
//       ray that only creeps towards it). leaves_interior: for a ray that starts on or inside that guard, true
//       when it comes out (a camera inside a black hole looking back at the ray's past: the ray leaves through
//       the future horizon); the guard then takes effect only once the ray is outside it. Generic answers:
//       horizon_radius(), and false (a ray that starts inside the guard is captured at once).
//   static constexpr bool equator_mirror_symmetric = true;  static constexpr bool meridian_mirror_symmetric = true;
//       In a spherical chart: the metric is unchanged by the reflection theta -> pi - theta (Kerr, every spherically
//       symmetric metric), or by every reflection phi -> 2 phi0 - phi (axisymmetric and not rotating: Schwarzschild,
//       not Kerr). A frame whose scene and camera are mirror symmetric too traces only the pixels of one half or
//       one quarter (render/mirror_symmetry.hpp). Generic answer: false, except both true for a
//       StaticSphericalMetric (metric/static_spherical.hpp), which is spherically symmetric by construction.
//   static constexpr bool flat = true;
//       The metric is flat everywhere: light moves on straight lines, so trace/straight_line.hpp follows rays
//       without integrating (MinkowskiMetric, MinkowskiSpherical). Default: false.
//   template <int W> std::array<Lanes<W>, 4> acceleration_lanes(const std::array<Lanes<W>, 4>& x,
//                                                                 const std::array<Lanes<W>, 4>& k) const;
//       acceleration(x, k) of W rays at once in SIMD registers (core/lanes.hpp; lane l of each argument is ray l),
//       every lane acceleration()'s bits for its ray, for the batched geodesic right-hand side
//       (SchwarzschildMetric). Detected by HasLaneAcceleration<M, W>. No generic answer: without it a caller
//       evaluates acceleration() ray by ray.
//
// Generic answers computed from the required members (no metric has to write these):
//   embedded_velocity_of(m, y)   dx/dlambda in the chart's Euclidean embedding (spherical or Cartesian charts)
//   position_direction(m, x)     (theta, phi) of the event in the embedding: where on its sphere a hit lies
//   continued_direction(m, y, c) the sky direction of an escaped ray under an AngleCorrection
// Observers and emitters "at rest" (static, ZAMO) are in observer/observers.hpp.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/lanes.hpp"
#include "grtrace/core/sky_direction.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/spherical_chart.hpp"
#include "grtrace/metric/static_spherical.hpp"

#include <array>
#include <cmath>
#include <concepts>
#include <numbers>
#include <optional>
#include <type_traits>

namespace grtrace {

/// How the direction of an escaped ray is read off where it leaves the traced region (the sky sphere).
enum class AngleCorrection {
  none,   ///< the direction of the point where the ray meets the sky sphere (seed Fig. 4b)
  flat,   ///< the ray's Cartesian direction there, i.e. flat space beyond (seed eq. 7-8, Fig. 4a)
  exact,  ///< the metric's exact continuation to infinity where it has one (asymptotic_direction), else flat
};

/// True when the metric can continue a ray exactly from a state to infinity.
template <class M>
concept HasExactContinuation = requires(const M m, const GeodesicState y) {
  { m.asymptotic_direction(y) } -> std::convertible_to<std::optional<SkyDirection>>;
};

/// True when the metric evaluates acceleration() for W rays at once, bit for bit per lane (see the top of this file).
template <class M, int W>
concept HasLaneAcceleration = requires(const M m, const std::array<Lanes<W>, 4> x) {
  { m.template acceleration_lanes<W>(x, x) } -> std::same_as<std::array<Lanes<W>, 4>>;
};

/// True for metrics that declare themselves flat everywhere (the straight-line tracer's precondition).
template <class M>
concept FlatMetric = MetricPolicy<M> && requires { requires M::flat; };

/// True when the metric, in a spherical chart, is unchanged by theta -> pi - theta (see the top of this file).
template <MetricPolicy M>
constexpr GRTRACE_HD bool metric_is_equator_mirror_symmetric() {
  if constexpr (M::chart != Chart::spherical) return false;
  else if constexpr (requires { M::equator_mirror_symmetric; }) return M::equator_mirror_symmetric;
  else return StaticSphericalMetric<M>;
}

/// True when the metric, in a spherical chart, is unchanged by every phi -> 2 phi0 - phi (see the top of this file).
template <MetricPolicy M>
constexpr GRTRACE_HD bool metric_is_meridian_mirror_symmetric() {
  if constexpr (M::chart != Chart::spherical) return false;
  else if constexpr (requires { M::meridian_mirror_symmetric; }) return M::meridian_mirror_symmetric;
  else return StaticSphericalMetric<M>;
}

template <class M>
concept HasSphericalMap = requires(const M m, const Vec4 x) {
  { m.event_from_spherical(x) } -> std::convertible_to<Vec4>;
  { m.jacobian_from_spherical(x) } -> std::convertible_to<Mat4>;
};

/// True for a chart that names its spacetime's spherical chart (see the top of this file).
template <class M>
concept HasSphericalChart = requires(const M m, const Vec4 x) {
  { m.spherical_event(x) } -> std::convertible_to<Vec4>;
  requires MetricPolicy<std::remove_cvref_t<decltype(m.spherical_chart())>>;
  requires std::remove_cvref_t<decltype(m.spherical_chart())>::chart == Chart::spherical;
};

template <class M>
concept HasDirectedCapture = requires(const M m, const GeodesicState y) {
  { m.capture_radius(y) } -> std::convertible_to<double>;
  { m.leaves_interior(y) } -> std::convertible_to<bool>;
};

/// The radius of the horizon guard for the ray (or body) starting at y0 (see the top of this file); 0: no horizon.
template <MetricPolicy M>
GRTRACE_HD double capture_radius_of(const M& metric, const GeodesicState& y0) {
  if constexpr (HasDirectedCapture<M>) return metric.capture_radius(y0);
  else return metric.horizon_radius();
}

/// For a ray starting on or inside its horizon guard: true when it comes out of the hole (see the top of this file).
template <MetricPolicy M>
GRTRACE_HD bool leaves_interior_of(const M& metric, const GeodesicState& y0) {
  if constexpr (HasDirectedCapture<M>) return metric.leaves_interior(y0);
  else return false;
}

/// The event with spherical coordinates x = (t, r, theta, phi) in the metric's chart (see the top of this file).
template <MetricPolicy M>
GRTRACE_HD Vec4 event_from_spherical(const M& metric, const Vec4& x) {
  if constexpr (HasSphericalMap<M>) return metric.event_from_spherical(x);
  else if constexpr (M::chart == Chart::spherical) return x;
  else {
    Vec4 y;
    y << x[0], spherical_to_cartesian(x);
    return y;
  }
}

/// d(chart)/d(spherical) at the spherical event x: maps vectors given in (t, r, theta, phi) to the metric's chart
/// (the identity for a spherical chart).
template <MetricPolicy M>
GRTRACE_HD Mat4 jacobian_of_spherical(const M& metric, const Vec4& x) {
  Mat4 j = Mat4::Identity();
  if constexpr (HasSphericalMap<M>) j = metric.jacobian_from_spherical(x);
  else if constexpr (M::chart == Chart::cartesian) {
    const SphericalBasis e = spherical_basis(x[2], x[3]);
    j.block<3, 1>(1, 1) = e.r;
    j.block<3, 1>(1, 2) = x[1] * e.theta;
    j.block<3, 1>(1, 3) = x[1] * e.sin_theta * e.phi;
  }
  return j;
}

/// The coordinate vectors d_r, d_theta, d_phi at the spherical event x, as vectors of the metric's chart.
template <MetricPolicy M>
GRTRACE_HD std::array<Vec4, 3> spherical_axes(const M& metric, const Vec4& x) {
  const Mat4 j = jacobian_of_spherical(metric, x);
  return {Vec4(j.col(1)), Vec4(j.col(2)), Vec4(j.col(3))};
}

/// dx/dlambda of a state as a vector of the chart's Euclidean embedding.
template <MetricPolicy M>
GRTRACE_HD Vec3 embedded_velocity_of(const M& /*metric*/, const GeodesicState& y) {
  if constexpr (M::chart == Chart::spherical) return embedded_velocity(y, spherical_basis(y[2], y[3]));
  else return y.tail<3>();
}

/// (theta, phi) of the event x seen from the centre of the embedding, phi reduced to (-pi, pi] (azimuth_in_range:
/// a spherical chart's phi keeps counting turns).
template <MetricPolicy M>
GRTRACE_HD SkyDirection position_direction(const M& metric, const Vec4& x) {
  if constexpr (M::chart == Chart::spherical) return {x[2], azimuth_in_range(x[3])};
  else return sky_direction_of(metric.to_cartesian(x));
}

/// The sky direction of a ray that left the traced region. `at_sphere` is the state on the sky sphere;
/// `from` is where the exact continuation starts (any point of the outgoing leg: the end of the last accepted
/// step carries the integrator's error only, the point on the sphere the interpolant's too).
template <MetricPolicy M>
GRTRACE_HD SkyDirection continued_direction(const M& metric, const GeodesicState& from, const GeodesicState& at_sphere,
                                            AngleCorrection correction) {
  if (correction == AngleCorrection::none) return position_direction(metric, at_sphere.head<4>());
  if constexpr (HasExactContinuation<M>) {
    if (correction == AngleCorrection::exact) {
      if (auto d = metric.asymptotic_direction(from)) return *d;
    }
  }
  return sky_direction_of(embedded_velocity_of(metric, at_sphere));
}

}  // namespace grtrace
