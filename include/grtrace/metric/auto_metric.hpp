// grtrace/metric/auto_metric.hpp
// A metric policy from the metric components alone: the Christoffel symbols and the geodesic acceleration come
// from forward-mode automatic differentiation (metric/dual.hpp) of g_{mu nu}(x).
//
// Takes:   a components type C (concept MetricComponents below) that writes g_{mu nu}(x) ONCE as a template on
//          the scalar type, plus radius(x) and horizon_radius():
//            struct MyMetric {
//              static constexpr std::string_view name = "my-metric";
//              static constexpr grtrace::Chart chart = grtrace::Chart::spherical;
//              double mass = 1.0;
//              template <class S> Eigen::Matrix<S, 4, 4> metric_components(const Eigen::Matrix<S, 4, 1>& x) const;
//              double radius(const grtrace::Vec4& x) const;
//              double horizon_radius() const;
//              grtrace::Vec3 to_cartesian(const grtrace::Vec4& x) const;   // optional: default from the chart
//              static constexpr std::array<int, 2> depends_on = {1, 2};      // optional: see below
//            };
//          Inside metric_components write `using std::sin;` (etc.) and call sin(...) unqualified, so the same code
//          runs on double and on Dual<4> (std::sin(x) would not accept a Dual).
// Returns: AutoMetric<C>, which derives from C (so C's members stay reachable: m.mass, m.energy(y), ...) and adds
//          metric(x), inverse_metric(x), christoffel(x), acceleration(x, k) and to_cartesian(x): it satisfies
//          MetricPolicy and goes into GeodesicTracer unchanged.
// Assumes: g is symmetric and non-degenerate at the points asked for. The derivative pass reads only the upper
//          triangle (the 10 independent components); metric(x) returns C's matrix as written, so the testing kit
//          (grtrace/testing.hpp) still sees a lower triangle that disagrees.
//
// Optional C::depends_on lists the coordinates g depends on (the others are Killing directions, e.g. t and phi of
// a static axisymmetric metric): acceleration() then differentiates along those only (Dual<2> instead of Dual<4>
// for g(r, theta): about half the work). jet() and christoffel() always differentiate along all four, so they stay
// the reference: a wrong depends_on makes acceleration() disagree with -Gamma(k, k) from christoffel(), which
// grtrace::testing::christoffel_consistent (testing.hpp) reports.
//
// Cost of acceleration(): one evaluation of g with Dual<K> (value + K partial derivatives per component; sin,
// sqrt, 1/r ... are evaluated once each, on the value), then the contraction
//     Gamma_{nu ab} k^a k^b = (d_k g)_{nu b} k^b - 1/2 d_nu (g_ab k^a k^b),   d_k = k^a d_a,
// done on the gradients of the 10 upper-triangle components directly (no 4x4x4 table), and one solve with g
// (4 divisions when g is diagonal at x, else a 4x4 inverse). The full table is only built by christoffel(),
// which tests and tools use.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/dual.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/spherical_chart.hpp"

#include <Eigen/LU>

#include <array>
#include <concepts>
#include <cstddef>
#include <string_view>
#include <type_traits>

namespace grtrace {

/// The scalar AutoMetric differentiates with: a value and the 4 partial derivatives d/dx^0 .. d/dx^3.
using MetricDual = Dual<4>;
template <class S>
using Vec4Of = Eigen::Matrix<S, 4, 1>;
template <class S>
using Mat4Of = Eigen::Matrix<S, 4, 4>;

namespace auto_metric_detail {

template <class C>
concept has_name = requires {
  { C::name } -> std::convertible_to<std::string_view>;
};
template <class C>
concept has_chart = requires {
  { C::chart } -> std::convertible_to<Chart>;
};
/// metric_components callable on a plain event, returning Eigen::Matrix<double, 4, 4>.
template <class C>
concept components_of_double = requires(const C c, const Vec4 x) {
  { c.metric_components(x) } -> std::same_as<Mat4>;
};
/// ... also when the object is not const (to tell a missing `const` from a missing function).
template <class C>
concept components_of_double_nonconst = requires(C c, const Vec4 x) {
  { c.metric_components(x) } -> std::same_as<Mat4>;
};
/// metric_components callable on Dual numbers, returning a matrix of Duals (so it is a template on the scalar
/// type: a function of Vec4 would either not accept the Duals or return doubles, which have lost the derivative).
template <class C>
concept components_of_dual = requires(const C c, const Vec4Of<MetricDual> x) {
  { c.metric_components(x) } -> std::same_as<Mat4Of<MetricDual>>;
};
template <class C>
concept has_radius = requires(const C c, const Vec4 x) {
  { c.radius(x) } -> std::convertible_to<double>;
};
template <class C>
concept has_horizon_radius = requires(const C c) {
  { c.horizon_radius() } -> std::convertible_to<double>;
};
template <class C>
concept has_to_cartesian = requires(const C c, const Vec4 x) {
  { c.to_cartesian(x) } -> std::convertible_to<Vec3>;
};

/// Optional: `static constexpr std::array<int, K> depends_on = {1, 2};` lists the coordinates g depends on.
template <class C>
concept declares_dependencies = requires {
  C::depends_on;
};

template <class C>
constexpr GRTRACE_HD auto active_coordinates() {
  if constexpr (declares_dependencies<C>) {
    return C::depends_on;
  } else {
    return std::array<int, 4>{0, 1, 2, 3};
  }
}

/// depends_on is a std::array<int, K>, 1 <= K <= 4, of distinct increasing indices in 0..3.
template <class C>
constexpr GRTRACE_HD bool dependencies_valid() {
  constexpr auto a = active_coordinates<C>();
  if (a.size() < 1 || a.size() > 4) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] < 0 || a[i] > 3) return false;
    if (i > 0 && a[i] <= a[i - 1]) return false;
  }
  return true;
}

}  // namespace auto_metric_detail

/// What a user writes to get a metric by automatic differentiation (see the top of this header).
template <class C>
concept MetricComponents = auto_metric_detail::has_name<C> && auto_metric_detail::has_chart<C> &&
    auto_metric_detail::components_of_double<C> && auto_metric_detail::components_of_dual<C> &&
    auto_metric_detail::has_radius<C> && auto_metric_detail::has_horizon_radius<C>;

/// g_{ab} and its first derivatives at one event.
struct MetricJet {
  Mat4 g;                  ///< g_{ab}, symmetric (mirrored from the upper triangle)
  std::array<Mat4, 4> dg;  ///< dg[c](a, b) = d g_{ab} / d x^c
};

/// A diagonal metric diag(g00, g11, g22, g33) in any scalar type (most of the example metrics).
template <class S>
GRTRACE_HD Mat4Of<S> diagonal_metric(const S& g00, const S& g11, const S& g22, const S& g33) {
  Mat4Of<S> g = Mat4Of<S>::Zero();
  g(0, 0) = g00;
  g(1, 1) = g11;
  g(2, 2) = g22;
  g(3, 3) = g33;
  return g;
}

template <class C>
struct AutoMetric : C {
  // Each requirement on C on its own, so the compiler names the one that is missing.
  static_assert(auto_metric_detail::has_name<C>,
                "AutoMetric<C>: C needs `static constexpr std::string_view name = \"...\";`");
  static_assert(auto_metric_detail::has_chart<C>,
                "AutoMetric<C>: C needs `static constexpr grtrace::Chart chart = grtrace::Chart::spherical;` "
                "(or Chart::cartesian)");
  static_assert(auto_metric_detail::components_of_double<C> || !auto_metric_detail::components_of_double_nonconst<C>,
                "AutoMetric<C>: C::metric_components must be a const member function");
  static_assert(auto_metric_detail::components_of_double<C> || auto_metric_detail::components_of_double_nonconst<C>,
                "AutoMetric<C>: C needs `template <class S> Eigen::Matrix<S, 4, 4> "
                "metric_components(const Eigen::Matrix<S, 4, 1>& x) const` returning g_{mu nu}(x)");
  static_assert(!auto_metric_detail::components_of_double<C> || auto_metric_detail::components_of_dual<C>,
                "AutoMetric<C>: C::metric_components must be a template on the scalar type, "
                "template <class S> Eigen::Matrix<S, 4, 4> metric_components(const Eigen::Matrix<S, 4, 1>& x) const, "
                "returning Eigen::Matrix<S, 4, 4>: AutoMetric calls it with S = grtrace::Dual<4> to differentiate it "
                "(a function of Vec4, or one returning Mat4 for every S, has no derivatives to give)");
  static_assert(auto_metric_detail::dependencies_valid<C>(),
                "AutoMetric<C>: C::depends_on must be a std::array<int, K> (1 <= K <= 4) of increasing coordinate "
                "indices 0..3, e.g. `static constexpr std::array<int, 2> depends_on = {1, 2};` for g(r, theta)");
  static_assert(auto_metric_detail::has_radius<C>,
                "AutoMetric<C>: C needs `double radius(const grtrace::Vec4& x) const` (the escape test's distance)");
  static_assert(auto_metric_detail::has_horizon_radius<C>,
                "AutoMetric<C>: C needs `double horizon_radius() const` (0 when there is no horizon)");

  using Components = C;

  GRTRACE_HD const C& components() const { return *this; }

  /// g_{mu nu}(x) as C writes it (evaluated on doubles: no derivative work).
  GRTRACE_HD Mat4 metric(const Vec4& x) const { return C::metric_components(x); }

  /// g^{mu nu}(x) (a general 4x4 inverse: C says nothing about its block structure).
  GRTRACE_HD Mat4 inverse_metric(const Vec4& x) const { return metric(x).inverse(); }

  /// g and all its first partial derivatives in one pass of Dual<4>.
  GRTRACE_HD MetricJet jet(const Vec4& x) const {
    const Mat4Of<MetricDual> G = dual_components(x);
    MetricJet j;
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        const MetricDual& gab = G(a, b);
        j.g(a, b) = j.g(b, a) = gab.v;
        for (std::size_t c = 0; c < 4; ++c) j.dg[c](a, b) = j.dg[c](b, a) = gab.d[c];
      }
    return j;
  }

  /// Gamma^mu_{ab} = 1/2 g^{mu nu} (d_a g_{nu b} + d_b g_{nu a} - d_nu g_{ab}), the full table.
  GRTRACE_HD Christoffel christoffel(const Vec4& x) const {
    const MetricJet j = jet(x);
    const Mat4 g_inv = j.g.inverse();
    std::array<Mat4, 4> first;  // Gamma_{nu ab}
    for (int nu = 0; nu < 4; ++nu) {
      Mat4& F = first[static_cast<std::size_t>(nu)];
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b)
          F(a, b) = F(b, a) =
              0.5 * (j.dg[static_cast<std::size_t>(a)](nu, b) + j.dg[static_cast<std::size_t>(b)](nu, a) -
                     j.dg[static_cast<std::size_t>(nu)](a, b));
    }
    Christoffel G;
    for (int mu = 0; mu < 4; ++mu) {
      Mat4& Gm = G[static_cast<std::size_t>(mu)];
      Gm = g_inv(mu, 0) * first[0] + g_inv(mu, 1) * first[1] + g_inv(mu, 2) * first[2] + g_inv(mu, 3) * first[3];
    }
    return G;
  }

  /// The coordinates acceleration() differentiates along: C::depends_on when C declares it, else all four.
  static constexpr auto active = auto_metric_detail::active_coordinates<C>();
  static constexpr int active_count = static_cast<int>(active.size());

  /// -Gamma^mu_{ab} k^a k^b without the table. From the 10 upper-triangle components g_ab (Duals over the active
  /// coordinates) it forms the directional derivatives (d_k g)_ab = k^c d_c g_ab and q_c = d_c g(k, k), then
  ///   Gamma_{nu ab} k^a k^b = (d_k g)_{nu b} k^b - q_nu / 2,
  /// and raises the index with one solve: a division per component when g is diagonal at x (checked at run time,
  /// exact zeros), else the general 4x4 inverse.
  GRTRACE_HD Vec4 acceleration(const Vec4& x, const Vec4& k) const {
    using D = Dual<active_count>;
    // A local copy of the static member: device code cannot read a host variable (core/host_device.hpp).
    constexpr auto coords = auto_metric_detail::active_coordinates<C>();
    Vec4Of<D> xd;
    for (int i = 0; i < 4; ++i) xd[i] = D(x[i]);
    for (std::size_t j = 0; j < coords.size(); ++j) xd[coords[j]] = D::variable(x[coords[j]], static_cast<int>(j));
    const Mat4Of<D> G = C::metric_components(xd);
    Mat4 g, dk;
    Vec4 q = Vec4::Zero();
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b) {
        const D& e = G(a, b);
        g(a, b) = g(b, a) = e.v;
        const double w = (a == b ? 1.0 : 2.0) * k[a] * k[b];
        double along_k = 0.0;
        for (std::size_t j = 0; j < coords.size(); ++j) {
          along_k += e.d[j] * k[coords[j]];
          q[coords[j]] += w * e.d[j];
        }
        dk(a, b) = dk(b, a) = along_k;
      }
    const Vec4 lowered = dk * k - 0.5 * q;  // Gamma_{nu ab} k^a k^b
    if (g(0, 1) == 0.0 && g(0, 2) == 0.0 && g(0, 3) == 0.0 && g(1, 2) == 0.0 && g(1, 3) == 0.0 && g(2, 3) == 0.0)
      return Vec4(-lowered[0] / g(0, 0), -lowered[1] / g(1, 1), -lowered[2] / g(2, 2), -lowered[3] / g(3, 3));
    return -(g.inverse() * lowered);
  }

  /// The Euclidean embedding for drawing: C's own when it has one, else the chart's.
  GRTRACE_HD Vec3 to_cartesian(const Vec4& x) const {
    if constexpr (auto_metric_detail::has_to_cartesian<C>) {
      return C::to_cartesian(x);
    } else if constexpr (C::chart == Chart::spherical) {
      return spherical_to_cartesian(x);
    } else {
      return x.template tail<3>();
    }
  }

 private:
  GRTRACE_HD Mat4Of<MetricDual> dual_components(const Vec4& x) const {
    Vec4Of<MetricDual> xd;
    for (int i = 0; i < 4; ++i) xd[i] = MetricDual::variable(x[i], i);
    return C::metric_components(xd);
  }
};

}  // namespace grtrace
