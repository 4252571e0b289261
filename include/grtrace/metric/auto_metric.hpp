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
// Cost: one evaluation of g with Dual<4> (value + 4 partial derivatives per component; sin, sqrt, 1/r ... are
// evaluated once each, on the value), then the contraction
//     Gamma_{nu ab} k^a k^b = (d_k g)_{nu b} k^b - 1/2 d_nu (g_ab k^a k^b),   d_k = k^a d_a,
// done on the gradients directly (no 4x4x4 table), and one 4x4 solve with g. The full table is only built by
// christoffel(), which tests and tools use.
#pragma once

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

}  // namespace auto_metric_detail

/// What a user writes to get a metric by automatic differentiation (see the top of this header).
template <class C>
concept MetricComponents =
    auto_metric_detail::has_name<C> && auto_metric_detail::has_chart<C> &&
    auto_metric_detail::components_of_double<C> && auto_metric_detail::components_of_dual<C> &&
    auto_metric_detail::has_radius<C> && auto_metric_detail::has_horizon_radius<C>;

/// g_{ab} and its first derivatives at one event.
struct MetricJet {
  Mat4 g;                    ///< g_{ab}, symmetric (mirrored from the upper triangle)
  std::array<Mat4, 4> dg;    ///< dg[c](a, b) = d g_{ab} / d x^c
};

/// A diagonal metric diag(g00, g11, g22, g33) in any scalar type (most of the example metrics).
template <class S>
Mat4Of<S> diagonal_metric(const S& g00, const S& g11, const S& g22, const S& g33) {
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
  static_assert(auto_metric_detail::components_of_double<C> ||
                    !auto_metric_detail::components_of_double_nonconst<C>,
                "AutoMetric<C>: C::metric_components must be a const member function");
  static_assert(auto_metric_detail::components_of_double<C> ||
                    auto_metric_detail::components_of_double_nonconst<C>,
                "AutoMetric<C>: C needs `template <class S> Eigen::Matrix<S, 4, 4> "
                "metric_components(const Eigen::Matrix<S, 4, 1>& x) const` returning g_{mu nu}(x)");
  static_assert(!auto_metric_detail::components_of_double<C> || auto_metric_detail::components_of_dual<C>,
                "AutoMetric<C>: C::metric_components must be a template on the scalar type, "
                "template <class S> Eigen::Matrix<S, 4, 4> metric_components(const Eigen::Matrix<S, 4, 1>& x) const, "
                "returning Eigen::Matrix<S, 4, 4>: AutoMetric calls it with S = grtrace::Dual<4> to differentiate it "
                "(a function of Vec4, or one returning Mat4 for every S, has no derivatives to give)");
  static_assert(auto_metric_detail::has_radius<C>,
                "AutoMetric<C>: C needs `double radius(const grtrace::Vec4& x) const` (the escape test's distance)");
  static_assert(auto_metric_detail::has_horizon_radius<C>,
                "AutoMetric<C>: C needs `double horizon_radius() const` (0 when there is no horizon)");

  using Components = C;

  const C& components() const { return *this; }

  /// g_{mu nu}(x) as C writes it (evaluated on doubles: no derivative work).
  Mat4 metric(const Vec4& x) const { return C::metric_components(x); }

  /// g^{mu nu}(x) (a general 4x4 inverse: C says nothing about its block structure).
  Mat4 inverse_metric(const Vec4& x) const { return metric(x).inverse(); }

  /// g and all its first partial derivatives in one pass of Dual<4>.
  MetricJet jet(const Vec4& x) const {
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
  Christoffel christoffel(const Vec4& x) const {
    const MetricJet j = jet(x);
    const Mat4 g_inv = j.g.inverse();
    std::array<Mat4, 4> first;  // Gamma_{nu ab}
    for (int nu = 0; nu < 4; ++nu) {
      Mat4& F = first[static_cast<std::size_t>(nu)];
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b)
          F(a, b) = F(b, a) = 0.5 * (j.dg[static_cast<std::size_t>(a)](nu, b) +
                                     j.dg[static_cast<std::size_t>(b)](nu, a) -
                                     j.dg[static_cast<std::size_t>(nu)](a, b));
    }
    Christoffel G;
    for (int mu = 0; mu < 4; ++mu) {
      Mat4& Gm = G[static_cast<std::size_t>(mu)];
      Gm = g_inv(mu, 0) * first[0] + g_inv(mu, 1) * first[1] + g_inv(mu, 2) * first[2] + g_inv(mu, 3) * first[3];
    }
    return G;
  }

  /// -Gamma^mu_{ab} k^a k^b without the table: with s_nu = g_{nu b} k^b (a Dual, so it carries d_c s_nu),
  ///   Gamma_{nu ab} k^a k^b = k^c d_c s_nu - 1/2 d_nu (k^b s_b),
  /// then one solve with g raises the index.
  Vec4 acceleration(const Vec4& x, const Vec4& k) const {
    const Mat4Of<MetricDual> G = dual_components(x);
    Mat4 g;
    Vec4 lowered;  // Gamma_{nu ab} k^a k^b
    MetricDual kk(0.0);  // g(k, k) with its gradient
    for (int nu = 0; nu < 4; ++nu) {
      MetricDual s(0.0);
      for (int b = 0; b < 4; ++b) {
        const MetricDual& gnb = nu <= b ? G(nu, b) : G(b, nu);  // upper triangle only
        g(nu, b) = gnb.v;
        s += gnb * k[b];
      }
      lowered[nu] = s.d[0] * k[0] + s.d[1] * k[1] + s.d[2] * k[2] + s.d[3] * k[3];
      kk += s * k[nu];
    }
    for (int nu = 0; nu < 4; ++nu) lowered[nu] -= 0.5 * kk.d[static_cast<std::size_t>(nu)];
    return -(g.inverse() * lowered);
  }

  /// The Euclidean embedding for drawing: C's own when it has one, else the chart's.
  Vec3 to_cartesian(const Vec4& x) const {
    if constexpr (auto_metric_detail::has_to_cartesian<C>) {
      return C::to_cartesian(x);
    } else if constexpr (C::chart == Chart::spherical) {
      return spherical_to_cartesian(x);
    } else {
      return x.template tail<3>();
    }
  }

 private:
  Mat4Of<MetricDual> dual_components(const Vec4& x) const {
    Vec4Of<MetricDual> xd;
    for (int i = 0; i < 4; ++i) xd[i] = MetricDual::variable(x[i], i);
    return C::metric_components(xd);
  }
};

}  // namespace grtrace
