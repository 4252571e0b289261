// grtrace/integrate/batch_stepper.hpp
// One explicit Runge-Kutta step of W independent problems at once (W "lanes", each with its own state and step).
//
// Why: a small system (the planar table's u'' = G(u), two components) leaves the processor waiting: every stage
// sum is a chain of dependent additions, one per earlier stage, and two components are too few to overlap them.
// W problems side by side give W independent chains per component, laid out lane-innermost so the compiler keeps
// them in vector registers (two lanes per SSE2 register as built, more with wider instruction sets).
//
// Takes:   a batched right-hand side f(const Batch&, Batch&) (all lanes), the lanes' states y, their derivatives
//          f0 = f(y) (kept by the caller, so stage 1 is never evaluated again) and steps h (one per lane).
// Returns: y_new = y + h sum_i b_i k_i and, for embedded pairs, err = h sum_i (b_i - b_hat_i) k_i, per lane.
// Guarantees: each lane's numbers are bit for bit those of RungeKuttaStepper<T, N> on that lane alone: the same
//          sums (StageSums, integrate/runge_kutta_stepper.hpp), the same operations in the same order; a lane
//          never reads another. Lanes the caller does not use still compute (on whatever values they hold); keep
//          them finite or ignore their results.
#pragma once

#include "grtrace/integrate/runge_kutta_stepper.hpp"

#include <array>
#include <cstddef>
#include <utility>

namespace grtrace {

/// N components of W lanes, component-major: b[i][l] is component i of lane l.
template <int N, int W>
using Batch = std::array<std::array<double, static_cast<std::size_t>(W)>, static_cast<std::size_t>(N)>;

template <ExplicitTableau T, int N, int W>
class RungeKuttaBatchStepper {
  static_assert(W >= 1, "a batch needs at least one lane");
  static_assert(tableau_is_valid<T>(), "tableau fails its compile-time checks (see GRTRACE_CHECK_TABLEAU)");

 public:
  using State = Batch<N, W>;
  using Steps = std::array<double, static_cast<std::size_t>(W)>;
  static constexpr std::size_t S = T::stages;
  /// Right-hand-side evaluations one call of step() costs per lane (stage 1 reuses f0), as for the scalar stepper.
  static constexpr int evals_per_step = static_cast<int>(S) - 1;

  template <class Rhs>
  void step(const Rhs& f, const State& y, const State& f0, const Steps& h, State& y_new) {
    k_[0] = f0;
    compute_stages(f, y, h, std::make_index_sequence<S - 1>{});
    for (int i = 0; i < N; ++i)
      for (int l = 0; l < W; ++l)
        y_new[idx(i)][idx(l)] = Sums::template update<Weights::b>(at(i, l), h[idx(l)], y[idx(i)][idx(l)]);
  }

  template <class Rhs>
  void step(const Rhs& f, const State& y, const State& f0, const Steps& h, State& y_new, State& err) {
    step(f, y, f0, h, y_new);
    if constexpr (has_embedded_pair<T>)
      for (int i = 0; i < N; ++i)
        for (int l = 0; l < W; ++l)
          err[idx(i)][idx(l)] = Sums::template scaled<Weights::difference>(at(i, l), h[idx(l)]);
  }

  /// k_i of the last step, all lanes (k_0 = f0; for FSAL tableaux k_{S-1} = f(y_new)).
  const State& stage(std::size_t i) const { return k_[i]; }

 private:
  using Sums = StageSums<T>;
  using Weights = typename Sums::Weights;

  static constexpr std::size_t idx(int i) { return static_cast<std::size_t>(i); }

  template <class Rhs, std::size_t... I>
  void compute_stages(const Rhs& f, const State& y, const Steps& h, std::index_sequence<I...>) {
    (compute_stage<I + 1>(f, y, h), ...);
  }

  template <std::size_t I, class Rhs>
  void compute_stage(const Rhs& f, const State& y, const Steps& h) {
    State y_stage;
    for (int i = 0; i < N; ++i)
      for (int l = 0; l < W; ++l)
        y_stage[idx(i)][idx(l)] = Sums::template input<I>(at(i, l), h[idx(l)], y[idx(i)][idx(l)]);
    f(y_stage, k_[I]);
  }

  /// Stage J's value of component i in lane l, for StageSums.
  auto at(int i, int l) const {
    return [this, i, l](auto J) { return k_[decltype(J)::value][idx(i)][idx(l)]; };
  }

  std::array<State, S> k_{};
};

/// Lane l of a batch as a state of the scalar integrator, and back.
template <std::size_t N, std::size_t W>
Vector<static_cast<int>(N)> lane_of(const std::array<std::array<double, W>, N>& b, int l) {
  Vector<static_cast<int>(N)> v;
  for (std::size_t i = 0; i < N; ++i) v[static_cast<Eigen::Index>(i)] = b[i][static_cast<std::size_t>(l)];
  return v;
}
template <std::size_t N, std::size_t W>
void set_lane(std::array<std::array<double, W>, N>& b, int l, const Vector<static_cast<int>(N)>& v) {
  for (std::size_t i = 0; i < N; ++i) b[i][static_cast<std::size_t>(l)] = v[static_cast<Eigen::Index>(i)];
}

}  // namespace grtrace
