// grtrace/tableau/butcher_tableau.hpp
// Butcher tableaux as compile-time data, and the compile-time checks every tableau must pass.
//
// A tableau is a struct with static constexpr members (see ExplicitTableau below):
//     name, stages, order, embedded_order (0 = no embedded pair), fsal,
//     a (stages x stages, strictly lower triangular), b, c, b_hat (zeros when there is no embedded pair),
//     optionally dense_degree and dense[i][d] = coefficient of theta^(d+1) in the continuous weight b_i(theta).
// The generic stepper (integrate/runge_kutta_stepper.hpp) reads only these members.
//
// Checks (Butcher, "Numerical Methods for ODEs", ch. 3; Hairer, Norsett & Wanner I, sec. II.2):
//   * row sums      c_i = sum_j a_ij
//   * explicitness  a_ij = 0 for j >= i
//   * order         gamma(t) * Phi(t) = 1 for every rooted tree t with |t| <= order (and <= embedded order for b_hat)
//   * FSAL          last row of A equals b and c_last = 1
// The rooted trees are enumerated at compile time, so the checks cover any order up to kMaxCheckedOrder.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <stdexcept>
#include <string_view>

namespace grtrace {

template <std::size_t S>
using TableauRow = std::array<double, S>;
template <std::size_t S>
using TableauMatrix = std::array<std::array<double, S>, S>;

namespace tableau_detail {

constexpr double abs(double x) { return x < 0 ? -x : x; }
constexpr double max(double a, double b) { return a < b ? b : a; }

/// Highest order whose rooted trees we enumerate (1+1+2+4+9+20+48+115 = 200 trees).
inline constexpr int kMaxCheckedOrder = 8;
inline constexpr std::size_t kMaxTrees = 200;

/// One rooted tree, stored through what the order conditions need of it:
/// g_i = prod over children u of (A g_u)_i (the stage weights of the tree), A g, and gamma(t).
template <std::size_t S>
struct Tree {
  int order = 0;
  double gamma = 1.0;
  TableauRow<S> Ag{};
};

/// Enumerates rooted trees order by order (a tree of order n is a multiset of trees whose orders sum
/// to n - 1) and records the worst residual |gamma(t) Phi(t) - 1| for the weights b.
template <std::size_t S>
struct OrderConditionChecker {
  const TableauMatrix<S>& a;
  const TableauRow<S>& b;
  std::array<Tree<S>, kMaxTrees> trees{};
  std::size_t count = 0;
  double worst = 0.0;
  int top_order = 0;  // trees of this order are never children, so their A g is not needed

  constexpr void add_tree(int n, const TableauRow<S>& g, double gamma_children) {
    Tree<S> t;
    t.order = n;
    t.gamma = n * gamma_children;
    double phi = 0.0;
    for (std::size_t i = 0; i < S; ++i) phi += b[i] * g[i];
    worst = max(worst, abs(t.gamma * phi - 1.0));
    if (n < top_order) {
      for (std::size_t i = 0; i < S; ++i) {
        double s = 0.0;
        for (std::size_t j = 0; j < i; ++j) s += a[i][j] * g[j];  // A is strictly lower triangular
        t.Ag[i] = s;
      }
    }
    trees[count++] = t;
  }

  // Children are chosen with non-increasing tree index, so each multiset is produced once.
  constexpr void choose_children(int n, int remaining, std::size_t bound, const TableauRow<S>& g, double gamma) {
    if (remaining == 0) {
      add_tree(n, g, gamma);
      return;
    }
    for (std::size_t u = 0; u < bound; ++u) {
      if (trees[u].order > remaining) continue;
      TableauRow<S> g2{};
      for (std::size_t i = 0; i < S; ++i) g2[i] = g[i] * trees[u].Ag[i];
      choose_children(n, remaining - trees[u].order, u + 1, g2, gamma * trees[u].gamma);
    }
  }

  constexpr double run(int max_order) {
    top_order = max_order;
    TableauRow<S> ones{};
    for (auto& v : ones) v = 1.0;
    for (int n = 1; n <= max_order; ++n) choose_children(n, n - 1, count, ones, 1.0);
    return worst;
  }
};

}  // namespace tableau_detail

/// Largest residual |gamma(t) Phi(t) - 1| over all rooted trees t with |t| <= order, for weights b.
/// Zero (to round-off) exactly when (A, b) has at least that order.
/// Assumes order <= kMaxCheckedOrder (throws otherwise; at compile time that is an error).
/// Only meaningful for explicit tableaux (the A g products skip the upper triangle).
template <std::size_t S>
constexpr double order_condition_residual(const TableauMatrix<S>& a, const TableauRow<S>& b, int order) {
  if (order < 1 || order > tableau_detail::kMaxCheckedOrder)
    throw std::out_of_range("order_condition_residual: order must be in 1..8 (rooted trees enumerated)");
  tableau_detail::OrderConditionChecker<S> checker{a, b};
  return checker.run(order);
}

/// Number of rooted trees of each order 1..8, for tests of the enumeration itself (OEIS A000081).
template <std::size_t S = 1>
constexpr std::size_t rooted_tree_count(int order) {
  TableauMatrix<S> a{};
  TableauRow<S> b{};
  tableau_detail::OrderConditionChecker<S> checker{a, b};
  checker.run(order);
  std::size_t n = 0;
  for (std::size_t i = 0; i < checker.count; ++i)
    if (checker.trees[i].order == order) ++n;
  return n;
}

/// Round-off allowances. Coefficients are stored to double precision; sums over a tableau of 13 stages with
/// coefficients of size ~10 lose a few digits, so order conditions are held to 1e-11 (a single wrong digit in
/// any coefficient beyond the 10th significant figure is the only mistake that could slip through).
inline constexpr double kRowSumTolerance = 1e-14;
inline constexpr double kOrderTolerance = 1e-11;

/// What the generic stepper needs of a tableau.
template <class T>
concept ExplicitTableau = requires {
  { T::name } -> std::convertible_to<std::string_view>;
  { T::stages } -> std::convertible_to<std::size_t>;
  { T::order } -> std::convertible_to<int>;
  { T::embedded_order } -> std::convertible_to<int>;
  { T::fsal } -> std::convertible_to<bool>;
  T::a[0][0];
  T::b[0];
  T::c[0];
  T::b_hat[0];
};

/// A tableau whose continuous extension (dense output) comes with it.
template <class T>
concept TableauWithDenseOutput = ExplicitTableau<T> && requires {
  { T::dense_degree } -> std::convertible_to<int>;
  T::dense[0][0];
};

template <class T>
inline constexpr bool has_embedded_pair = T::embedded_order > 0;

/// c_i = sum_j a_ij within round-off.
template <ExplicitTableau T>
constexpr bool row_sums_match() {
  for (std::size_t i = 0; i < T::stages; ++i) {
    double s = 0.0;
    for (std::size_t j = 0; j < T::stages; ++j) s += T::a[i][j];
    if (tableau_detail::abs(s - T::c[i]) > kRowSumTolerance * (1.0 + tableau_detail::abs(T::c[i]))) return false;
  }
  return true;
}

/// a_ij = 0 for j >= i (the method is explicit).
template <ExplicitTableau T>
constexpr bool is_explicit() {
  for (std::size_t i = 0; i < T::stages; ++i)
    for (std::size_t j = i; j < T::stages; ++j)
      if (T::a[i][j] != 0.0) return false;
  return true;
}

// is_explicit is checked first in tableau_is_valid (the residual below assumes a strictly lower A).
template <ExplicitTableau T>
constexpr bool has_stated_order() {
  return T::order <= tableau_detail::kMaxCheckedOrder &&
         order_condition_residual<T::stages>(T::a, T::b, T::order) < kOrderTolerance;
}

template <ExplicitTableau T>
constexpr bool has_stated_embedded_order() {
  if constexpr (!has_embedded_pair<T>) {
    for (double v : T::b_hat)
      if (v != 0.0) return false;  // no embedded order claimed, so no embedded weights either
    return true;
  } else {
    return T::embedded_order <= tableau_detail::kMaxCheckedOrder &&
           order_condition_residual<T::stages>(T::a, T::b_hat, T::embedded_order) < kOrderTolerance;
  }
}

/// First Same As Last: the last stage is evaluated at (t + h, y_new), so its derivative starts the next step.
template <ExplicitTableau T>
constexpr bool fsal_is_consistent() {
  if constexpr (!T::fsal) {
    return true;
  } else {
    constexpr std::size_t last = T::stages - 1;
    if (T::c[last] != 1.0) return false;
    for (std::size_t j = 0; j < T::stages; ++j)
      if (T::a[last][j] != T::b[j]) return false;
    return true;
  }
}

/// The continuous weights must reproduce b at theta = 1 (the interpolant ends on the step's result).
template <ExplicitTableau T>
constexpr bool dense_output_is_consistent() {
  if constexpr (!TableauWithDenseOutput<T>) {
    return true;
  } else {
    for (std::size_t i = 0; i < T::stages; ++i) {
      double s = 0.0;
      for (int d = 0; d < T::dense_degree; ++d) s += T::dense[i][static_cast<std::size_t>(d)];
      if (tableau_detail::abs(s - T::b[i]) > 1e-13) return false;
    }
    return true;
  }
}

/// All checks together; the stepper refuses (at compile time) any tableau for which this is false.
template <ExplicitTableau T>
constexpr bool tableau_is_valid() {
  return is_explicit<T>() && row_sums_match<T>() && has_stated_order<T>() && has_stated_embedded_order<T>() &&
         fsal_is_consistent<T>() && dense_output_is_consistent<T>();
}

/// Put this after a tableau's definition; each failed check names itself in the compiler output.
#define GRTRACE_CHECK_TABLEAU(T)                                                                          \
  static_assert(::grtrace::is_explicit<T>(), #T ": A must be strictly lower triangular");                \
  static_assert(::grtrace::row_sums_match<T>(), #T ": row sums of A must equal c");                      \
  static_assert(::grtrace::has_stated_order<T>(), #T ": b fails an order condition of the stated order"); \
  static_assert(::grtrace::has_stated_embedded_order<T>(),                                                \
                #T ": b_hat fails an order condition of the stated embedded order");                      \
  static_assert(::grtrace::fsal_is_consistent<T>(), #T ": FSAL claimed but last row of A != b or c != 1"); \
  static_assert(::grtrace::dense_output_is_consistent<T>(), #T ": dense weights at theta=1 must equal b")

}  // namespace grtrace
