// grtrace/observer/observers.hpp
// The two observers "at rest" that every stationary spacetime offers, and the orthonormal frame each one carries,
// for any metric policy (no assumption of a diagonal metric or of a particular chart):
//   static observer  u = d_t / sqrt(g_tt): at rest with respect to the Killing time t. Exists only where
//                    g_tt > 0 (outside horizons and, for rotating holes, outside the ergosphere).
//   ZAMO             u^mu = g^{mu t} / sqrt(g^{tt}): the zero-angular-momentum observer, normal to the t = const
//                    slices (Bardeen, Press & Teukolsky 1972). Exists wherever t is a time function (g^{tt} > 0),
//                    i.e. everywhere outside a horizon; equal to the static observer when g_{t i} = 0.
// The frame's spatial axes are the chart's basis vectors d_1, d_2, d_3 orthonormalised against u and each other
// (Gram-Schmidt in the metric): (r, theta, phi) in a spherical chart, (x, y, z) in a Cartesian one. For a diagonal
// metric and the static observer this is the familiar local static frame.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/optional.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grtrace {

enum class ObserverKind {
  static_observer,  ///< at rest in the Killing time; refused where g_tt <= 0
  zamo,             ///< zero angular momentum, normal to t = const; valid everywhere outside a horizon
};

inline std::optional<ObserverKind> observer_kind_from_string(std::string_view s) {
  if (s == "static") return ObserverKind::static_observer;
  if (s == "zamo") return ObserverKind::zamo;
  return std::nullopt;
}

/// The static observer's 4-velocity from g at the event, or nothing where g_tt <= 0.
inline GRTRACE_HD Optional<Vec4> static_velocity(const Mat4& g) {
  if (!(g(0, 0) > 0.0)) return no_value;
  return Vec4(1.0 / std::sqrt(g(0, 0)), 0.0, 0.0, 0.0);
}

/// The ZAMO's 4-velocity from g at the event, or nothing where g^{tt} <= 0 (or g is singular).
inline GRTRACE_HD Optional<Vec4> zamo_velocity(const Mat4& g) {
  const Mat4 inverse = g.inverse();
  if (!all_finite(inverse) || !(inverse(0, 0) > 0.0)) return no_value;
  return Vec4(inverse.col(0) / std::sqrt(inverse(0, 0)));
}

/// The 4-velocity of an emitter at rest at x for the sky and the horizon: static where it exists, else the ZAMO,
/// else NaN (the redshift is then undefined and reported as NaN, never guessed).
template <MetricPolicy M>
GRTRACE_HD Vec4 rest_emitter_velocity(const M& metric, const Vec4& x) {
  const Mat4 g = metric.metric(x);
  if (auto u = static_velocity(g)) return *u;
  if (auto u = zamo_velocity(g)) return *u;
  return Vec4::Constant(std::numeric_limits<double>::quiet_NaN());
}

/// An observer's orthonormal frame: e[0] its 4-velocity, e[1..3] its spatial axes (see the top of this file).
struct ObserverFrame {
  std::array<Vec4, 4> e;

  /// Takes g at the event and a future-directed timelike u; throws std::invalid_argument otherwise. The spatial
  /// axes come from the chart's basis vectors d_1, d_2, d_3.
  ObserverFrame(const Mat4& g, const Vec4& u) : ObserverFrame(g, u, {Vec4::Unit(1), Vec4::Unit(2), Vec4::Unit(3)}) {}

  /// The same with the spatial axes orthonormalised from the given coordinate vectors (e.g. d_r, d_theta, d_phi of
  /// another chart mapped into this one, metric/metric_traits.hpp spherical_axes).
  ObserverFrame(const Mat4& g, const Vec4& u, const std::array<Vec4, 3>& axes) {
    auto dot = [&](const Vec4& a, const Vec4& b) { return a.dot(g * b); };
    const double uu = dot(u, u);
    if (!u.allFinite() || !(uu > 0.0) || !(u[0] > 0.0))
      throw std::invalid_argument("observer frame: the 4-velocity must be finite, timelike and future-directed");
    e[0] = u / std::sqrt(uu);
    for (int a = 1; a <= 3; ++a) {
      Vec4 v = axes[static_cast<std::size_t>(a - 1)];
      v -= dot(v, e[0]) * e[0];
      for (int b = 1; b < a; ++b) v += dot(v, e[static_cast<std::size_t>(b)]) * e[static_cast<std::size_t>(b)];
      const double n2 = -dot(v, v);
      if (!(n2 > 0.0)) throw std::invalid_argument("observer frame: the chart's spatial axes are degenerate here");
      e[static_cast<std::size_t>(a)] = v / std::sqrt(n2);
    }
  }

  /// Spatial vector with components along the frame's axes, as a coordinate vector.
  GRTRACE_HD Vec4 spatial(const Vec3& v) const { return v[0] * e[1] + v[1] * e[2] + v[2] * e[3]; }

  /// 4-velocity of an observer moving with 3-velocity beta (fraction of c) through this frame.
  Vec4 velocity(const Vec3& beta) const {
    const double b2 = beta.squaredNorm();
    if (!(b2 < 1.0)) throw std::invalid_argument("velocity: |beta| must be below 1 (the speed of light)");
    const double gamma = 1.0 / std::sqrt(1.0 - b2);
    return gamma * (e[0] + spatial(beta));
  }
};

/// The frame of the chosen observer at x, its spatial axes orthonormalised from `axes` (default: the chart's basis
/// vectors). Throws std::invalid_argument, saying what to change, where that observer does not exist.
/// `from_defining_chart` is d(metric's chart)/d(chart that defines the observer) at x: "static" and "ZAMO" are
/// defined by a chart's t (its Killing time and its t = const slices), and two charts of one spacetime can have
/// different slices: the ZAMO of Kerr is the observer normal to the Boyer-Lindquist slices, while the observer normal
/// to the Kerr-Schild slices is another one (it falls in). Pass metric/metric_traits.hpp jacobian_of_spherical for
/// a camera placed in Boyer-Lindquist coordinates; the identity (default) defines the observer in the metric's own
/// chart.
template <MetricPolicy M>
ObserverFrame observer_frame(const M& metric, const Vec4& x, ObserverKind kind,
                             const std::array<Vec4, 3>& axes = {Vec4::Unit(1), Vec4::Unit(2), Vec4::Unit(3)},
                             const Mat4& from_defining_chart = Mat4::Identity()) {
  const Mat4 g = metric.metric(x);
  // The metric in the defining chart (the pull-back J^T g J), and its observers pushed forward with J.
  const Mat4& J = from_defining_chart;
  const Mat4 g_def = J.transpose() * g * J;
  if (!g.allFinite()) throw std::invalid_argument("observer: the metric is not finite at the camera's position");
  // The signature of g read off the congruent D g D, D = diag(|g_ii|^(-1/2)) (Sylvester's law of inertia): its
  // diagonal is +-1, so its eigenvalues keep their precision where g's entries span many orders of magnitude (g_tt
  // ~ 1 beside g_phiphi ~ r^2 ~ 1e21 for a camera at 4e10 M, where g's own eigenvalues lose the positive one).
  Vec4 d;
  for (int i = 0; i < 4; ++i) d[i] = g(i, i) != 0.0 ? 1.0 / std::sqrt(std::abs(g(i, i))) : 1.0;
  const Mat4 scaled = d.asDiagonal() * g * d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Mat4> spectrum(scaled, Eigen::EigenvaluesOnly);
  const Vec4 ev = spectrum.eigenvalues();  // ascending: a Lorentzian g (+,-,-,-) has three negative, one positive
  if (!(ev[2] < 0.0 && ev[3] > 0.0))
    throw std::invalid_argument("observer: the metric at the camera's position is singular or not of signature "
                                "(+,-,-,-); move the camera or check the metric");
  if (kind == ObserverKind::static_observer) {
    if (auto u = static_velocity(g_def)) return ObserverFrame(g, J * *u, axes);
    throw std::invalid_argument(
        "observer: no static observer exists at the camera's position (g_tt <= 0: inside a horizon or an "
        "ergosphere); use the ZAMO observer (--observer zamo) or move the camera out");
  }
  if (auto u = zamo_velocity(g_def)) return ObserverFrame(g, J * *u, axes);
  throw std::invalid_argument(
      "observer: no zero-angular-momentum observer exists at the camera's position (g^tt <= 0: inside a "
      "horizon); move the camera out");
}

}  // namespace grtrace
