// grtrace/integrate/batch_integrator.hpp
// W independent adaptive integrations advanced side by side, their states kept lane-innermost between steps.
//
// Why: one ray's step is a chain of dependent operations (each stage waits for the last right-hand side), so a
// processor with four-wide registers runs it at a quarter of its width. W rays in lanes give W independent chains
// per instruction: the stage sums and, for a metric with a lane acceleration (metric/metric_traits.hpp
// HasLaneAcceleration), the right-hand side itself. Lanes gathered from and scattered back into W scalar integrators
// every trial measured slower than one ray at a time: the traffic cost more than the overlap saved
// (docs/benchmarks-archive.md, "The build machine's instruction set": "Tried, not kept: batching the general tracer
// through per-ray integrators"). Here the lanes' states stay in the batch, and only the controller's decision (a
// few scalars) is taken lane by lane.
//
// Takes:   a batched right-hand side f(const Batch<N, W>&, Batch<N, W>&) (integrate/batch_stepper.hpp), each lane
//          loaded from a started ControlledIntegrator (load) with the same settings and controller type.
// Returns: per trial() and lane, a TrialVerdict: the trial was rejected (the lane already holds the smaller step),
//          accepted (the new point is pending: commit(l) moves the lane on, or the caller leaves the lane where it
//          was and takes the integration over with unload(l), which hands back the point before the trial), or
//          not taken (the next step is below h_min: advance() would fail with step_underflow there).
// Guarantees: each lane takes advance()'s steps bit for bit (the same stage sums, norm, controller and verdict; the
//          lanes' right-hand sides must equal the scalar one per lane), so a ray that moves between a lane and a
//          ControlledIntegrator (load, unload) follows the same steps as one integrated alone throughout
//          (tests/batch_stepper_test.cpp). Embedded error estimates only (I and PI controllers).
#pragma once

#include "grtrace/integrate/batch_stepper.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"

#include <algorithm>
#include <array>
#include <concepts>
#include <cstddef>
#include <limits>

namespace grtrace {

enum class TrialVerdict { idle, accepted, rejected, not_taken };

template <ExplicitTableau T, StepController Controller, int N, int W, class Norm = RmsNorm>
requires(Controller::estimate == ErrorEstimate::embedded) class BatchedIntegrator {
 public:
  using Single = ControlledIntegrator<T, Controller, N, Norm>;
  using State = Vector<N>;
  using Lanes = Batch<N, W>;
  using Verdicts = std::array<TrialVerdict, static_cast<std::size_t>(W)>;
  static constexpr int width = W;

  explicit BatchedIntegrator(IntegratorSettings settings = {}, Norm norm = {}) : settings_(settings), norm_(norm) {
    for (auto& component : y_) component.fill(0.0);
    f_ = y_;
    busy_.fill(false);
  }

  /// Lane l takes over the integration `integ` stands at (started, or resumed; its dense output is not needed).
  void load(int l, const Single& integ) {
    set_lane(y_, l, integ.state());
    set_lane(f_, l, integ.derivative());
    counters_[at(l)] = integ.counters();
    busy_[at(l)] = true;
  }

  /// Hands lane l's current point to integ (ControlledIntegrator::resume_at) and leaves the lane idle. After an
  /// accepted but uncommitted trial that is the point before the trial.
  void unload(int l, Single& integ) {
    integ.resume_at(lane_of(y_, l), lane_of(f_, l), counters_[at(l)]);
    busy_[at(l)] = false;
  }

  /// Lane l stops (its last values stay, finite, so the idle lane computes harmlessly).
  void idle(int l) { busy_[at(l)] = false; }
  bool busy(int l) const { return busy_[at(l)]; }
  const IntegrationCounters<Controller>& counters(int l) const { return counters_[at(l)]; }

  /// One trial step on every busy lane (see the top of this file for the verdicts).
  template <class BatchRhs>
  [[gnu::flatten]] Verdicts trial(const BatchRhs& f) {
    Verdicts verdict{};
    std::array<double, static_cast<std::size_t>(W)> h{};
    for (int l = 0; l < W; ++l) {
      verdict[at(l)] = TrialVerdict::idle;
      if (!busy_[at(l)]) continue;
      // ControlledIntegrator::trial_step
      const double step = std::min(counters_[at(l)].h_next, settings_.h_max);
      if (step >= settings_.h_min) {
        h[at(l)] = step;
        verdict[at(l)] = TrialVerdict::rejected;  // until judged
      } else {
        verdict[at(l)] = TrialVerdict::not_taken;
      }
    }
    stepper_.step(f, y_, f_, h, y_new_, err_);
    std::array<StepDecision, static_cast<std::size_t>(W)> decision{};
    const std::array<double, static_cast<std::size_t>(W)> norms = lane_norms();
    bool any_accept = false;
    for (int l = 0; l < W; ++l) {
      if (verdict[at(l)] != TrialVerdict::rejected) continue;
      const double err_norm = all_finite(lane_of(y_new_, l)) ? norms[at(l)] : std::numeric_limits<double>::infinity();
      pending_[at(l)] = counters_[at(l)];
      pending_[at(l)].rhs_evals += Stepper::evals_per_step;
      decision[at(l)] = pending_[at(l)].controller.decide(err_norm, h[at(l)], Single::error_exponent());
      any_accept = any_accept || decision[at(l)].accept;
    }
    // The new points' derivatives: the last stage of an FSAL tableau, else one more evaluation (counted only for
    // the lanes whose step the controller accepted, as advance() counts it).
    if constexpr (T::fsal) {
      f_new_ = stepper_.stage(T::stages - 1);
    } else {
      if (any_accept) f(y_new_, f_new_);
    }
    for (int l = 0; l < W; ++l) {
      if (verdict[at(l)] != TrialVerdict::rejected) continue;
      IntegrationCounters<Controller>& c = pending_[at(l)];
      const StepDecision d = decision[at(l)];
      // ControlledIntegrator::conclude_trial, embedded estimate
      if (d.accept) {
        if constexpr (!T::fsal) ++c.rhs_evals;
        if (all_finite(lane_of(f_new_, l)) && all_finite(lane_of(y_new_, l))) {
          c.lambda += h[at(l)];
          c.h_next = d.h_next;
          ++c.accepted;
          verdict[at(l)] = TrialVerdict::accepted;
          continue;
        }
        ++c.rejected;  // the new point itself is singular: shrink and retry
        c.h_next = h[at(l)] * StepFactorLimits{}.min_factor;
      } else {
        ++c.rejected;
        c.h_next = d.h_next;
      }
      counters_[at(l)] = c;
    }
    return verdict;
  }

  /// The pending new point of lane l after an accepted trial.
  State candidate(int l) const { return lane_of(y_new_, l); }

  /// Lane l moves on to its pending new point (after an accepted trial).
  void commit(int l) {
    for (int i = 0; i < N; ++i) {
      y_[at(i)][at(l)] = y_new_[at(i)][at(l)];
      f_[at(i)][at(l)] = f_new_[at(i)][at(l)];
    }
    counters_[at(l)] = pending_[at(l)];
  }

 private:
  using Stepper = RungeKuttaBatchStepper<T, N, W>;
  static constexpr std::size_t at(int i) { return static_cast<std::size_t>(i); }

  // The error norm of every lane's trial: all lanes at once where the norm offers it (RmsNorm), else lane by lane.
  std::array<double, static_cast<std::size_t>(W)> lane_norms() const {
    if constexpr (requires {
                    {
                      norm_(err_, y_, y_new_, settings_.tolerance)
                      } -> std::same_as<std::array<double, static_cast<std::size_t>(W)>>;
                  }) {
      return norm_(err_, y_, y_new_, settings_.tolerance);
    } else {
      std::array<double, static_cast<std::size_t>(W)> norms{};
      for (int l = 0; l < W; ++l)
        norms[at(l)] = norm_(lane_of(err_, l), lane_of(y_, l), lane_of(y_new_, l), settings_.tolerance);
      return norms;
    }
  }

  IntegratorSettings settings_;
  Norm norm_;
  Stepper stepper_;
  Lanes y_, f_, y_new_, err_, f_new_;
  std::array<bool, static_cast<std::size_t>(W)> busy_{};
  std::array<IntegrationCounters<Controller>, static_cast<std::size_t>(W)> counters_{}, pending_{};
};

}  // namespace grtrace
