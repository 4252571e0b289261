// grtrace/integrate/runge_kutta_stepper.hpp
// One generic explicit Runge-Kutta step for any tableau, unrolled at compile time.
//
// Takes:   an autonomous right-hand side f (State -> State), the state y, its derivative f0 = f(y)
//          (kept from the previous step, so stage 1 is never re-evaluated), and a step h.
// Returns: y_new = y + h sum_i b_i k_i and, for embedded pairs, err = h sum_i (b_i - b_hat_i) k_i.
// Assumes: T passed GRTRACE_CHECK_TABLEAU (checked again here), N is the state dimension.
// Zero entries of A, b and b - b_hat cost nothing: each term is guarded by `if constexpr`.
// Stages are kept after the step so that dense output (dense_output.hpp) can reuse them.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/integrate/rhs_call.hpp"
#include "grtrace/tableau/butcher_tableau.hpp"

#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

namespace grtrace {

/// The sums a Runge-Kutta step is made of, for one component (of one ray): a stage's input y + h sum_j a_Ij k_j, the
/// new state y + h sum_j b_j k_j and the embedded error h sum_j (b_j - b_hat_j) k_j, with the coefficients as
/// compile-time constants and zero terms left out. `k(J)` gives stage J's value of that component (J a
/// std::integral_constant). Shared by the scalar stepper below and the batched one (integrate/batch_stepper.hpp), so
/// both do the same operations in the same order: the batched stepper's lanes are bit for bit the scalar stepper's
/// rays.
///
/// Each is formed as (what the earlier stages give) + (h c_L) k_L, with k_L the last stage the sum reads, in one
/// multiply-add: a step is one chain of dependent operations (a stage's input waits for the stage before it), and
/// k_L is the link that arrives last. Everything else is ready before it: the earlier stages' sum (additions of
/// products, in the order of j), y + h times that sum, and h c_L. So the chain from k_L to the next stage's input
/// is one multiply-add, where y + h (sum + c_L k_L) made it a product, a sum and a multiply-add. Measured against
/// the same sums with k_L inside them: one accepted rkf78 step around Schwarzschild 336 -> 316 ns, tsit5 within
/// 1 %; the 5-variable reduced Kerr system with dopri5 up to 5 % slower (its right-hand side, not the sums, is its
/// chain).
template <ExplicitTableau T>
struct StageSums {
  enum class Weights { b, difference };

  /// y + h sum_{J < I} a_IJ k_J: stage I's input.
  template <std::size_t I, class K>
  static GRTRACE_HD double input(const K& k, double h, double y) {
    return split<Row<I>, I>(k, h, y);
  }

  /// y + h sum_J w_J k_J over all stages, w = b or b - b_hat.
  template <Weights W, class K>
  static GRTRACE_HD double update(const K& k, double h, double y) {
    return split<Weight<W>, T::stages>(k, h, y);
  }

  /// h sum_J w_J k_J over all stages (the embedded error estimate for w = b - b_hat).
  template <Weights W, class K>
  static GRTRACE_HD double scaled(const K& k, double h) {
    return split<Weight<W>, T::stages, false>(k, h, 0.0);
  }

 private:
  template <std::size_t I>
  struct Row {
    template <std::size_t J>
    static constexpr GRTRACE_HD double of() {
      return T::a[I][J];
    }
  };
  template <Weights W>
  struct Weight {
    template <std::size_t J>
    static constexpr GRTRACE_HD double of() {
      if constexpr (W == Weights::b) return T::b[J];
      else return T::b[J] - T::b_hat[J];
    }
  };

  /// The last J < Count with a nonzero coefficient (Count when there is none).
  template <class Coefficients, std::size_t Count>
  static consteval std::size_t last_term() {
    std::size_t last = Count;
    [&]<std::size_t... J>(std::index_sequence<J...>) {
      ((last = Coefficients::template of<J>() != 0.0 ? J : last), ...);
    }(std::make_index_sequence<Count>{});
    return last;
  }

  /// base + h sum_{J < Count} c_J k_J as (base + h sum_{J < L} c_J k_J) + (h c_L) k_L, L = last_term; with
  /// WithBase false, h sum_{J < L} c_J k_J + (h c_L) k_L.
  template <class Coefficients, std::size_t Count, bool WithBase = true, class K>
  static GRTRACE_HD double split(const K& k, double h, double base) {
    constexpr std::size_t L = last_term<Coefficients, Count>();
    if constexpr (L == Count) {
      return WithBase ? base : 0.0;
    } else {
      constexpr double c_last = Coefficients::template of<L>();
      double earlier = base;
      if constexpr (L > 0) {
        const double sum = sum_of<Coefficients>(k, std::make_index_sequence<L>{});
        earlier = WithBase ? mul_add(h, sum, base) : h * sum;
      }
      return mul_add(h * c_last, k(std::integral_constant<std::size_t, L>{}), earlier);
    }
  }

  template <class Coefficients, class K, std::size_t... J>
  static GRTRACE_HD double sum_of(const K& k, std::index_sequence<J...>) {
    double acc = 0.0;
    ((acc = term<Coefficients::template of<J>()>(acc, k, std::integral_constant<std::size_t, J>{})), ...);
    return acc;
  }

  // A product and a sum, not a mul_add (core/mul_add.hpp): the products of the earlier stages are ready long before
  // the sum needs them and overlap, and a chain of fused operations is longer (4 cycles a link against 3 for an
  // addition). Measured in frames (docs/benchmarks.md): fusing these terms made the 5-variable Kerr system's step
  // up to 1.1x slower.
  template <double Coefficient, class K, class J>
  static GRTRACE_HD double term(double acc, const K& k, J j) {
    if constexpr (Coefficient != 0.0) return acc + Coefficient * k(j);
    else return acc;
  }
};

template <ExplicitTableau T, int N>
class RungeKuttaStepper {
  static_assert(tableau_is_valid<T>(), "tableau fails its compile-time checks (see GRTRACE_CHECK_TABLEAU)");

 public:
  using Tableau = T;
  using State = Vector<N>;
  static constexpr std::size_t S = T::stages;

  /// Right-hand-side evaluations one call of step() costs (stage 1 reuses f0).
  static constexpr int evals_per_step = static_cast<int>(S) - 1;

  template <class Rhs>
  GRTRACE_HD void step(const Rhs& f, const State& y, const State& f0, double h, State& y_new) {
    k_[0] = f0;
    compute_stages(f, y, h, std::make_index_sequence<S - 1>{});
    weighted_update<Weights::b>(y, h, y_new);
  }

  template <class Rhs>
  GRTRACE_HD void step(const Rhs& f, const State& y, const State& f0, double h, State& y_new, State& err) {
    step(f, y, f0, h, y_new);
    if constexpr (has_embedded_pair<T>) weighted_scaled<Weights::difference>(h, err);
  }

  /// k_i of the last step (k_0 = f0; for FSAL tableaux k_{S-1} = f(y_new)).
  GRTRACE_HD const State& stage(std::size_t i) const { return k_[i]; }

  /// y(theta) on the last step, for tableaux that carry their own continuous extension.
  GRTRACE_HD State interpolate(const State& y, double h, double theta) const requires TableauWithDenseOutput<T> {
    // A local copy of the tableau's table: device code cannot read a host variable (core/host_device.hpp).
    constexpr auto dense = T::dense;
    State acc = State::Zero();
    for (std::size_t i = 0; i < S; ++i) {
      double w = 0.0, power = theta;
      for (int d = 0; d < T::dense_degree; ++d, power *= theta) w += dense[i][static_cast<std::size_t>(d)] * power;
      acc.noalias() += w * k_[i];
    }
    return y + h * acc;
  }

 private:
  using Sums = StageSums<T>;
  using Weights = typename Sums::Weights;

  // The stage sums are written per component, with the coefficients as compile-time constants (StageSums): one
  // pass over the N components per sum, no Eigen temporaries or out-of-line expression calls (which the profile
  // showed as 15-25 % of a step). The order of the operations is StageSums': the newest stage enters last, in
  // one mul_add (core/mul_add.hpp).
  template <class Rhs, std::size_t... I>
  GRTRACE_HD void compute_stages([[maybe_unused]] const Rhs& f, [[maybe_unused]] const State& y,
                                 [[maybe_unused]] double h, std::index_sequence<I...>) {
    (compute_stage<I + 1>(f, y, h), ...);
  }

  template <std::size_t I, class Rhs>
  GRTRACE_HD void compute_stage(const Rhs& f, const State& y, double h) {
    State y_stage;
    for (int i = 0; i < N; ++i) y_stage[i] = Sums::template input<I>(component(i), h, y[i]);
    k_[I] = evaluate_rhs(f, y_stage);
  }

  /// Stage J's value of component i, for StageSums.
  GRTRACE_HD auto component(int i) const {
    return [this, i](auto J) { return k_[decltype(J)::value][i]; };
  }

  /// out = base + h sum_j w_j k_j (base given) or h sum_j w_j k_j (no base), component by component.
  template <Weights W>
  GRTRACE_HD void weighted_update(const State& base, double h, State& out) const {
    for (int i = 0; i < N; ++i) out[i] = Sums::template update<W>(component(i), h, base[i]);
  }
  template <Weights W>
  GRTRACE_HD void weighted_scaled(double h, State& out) const {
    for (int i = 0; i < N; ++i) out[i] = Sums::template scaled<W>(component(i), h);
  }

  std::array<State, S> k_;
};

}  // namespace grtrace
