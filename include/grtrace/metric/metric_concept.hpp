// grtrace/metric/metric_concept.hpp
// What the tracers need of a metric policy, and the geodesic equation built from it.
//
// A metric policy is a small value type (no virtual functions) with:
//   name                      "schwarzschild", "minkowski", ...
//   metric(x)                 g_{mu nu} at the event x (signature +,-,-,-)
//   christoffel(x)            Gamma^mu_{ab} as four symmetric 4x4 matrices (tests and tools; not the hot loop)
//   acceleration(x, k)        -Gamma^mu_{ab} k^a k^b in closed form (the hot loop)
//   radius(x)                 distance from the centre used for escape tests
//   horizon_radius()          r of the event horizon in this chart, 0 when there is none
//   to_cartesian(x)           a point of flat R^3 for drawing (the chart's Euclidean embedding)
//   chart                     Chart::cartesian or Chart::spherical (x = t, r, theta, phi)
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"

#include <array>
#include <concepts>
#include <string_view>

namespace grtrace {

enum class Chart { cartesian, spherical };

using Christoffel = std::array<Mat4, 4>;  ///< Gamma[mu](a, b)

template <class M>
concept MetricPolicy = requires(const M m, const Vec4 x, const Vec4 k) {
  { M::name } -> std::convertible_to<std::string_view>;
  { M::chart } -> std::convertible_to<Chart>;
  { m.metric(x) } -> std::convertible_to<Mat4>;
  { m.christoffel(x) } -> std::convertible_to<Christoffel>;
  { m.acceleration(x, k) } -> std::convertible_to<Vec4>;
  { m.radius(x) } -> std::convertible_to<double>;
  { m.horizon_radius() } -> std::convertible_to<double>;
  { m.to_cartesian(x) } -> std::convertible_to<Vec3>;
};

/// g(a, b) = g_{mu nu} a^mu b^nu at x.
template <MetricPolicy M>
GRTRACE_HD double inner_product(const M& metric, const Vec4& x, const Vec4& a, const Vec4& b) {
  return a.dot(metric.metric(x) * b);
}

/// The geodesic equation as a first-order autonomous system: d/dlambda (x, k) = (k, -Gamma(k, k)).
template <MetricPolicy M>
struct GeodesicEquation {
  const M* metric;
  // Forced inline (also through MetricGeodesicSystem, trace/geodesic_system.hpp): out of line, the call and the
  // copy of its 8-vector result cost a quarter of a Schwarzschild step (measured with perf, kerr_benchmark).
  [[gnu::always_inline]] GRTRACE_HD GeodesicState operator()(const GeodesicState& y) const {
    GeodesicState dy;
    const Vec4 x = y.head<4>(), k = y.tail<4>();
    dy.head<4>() = k;
    // Copied component by component: a 4-vector built by scalar stores and read back as two 16-byte loads
    // stalls on store forwarding (the profile showed it as the most expensive instruction of Kerr's right-hand side).
    const Vec4 a = metric->acceleration(x, k);
    dy[4] = a[0];
    dy[5] = a[1];
    dy[6] = a[2];
    dy[7] = a[3];
    return dy;
  }
};

/// -Gamma^mu_{ab} k^a k^b from a Christoffel table (reference for the closed forms in the tests).
inline GRTRACE_HD Vec4 acceleration_from_christoffel(const Christoffel& gamma, const Vec4& k) {
  Vec4 a;
  for (int mu = 0; mu < 4; ++mu) a[mu] = -k.dot(gamma[static_cast<std::size_t>(mu)] * k);
  return a;
}

}  // namespace grtrace
