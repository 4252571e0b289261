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

#include "grtrace/core/mul_add.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/tableau/butcher_tableau.hpp"

#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

namespace grtrace {

/// The sums a Runge-Kutta step is made of, for one component (of one ray): sum_j a_Ij k_j, sum_j b_j k_j and
/// sum_j (b_j - b_hat_j) k_j, with the coefficients as compile-time constants and zero terms left out. `k(J)` gives
/// stage J's value of that component (J a std::integral_constant). Shared by the scalar stepper below and the
/// batched one (integrate/batch_stepper.hpp), so both do the same operations in the same order: the batched
/// stepper's lanes are bit for bit the scalar stepper's rays.
template <ExplicitTableau T>
struct StageSums {
  enum class Weights { b, difference };

  /// sum_{J < I} a_IJ k_J, accumulated from 0 in the order of J.
  template <std::size_t I, class K>
  static double row(const K& k) {
    return sum<Row<I>>(k, std::make_index_sequence<I>{});
  }

  /// sum_J w_J k_J over all stages, w = b or b - b_hat.
  template <Weights W, class K>
  static double weighted(const K& k) {
    return sum<Weight<W>>(k, std::make_index_sequence<T::stages>{});
  }

 private:
  template <std::size_t I>
  struct Row {
    template <std::size_t J>
    static constexpr double of() { return T::a[I][J]; }
  };
  template <Weights W>
  struct Weight {
    template <std::size_t J>
    static constexpr double of() {
      if constexpr (W == Weights::b) return T::b[J];
      else return T::b[J] - T::b_hat[J];
    }
  };

  template <class Coefficients, class K, std::size_t... J>
  static double sum(const K& k, std::index_sequence<J...>) {
    double acc = 0.0;
    ((acc = term<Coefficients::template of<J>()>(acc, k, std::integral_constant<std::size_t, J>{})), ...);
    return acc;
  }

  // A product and a sum, not a mul_add (core/mul_add.hpp): the products of the earlier stages are ready long before
  // the sum needs them and overlap, and a chain of fused operations is longer (4 cycles a link against 3 for an
  // addition). Measured in frames (docs/benchmarks.md): fusing the terms made the 5-variable Kerr system's step up
  // to 1.1x slower; fusing only y + h sum (below) made every system tried faster.
  template <double Coefficient, class K, class J>
  static double term(double acc, const K& k, J j) {
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
  void step(const Rhs& f, const State& y, const State& f0, double h, State& y_new) {
    k_[0] = f0;
    compute_stages(f, y, h, std::make_index_sequence<S - 1>{});
    weighted_update<Weights::b>(y, h, y_new);
  }

  template <class Rhs>
  void step(const Rhs& f, const State& y, const State& f0, double h, State& y_new, State& err) {
    step(f, y, f0, h, y_new);
    if constexpr (has_embedded_pair<T>) weighted_scaled<Weights::difference>(h, err);
  }

  /// k_i of the last step (k_0 = f0; for FSAL tableaux k_{S-1} = f(y_new)).
  const State& stage(std::size_t i) const { return k_[i]; }

  /// y(theta) on the last step, for tableaux that carry their own continuous extension.
  State interpolate(const State& y, double h, double theta) const
    requires TableauWithDenseOutput<T>
  {
    State acc = State::Zero();
    for (std::size_t i = 0; i < S; ++i) {
      double w = 0.0, power = theta;
      for (int d = 0; d < T::dense_degree; ++d, power *= theta) w += T::dense[i][static_cast<std::size_t>(d)] * power;
      acc.noalias() += w * k_[i];
    }
    return y + h * acc;
  }

 private:
  using Sums = StageSums<T>;
  using Weights = typename Sums::Weights;

  // The stage sums are written per component, with the coefficients as compile-time constants (StageSums): one
  // pass over the N components per sum, no Eigen temporaries or out-of-line expression calls (which the profile
  // showed as 15-25 % of a step). The arithmetic is acc = 0; acc += c_0 k_0; acc += c_1 k_1; ...; y + h acc, term by
  // term and in that order, the last "y + h acc" a mul_add (core/mul_add.hpp): rounded once where the processor
  // fuses it (one link less in the chain from a stage to the next), else exactly the Eigen expressions these sums
  // replaced.
  template <class Rhs, std::size_t... I>
  void compute_stages([[maybe_unused]] const Rhs& f, [[maybe_unused]] const State& y, [[maybe_unused]] double h,
                      std::index_sequence<I...>) {
    (compute_stage<I + 1>(f, y, h), ...);
  }

  template <std::size_t I, class Rhs>
  void compute_stage(const Rhs& f, const State& y, double h) {
    State y_stage;
    for (int i = 0; i < N; ++i) y_stage[i] = mul_add(h, Sums::template row<I>(component(i)), y[i]);
    k_[I] = f(y_stage);
  }

  /// Stage J's value of component i, for StageSums.
  auto component(int i) const {
    return [this, i](auto J) { return k_[decltype(J)::value][i]; };
  }

  /// out = base + h sum_j w_j k_j (base given) or h sum_j w_j k_j (no base), component by component.
  template <Weights W>
  void weighted_update(const State& base, double h, State& out) const {
    for (int i = 0; i < N; ++i) out[i] = mul_add(h, Sums::template weighted<W>(component(i)), base[i]);
  }
  template <Weights W>
  void weighted_scaled(double h, State& out) const {
    for (int i = 0; i < N; ++i) out[i] = h * Sums::template weighted<W>(component(i));
  }

  std::array<State, S> k_;
};

}  // namespace grtrace
