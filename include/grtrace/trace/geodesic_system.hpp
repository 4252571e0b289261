// grtrace/trace/geodesic_system.hpp
// What the tracing loop (trace/geodesic_tracer.hpp trace_geodesic_system) integrates: a system of first-order
// equations whose state describes one geodesic, possibly in reduced variables, with the map back to (x, k).
//
// A geodesic system is a small value type built for one ray, with:
//   static constexpr int dimension               the number of integrated variables (8 for (x, k))
//   using State = Vector<dimension>
//   State operator()(const State& z) const       dz/ds, autonomous (s: the affine parameter for the geodesic
//                                                equation of a metric, Mino time for the reduced Kerr system)
//   double radius(const State& z) const          the metric's radius at z
//   double radial_coordinate(const State& z) const   an increasing function rho(r) of that radius, smooth along
//                                                the ray: what the horizon guard and the sky sphere are located on
//                                                (r itself; -1/r for a system in u = 1/r, whose rays pass through
//                                                u = 0, infinity, within a step, where r jumps from +inf to -inf)
//   double radial_coordinate_at(double r) const  rho at the radius r (the guard's, the sky sphere's)
//   geodesic_state(const State& z) const         the state (x^mu, k^mu = dx^mu/dlambda, affine) in the metric's
//                                                chart: what events, observers of results and colours see
//                                                (a GeodesicState, or a reference to z when z is one)
//   double constraint_violation(const State& z) const   the relative violation of the conserved quantities the
//                                                equations do not enforce (g(k, k) for the geodesic equation):
//                                                the tracer's guard against a lost geodesic (TraceSettings)
//   double constraint_drift(const State& z) const       g(k, k) at z minus its value at the start
//   bool wrap_chart(State& z) const              maps z back into the chart's range where the integration left
//                                                it (a spherical chart's polar axis) and says whether it did
// and optionally
//   double equatorial_latitude(const State& z) const   the angle of the ray's point above the equatorial plane
//                                                (pi/2 - theta; in a Cartesian chart asin(z / |x|)), of which
//                                                the tracing loop needs the sign only: it counts the ray's
//                                                crossings of the plane, each image's order (TraceResult)
// The library's systems: MetricGeodesicSystem (any metric policy: the geodesic equation itself, below) and
// KerrMinoSystem (trace/kerr_mino_tracer.hpp: Kerr's separated equations in Mino time).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/integrate/batch_stepper.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/metric_traits.hpp"

#include <cmath>
#include <concepts>
#include <limits>
#include <numbers>

namespace grtrace {

template <class S>
concept GeodesicSystem = requires(const S s, typename S::State z) {
  { S::dimension } -> std::convertible_to<int>;
  requires std::same_as<typename S::State, Vector<S::dimension>>;
  { s(z) } -> std::convertible_to<typename S::State>;
  { s.radius(z) } -> std::convertible_to<double>;
  { s.radial_coordinate(z) } -> std::convertible_to<double>;
  { s.radial_coordinate_at(1.0) } -> std::convertible_to<double>;
  { s.geodesic_state(z) } -> std::convertible_to<GeodesicState>;
  { s.constraint_violation(z) } -> std::convertible_to<double>;
  { s.constraint_drift(z) } -> std::convertible_to<double>;
  { s.wrap_chart(z) } -> std::same_as<bool>;
};

/// The angle of the event of y above the equatorial plane of the metric's chart: pi/2 - theta in a spherical
/// chart, asin(z / |x|) in a Cartesian one (the spin axis is z for the library's Cartesian metrics), to first order
/// (z / |x|: only its sign and its size near 0 are used). Zero on the plane.
template <MetricPolicy Metric>
GRTRACE_HD double equatorial_latitude(const GeodesicState& y) {
  if constexpr (Metric::chart == Chart::spherical) return 0.5 * std::numbers::pi - y[2];
  else return y[3] / std::sqrt(y[1] * y[1] + y[2] * y[2] + y[3] * y[3]);
}

/// Relative violation of the geodesic's constraint g(k,k) = const: |g(k,k) - norm0| / sum |g_mn k^m k^n|.
template <MetricPolicy Metric>
GRTRACE_HD double constraint_violation(const Metric& metric, const GeodesicState& y, double norm0) {
  const Vec4 x = y.head<4>(), k = y.tail<4>();
  const Mat4 g = metric.metric(x);
  const double size = k.cwiseAbs().dot(g.cwiseAbs() * k.cwiseAbs());
  const double v = std::abs(k.dot(g * k) - norm0) / size;
  return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
}

/// Spherical charts cover the sphere once with theta in [0, pi]. A ray through (or numerically across) the axis
/// comes out with theta < 0 or > pi; the same event and direction are theta' = -theta (or 2 pi - theta),
/// phi' = phi + pi, dtheta'/dlambda = -dtheta/dlambda. Theta, Phi and ThetaRate are the slots of theta, phi and
/// dtheta/dlambda in the state (any system that carries them: the reduced Kerr system's are 1, 2, 4).
/// Returns true when it changed y.
template <int Theta, int Phi, int ThetaRate, class State>
GRTRACE_HD bool wrap_polar_axis(State& y) {
  constexpr double pi = std::numbers::pi;
  if (y[Theta] >= 0.0 && y[Theta] <= pi) return false;
  y[Theta] = y[Theta] < 0.0 ? -y[Theta] : 2.0 * pi - y[Theta];
  y[Phi] += pi;
  y[ThetaRate] = -y[ThetaRate];
  return true;
}

/// The same for a geodesic state (x, k) of a spherical chart: theta = x^2, phi = x^3, k^theta.
inline GRTRACE_HD bool wrap_polar_axis(GeodesicState& y) { return wrap_polar_axis<2, 3, 6>(y); }

/// The geodesic equation of a metric policy, d/dlambda (x, k) = (k, -Gamma(k, k)), as a geodesic system: the
/// state is (x, k) itself; the constraint is g(k, k) = its value at the start (norm0).
template <MetricPolicy Metric>
struct MetricGeodesicSystem {
  static constexpr int dimension = 8;
  using State = GeodesicState;
  const Metric* metric;
  double norm0 = 0.0;

  GRTRACE_HD MetricGeodesicSystem(const Metric& m, const GeodesicState& y0)
      : metric(&m), norm0(inner_product(m, y0.head<4>(), y0.tail<4>(), y0.tail<4>())) {}

  /// Forced inline: the stepper calls it once per stage, and it is no more than the metric's acceleration.
  [[gnu::always_inline]] GRTRACE_HD State operator()(const State& y) const {
    return GeodesicEquation<Metric>{metric}(y);
  }
  /// The same on W states at once, lane-innermost (a Batch<8, W>, integrate/batch_stepper.hpp): lane l is
  /// operator() of lane l bit for bit, so a batched lane stays its ray alone.
  template <std::size_t W>
  [[gnu::always_inline]] void operator()(const std::array<std::array<double, W>, 8>& y,
                                         std::array<std::array<double, W>, 8>& dy) const {
    for (std::size_t i = 0; i < 4; ++i) dy[i] = y[i + 4];
    if constexpr (lane_acceleration<W>()) {
      // All lanes per instruction (metric/metric_traits.hpp); else the scalar acceleration lane by lane.
      std::array<Lanes<static_cast<int>(W)>, 4> x, k;
      for (std::size_t i = 0; i < 4; ++i) {
        x[i] = load_lanes(y[i]);
        k[i] = load_lanes(y[i + 4]);
      }
      const auto a = metric->template acceleration_lanes<static_cast<int>(W)>(x, k);
      for (std::size_t i = 0; i < 4; ++i) store_lanes(a[i], dy[i + 4]);
      return;
    }
    for (std::size_t l = 0; l < W; ++l) {
      Vec4 x, k;
      for (std::size_t i = 0; i < 4; ++i) {
        x[static_cast<int>(i)] = y[i][l];
        k[static_cast<int>(i)] = y[i + 4][l];
      }
      const Vec4 a = metric->acceleration(x, k);
      for (std::size_t i = 0; i < 4; ++i) dy[i + 4][l] = a[static_cast<int>(i)];
    }
  }
  // True when the metric evaluates W lanes at once (Lanes<W> exists for W = 2, 4, 8: core/lanes.hpp).
  template <std::size_t W>
  static constexpr GRTRACE_HD bool lane_acceleration() {
    if constexpr (W == 2 || W == 4 || W == 8) return HasLaneAcceleration<Metric, static_cast<int>(W)>;
    else return false;
  }
  GRTRACE_HD double radius(const State& y) const { return metric->radius(y.head<4>()); }
  GRTRACE_HD double radial_coordinate(const State& y) const { return radius(y); }
  static GRTRACE_HD double radial_coordinate_at(double r) { return r; }
  GRTRACE_HD const GeodesicState& geodesic_state(const State& y) const { return y; }
  GRTRACE_HD double constraint_violation(const State& y) const {
    return grtrace::constraint_violation(*metric, y, norm0);
  }
  GRTRACE_HD double constraint_drift(const State& y) const {
    return inner_product(*metric, y.head<4>(), y.tail<4>(), y.tail<4>()) - norm0;
  }
  GRTRACE_HD bool wrap_chart(State& y) const {
    if constexpr (Metric::chart == Chart::spherical) return wrap_polar_axis(y);
    else return false;
  }
  GRTRACE_HD double equatorial_latitude(const State& y) const { return grtrace::equatorial_latitude<Metric>(y); }

  /// A state near the polar axis of a spherical chart (sin theta < 1e-4) on a light ray that passes the axis closer
  /// than kThroughAxis (|k_phi| <= kThroughAxis sqrt(k_theta^2 + k_phi^2 / sin^2 theta), the sine of its closest pass
  /// for a metric symmetric about the axis) is moved onto the ray parallel to it through the axis, k_phi = 0, and
  /// the function says whether it moved it (the tracing loop calls it at the start and after every accepted step).
  /// Why: such a ray turns around the axis at sin theta ~ |k_phi| / sqrt(reach), where k^phi ~ k_phi / sin^2 theta
  /// is a spike the step control must resolve, and a ray with k_phi = 0 exactly regains a k_phi of round-off
  /// wherever the metric rotates (k^phi = omega k^t, not 0): measured, a ray of a camera 1e-3 rad from Kerr's axis
  /// with k_phi = 1e-23 closed in on the axis by a factor 0.84 a step down to sin theta = 3e-14, then ended as
  /// step_underflow; a camera 1e-9 rad from the axis (placed there for one on it) starts every ray at such a pass.
  /// The parallel ray differs from the ray by less than kThroughAxis in direction and 2 r kThroughAxis in place.
  /// Method: near the axis the sphere is a plane with polar coordinates (rho, phi), rho = theta (pi - theta in the
  /// south); the ray crosses it on a straight line with velocity rho' e_rho + rho phi'_L e_phi, phi'_L the part of
  /// k^phi from k_phi (k^phi minus the frame dragging's -g_t_phi k^t / g_phi_phi). The parallel line through the
  /// axis keeps that velocity; the state goes to its point at the same rho, on the side of the pass it is on (the
  /// nearest point can be the axis itself, where Boyer-Lindquist's cot theta terms of a frame-dragged ray cancel
  /// only to round-off: dk^phi/dlambda = -7.5e3 at theta = 6e-26, and every step was rejected), with k^phi the frame
  /// dragging's and k^theta the root of g(k, k) = its value at the start that keeps the direction (k^t, k^r kept).
  GRTRACE_HD bool align_with_axis(State& y) const {
    if constexpr (Metric::chart == Chart::spherical) {
      constexpr double pi = std::numbers::pi;
      const bool north = y[2] < pi / 2.0;
      const double rho = north ? y[2] : pi - y[2];
      if (!(rho >= 0.0 && rho < kNearAxis)) return false;
      const Vec4 x = y.head<4>(), k = y.tail<4>();
      const Mat4 g = metric->metric(x);
      const double k_phi = g.row(3).dot(k), k_theta = g.row(2).dot(k), s = std::sin(rho);
      if (k_phi == 0.0 || !(s > 0.0) || g(3, 3) == 0.0) return false;
      // Light only: a timelike worldline along the axis (a camera falling from it) has no velocity across it, and
      // moving it onto a line of round-off's direction would turn its frame about the axis.
      if (!(std::abs(norm0) <= 1e-8 * k.cwiseAbs().dot(g.cwiseAbs() * k.cwiseAbs()))) return false;
      const double reach = k_theta * k_theta + k_phi * k_phi / (s * s);
      if (!(k_phi * k_phi <= kThroughAxis * kThroughAxis * reach)) return false;
      const double rho_rate = north ? k[2] : -k[2], across = rho * (k[3] + g(0, 3) * k[0] / g(3, 3));
      const double cp = std::cos(x[3]), sp = std::sin(x[3]);
      const double vx = rho_rate * cp - across * sp, vy = rho_rate * sp + across * cp, speed = std::hypot(vx, vy);
      if (!(speed > 0.0)) return false;
      // Ahead of the line's pass through the axis (moving away from it) or behind it.
      const bool ahead = cp * vx + sp * vy >= 0.0;
      State moved = y;  // theta (rho) kept
      // phi kept continuous
      moved[3] = x[3] + std::remainder(std::atan2(vy, vx) + (ahead ? 0.0 : pi) - x[3], 2.0 * pi);
      const Vec4 x1 = moved.head<4>();
      const Mat4 g1 = metric->metric(x1);
      if (g1(3, 3) == 0.0 || g1(2, 2) == 0.0) return false;
      moved[7] = -g1(0, 3) * k[0] / g1(3, 3);
      // g(k, k) = norm0 as a quadratic in k^theta: g_th_th x^2 + 2 b x + c = norm0.
      Vec4 k1 = moved.tail<4>();
      k1[2] = 0.0;
      const double b = g1.row(2).dot(k1), c = k1.dot(g1 * k1) - norm0, disc = b * b - g1(2, 2) * c;
      if (!(disc >= 0.0)) return false;
      // Away from the axis ahead of the nearest point (rho' > 0), towards it behind; the root of that sign (g_th_th
      // is negative in a chart of signature (+, -, -, -)).
      const double rate_sign = ahead == north ? 1.0 : -1.0;
      moved[6] = (-b + (g1(2, 2) > 0.0 ? rate_sign : -rate_sign) * std::sqrt(disc)) / g1(2, 2);
      if (!all_finite(moved)) return false;
      y = moved;
      return true;
    } else {
      return false;
    }
  }

 private:
  /// Where align_with_axis looks (rho, the angle from the axis, below this): within it L^2 / sin^2 theta of a ray that
  /// passes the axis closer than kThroughAxis is at most 1e-8 of its polar speed.
  static constexpr double kNearAxis = 1e-4;
  /// The closest pass (sine) below which a ray is taken through the axis (as in trace/kerr_mino_system.hpp): the
  /// step control resolves passes above it (about ten steps a decade of distance from the axis).
  static constexpr double kThroughAxis = 1e-8;
};

}  // namespace grtrace
