// The line profile of a thin disk (spectra/line_profile.hpp) against an independent computation: a direct
// integration over the image plane of the exact Schwarzschild disk map, written here from Darwin's orbit equation
// (u = 1/r as an elliptic function of the angle swept, inverted by Newton on the standard library's
// std::ellint_1), in polar screen coordinates (b, psi), each slice of constant psi sampled finely in b with its
// disk edges found by bisection. Also: the map's redshift against the disk's own emitter velocity, the order
// channels, and the transparent disk.
#include "grtrace/spectra/line_profile.hpp"

#include "grtrace/exact/kerr_null_geodesic.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/scene/thin_disk.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

namespace {

using namespace grtrace;
constexpr double kPi = std::numbers::pi;

/// Schwarzschild (M = 1), an observer at infinity at inclination i, a Keplerian disk r_in..r_out, emissivity r^-q.
/// The ray of impact parameter b lies in the plane of the line of sight n = (sin i, 0, cos i) and its screen
/// direction e (alpha = b e.(0, 1, 0), beta = b e.(-cos i, 0, sin i), towards the disk's axis); after sweeping
/// the angle gamma from infinity it is at cos(gamma) n + sin(gamma) e, and u = 1/r obeys Darwin's
/// (du/dgamma)^2 = 2u^3 - u^2 + 1/b^2. L_z = alpha sin i (the disk's sense fixes the sign: the profile is the
/// same for both, the image being mirrored).
struct SchwarzschildReference {
  double inclination, r_in, r_out, q;

  struct Hit {
    bool exists = false;
    double r = 0.0;
  };

  /// F^-1(T | k) on [0, pi/2] by safeguarded Newton on std::ellint_1; on [0, pi) by F(pi - x) = 2K - F(x).
  static double inverse_f(double target, double k) {
    const double kk = std::comp_ellint_1(k);
    if (target > kk) return kPi - inverse_f(2.0 * kk - target, k);
    double lo = 0.0, hi = kPi / 2.0, phi = std::clamp(target / kk * kPi / 2.0, lo, hi);
    for (int it = 0; it < 100; ++it) {
      const double f = std::ellint_1(k, phi) - target;
      (f > 0.0 ? hi : lo) = phi;
      double next = phi - f * std::sqrt(1.0 - k * k * std::sin(phi) * std::sin(phi));
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (std::abs(next - phi) < 1e-15) return next;
      phi = next;
    }
    return phi;
  }

  /// The real roots of 2u^3 - u^2 + 1/b^2 (Cardano / Viete on u = t + 1/6, one Newton step each in long double).
  static std::vector<double> cubic_roots(double b) {
    const double c = 1.0 / (b * b), p = -1.0 / 12.0, qq = c / 2.0 - 1.0 / 108.0;
    std::vector<double> u;
    const double disc = qq * qq / 4.0 + p * p * p / 27.0;
    if (disc > 0.0) {
      const double s = std::sqrt(disc);
      u.push_back(std::cbrt(-qq / 2.0 + s) + std::cbrt(-qq / 2.0 - s) + 1.0 / 6.0);
    } else {
      const double m = 2.0 * std::sqrt(-p / 3.0), th = std::acos(std::clamp(3.0 * qq / (p * m), -1.0, 1.0)) / 3.0;
      for (int j = 0; j < 3; ++j) u.push_back(m * std::cos(th - 2.0 * kPi * j / 3.0) + 1.0 / 6.0);
      std::sort(u.begin(), u.end());
    }
    for (double& x : u) {
      const long double v = x, f = 2.0L * v * v * v - v * v + static_cast<long double>(c), df = 6.0L * v * v - 2.0L * v;
      if (df != 0.0L) x = static_cast<double>(v - f / df);
    }
    return u;
  }

  /// The radius where the ray of impact parameter b has swept gamma from infinity, if it gets there (before it
  /// escapes again or falls in). Byrd & Friedman 233.00 (three real roots) and 239.00 (one).
  static Hit radius_after(double b, double gamma) {
    Hit hit;
    const std::vector<double> u = cubic_roots(b);
    if (u.size() == 3) {
      const double u1 = u[0], u2 = u[1], u3 = u[2];
      const double k = std::sqrt((u2 - u1) / (u3 - u1)), c = 2.0 / std::sqrt(2.0 * (u3 - u1));
      const double f0 = std::ellint_1(k, std::asin(std::sqrt(-u1 / (u2 - u1))));
      const double target = gamma / c + f0;
      if (!(target < 2.0 * std::comp_ellint_1(k) - f0)) return hit;  // escaped before
      const double s = std::sin(inverse_f(target, k));
      hit.exists = true;
      hit.r = 1.0 / (u1 + (u2 - u1) * s * s);
      return hit;
    }
    const double u1 = u[0], m = 0.5 * (0.5 - u1);
    const double n2 = -1.0 / (2.0 * b * b * u1) - m * m, big_a = std::sqrt((m - u1) * (m - u1) + n2);
    const double k = std::sqrt((big_a + m - u1) / (2.0 * big_a));
    auto amplitude = [&](double v) { return std::acos((big_a - (v - u1)) / (big_a + (v - u1))); };
    const double target = gamma * std::sqrt(2.0 * big_a) + std::ellint_1(k, amplitude(0.0));
    if (!(target < std::ellint_1(k, amplitude(0.5)))) return hit;  // fell in before
    const double c = std::cos(inverse_f(target, k));
    hit.exists = true;
    hit.r = 1.0 / (u1 + big_a * (1.0 - c) / (1.0 + c));
    return hit;
  }

  /// The impact parameter whose ray reaches r after sweeping gamma: r(b) rises from the horizon (or, for
  /// gamma < pi, from rays that fall in first) to infinity (rays that escape first); bisection, then regula falsi.
  static double impact_for(double r, double gamma) {
    const double bc = 3.0 * std::sqrt(3.0), nan = std::numeric_limits<double>::quiet_NaN();
    double lo = gamma < kPi ? 0.0 : bc - 3.0, hi = gamma < kPi ? 3.0 * r + 20.0 : 80.0, f_lo = nan, f_hi = nan;
    int last = 0;
    for (int it = 0; it < 300 && hi - lo > 1e-15 * hi; ++it) {
      double b = 0.5 * (lo + hi);
      if (std::isfinite(f_lo) && std::isfinite(f_hi)) {
        b = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        if (!(b > lo && b < hi)) b = 0.5 * (lo + hi);
      }
      const Hit h = radius_after(b, gamma);
      const double f = h.exists ? h.r - r : nan;
      if (h.exists && std::abs(f) < 1e-13 * r) return b;
      if (h.exists ? f < 0.0 : b < bc) {  // below r, or fell in first
        lo = b, f_lo = f;
        if (last == -1) f_hi *= 0.5;  // Illinois: the end kept twice has its value halved
        last = -1;
      } else {  // beyond r, or escaped first
        hi = b, f_hi = f;
        if (last == 1) f_lo *= 0.5;
        last = 1;
      }
    }
    return 0.5 * (lo + hi);
  }

  /// The profile of image order n (transparent disk: every crossing on it shines), energy flux per unit energy in
  /// each bin: the disk meshed in (log r, phi), each triangle carried to the screen with its corners (its area
  /// there the Jacobian), g and w = g^4 r^-q linear over it, the part in each bin clipped out as a polygon.
  std::vector<double> profile(int n, const std::vector<double>& edges, double e0, int radii, int angles) const {
    const double si = std::sin(inclination), ci = std::cos(inclination);
    struct Corner {
      double alpha, beta, g, w;
    };
    std::vector<Corner> corners(static_cast<std::size_t>((radii + 1) * angles));
    for (int i = 0; i <= radii; ++i)
      for (int j = 0; j < angles; ++j) {
        const double r = r_in * std::pow(r_out / r_in, static_cast<double>(i) / radii);
        const double phi = 2.0 * kPi * (j + 0.5) / angles;
        // the disk point p = (cos phi, sin phi, 0); e along p's part across n (against it for odd orders)
        const double cos_g0 = si * std::cos(phi), g0 = std::acos(cos_g0);
        const double gamma = n % 2 == 0 ? g0 + kPi * n : kPi * (n + 1) - g0;
        Vec3 e(std::cos(phi) - cos_g0 * si, std::sin(phi), -cos_g0 * ci);
        e *= (n % 2 == 0 ? 1.0 : -1.0) / e.norm();
        const double b = impact_for(r, gamma);
        const double alpha = b * e[1], beta = b * (-ci * e[0] + si * e[2]);
        const double g = std::sqrt(1.0 - 3.0 / r) / (1.0 - std::pow(r, -1.5) * alpha * si);
        corners[static_cast<std::size_t>(i * angles + j)] = {alpha, beta, g, g * g * g * g * std::pow(r, -q)};
      }
    std::vector<double> out(edges.size() - 1, 0.0);
    auto add = [&](const Corner& a, const Corner& b, const Corner& c) {
      for (std::size_t k = 0; k + 1 < edges.size(); ++k)
        out[k] += weight_between(a, b, c, edges[k] / e0, edges[k + 1] / e0);
    };
    for (int i = 0; i < radii; ++i)
      for (int j = 0; j < angles; ++j) {
        const auto at = [&](int ii, int jj) { return corners[static_cast<std::size_t>(ii * angles + jj % angles)]; };
        add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
    for (double& v : out) v /= edges[1] - edges[0];
    return out;
  }

  /// int over the screen triangle abc where lo <= g < hi of w (both linear): the triangle clipped by the two
  /// half-planes (Sutherland-Hodgman), its fan's areas times their corners' mean w.
  template <class C>
  static double weight_between(const C& a, const C& b, const C& c, double lo, double hi) {
    const double g_min = std::min({a.g, b.g, c.g}), g_max = std::max({a.g, b.g, c.g});
    if (g_max < lo || g_min >= hi) return 0.0;
    std::vector<std::array<double, 4>> poly{
        {a.alpha, a.beta, a.g, a.w}, {b.alpha, b.beta, b.g, b.w}, {c.alpha, c.beta, c.g, c.w}};
    auto clip = [&](double t, double sign) {  // keep sign * (g - t) >= 0
      std::vector<std::array<double, 4>> kept;
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const auto& p = poly[i];
        const auto& nx = poly[(i + 1) % poly.size()];
        const double dp = sign * (p[2] - t), dn = sign * (nx[2] - t);
        if (dp >= 0.0) kept.push_back(p);
        if ((dp >= 0.0) != (dn >= 0.0)) {
          const double s = dp / (dp - dn);
          std::array<double, 4> x{};
          for (std::size_t k = 0; k < 4; ++k) x[k] = p[k] + s * (nx[k] - p[k]);
          kept.push_back(x);
        }
      }
      poly = kept;
    };
    clip(lo, 1.0);
    clip(hi, -1.0);
    double sum = 0.0;
    for (std::size_t i = 1; i + 1 < poly.size(); ++i) {
      const auto &p = poly[0], &s = poly[i], &t = poly[i + 1];
      const double area = 0.5 * std::abs((s[0] - p[0]) * (t[1] - p[1]) - (t[0] - p[0]) * (s[1] - p[1]));
      sum += area * (p[3] + s[3] + t[3]) / 3.0;
    }
    return sum;
  }

  /// Per order n = 0, 1, 2 at a screen point: the radius of the crossing and g (nothing where the ray does not get
  /// there), for the pointwise check of the map.
  std::array<std::optional<std::array<double, 2>>, 3> at(double alpha, double beta) const {
    std::array<std::optional<std::array<double, 2>>, 3> out;
    const double b = std::hypot(alpha, beta), sin_psi = beta / b;
    const double gamma0 = kPi / 2.0 + std::atan(sin_psi * std::tan(inclination));
    for (std::size_t n = 0; n < 3; ++n) {
      const Hit h = radius_after(b, gamma0 + kPi * static_cast<double>(n));
      if (!h.exists) break;
      const double g = std::sqrt(1.0 - 3.0 / h.r) / (1.0 - std::pow(h.r, -1.5) * alpha * std::sin(inclination));
      out[n] = std::array<double, 2>{h.r, g};
    }
    return out;
  }
};

std::vector<double> uniform_edges(double lo, double hi, int bins) {
  std::vector<double> e(static_cast<std::size_t>(bins) + 1);
  for (int i = 0; i <= bins; ++i) e[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / bins;
  return e;
}

double peak_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
double worst_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

// The reference's mesh on the disk (log r, phi), fine enough that it is 1e-5 of the peak from a twice finer one.
#ifndef GRTRACE_LINE_REFERENCE_RADII
#define GRTRACE_LINE_REFERENCE_RADII 120
#define GRTRACE_LINE_REFERENCE_ANGLES 400
#endif
constexpr int kRadii = GRTRACE_LINE_REFERENCE_RADII, kAngles = GRTRACE_LINE_REFERENCE_ANGLES;

struct Case {
  double inclination_degrees;
  int bins;
};

}  // namespace

// The closed-form map's redshift (from the ray's k_t, k_phi and BPT's u^t, Omega) equals the redshift against
// ThinDisk's own emitter velocity (circular orbits from the metric) at the crossing's full state.
TEST(LineProfile, MapRedshiftEqualsTheDiskEmitters) {
  for (double spin : {0.0, 0.7, -0.9}) {
    KerrMetric metric;
    metric.spin = spin;
    const double r_in = 1.2 * metric.horizon_radius() + 4.0;
    for (int sense : {+1, -1}) {
      ThinDisk disk;
      disk.r_in = r_in;
      disk.r_out = 40.0;
      disk.sense = sense;
      const KerrDiskMap map(metric, 1e4, 1.1, disk.r_in, disk.r_out, sense);
      int checked = 0;
      for (double alpha = -30.0; alpha <= 30.0; alpha += 2.5)
        for (double beta = -30.0; beta <= 30.0; beta += 2.5) {
          const DiskRaySample s = map.sample(alpha, beta);
          const KerrNullGeodesic ray(metric, map.ray(alpha, beta), 1e5, 1.000001 * metric.horizon_radius());
          for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
            if (s.where[n] != DiskRaySample::on_disk) continue;
            const GeodesicState y = ray.crossing_state(static_cast<int>(n));
            EXPECT_NEAR(y[1], s.radius[n], 1e-12 * y[1]);
            const double g = redshift_at(metric, disk.emitter_velocity(metric, y.head<4>()), y);
            EXPECT_NEAR(s.redshift[n], g, 1e-11) << spin << " " << sense << " " << alpha << " " << beta;
            ++checked;
          }
        }
      EXPECT_GT(checked, 150);
    }
  }
}

// The closed-form map against Darwin's orbit at screen points around a Schwarzschild hole: where each order meets
// the plane, and g there (alpha mirrored: the reference's L_z = alpha sin i has the other sign convention).
TEST(LineProfile, SchwarzschildMapPointByPoint) {
  for (double inc_degrees : {30.0, 75.0}) {
    const double inc = inc_degrees * kPi / 180.0;
    const SchwarzschildReference ref{inc, 6.0, 30.0, 3.0};
    const KerrMetric metric;
    const KerrDiskMap map(metric, 1e8, inc, 6.0, 30.0);
    int compared = 0;
    for (double b = 0.3; b < 40.0; b += 0.37)
      for (double psi = 0.01; psi < 2.0 * kPi; psi += 0.05) {
        const double alpha = b * std::cos(psi), beta = b * std::sin(psi);
        const auto expected = ref.at(-alpha, beta);
        const DiskRaySample got = map.sample(alpha, beta);
        for (std::size_t n = 0; n < 3; ++n) {
          if (!expected[n] || (*expected[n])[0] > 1e3) continue;  // no crossing, or one far out (ill-conditioned)
          const auto& e = *expected[n];
          EXPECT_EQ(got.where[n], e[0] < 6.0     ? DiskRaySample::inside_edge
                                  : e[0] <= 30.0 ? DiskRaySample::on_disk
                                                 : DiskRaySample::beyond_edge);
          EXPECT_NEAR(got.radius[n], e[0], 2e-6 * e[0] * e[0]) << b << " " << psi << " order " << n;
          if (got.where[n] == DiskRaySample::on_disk) {
            EXPECT_NEAR(got.redshift[n], e[1], 1e-6) << b << " " << psi << " order " << n;
            ++compared;
          }
        }
      }
    EXPECT_GT(compared, 4000);
  }
}

// Schwarzschild disks (r 6..30, emissivity r^-3, transparent) at 30 and 75 degrees: every bin of orders 0, 1, 2 and
// of their sum within 1e-3 of the sum's peak in the independent integration, nearer at a finer mesh than at a
// coarser one.
TEST(LineProfile, SchwarzschildAgainstDirectIntegration) {
  constexpr double kE0 = 6.4;
  for (const Case c : {Case{30.0, 50}, Case{75.0, 60}}) {
    const double inc = c.inclination_degrees * kPi / 180.0;
    LineProfileSpec spec;
    spec.line_energy = kE0;
    spec.bins = c.bins;
    spec.energy_min = 0.4 * kE0;
    spec.energy_max = 1.4 * kE0;
    spec.transparent = true;
    const SchwarzschildReference ref{inc, 6.0, 30.0, 3.0};
    const std::vector<double> edges = uniform_edges(spec.energy_min, spec.energy_max, spec.bins);
    std::array<std::vector<double>, 3> expected;
    std::vector<double> expected_total(edges.size() - 1, 0.0);
    for (int n = 0; n < 3; ++n) {
      // n = 2 is ~1e-4 of the light: a mesh half as fine leaves it 1e-6 of the peak from a twice finer one
      const int coarser = n == 2 ? 2 : 1;
      expected[static_cast<std::size_t>(n)] = ref.profile(n, edges, kE0, kRadii / coarser, kAngles / coarser);
      for (std::size_t i = 0; i < expected_total.size(); ++i)
        expected_total[i] += expected[static_cast<std::size_t>(n)][i];
    }
    const double peak = peak_of(expected_total);

    const KerrMetric metric;  // spin 0
    const KerrDiskMap map(metric, 1e7, inc, 6.0, 30.0);
    double coarse_error = 0.0;
    for (const bool fine : {false, true}) {
      LineSampling sampling;  // fine: the defaults
      if (!fine) {
        sampling.finest_cell = 1.0 / 16.0;
        sampling.edge_tolerance = 1e-6;
        sampling.g_tolerance = 0.1;
        sampling.weight_tolerance = 1e-2;
      }
      const LineProfile got = line_profile(map, spec, sampling);
      ASSERT_EQ(got.flux.size(), expected_total.size());
      std::vector<double> got_012(got.flux.size(), 0.0);
      for (std::size_t i = 0; i < got_012.size(); ++i)
        got_012[i] = got.flux_by_order[0][i] + got.flux_by_order[1][i] + got.flux_by_order[2][i];
      const double total_error = worst_difference(got_012, expected_total) / peak;
      std::array<double, 3> order_error{};
      for (std::size_t n = 0; n < 3; ++n) order_error[n] = worst_difference(got.flux_by_order[n], expected[n]) / peak;
      std::printf("  i = %.0f, finest %.4f M: %ld rays, worst bin %.2e of the peak (n = 0: %.2e, 1: %.2e, 2: %.2e)\n",
                  c.inclination_degrees, sampling.finest_cell, got.rays, total_error, order_error[0], order_error[1],
                  order_error[2]);
      if (fine) {
        EXPECT_LT(total_error, 1e-3);
        for (std::size_t n = 0; n < 3; ++n) EXPECT_LT(order_error[n], 1e-3) << "order " << n;
        EXPECT_LT(total_error, coarse_error) << "refining the mesh did not bring it nearer";
      } else {
        coarse_error = total_error;
      }
      EXPECT_EQ(got.outside, 0.0);
      EXPECT_LE(got.uncovered, 4);  // the ray at the centre of the screen (radial: eta = 0), seen at each corner
    }
  }
}

// The order channels sum to the total bin by bin and in the totals; automatic bins hold every image's light (an
// inner edge near the horizon sends some at g -> 0, which the start grid does not see); a transparent disk shows the same n = 0 image
// and more light in every higher order (each ring is then the whole disk's, not only what the nearer images leave).
TEST(LineProfile, OrdersAndTransparentDisk) {
  KerrMetric metric;
  metric.spin = 0.9;
  const double r_in = 2.4;  // inside the prograde ISCO (2.32) is allowed: the map only needs r_in > r_+
  const KerrDiskMap map(metric, 1e5, 60.0 * kPi / 180.0, r_in, 20.0);
  LineProfileSpec spec;
  spec.bins = 40;
  LineSampling sampling;
  sampling.finest_cell = 1.0 / 32.0;
  const LineProfile opaque = line_profile(map, spec, sampling);
  spec.transparent = true;
  const LineProfile clear = line_profile(map, spec, sampling);
  for (const LineProfile* p : {&opaque, &clear}) {
    double sum_of_totals = 0.0;
    for (std::size_t b = 0; b < p->flux.size(); ++b) {
      double sum = 0.0;
      for (const auto& o : p->flux_by_order) sum += o[b];
      EXPECT_EQ(sum, p->flux[b]);
    }
    for (double t : p->total_by_order) sum_of_totals += t;
    EXPECT_EQ(sum_of_totals, p->total);
    EXPECT_GT(p->total_by_order[1], 0.0);
    EXPECT_GT(p->total_by_order[2], 0.0);
    EXPECT_EQ(p->outside, 0.0);  // automatic bins hold all the light (the range made again where they did not)
  }
  // The same first image: equal to the meshes' accuracy (the transparent disk's extra lit corners refine the mesh
  // elsewhere).
  const double peak = peak_of(opaque.flux);
  for (std::size_t b = 0; b < opaque.flux.size(); ++b)
    EXPECT_NEAR(opaque.flux_by_order[0][b], clear.flux_by_order[0][b], 1e-3 * peak);
  for (std::size_t n = 1; n < 3; ++n) EXPECT_GT(clear.total_by_order[n], 1.05 * opaque.total_by_order[n]) << n;
}

// Bad requests are refused before any work, saying what to change.
TEST(LineProfile, RefusesBadInput) {
  KerrMetric metric;
  EXPECT_THROW(KerrDiskMap(metric, 1e4, 1.0, 1.5, 20.0), std::invalid_argument);    // inside the horizon
  EXPECT_THROW(KerrDiskMap(metric, 1e4, 1.0, 2.9, 20.0), std::invalid_argument);  // inside the photon orbit (3 M)
  EXPECT_THROW(KerrDiskMap(metric, 1e4, 1.0, 10.0, 8.0), std::invalid_argument);    // r_out < r_in
  EXPECT_THROW(KerrDiskMap(metric, 100.0, 1.0, 6.0, 20.0), std::invalid_argument);  // camera too near
  EXPECT_THROW(KerrDiskMap(metric, 1e4, 0.0, 6.0, 20.0), std::invalid_argument);    // on the axis
  const KerrDiskMap map(metric, 1e4, 1.0, 6.0, 20.0);
  LineProfileSpec spec;
  spec.bins = 0;
  EXPECT_THROW(line_profile(map, spec), std::invalid_argument);
  spec = {};
  spec.energy_min = 5.0;
  spec.energy_max = 4.0;
  EXPECT_THROW(line_profile(map, spec), std::invalid_argument);
  spec = {};
  LineSampling sampling;
  sampling.finest_cell = 0.0;
  EXPECT_THROW(line_profile(map, spec, sampling), std::invalid_argument);
}
