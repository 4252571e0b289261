// grtrace/testing.hpp
// GoogleTest checks for metric policies, to call from a user's own test suite (link GTest; with the installed
// package: find_package(grtrace CONFIG REQUIRED COMPONENTS testing) and target grtrace::testing). The header-only
// core never includes this file.
//
// Takes:   a metric policy (MetricPolicy), events to check it at (or a Region to sample them from), optionally a
//          MetricComponents reference for its Christoffel symbols, and named conserved quantities (callables on
//          the state y = (x, k)).
// Returns: ::testing::AssertionResult from every check, so each one works as
//            EXPECT_TRUE(grtrace::testing::metric_is_lorentzian(metric, points));
//          and inside EXPECT_NONFATAL_FAILURE. A failure message names the metric, the component (g_{r r},
//          Gamma^theta_{phi phi}, acceleration^r, the quantity's name), the event (and k) and both values.
//          Each check reports ONE failure: the worst event (or the first failing ray), not one per event.
//          expect_valid_metric(...) / GRTRACE_EXPECT_VALID_METRIC(...) run the whole set with EXPECT_TRUE.
// Assumes: signature (+,-,-,-); spherical charts are (t, r, theta, phi) with x[1] the radial coordinate.
//
//   metric_is_symmetric      g_ab = g_ba
//   metric_is_lorentzian     one positive and three negative eigenvalues, none (near) zero
//   inverse_is_consistent    g g^-1 = 1 (M::inverse_metric when it has one, else Eigen's inverse of g)
//   christoffel_consistent   Gamma^mu_ab = Gamma^mu_ba; acceleration(x, k) = -Gamma^mu_ab k^a k^b of christoffel()
//   christoffel_matches      christoffel() and acceleration() against the automatic derivative of a reference g
//   conserved_along_null_geodesics   g(k, k) and each named quantity along random null rays (GeodesicTracer)
//   approaches_flat          g -> flat space (Minkowski in the same chart, or a given flat metric) at a radius
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/metric/auto_metric.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace grtrace::testing {

// ---- where to look -------------------------------------------------------------------------------------------

/// A shell of events: radial coordinate in [r_min, r_max] (x[1] for spherical charts, |x| for Cartesian ones),
/// theta at least theta_margin from the axis. r_min = r_max = 0 means "choose from the horizon".
struct Region {
  double r_min = 0.0;
  double r_max = 0.0;
  double theta_margin = 0.2;
};

/// Settings of the whole-metric check (expect_valid_metric); every tolerance is the one the single check takes.
struct MetricCheckOptions {
  Region points{};  ///< where the pointwise checks look (default: [1.1 r_h, 30 r_h], or [0.5, 30])
  Region rays{};    ///< where null rays start (default: [3 r_h, 15 r_h], or [2, 30])
  int point_count = 25;
  int ray_count = 6;
  std::uint32_t seed = 20261122u;
  double symmetry_tolerance = 1e-12;     ///< |g_ab - g_ba| / max |g|
  double inverse_tolerance = 1e-10;      ///< max |g g^-1 - 1|
  double christoffel_tolerance = 1e-11;  ///< relative, per symbol (absolute below 1e-300 of the largest)
  double ray_rtol = 1e-10;               ///< integrator tolerance of the conservation runs
  double conservation_tolerance = 1e-7;  ///< |Q - Q0| / (1 + |Q0|); g(k, k) relative to its terms
  double escape_radius = 0.0;            ///< 0: 2 * rays.r_max
  double flat_radius = 0.0;              ///< > 0: also check approaches_flat at this radius
  double flat_tolerance = 1e-6;
};

/// A named conserved quantity Q(y) (energy, angular momentum, Carter's constant ...).
struct Conserved {
  std::string name;
  std::function<double(const GeodesicState&)> value;
};

namespace detail {

/// A value with 10 significant digits (enough to tell two values apart that a check found different).
inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}
/// A difference or tolerance with 3 digits.
inline std::string small(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}
inline std::string vec(const Vec4& x) {
  return "(" + num(x[0]) + ", " + num(x[1]) + ", " + num(x[2]) + ", " + num(x[3]) + ")";
}

template <MetricPolicy M>
const char* coordinate(int i) {
  static constexpr std::array<const char*, 4> spherical = {"t", "r", "theta", "phi"};
  static constexpr std::array<const char*, 4> cartesian = {"t", "x", "y", "z"};
  const auto& names = M::chart == Chart::spherical ? spherical : cartesian;
  return names[static_cast<std::size_t>(i)];
}
/// "g_{t r} = g(0, 1)"
template <MetricPolicy M>
std::string g_name(int a, int b) {
  return std::string("g_{") + coordinate<M>(a) + " " + coordinate<M>(b) + "} = g(" + std::to_string(a) + ", " +
         std::to_string(b) + ")";
}
/// "Gamma^theta_{phi phi} = Gamma[2](3, 3)"
template <MetricPolicy M>
std::string gamma_name(int mu, int a, int b) {
  return std::string("Gamma^") + coordinate<M>(mu) + "_{" + coordinate<M>(a) + " " + coordinate<M>(b) + "} = Gamma[" +
         std::to_string(mu) + "](" + std::to_string(a) + ", " + std::to_string(b) + ")";
}
template <MetricPolicy M>
std::string who() {
  return std::string(M::name) + ": ";
}

template <class M>
concept has_inverse_metric = requires(const M m, const Vec4 x) {
  { m.inverse_metric(x) } -> std::convertible_to<Mat4>;
};

template <MetricPolicy M>
Region resolve_points(const M& m, Region r) {
  if (r.r_max > r.r_min) return r;
  const double rh = m.horizon_radius();
  r.r_min = rh > 0.0 ? 1.1 * rh : 0.5;
  r.r_max = rh > 0.0 ? 30.0 * rh : 30.0;
  return r;
}
template <MetricPolicy M>
Region resolve_rays(const M& m, Region r) {
  if (r.r_max > r.r_min) return r;
  const double rh = m.horizon_radius();
  r.r_min = rh > 0.0 ? 3.0 * rh : 2.0;
  r.r_max = rh > 0.0 ? 15.0 * rh : 30.0;
  return r;
}

}  // namespace detail

/// `count` random events of the region in M's chart (t in [-10, 10]).
template <MetricPolicy M>
std::vector<Vec4> sample_events(const M& metric, Region region, int count, std::uint32_t seed = 20261122u) {
  region = detail::resolve_points(metric, region);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec4> out;
  for (int i = 0; i < count; ++i) {
    const double t = 20.0 * u(rng) - 10.0, r = region.r_min + (region.r_max - region.r_min) * u(rng);
    const double theta = region.theta_margin + (std::numbers::pi - 2.0 * region.theta_margin) * u(rng);
    const double phi = 2.0 * std::numbers::pi * u(rng);
    if constexpr (M::chart == Chart::spherical) {
      out.emplace_back(t, r, theta, phi);
    } else {
      out.emplace_back(t, r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi),
                       r * std::cos(theta));
    }
  }
  return out;
}

// ---- pointwise checks ---------------------------------------------------------------------------------------

/// g_ab = g_ba to `tolerance` relative to the largest component.
template <MetricPolicy M>
::testing::AssertionResult metric_is_symmetric(const M& metric, const std::vector<Vec4>& points,
                                               double tolerance = 1e-12) {
  for (const Vec4& x : points) {
    const Mat4 g = metric.metric(x);
    const double scale = std::max(g.cwiseAbs().maxCoeff(), 1e-300);
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b)
        if (!(std::abs(g(a, b) - g(b, a)) <= tolerance * scale))
          return ::testing::AssertionFailure()
                 << detail::who<M>() << "g is not symmetric at x = " << detail::vec(x) << ": "
                 << detail::g_name<M>(a, b) << " is " << detail::num(g(a, b)) << " but " << detail::g_name<M>(b, a)
                 << " is " << detail::num(g(b, a)) << " (difference " << detail::small(g(a, b) - g(b, a)) << " > "
                 << detail::small(tolerance) << " of the largest component " << detail::num(scale) << ")";
  }
  return ::testing::AssertionSuccess();
}

/// Signature (+,-,-,-): one positive and three negative eigenvalues of g, each at least `tolerance` times the
/// largest in size. The message lists the eigenvalues and every diagonal component whose sign contradicts
/// (+,-,-,-) (the usual typo).
template <MetricPolicy M>
::testing::AssertionResult metric_is_lorentzian(const M& metric, const std::vector<Vec4>& points,
                                                double tolerance = 1e-12) {
  for (const Vec4& x : points) {
    const Mat4 g = metric.metric(x);
    if (!g.allFinite())
      return ::testing::AssertionFailure() << detail::who<M>() << "g is not finite at x = " << detail::vec(x);
    const Mat4 sym = 0.5 * (g + g.transpose());
    const Vec4 ev = Eigen::SelfAdjointEigenSolver<Mat4>(sym, Eigen::EigenvaluesOnly).eigenvalues();
    const double big = ev.cwiseAbs().maxCoeff();
    int pos = 0, neg = 0;
    for (int i = 0; i < 4; ++i) {
      if (ev[i] > tolerance * big) ++pos;
      else if (ev[i] < -tolerance * big) ++neg;
    }
    if (pos == 1 && neg == 3) continue;
    auto f = ::testing::AssertionFailure();
    f << detail::who<M>() << "g is not Lorentzian (+,-,-,-) at x = " << detail::vec(x) << ": eigenvalues "
      << detail::vec(ev) << " (" << pos << " positive, " << neg << " negative, " << 4 - pos - neg << " zero)";
    for (int a = 0; a < 4; ++a) {
      const bool wrong = a == 0 ? g(a, a) < 0.0 : g(a, a) > 0.0;
      if (wrong)
        f << "; " << detail::g_name<M>(a, a) << " = " << detail::num(g(a, a)) << " should be "
          << (a == 0 ? "positive" : "negative");
    }
    return f;
  }
  return ::testing::AssertionSuccess();
}

/// g g^-1 = 1 within `tolerance` (each entry). Uses metric.inverse_metric(x) when M provides one; otherwise Eigen's
/// inverse of g, so the check then says whether g is invertible to working precision.
template <MetricPolicy M>
::testing::AssertionResult inverse_is_consistent(const M& metric, const std::vector<Vec4>& points,
                                                 double tolerance = 1e-10) {
  for (const Vec4& x : points) {
    const Mat4 g = metric.metric(x);
    Mat4 g_inv;
    if constexpr (detail::has_inverse_metric<M>) g_inv = metric.inverse_metric(x);
    else g_inv = g.inverse();
    const Mat4 p = g * g_inv;
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const double want = a == b ? 1.0 : 0.0;
        if (!(std::abs(p(a, b) - want) <= tolerance))
          return ::testing::AssertionFailure()
                 << detail::who<M>() << "g g^-1 is not the identity at x = " << detail::vec(x) << ": entry (" << a
                 << ", " << b << ") is " << detail::num(p(a, b)) << " instead of " << detail::num(want)
                 << " (tolerance " << detail::small(tolerance) << "; det g = " << detail::num(g.determinant())
                 << (detail::has_inverse_metric<M> ? ", inverse from inverse_metric()" : ", inverse of g") << ")";
      }
  }
  return ::testing::AssertionSuccess();
}

namespace detail {

/// Worst relative symbol mismatch of `got` against `want` at one event ("" when within tolerance).
template <MetricPolicy M>
std::string compare_christoffel(const Christoffel& got, const Christoffel& want, double rtol, const char* got_what,
                                const char* want_what, const Vec4& x) {
  double largest = 0.0;
  for (const Mat4& G : want) largest = std::max(largest, G.cwiseAbs().maxCoeff());
  double worst = -1.0;
  int wm = 0, wa = 0, wb = 0;
  for (int mu = 0; mu < 4; ++mu)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        const double g = got[static_cast<std::size_t>(mu)](a, b), w = want[static_cast<std::size_t>(mu)](a, b);
        const double scale = std::max(std::abs(w), 1e-300 + 1e-3 * largest);  // vanishing symbols: vs the largest
        const double err = std::abs(g - w) / scale;
        if ((!(err <= rtol) || !std::isfinite(g)) && (err > worst || !std::isfinite(g))) {
          worst = std::isfinite(err) ? err : 1e300;
          wm = mu, wa = a, wb = b;
        }
      }
  if (worst < 0.0) return {};
  const double g = got[static_cast<std::size_t>(wm)](wa, wb), w = want[static_cast<std::size_t>(wm)](wa, wb);
  return gamma_name<M>(wm, wa, wb) + " at x = " + vec(x) + ": " + got_what + " gives " + num(g) + " but " + want_what +
         " gives " + num(w) + " (relative difference " + small(worst) + " > " + small(rtol) + ")";
}

/// Worst component of acceleration(x, k) against -Gamma(k, k) ("" when within tolerance); relative to the size of
/// the terms sum |Gamma^mu_ab k^a k^b|.
template <MetricPolicy M>
std::string compare_acceleration(const Vec4& got, const Christoffel& gamma, const Vec4& x, const Vec4& k, double rtol,
                                 const char* want_what) {
  const Vec4 want = acceleration_from_christoffel(gamma, k);
  for (int mu = 0; mu < 4; ++mu) {
    const Mat4& G = gamma[static_cast<std::size_t>(mu)];
    const double terms = k.cwiseAbs().dot(G.cwiseAbs() * k.cwiseAbs());
    const double err = std::abs(got[mu] - want[mu]) / std::max(terms, 1e-300);
    if (!(err <= rtol))
      return std::string("acceleration^") + coordinate<M>(mu) + " = acceleration(x, k)[" + std::to_string(mu) +
             "] at x = " + vec(x) + ", k = " + vec(k) + ": acceleration() gives " + num(got[mu]) + " but -Gamma^" +
             coordinate<M>(mu) + "_ab k^a k^b from " + want_what + " gives " + num(want[mu]) +
             " (relative difference " + small(err) + " > " + small(rtol) + ")";
  }
  return {};
}

inline Vec4 random_direction(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Vec4(n(rng), n(rng), n(rng), n(rng));
}

}  // namespace detail

/// christoffel() symmetric in its lower indices, and acceleration(x, k) = -Gamma^mu_ab k^a k^b from christoffel()
/// for a random k at each event (the two are written separately in closed-form metrics, and AutoMetric's
/// acceleration uses C::depends_on where christoffel() does not: this catches a wrong depends_on).
template <MetricPolicy M>
::testing::AssertionResult christoffel_consistent(const M& metric, const std::vector<Vec4>& points, double rtol = 1e-11,
                                                  std::uint32_t seed = 7u) {
  std::mt19937 rng(seed);
  for (const Vec4& x : points) {
    const Christoffel G = metric.christoffel(x);
    for (int mu = 0; mu < 4; ++mu) {
      const Mat4& Gm = G[static_cast<std::size_t>(mu)];
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          if (!(std::abs(Gm(a, b) - Gm(b, a)) <= rtol * std::max({std::abs(Gm(a, b)), std::abs(Gm(b, a)), 1e-300})))
            return ::testing::AssertionFailure()
                   << detail::who<M>()
                   << "christoffel() is not symmetric in its lower indices at x = " << detail::vec(x) << ": "
                   << detail::gamma_name<M>(mu, a, b) << " is " << detail::num(Gm(a, b)) << " but "
                   << detail::gamma_name<M>(mu, b, a) << " is " << detail::num(Gm(b, a));
    }
    const Vec4 k = detail::random_direction(rng);
    const std::string bad = detail::compare_acceleration<M>(metric.acceleration(x, k), G, x, k, rtol, "christoffel()");
    if (!bad.empty()) return ::testing::AssertionFailure() << detail::who<M>() << bad;
  }
  return ::testing::AssertionSuccess();
}

/// The metric's christoffel() and acceleration() against the automatic derivative of `reference`'s g_{mu nu}
/// (AutoMetric<C>): the check for a hand-written metric (give its components as the reference), or for two
/// charts/metrics that must agree. Also checks that metric() equals the reference's g.
template <MetricPolicy M, MetricComponents C>
::testing::AssertionResult christoffel_matches(const M& metric, const C& reference, const std::vector<Vec4>& points,
                                               double rtol = 1e-11, std::uint32_t seed = 11u) {
  const AutoMetric<C> automatic{reference};
  std::mt19937 rng(seed);
  for (const Vec4& x : points) {
    const Mat4 g = metric.metric(x), g_ref = automatic.metric(x);
    const double scale = std::max(g_ref.cwiseAbs().maxCoeff(), 1e-300);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (!(std::abs(g(a, b) - g_ref(a, b)) <= rtol * scale))
          return ::testing::AssertionFailure()
                 << detail::who<M>() << detail::g_name<M>(a, b) << " at x = " << detail::vec(x) << " is "
                 << detail::num(g(a, b)) << " but the reference " << C::name << " has " << detail::num(g_ref(a, b));
    const Christoffel ad = automatic.christoffel(x);
    std::string bad = detail::compare_christoffel<M>(metric.christoffel(x), ad, rtol, "christoffel()",
                                                     "differentiating the reference g", x);
    if (bad.empty()) {
      const Vec4 k = detail::random_direction(rng);
      bad =
          detail::compare_acceleration<M>(metric.acceleration(x, k), ad, x, k, rtol, "the differentiated reference g");
    }
    if (!bad.empty()) return ::testing::AssertionFailure() << detail::who<M>() << bad;
  }
  return ::testing::AssertionSuccess();
}

// ---- along geodesics ----------------------------------------------------------------------------------------

/// A null k at x with the given spatial direction: k^0 from g(k, k) = 0, the future root (k^0 > 0) where g_00 > 0.
/// Spatial components are normalised like an orthonormal frame of flat space (k^theta ~ 1/r, k^phi ~ 1/(r sin)).
template <MetricPolicy M>
std::optional<Vec4> null_direction(const M& metric, const Vec4& x, const Vec3& n) {
  Vec4 k = Vec4::Zero();
  if constexpr (M::chart == Chart::spherical) {
    k[1] = n[0];
    k[2] = n[1] / x[1];
    k[3] = n[2] / (x[1] * std::sin(x[2]));
  } else {
    k.tail<3>() = n;
  }
  const Mat4 g = metric.metric(x);
  const double A = g(0, 0), B = g(0, 1) * k[1] + g(0, 2) * k[2] + g(0, 3) * k[3];
  const double C = k.tail<3>().dot(g.bottomRightCorner<3, 3>() * k.tail<3>());
  double k0;
  if (std::abs(A) < 1e-14 * g.cwiseAbs().maxCoeff()) {
    if (B == 0.0) return std::nullopt;
    k0 = -C / (2.0 * B);
  } else {
    const double disc = B * B - A * C;
    if (!(disc >= 0.0)) return std::nullopt;
    k0 = (-B + std::sqrt(disc)) / A;  // A > 0: the larger root, positive when C <= 0
    if (A < 0.0 && k0 < 0.0) k0 = (-B - std::sqrt(disc)) / A;
  }
  k[0] = k0;
  if (!k.allFinite()) return std::nullopt;
  return k;
}

/// Traces `rays` random null geodesics (starts in `region`, directions uniform) with GeodesicTracer<M, Tableau,
/// PIController> at integrator tolerance rtol, and checks at the end of every accepted step that g(k, k) stays 0
/// (relative to its terms sum |g_mn k^m k^n|) and each named quantity Q stays at its start value:
/// |Q - Q0| <= tolerance (1 + |Q0|). A ray that ends in an integration failure (max_steps, step_underflow,
/// non_finite) fails the check too. The first ray with a problem gives one failure, one line per quantity that
/// moved (its worst point along the ray). The tracer's own constraint guard is off, so a broken metric shows as
/// "g(k, k) not conserved" rather than as an early non_finite.
template <MetricPolicy M, ExplicitTableau Tableau = DormandPrince54>
::testing::AssertionResult conserved_along_null_geodesics(const M& metric, const std::vector<Conserved>& quantities,
                                                          const MetricCheckOptions& options = {}) {
  const Region region = detail::resolve_rays(metric, options.rays);
  TraceSettings settings;
  settings.integrator.tolerance = {options.ray_rtol, 1e-2 * options.ray_rtol};
  settings.escape_radius = options.escape_radius > 0.0 ? options.escape_radius : 2.0 * region.r_max;
  settings.max_steps = 50000;
  settings.constraint_tolerance = 0.0;  // the check watches g(k, k) itself and says which quantity broke
  const GeodesicTracer<M, Tableau, PIController> tracer(metric, settings);
  std::mt19937 rng(options.seed + 1u);
  std::normal_distribution<double> n(0.0, 1.0);
  const std::vector<Vec4> starts = sample_events(metric, region, 4 * options.ray_count, options.seed + 2u);
  int traced = 0;
  for (const Vec4& x : starts) {
    if (traced == options.ray_count) break;
    const auto k = null_direction(metric, x, Vec3(n(rng), n(rng), n(rng)).normalized());
    if (!k) continue;
    ++traced;
    const GeodesicState y0 = make_state(x, *k);
    std::vector<double> q0;
    for (const Conserved& q : quantities) q0.push_back(q.value(y0));
    // Worst violation of each quantity (slot 0: g(k, k)), where it happened and the value there.
    struct Worst {
      double error = 0.0, value = 0.0;
      int step = -1;
      GeodesicState y;
    };
    std::vector<Worst> worst(quantities.size() + 1);
    int step = 0;
    auto note = [&](std::size_t i, double error, double value, const GeodesicState& y) {
      if (!(error <= options.conservation_tolerance) && (worst[i].step < 0 || error > worst[i].error)) {
        worst[i] = {std::isfinite(error) ? error : 1e300, value, step, y};
      }
    };
    auto check = [&](const GeodesicState& y) {
      note(0, constraint_violation(metric, y, 0.0), inner_product(metric, y.head<4>(), y.tail<4>(), y.tail<4>()), y);
      for (std::size_t i = 0; i < quantities.size(); ++i) {
        const double qv = quantities[i].value(y);
        note(i + 1, std::abs(qv - q0[i]) / (1.0 + std::abs(q0[i])), qv, y);
      }
    };
    auto observer = [&](const auto& integ, double theta_end) {
      ++step;
      if (theta_end == 1.0) check(integ.state());
    };
    const TraceResult r = tracer.trace_observed(y0, observer);
    check(r.step_end_state);
    const std::string ray =
        "null geodesic " + std::to_string(traced) + " from x = " + detail::vec(x) + ", k = " + detail::vec(*k);
    // One failure for the ray, one line per quantity that moved (the user's first, g(k, k) last).
    std::string lines;
    for (std::size_t j = 1; j <= quantities.size() + 1; ++j) {
      const std::size_t i = j % (quantities.size() + 1);
      const Worst& w = worst[i];
      if (w.step < 0) continue;
      if (!lines.empty()) lines += "\n" + detail::who<M>();
      if (i == 0) {
        lines += "g(k, k) not conserved along the " + ray + ": 0 at the start, " + detail::num(w.value) + " at step " +
                 std::to_string(w.step) + " (x = " + detail::vec(w.y.template head<4>()) + "; relative to its terms " +
                 detail::small(w.error) + " > " + detail::small(options.conservation_tolerance) + ")";
      } else {
        lines += quantities[i - 1].name + " not conserved along the " + ray + ": " + detail::num(q0[i - 1]) +
                 " at the start, " + detail::num(w.value) + " at step " + std::to_string(w.step) +
                 " (x = " + detail::vec(w.y.template head<4>()) +
                 "; |change| / (1 + |start|) = " + detail::small(w.error) + " > " +
                 detail::small(options.conservation_tolerance) + ")";
      }
    }
    if (is_failure(r.status)) {
      if (!lines.empty()) lines += "\n" + detail::who<M>();
      lines += "the " + ray + " ended as " + std::string(to_string(r.status)) + " after " + std::to_string(r.accepted) +
               " steps at x = " + detail::vec(r.final_state.template head<4>()) + " (rtol " +
               detail::small(options.ray_rtol) + ")";
    }
    if (!lines.empty()) return ::testing::AssertionFailure() << detail::who<M>() << lines;
  }
  if (traced == 0)
    return ::testing::AssertionFailure() << detail::who<M>() << "no null direction could be built in the region r in ["
                                         << region.r_min << ", " << region.r_max << "]";
  return ::testing::AssertionSuccess();
}

// ---- limits -------------------------------------------------------------------------------------------------

/// Flat far away: at radius R (x[1] = R for spherical charts, |x| = R for Cartesian ones; a few directions), every
/// g_ab is within `tolerance` of `flat`'s, measured in units of sqrt(s_a s_b) with s_a the largest |flat_ab| of row
/// a (the orthonormal-frame size, so r^2 sin^2 theta components are compared relatively).
template <MetricPolicy M, MetricPolicy Flat>
::testing::AssertionResult approaches_flat(const M& metric, double radius, double tolerance, const Flat& flat) {
  for (double theta : {0.4, 1.3, 2.2})
    for (double phi : {0.1, 2.5}) {
      Vec4 x;
      if constexpr (M::chart == Chart::spherical) x = Vec4(0.0, radius, theta, phi);
      else
        x = Vec4(0.0, radius * std::sin(theta) * std::cos(phi), radius * std::sin(theta) * std::sin(phi),
                 radius * std::cos(theta));
      const Mat4 g = metric.metric(x), eta = flat.metric(x);
      Vec4 s;
      for (int a = 0; a < 4; ++a) s[a] = std::max(eta.row(a).cwiseAbs().maxCoeff(), 1e-300);
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b) {
          const double err = std::abs(g(a, b) - eta(a, b)) / std::sqrt(s[a] * s[b]);
          if (!(err <= tolerance))
            return ::testing::AssertionFailure()
                   << detail::who<M>() << "not flat at radius " << detail::num(radius) << ": "
                   << detail::g_name<M>(a, b) << " at x = " << detail::vec(x) << " is " << detail::num(g(a, b))
                   << " but flat space (" << Flat::name << ") has " << detail::num(eta(a, b)) << " (difference "
                   << detail::small(err) << " in frame units > " << detail::small(tolerance) << ")";
        }
    }
  return ::testing::AssertionSuccess();
}

/// ... against Minkowski in M's chart (MinkowskiSpherical or MinkowskiMetric).
template <MetricPolicy M>
::testing::AssertionResult approaches_flat(const M& metric, double radius, double tolerance = 1e-6) {
  if constexpr (M::chart == Chart::spherical) return approaches_flat(metric, radius, tolerance, MinkowskiSpherical{});
  else return approaches_flat(metric, radius, tolerance, MinkowskiMetric{});
}

// ---- everything at once ---------------------------------------------------------------------------------------

/// Runs every check with EXPECT_TRUE (one failure per failed check): symmetry, signature, inverse, Christoffel
/// consistency, conservation of g(k, k) and `quantities` along null rays, and approaches_flat when
/// options.flat_radius > 0.
template <MetricPolicy M>
void expect_valid_metric(const M& metric, const std::vector<Conserved>& quantities = {},
                         const MetricCheckOptions& options = {}) {
  const std::vector<Vec4> points = sample_events(metric, options.points, options.point_count, options.seed);
  EXPECT_TRUE(metric_is_symmetric(metric, points, options.symmetry_tolerance));
  EXPECT_TRUE(metric_is_lorentzian(metric, points));
  EXPECT_TRUE(inverse_is_consistent(metric, points, options.inverse_tolerance));
  EXPECT_TRUE(christoffel_consistent(metric, points, options.christoffel_tolerance));
  EXPECT_TRUE(conserved_along_null_geodesics(metric, quantities, options));
  if (options.flat_radius > 0.0) {
    EXPECT_TRUE(approaches_flat(metric, options.flat_radius, options.flat_tolerance));
  }
}

/// ... and christoffel()/acceleration() against the automatic derivative of `reference`.
template <MetricPolicy M, MetricComponents C>
void expect_valid_metric(const M& metric, const C& reference, const std::vector<Conserved>& quantities = {},
                         const MetricCheckOptions& options = {}) {
  expect_valid_metric(metric, quantities, options);
  const std::vector<Vec4> points = sample_events(metric, options.points, options.point_count, options.seed);
  EXPECT_TRUE(christoffel_matches(metric, reference, points, options.christoffel_tolerance));
}

}  // namespace grtrace::testing

/// GRTRACE_EXPECT_VALID_METRIC(metric [, reference] [, quantities] [, options]): expect_valid_metric with the
/// caller's file and line in every failure.
#define GRTRACE_EXPECT_VALID_METRIC(...)                           \
  do {                                                             \
    SCOPED_TRACE("GRTRACE_EXPECT_VALID_METRIC(" #__VA_ARGS__ ")"); \
    ::grtrace::testing::expect_valid_metric(__VA_ARGS__);          \
  } while (false)
