// grtrace/integrate/gauss_legendre.hpp
// Implicit Gauss-Legendre Runge-Kutta methods (2 and 3 stages, orders 4 and 6) with a fixed step, for long
// timelike orbits, and the geodesic equation in Hamiltonian (canonical) form that makes them symplectic.
//
// The methods (Hairer, Lubich & Wanner, "Geometric Numerical Integration" (GNI), sec. II.1.3 and VI.4;
// Hairer & Wanner II, sec. IV.5): s-stage collocation at the zeros of the shifted Legendre polynomial P_s(2c-1).
// Order 2s, A-stable (R(z) is the (s,s) Pade approximant of e^z, |R(iy)| = 1), symmetric, and symplectic:
// the coefficients satisfy b_i a_ij + b_j a_ji = b_i b_j for all i, j (GNI VI.4, Theorem 4.3), which is checked
// at compile time below together with the row sums and Butcher's simplifying assumptions B(2s), C(s), D(s),
// which imply order 2s.
// Coefficients are the closed forms with sqrt(3) and sqrt(15), evaluated at compile time.
//
// The stage equations K_i = f(y + h sum_j a_ij K_j) are solved by fixed-point iteration (no Jacobian), started
// from the previous step's collocation polynomial extrapolated to the new stages (GNI VIII.6.1), and iterated to
// round-off: until the scaled increment max |h dK_i| / (1 + |y|) is below eps/100, or stops decreasing once below
// `accept` (the round-off floor), capped at `max_iterations` (Hairer, McLachlan & Razakarivony, BIT 48 (2008)).
// A step whose iteration did not converge is NOT taken: advance() returns not_converged and leaves the state as
// it was (a smaller h is the cure: the iteration contracts when h L rho(A) < 1, L the Lipschitz constant of f).
// Why to round-off: stopping at a tolerance (even at 1 ulp) leaves a systematic residual in every step, and
// invariants then drift linearly (measured: with a 1-ulp stop, g(u,u) on the seed orbit grows ~4x over 100 orbits
// with gl6, and x^2 + v^2 of an oscillator drifts to 1.5e-13 in 1e5 steps instead of 1.6e-15). Run to the floor,
// and with the update y + h sum b_i K_i in compensated (Kahan) summation, round-off grows like a random walk
// (GNI VIII.5). What remains at large h is the rounding of the coefficients themselves (b_i a_ij + b_j a_ji =
// b_i b_j holds only to ~1e-17 in doubles): a drift of order 1e-17 per step.
// Cost: the iteration needs ~10-15 sweeps of s evaluations per step when h is a sizeable fraction of the orbital
// time scale, so at equal work a Gauss method takes far fewer, larger steps than an explicit one.
//
// Which formulation gives bounded energy and norm errors. Symplecticity is a property with respect to the
// canonical two-form dp ^ dx, so it holds only for a system written in canonical variables. The geodesic
// equation in (x, k) (the Lagrangian form the tracers use, k = dx/dlambda) is not: the change of variables
// (x, k) -> (x, p = g(x) k) is nonlinear, and Runge-Kutta methods do not commute with nonlinear changes of
// variables. So the canonical form is offered here, Hamilton's equations for
//     H(x, p) = 1/2 g^{mu nu}(x) p_mu p_nu,
//     dx^mu/dlambda = g^{mu nu} p_nu,      dp_mu/dlambda = -1/2 (d_mu g^{ab}) p_a p_b,
// state y = (x^mu, p_mu), with H = 1/2 g(k, k) = 1/2 on a unit timelike orbit. A Gauss method conserves exactly:
//   * every linear invariant (true of any Runge-Kutta method): for a cyclic coordinate x^c (d_c g = 0) the
//     right-hand side of p_c is identically zero, so p_t = E (Killing energy) and p_phi = -L_z are constant to
//     the last bit (the closed-form Schwarzschild right-hand side below returns exact zeros for them);
//   * every quadratic invariant of the state (Cooper 1987; GNI IV.2, Theorem 2.2). H itself is not one, since
//     g^{mu nu} depends on x: g(u,u) = 2H is NOT conserved exactly, in any variables.
// What symplecticity buys instead (backward error analysis, GNI IX.8, Theorem 8.1): the numerical solution is
// the exact flow of a modified Hamiltonian H~ = H + O(h^{2s}), so the error in H, i.e. in g(u,u), stays bounded
// at O(h^{2s}) without secular drift, over exponentially long times.
// Explicit, non-symplectic methods drift instead: measured on the seed orbit over 100 orbits at equal work, DP5(4)
// in (x, k) grows ~9.5x in both g(u,u) and E, RK4 in (x, k) ~6.5x in E, and RK4 in the same canonical (x, p)
// variables ~10x in g(u,u) (E exact there as for any RK method): bounded against growing, which
// grtrace-orbit-drift charts and tests/stability_test.cpp asserts. (Gauss in the Lagrangian (x, k) form is still
// symmetric, and the geodesic flow is reversible under k -> -k, so for this integrable problem its errors are
// bounded in practice too (GNI XI, reversible perturbation theory), but E is not exact and the fixed-point
// iteration converges worse; grtrace-orbit-drift reports that variant as gl6-xk.)
#pragma once

#include "grtrace/metric/schwarzschild_lapse.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/tableau/butcher_tableau.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <limits>
#include <string_view>
#include <type_traits>

namespace grtrace {

namespace gauss_detail {
/// Square root by Newton's method, exact to the last bit or one ulp, usable in constant expressions.
constexpr double sqrt(double x) {
  double r = x > 1.0 ? x : 1.0;
  for (int i = 0; i < 200; ++i) {
    const double next = 0.5 * (r + x / r);
    if (next == r) break;
    r = next;
  }
  return r;
}
inline constexpr double sqrt3 = sqrt(3.0);
inline constexpr double sqrt15 = sqrt(15.0);
}  // namespace gauss_detail

/// Two-stage Gauss-Legendre, order 4: c = 1/2 -+ sqrt(3)/6.
struct GaussLegendre4 {
  static constexpr std::string_view name = "gl4";
  static constexpr std::size_t stages = 2;
  static constexpr int order = 4;
  static constexpr TableauMatrix<2> a = {{
      {0.25, 0.25 - gauss_detail::sqrt3 / 6.0},
      {0.25 + gauss_detail::sqrt3 / 6.0, 0.25},
  }};
  static constexpr TableauRow<2> b = {0.5, 0.5};
  static constexpr TableauRow<2> c = {0.5 - gauss_detail::sqrt3 / 6.0, 0.5 + gauss_detail::sqrt3 / 6.0};
};

/// Three-stage Gauss-Legendre, order 6: c = 1/2 - sqrt(15)/10, 1/2, 1/2 + sqrt(15)/10.
struct GaussLegendre6 {
  static constexpr std::string_view name = "gl6";
  static constexpr std::size_t stages = 3;
  static constexpr int order = 6;
  static constexpr TableauMatrix<3> a = {{
      {5.0 / 36.0, 2.0 / 9.0 - gauss_detail::sqrt15 / 15.0, 5.0 / 36.0 - gauss_detail::sqrt15 / 30.0},
      {5.0 / 36.0 + gauss_detail::sqrt15 / 24.0, 2.0 / 9.0, 5.0 / 36.0 - gauss_detail::sqrt15 / 24.0},
      {5.0 / 36.0 + gauss_detail::sqrt15 / 30.0, 2.0 / 9.0 + gauss_detail::sqrt15 / 15.0, 5.0 / 36.0},
  }};
  static constexpr TableauRow<3> b = {5.0 / 18.0, 4.0 / 9.0, 5.0 / 18.0};
  static constexpr TableauRow<3> c = {0.5 - gauss_detail::sqrt15 / 10.0, 0.5, 0.5 + gauss_detail::sqrt15 / 10.0};
};

/// What the implicit integrator needs of a tableau (A may be full).
template <class T>
concept ImplicitTableau = requires {
  { T::name } -> std::convertible_to<std::string_view>;
  { T::stages } -> std::convertible_to<std::size_t>;
  { T::order } -> std::convertible_to<int>;
  T::a[0][0];
  T::b[0];
  T::c[0];
};

/// max |b_i a_ij + b_j a_ji - b_i b_j|: zero exactly for symplectic Runge-Kutta methods (GNI VI.4).
template <ImplicitTableau T>
constexpr double symplecticity_residual() {
  double worst = 0.0;
  for (std::size_t i = 0; i < T::stages; ++i)
    for (std::size_t j = 0; j < T::stages; ++j)
      worst = tableau_detail::max(worst,
                                  tableau_detail::abs(T::b[i] * T::a[i][j] + T::b[j] * T::a[j][i] - T::b[i] * T::b[j]));
  return worst;
}

template <ImplicitTableau T>
constexpr bool implicit_row_sums_match() {
  for (std::size_t i = 0; i < T::stages; ++i) {
    double s = 0.0;
    for (std::size_t j = 0; j < T::stages; ++j) s += T::a[i][j];
    if (tableau_detail::abs(s - T::c[i]) > kRowSumTolerance) return false;
  }
  return true;
}

namespace gauss_detail {
constexpr double power(double x, int k) {
  double r = 1.0;
  for (int i = 0; i < k; ++i) r *= x;
  return r;
}
}  // namespace gauss_detail

/// Residual of Butcher's simplifying assumptions (Butcher 1964; Hairer, Norsett & Wanner I, sec. II.7):
///   B(p): sum_i b_i c_i^{k-1} = 1/k                          k = 1..p
///   C(q): sum_j a_ij c_j^{k-1} = c_i^k / k                   k = 1..q, every i
///   D(q): sum_i b_i c_i^{k-1} a_ij = b_j (1 - c_j^k) / k     k = 1..q, every j
/// B(2s), C(s), D(s) together give order 2s (HNW I, Theorem II.7.4), which is how Gauss methods get theirs.
/// (The rooted-tree checker of butcher_tableau.hpp assumes a strictly lower triangular A, so it does not apply.)
template <ImplicitTableau T>
constexpr double simplifying_assumptions_residual(int p, int q) {
  using gauss_detail::power;
  double worst = 0.0;
  for (int k = 1; k <= p; ++k) {
    double s = 0.0;
    for (std::size_t i = 0; i < T::stages; ++i) s += T::b[i] * power(T::c[i], k - 1);
    worst = tableau_detail::max(worst, tableau_detail::abs(s - 1.0 / k));
  }
  for (int k = 1; k <= q; ++k)
    for (std::size_t i = 0; i < T::stages; ++i) {
      double s = 0.0, d = 0.0;
      for (std::size_t j = 0; j < T::stages; ++j) {
        s += T::a[i][j] * power(T::c[j], k - 1);
        d += T::b[j] * power(T::c[j], k - 1) * T::a[j][i];
      }
      worst = tableau_detail::max(worst, tableau_detail::abs(s - power(T::c[i], k) / k));
      worst = tableau_detail::max(worst, tableau_detail::abs(d - T::b[i] * (1.0 - power(T::c[i], k)) / k));
    }
  return worst;
}

/// Row sums; B(2s), C(s), D(s) for the stated order 2s; B(2s+1) failing (the order is not higher); and the
/// symplecticity condition.
#define GRTRACE_CHECK_GAUSS_TABLEAU(T)                                                                  \
  static_assert(::grtrace::implicit_row_sums_match<T>(), #T ": row sums of A must equal c");            \
  static_assert(T::order == 2 * static_cast<int>(T::stages), #T ": a Gauss method has order 2s");       \
  static_assert(::grtrace::simplifying_assumptions_residual<T>(T::order, static_cast<int>(T::stages)) < \
                    ::grtrace::kOrderTolerance,                                                         \
                #T ": B(2s), C(s) or D(s) fails: a coefficient is wrong");                              \
  static_assert(::grtrace::simplifying_assumptions_residual<T>(T::order + 1, 0) > 1e-6,                 \
                #T ": the quadrature is exact beyond 2s, which is impossible for s nodes");             \
  static_assert(::grtrace::symplecticity_residual<T>() < 1e-15, #T                                      \
                ": b_i a_ij + b_j a_ji != b_i b_j (not "                                                \
                "symplectic)")

GRTRACE_CHECK_GAUSS_TABLEAU(GaussLegendre4);
GRTRACE_CHECK_GAUSS_TABLEAU(GaussLegendre6);

enum class ImplicitStepOutcome { ok, not_converged, non_finite };

struct ImplicitSolverSettings {
  int max_iterations = 60;  ///< fixed-point iterations per step before the step is refused
  double accept = 1e-12;    ///< a stagnating iteration counts as converged when its scaled increment is below this
};

/// Fixed-step Gauss(-Legendre) integrator for an autonomous system y' = f(y) of fixed size N.
/// Counts right-hand-side evaluations exactly: one at start() (the first predictor), s per iteration.
template <ImplicitTableau T, int N>
class GaussLegendreIntegrator {
 public:
  using State = Vector<N>;
  using Tableau = T;
  static constexpr std::size_t S = T::stages;

  explicit GaussLegendreIntegrator(double h, ImplicitSolverSettings settings = {}) : h_(h), settings_(settings) {}

  template <class Rhs>
  void start(const Rhs& f, const State& y0) {
    y_ = y0;
    compensation_ = State::Zero();
    const State f0 = f(y0);
    for (auto& k : k_) k = f0;
    rhs_evals_ = 1;
    accepted_ = 0;
    iterations_ = 0;
    max_iterations_seen_ = 0;
    not_converged_ = 0;
    lambda_ = 0.0;
    have_previous_ = false;
  }

  /// One step of size h. On not_converged / non_finite the state is unchanged.
  template <class Rhs>
  ImplicitStepOutcome advance(const Rhs& f) {
    std::array<State, S> k = have_previous_ ? extrapolated_stages() : k_;
    double previous_increment = std::numeric_limits<double>::infinity();
    bool converged = false;
    int it = 0;
    while (it < settings_.max_iterations) {
      ++it;
      std::array<State, S> k_new;
      for (std::size_t i = 0; i < S; ++i) {
        State z = State::Zero();
        for (std::size_t j = 0; j < S; ++j) z.noalias() += (h_ * T::a[i][j]) * k[j];
        k_new[i] = f(State(y_ + z));
      }
      rhs_evals_ += static_cast<long>(S);
      double increment = 0.0;  // max over stages and components of |h dK| / (1 + |y|)
      for (std::size_t i = 0; i < S; ++i) {
        if (!k_new[i].allFinite()) {
          iterations_ += it;
          return ImplicitStepOutcome::non_finite;
        }
        for (int m = 0; m < N; ++m)
          increment = std::max(increment, std::abs(h_ * (k_new[i][m] - k[i][m])) / (1.0 + std::abs(y_[m])));
      }
      k = k_new;
      // Below 1% of an ulp of (1 + |y|) the stage values no longer change: the round-off floor.
      if (increment <= 0.01 * std::numeric_limits<double>::epsilon()) {
        converged = true;
        break;
      }
      // No more progress once already small: the round-off floor. (Larger increments may grow for an iteration
      // or two while a correction propagates through coupled components, so they do not stop the iteration.)
      if (increment >= previous_increment && previous_increment <= settings_.accept) {
        converged = true;
        break;
      }
      previous_increment = increment;
    }
    if (!converged) converged = previous_increment <= settings_.accept;  // the cap was reached
    iterations_ += it;
    max_iterations_seen_ = std::max(max_iterations_seen_, it);
    if (!converged) {
      ++not_converged_;
      return ImplicitStepOutcome::not_converged;
    }
    State delta = State::Zero();
    for (std::size_t i = 0; i < S; ++i) delta.noalias() += (h_ * T::b[i]) * k[i];
    // Kahan: y_new = y + (delta + compensation), keeping what the addition rounded away.
    const State increment_total = delta + compensation_;
    const State y_new = y_ + increment_total;
    if (!y_new.allFinite()) return ImplicitStepOutcome::non_finite;
    compensation_ = (y_ - y_new) + increment_total;
    y_ = y_new;
    k_ = k;
    have_previous_ = true;
    lambda_ += h_;
    ++accepted_;
    return ImplicitStepOutcome::ok;
  }

  const State& state() const { return y_; }
  double lambda() const { return lambda_; }
  double step() const { return h_; }
  void set_step(double h) {
    h_ = h;
    have_previous_ = false;  // the extrapolation assumes equal steps
  }
  long rhs_evals() const { return rhs_evals_; }
  int accepted() const { return accepted_; }
  long iterations() const { return iterations_; }                   ///< total fixed-point iterations
  int max_iterations_seen() const { return max_iterations_seen_; }  ///< largest count in one step
  int not_converged() const { return not_converged_; }              ///< refused steps

 private:
  /// Stage derivatives predicted from the last step's collocation polynomial u', which interpolates K_j at c_j:
  /// K_i(new) ~ sum_j K_j l_j(1 + c_i), with l_j the Lagrange basis on the nodes c.
  std::array<State, S> extrapolated_stages() const {
    std::array<State, S> k;
    for (std::size_t i = 0; i < S; ++i) {
      k[i] = State::Zero();
      for (std::size_t j = 0; j < S; ++j) k[i].noalias() += kExtrapolation[i][j] * k_[j];
    }
    return k;
  }

  static constexpr TableauMatrix<S> extrapolation_matrix() {
    TableauMatrix<S> e{};
    for (std::size_t i = 0; i < S; ++i)
      for (std::size_t j = 0; j < S; ++j) {
        double l = 1.0;
        for (std::size_t m = 0; m < S; ++m)
          if (m != j) l *= (1.0 + T::c[i] - T::c[m]) / (T::c[j] - T::c[m]);
        e[i][j] = l;
      }
    return e;
  }
  static constexpr TableauMatrix<S> kExtrapolation = extrapolation_matrix();

  double h_;
  ImplicitSolverSettings settings_;
  State y_ = State::Zero(), compensation_ = State::Zero();
  std::array<State, S> k_{};
  bool have_previous_ = false;
  double lambda_ = 0.0;
  long rhs_evals_ = 0, iterations_ = 0;
  int accepted_ = 0, max_iterations_seen_ = 0, not_converged_ = 0;
};

// ----------------------------------------------------------------------------------------------------------
// The geodesic equation in canonical form: y = (x^mu, p_mu), H = 1/2 g^{mu nu}(x) p_mu p_nu.

/// p_mu = g_{mu nu} k^nu: from the tracers' (x, k) state to the canonical (x, p) state.
template <MetricPolicy M>
GeodesicState to_canonical(const M& metric, const GeodesicState& y) {
  const Vec4 x = y.head<4>();
  return make_state(x, metric.metric(x) * Vec4(y.tail<4>()));
}

/// k^mu = g^{mu nu} p_nu: back from (x, p) to (x, k).
template <MetricPolicy M>
GeodesicState from_canonical(const M& metric, const GeodesicState& y) {
  const Vec4 x = y.head<4>();
  const Mat4 g_inv = metric.metric(x).inverse();
  return make_state(x, g_inv * Vec4(y.tail<4>()));
}

/// 2H = g^{mu nu} p_mu p_nu = g(k, k): 1 for a unit timelike 4-velocity, 0 for light.
template <MetricPolicy M>
double canonical_norm(const M& metric, const GeodesicState& y) {
  const Vec4 x = y.head<4>(), p = y.tail<4>();
  if constexpr (std::derived_from<M, SchwarzschildMetric>) {
    const double r = x[1], f = schwarzschild_f(r, metric.mass), st = std::sin(x[2]), r2 = r * r;
    return p[0] * p[0] / f - f * p[1] * p[1] - p[2] * p[2] / r2 - p[3] * p[3] / (r2 * st * st);
  } else {
    return p.dot(metric.metric(x).inverse() * p);
  }
}

/// Hamilton's equations for H = 1/2 g^{mu nu}(x) p_mu p_nu. Schwarzschild (and MinkowskiSpherical) use closed
/// forms in which dp_t and dp_phi are exact zeros; other metrics use dp_mu = p_nu Gamma^nu_{mu b} k^b with
/// k = g^{-1} p (equal to -1/2 d_mu g^{ab} p_a p_b), exact only to round-off.
template <MetricPolicy M>
struct HamiltonianGeodesicEquation {
  const M* metric;

  GeodesicState operator()(const GeodesicState& y) const {
    const Vec4 x = y.head<4>(), p = y.tail<4>();
    GeodesicState dy;
    if constexpr (std::derived_from<M, SchwarzschildMetric>) {
      const double m = metric->mass, r = x[1], inv_r = 1.0 / r, inv_r2 = inv_r * inv_r;
      const double f = 1.0 - 2.0 * m * inv_r, df = 2.0 * m * inv_r2;  // f and df/dr
      const double st = std::sin(x[2]), ct = std::cos(x[2]), inv_s2 = 1.0 / (st * st);
      // g^tt = 1/f, g^rr = -f, g^thth = -1/r^2, g^phph = -1/(r^2 sin^2 theta)
      dy[0] = p[0] / f;
      dy[1] = -f * p[1];
      dy[2] = -p[2] * inv_r2;
      dy[3] = -p[3] * inv_r2 * inv_s2;
      dy[4] = 0.0;  // t is cyclic: p_t = E exactly
      dy[5] = 0.5 * df / (f * f) * p[0] * p[0] + 0.5 * df * p[1] * p[1] -
              inv_r2 * inv_r * (p[2] * p[2] + p[3] * p[3] * inv_s2);
      dy[6] = -ct * p[3] * p[3] * inv_r2 * inv_s2 / st;
      dy[7] = 0.0;  // phi is cyclic: p_phi = -L_z exactly
    } else {
      const Mat4 g_inv = metric->metric(x).inverse();
      const Vec4 k = g_inv * p;
      const Christoffel gamma = metric->christoffel(x);
      dy.head<4>() = k;
      for (int mu = 0; mu < 4; ++mu) {
        double s = 0.0;
        for (int nu = 0; nu < 4; ++nu) s += p[nu] * gamma[static_cast<std::size_t>(nu)].row(mu).dot(k);
        dy[4 + mu] = s;
      }
    }
    return dy;
  }
};

}  // namespace grtrace
