// grtrace/metric/schwarzschild.hpp
// Schwarzschild spacetime in Schwarzschild coordinates x = (t, r, theta, phi), G = c = 1 (seed eq. 3-4).
//   ds^2 = (1 - 2M/r) dt^2 - dr^2 / (1 - 2M/r) - r^2 dtheta^2 - r^2 sin^2(theta) dphi^2
// Chart singularities: the horizon r = 2M (g_rr blows up; steps must shrink to zero there) and the polar
// axis sin(theta) = 0 (cot theta). Conserved along geodesics: E = (1 - 2M/r) k^t and L_z = r^2 sin^2 theta k^phi.
// With mass 0 this is flat space in spherical coordinates (MinkowskiSpherical).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/lanes.hpp"
#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/sin_cos.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/schwarzschild_lapse.hpp"
#include "grtrace/metric/spherical_chart.hpp"

#include <array>
#include <cmath>
#include <optional>

namespace grtrace {

struct SchwarzschildMetric {
  static constexpr std::string_view name = "schwarzschild";
  static constexpr Chart chart = Chart::spherical;
  double mass = 1.0;

  GRTRACE_HD Mat4 metric(const Vec4& x) const {
    const double r = x[1], f = lapse_squared(r), st = std::sin(x[2]);
    Mat4 g = Mat4::Zero();
    g(0, 0) = f;
    g(1, 1) = -1.0 / f;
    g(2, 2) = -r * r;
    g(3, 3) = -r * r * st * st;
    return g;
  }

  GRTRACE_HD Christoffel christoffel(const Vec4& x) const {
    const double r = x[1], m = mass, st = std::sin(x[2]), ct = std::cos(x[2]);
    Christoffel G;
    for (auto& gm : G) gm.setZero();
    G[0](0, 1) = G[0](1, 0) = m / (r * (r - 2 * m));
    G[1](0, 0) = m * (r - 2 * m) / (r * r * r);
    G[1](1, 1) = -m / (r * (r - 2 * m));
    G[1](2, 2) = -(r - 2 * m);
    G[1](3, 3) = -(r - 2 * m) * st * st;
    G[2](1, 2) = G[2](2, 1) = 1.0 / r;
    G[2](3, 3) = -st * ct;
    G[3](1, 3) = G[3](3, 1) = 1.0 / r;
    G[3](2, 3) = G[3](3, 2) = ct / st;
    return G;
  }

  /// -Gamma^mu_{ab} k^a k^b, written out (14 multiplies, one division by r, one by sin theta, one inline sincos).
  GRTRACE_HD Vec4 acceleration(const Vec4& x, const Vec4& k) const {
    const std::array<double, 4> a = acceleration_of<double>(x[1], x[2], k);
    return Vec4(a[0], a[1], a[2], a[3]);
  }

  /// Optional trait (metric/metric_traits.hpp): acceleration() of W rays at once, lane l of each argument ray l;
  /// every lane is acceleration()'s bits for that ray (the same formula, acceleration_of, on Lanes<W>).
  template <int W>
  std::array<Lanes<W>, 4> acceleration_lanes(const std::array<Lanes<W>, 4>& x,
                                             const std::array<Lanes<W>, 4>& k) const {
    if constexpr (W > native_lanes) {  // e.g. 8 under AVX2: as two of 4 (core/lanes.hpp, in_halves)
      const auto half = [&metric = *this](const auto& xh, const auto& kh) {
        return metric.template acceleration_lanes<W / 2>(xh, kh);
      };
      return in_halves<W>(x, k, half);
    } else {
      return acceleration_of<Lanes<W>>(x[1], x[2], k);
    }
  }

  /// The formula of acceleration(), once for both scalar types S (double, Lanes<W>): the same operations in the
  /// same order, so a lane cannot round differently from the scalar (constants are broadcast to every lane).
  /// k: the four components k[0..3] of type S (a Vec4 or a std::array of lanes).
  template <class S, class K>
  [[gnu::always_inline]] GRTRACE_HD std::array<S, 4> acceleration_of(const S& r, const S& theta, const K& k) const {
    const auto sc = polar_sin_cos(theta);  // inline (core/sin_cos.hpp): libm's call was a quarter of a step
    const double m = mass;
    const S inv_r = 1.0 / r, st = sc.sin, ct = sc.cos;
    const S r2m = r - 2.0 * m;
    const S kt = k[0], kr = k[1], kth = k[2], kph = k[3];
    const S a_trt = m / (r * r2m);  // Gamma^t_rt = -Gamma^r_rr
    // Each "p + q" of the formula is a mul_add (core/mul_add.hpp): one rounding where the processor fuses them.
    std::array<S, 4> a;
    a[0] = -2.0 * a_trt * kt * kr;
    a[1] = mul_add(r2m, mul_add(st * st * kph, kph, kth * kth),
                   mul_add(a_trt * kr, kr, -m * r2m * inv_r * inv_r * inv_r * kt * kt));
    a[2] = mul_add(st * ct * kph, kph, -2.0 * inv_r * kr * kth);
    a[3] = mul_add(-2.0 * (ct / st) * kth, kph, -2.0 * inv_r * kr * kph);
    return a;
  }

  GRTRACE_HD double radius(const Vec4& x) const { return x[1]; }
  GRTRACE_HD double horizon_radius() const { return 2.0 * mass; }
  /// 1 - 2M/r: g_tt, the squared lapse of the static observers (any scalar type: the planar tracer
  /// differentiates it, metric/static_spherical.hpp).
  template <class S>
  GRTRACE_HD S lapse_squared(const S& r) const {
    return schwarzschild_f(r, mass);
  }
  /// r = 3M, the circular photon orbit (optional trait of metric/static_spherical.hpp).
  GRTRACE_HD double photon_sphere_radius() const { return 3.0 * mass; }
  /// u'' = 3 M u^2 - u, the orbit equation of light in u = 1 / r (optional trait of metric/static_spherical.hpp:
  /// the planar tracer's table integrates it; tests check it against the generic derivative).
  GRTRACE_HD double planar_ray_curvature(double u) const { return (3.0 * mass * u - 1.0) * u; }

  /// Optional trait (metric/metric_traits.hpp): the exact continuation of a ray from y to infinity, by elliptic
  /// integrals (exact/schwarzschild_exact.hpp); nothing when it falls into the hole.
  GRTRACE_HD std::optional<SkyDirection> asymptotic_direction(const GeodesicState& y) const {
    return exact::asymptotic_direction(y, mass);
  }
  GRTRACE_HD Vec3 to_cartesian(const Vec4& x) const { return spherical_to_cartesian(x); }

  /// Killing energy E = g_tt k^t and axial angular momentum L_z = -g_phiphi k^phi.
  GRTRACE_HD double energy(const GeodesicState& y) const { return lapse_squared(y[1]) * y[4]; }
  GRTRACE_HD double angular_momentum(const GeodesicState& y) const {
    const double st = std::sin(y[2]);
    return y[1] * y[1] * st * st * y[7];
  }
  /// Total angular momentum |L| (conserved in every plane through the centre, not only the equator).
  GRTRACE_HD double total_angular_momentum(const GeodesicState& y) const {
    const double r2 = y[1] * y[1], st = std::sin(y[2]);
    return r2 * std::sqrt(y[6] * y[6] + st * st * y[7] * y[7]);
  }
};

/// Flat space in spherical coordinates: Schwarzschild with M = 0, under its own name.
struct MinkowskiSpherical : SchwarzschildMetric {
  static constexpr std::string_view name = "minkowski-spherical";
  static constexpr bool flat = true;  ///< optional trait: straight lines, never integrated (metric_traits.hpp)
  MinkowskiSpherical() : SchwarzschildMetric{0.0} {}
};

static_assert(MetricPolicy<SchwarzschildMetric>);
static_assert(MetricPolicy<MinkowskiSpherical>);

}  // namespace grtrace
