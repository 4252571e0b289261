// grtrace/integrate/controlled_integrator.hpp
// The controlled, dense-output integrator: one tableau, one step controller, one error norm, fixed-size state.
//
// Takes:   an autonomous right-hand side f (State -> State) and an initial state.
// Returns: one accepted step per advance() (rejected trials are retried inside), or a failure:
//          step_underflow when the controller asks for h < h_min, non_finite when a fixed-step method
//          produces NaN/Inf (adaptive methods shrink instead, until they underflow).
// Assumes: the controller's error estimate is available for the tableau (an embedded pair for I/PI).
// Dense output on the last accepted step: the tableau's own interpolant where it has one, cubic Hermite otherwise;
// step_from_previous(theta) re-takes a shortened step from its start, as accurate as the integration itself.
// Counts right-hand-side evaluations exactly (FSAL stages are reused; stage 1 is always the stored f(y)).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/optional.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/integrate/dense_output.hpp"
#include "grtrace/integrate/error_norm.hpp"
#include "grtrace/integrate/runge_kutta_stepper.hpp"
#include "grtrace/integrate/step_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grtrace {

struct IntegratorSettings {
  Tolerance tolerance{};
  double h_min = 1e-12;                                    ///< below this the integration fails (step_underflow)
  double h_max = std::numeric_limits<double>::infinity();  ///< cap on any step
};

enum class StepOutcome { ok, step_underflow, non_finite };

/// Where an integration stands besides its state (x, f(x)): the parameter, the step to try next, the counts and the
/// controller's own state. With the state it is all advance() goes on from: what a batched lane keeps of each ray
/// (integrate/batch_integrator.hpp) and hands back with ControlledIntegrator::resume_at.
template <StepController Controller>
struct IntegrationCounters {
  double lambda = 0.0;
  double h_next = 0.0;
  int accepted = 0;
  int rejected = 0;
  long rhs_evals = 0;
  Controller controller{};
};

template <ExplicitTableau T, StepController Controller, int N, class Norm = RmsNorm>
class ControlledIntegrator {
  static_assert(Controller::estimate != ErrorEstimate::embedded || has_embedded_pair<T>,
                "this controller needs an embedded error estimate, but the tableau has no embedded pair: "
                "use StepDoubling or FixedStep with it");

 public:
  using State = Vector<N>;
  using Tableau = T;
  using ControllerType = Controller;

  GRTRACE_HD explicit ControlledIntegrator(IntegratorSettings settings = {}, Controller controller = {}, Norm norm = {})
      : settings_(settings), controller_(controller), norm_(norm) {}

  /// Exponent k of the controller law: (order of the local error estimate) + 1.
  static constexpr GRTRACE_HD int error_exponent() {
    if constexpr (Controller::estimate == ErrorEstimate::embedded) return std::min(T::order, T::embedded_order) + 1;
    else return T::order + 1;
  }

  /// Starts at y0 with step h0; h0 <= 0 picks one automatically (Hairer, Norsett & Wanner I, II.4, "hinit").
  template <class Rhs>
  GRTRACE_HD void start(const Rhs& f, const State& y0, double h0) {
    y_ = y0;
    f_ = evaluate_rhs(f, y0);
    rhs_evals_ = 1;
    accepted_ = rejected_ = 0;
    lambda_ = 0.0;
    h_last_ = 0.0;
    controller_.reset();
    h_ = h0 > 0.0 ? h0 : initial_step(f);
    h_ = std::min(h_, settings_.h_max);
  }

  /// One accepted step. Flattened on the CPU (GCC/Clang: everything it calls is inlined into it, the stepper's
  /// stages and the right-hand side each of them evaluates): measured 0.74-0.88 of the time per general-tracer frame
  /// against the compiler's own choices (tsit5, dopri5, rkf78; docs/benchmarks-archive.md, "The flattened step (all
  /// tracers)"), for ~20 % more compile time.
  /// Not on the GPU, where the code's size is the cost (core/host_device.hpp).
  /// Where a trial's stages live differs: on the CPU in the integrator's stepper; on the GPU in a stepper of this
  /// call, from copies of the state and its derivative, so that nothing the stages write or read is reachable from
  /// outside the call and they stay in registers. There the integrator itself is in local memory (event refinement
  /// takes it by reference, through a call), and stages kept in it were each stored and read back by every later
  /// stage: the Kerr disk kernel 20.9 -> 19.1 ms, the main frame's general kernel 21.8 -> 17.0 ms (H200,
  /// docs/benchmarks.md, "GPU"). On the CPU the same change made rays 3-6 % slower, so it is the GPU's only.
  template <class Rhs>
  GRTRACE_FLATTEN_CPU GRTRACE_HD StepOutcome advance(const Rhs& f) {
    for (;;) {
      const Optional<double> trial = trial_step();
      if (!trial) return StepOutcome::step_underflow;
      const double h = *trial;
      if constexpr (GRTRACE_DEVICE_PASS) {
        Stepper stepper;
        const State y = y_, f0 = f_;
        if (const auto outcome = try_step(f, stepper, y, f0, h)) {
          if constexpr (TableauWithDenseOutput<T>) {
            if (*outcome == StepOutcome::ok) stepper_ = stepper;  // dense() interpolates on the accepted stages
          }
          return *outcome;
        }
      } else {
        if (const auto outcome = try_step(f, stepper_, y_, f_, h)) return *outcome;
      }
    }
  }

  /// The step the next trial takes, min(next_step(), h_max); nothing when it is below h_min (advance() then ends
  /// with step_underflow).
  GRTRACE_HD Optional<double> trial_step() const {
    const double h = std::min(h_, settings_.h_max);
    if (!(h >= settings_.h_min)) return no_value;
    return h;
  }

  /// The verdict on a trial step of size h = *trial_step() from the current state that a batched stepper took on
  /// this integrator's behalf (integrate/batch_stepper.hpp): its result y_new, its embedded error estimate err, and
  /// its last stage (read only for FSAL tableaux). Exactly what advance() does after its own trial step, so a lane
  /// driven this way follows advance()'s steps bit for bit.
  /// Returns: true when the step was accepted (the state moved on: state(), lambda(), ...), false when it was
  /// rejected (next_step() is the step to try instead). Counts the trial's right-hand-side evaluations.
  /// Assumes: a controller on an embedded estimate (I, PI). The stages of a judged step stay in the batched
  /// stepper, so after it dense() reads a tableau's own interpolant from stale stages: use step_from_previous()
  /// (or a tableau without one: cubic Hermite from the kept states) where the step's interior is needed.
  template <class Rhs>
  GRTRACE_FLATTEN_CPU GRTRACE_HD bool judge_trial(const Rhs& f, double h, const State& y_new, const State& err,
                                                  const State& last_stage) requires(Controller::estimate ==
                                                                                    ErrorEstimate::embedded) {
    rhs_evals_ += Stepper::evals_per_step;
    const auto outcome =
        conclude_trial(f, h, y_new, embedded_error_norm(y_, y_new, err), [&]() -> const State& { return last_stage; });
    return outcome.has_value();  // an adaptive controller never ends a trial with non_finite
  }

  /// Replaces the current point by an equivalent one (e.g. the same event in another chart) and goes on from it
  /// with the same step size and controller state. The last step's dense output is no longer available.
  template <class Rhs>
  GRTRACE_HD void reseat(const Rhs& f, const State& y) {
    y_ = y;
    f_ = evaluate_rhs(f, y);
    ++rhs_evals_;
    y_prev_ = y_;
    f_prev_ = f_;
    h_last_ = 0.0;
  }

  /// Everything but the state that advance() goes on from (see IntegrationCounters).
  GRTRACE_HD IntegrationCounters<Controller> counters() const {
    return {lambda_, h_, accepted_, rejected_, rhs_evals_, controller_};
  }

  /// Puts the integrator at a point of an integration carried on elsewhere with the same settings (a lane of a
  /// batched integrator): the state y, its derivative f = f(y) and the counters there. advance() then goes on
  /// exactly, bit for bit, as the integration it was taken from would have. There is no dense output until the
  /// next accepted step (previous_state() is y, last_step() 0).
  GRTRACE_HD void resume_at(const State& y, const State& f, const IntegrationCounters<Controller>& c) {
    y_ = y_prev_ = y;
    f_ = f_prev_ = f;
    lambda_ = c.lambda;
    h_ = c.h_next;
    h_last_ = 0.0;
    accepted_ = c.accepted;
    rejected_ = c.rejected;
    rhs_evals_ = c.rhs_evals;
    controller_ = c.controller;
  }

  /// State at lambda_prev + theta * h on the last accepted step, theta in [0, 1].
  GRTRACE_HD State dense(double theta) const {
    if constexpr (TableauWithDenseOutput<T> && Controller::estimate != ErrorEstimate::step_doubling) {
      return stepper_.interpolate(y_prev_, h_last_, theta);
    } else {
      return hermite_interpolate<N>(y_prev_, f_prev_, y_, f_, h_last_, theta);
    }
  }

  /// The integrator's own step map on the last accepted step: the state it would have produced with the step
  /// theta * h from the step's start (the same tableau and propagated weights; for step doubling the same two
  /// half steps and, if enabled, the same Richardson extrapolation). More accurate than dense(theta) wherever
  /// the interpolant is of lower order than the method: this is what event location refines hits with.
  /// Takes:   the right-hand side f and theta in (0, 1]; theta = 1 reproduces state() bit for bit.
  /// Returns: the state at previous_lambda() + theta * last_step(). No error control: theta * h <= h, and h was
  ///          accepted. Its right-hand-side evaluations are counted in rhs_evals().
  /// Assumes: a step was accepted since start() or reseat() (last_step() > 0). Uses a stepper of its own, so
  ///          dense() still describes the accepted step afterwards.
  template <class Rhs>
  GRTRACE_HD State step_from_previous(const Rhs& f, double theta) {
    const double h = theta * h_last_;
    Stepper probe;
    State y_new;
    if constexpr (Controller::estimate == ErrorEstimate::step_doubling) {
      State y_mid, y_two;
      probe.step(f, y_prev_, f_prev_, 0.5 * h, y_mid);
      const State f_mid = evaluate_rhs(f, y_mid);
      probe.step(f, y_mid, f_mid, 0.5 * h, y_two);
      rhs_evals_ += 2 * Stepper::evals_per_step + 1;
      if (controller_.richardson) {
        State y_full;
        probe.step(f, y_prev_, f_prev_, h, y_full);
        rhs_evals_ += Stepper::evals_per_step;
        const State err = (y_two - y_full) / (std::pow(2.0, T::order) - 1.0);  // as in doubling_step
        y_new = y_two + err;
      } else {
        y_new = y_two;
      }
    } else {
      probe.step(f, y_prev_, f_prev_, h, y_new);
      rhs_evals_ += Stepper::evals_per_step;
    }
    return y_new;
  }

  /// f(y), counted in rhs_evals(): for work done on the integration's behalf outside advance() (event
  /// refinement), so that the count stays the honest total.
  template <class Rhs>
  GRTRACE_HD State evaluate(const Rhs& f, const State& y) {
    ++rhs_evals_;
    return evaluate_rhs(f, y);
  }

  GRTRACE_HD const State& state() const { return y_; }
  GRTRACE_HD const State& derivative() const { return f_; }
  GRTRACE_HD const State& previous_state() const { return y_prev_; }
  GRTRACE_HD double lambda() const { return lambda_; }
  GRTRACE_HD double previous_lambda() const { return lambda_ - h_last_; }
  GRTRACE_HD double last_step() const { return h_last_; }
  GRTRACE_HD double next_step() const { return h_; }
  GRTRACE_HD int accepted() const { return accepted_; }
  GRTRACE_HD int rejected() const { return rejected_; }
  GRTRACE_HD long rhs_evals() const { return rhs_evals_; }
  GRTRACE_HD const IntegratorSettings& settings() const { return settings_; }
  GRTRACE_HD Controller& controller() { return controller_; }

 private:
  using Stepper = RungeKuttaStepper<T, N>;

  // One trial step of size h from y (the current state) with f0 = f(y), its stages on `stepper`: the verdict of
  // conclude_trial, or non_finite for a fixed step whose result is not finite.
  template <class Rhs>
  GRTRACE_HD Optional<StepOutcome> try_step(const Rhs& f, Stepper& stepper, const State& y, const State& f0,
                                            double h) {
    State y_new;
    double err_norm = 0.0;
    if constexpr (Controller::estimate == ErrorEstimate::none) {
      stepper.step(f, y, f0, h, y_new);
      rhs_evals_ += Stepper::evals_per_step;
      if (!all_finite(y_new)) return StepOutcome::non_finite;
    } else if constexpr (Controller::estimate == ErrorEstimate::embedded) {
      State err;
      stepper.step(f, y, f0, h, y_new, err);
      rhs_evals_ += Stepper::evals_per_step;
      err_norm = embedded_error_norm(y, y_new, err);
    } else {
      err_norm = doubling_step(f, stepper, y, f0, h, y_new);
    }
    return conclude_trial(f, h, y_new, err_norm, [&]() -> const State& { return stepper.stage(T::stages - 1); });
  }

  // The scaled norm of an embedded error estimate of a step from y to y_new; infinite when y_new is not finite.
  GRTRACE_HD double embedded_error_norm(const State& y, const State& y_new, const State& err) const {
    return all_finite(y_new) ? norm_(err, y, y_new, settings_.tolerance) : std::numeric_limits<double>::infinity();
  }

  // The controller's verdict on a trial step of size h with result y_new and error norm err_norm: accepted (the
  // state moves on; StepOutcome::ok), a failure (StepOutcome::non_finite, fixed steps only), or rejected (nothing:
  // h_ is the step to try next). last_stage() is the trial's last stage, f(y_new) for FSAL tableaux.
  template <class Rhs, class LastStage>
  GRTRACE_HD Optional<StepOutcome> conclude_trial(const Rhs& f, double h, const State& y_new, double err_norm,
                                                  const LastStage& last_stage) {
    const StepDecision decision = controller_.decide(err_norm, h, error_exponent());
    if (decision.accept) {
      State f_new;
      if constexpr (T::fsal && Controller::estimate != ErrorEstimate::step_doubling) {
        f_new = last_stage();
      } else {
        f_new = evaluate_rhs(f, y_new);
        ++rhs_evals_;
      }
      if (all_finite(f_new) && all_finite(y_new)) {
        y_prev_ = y_;
        f_prev_ = f_;
        y_ = y_new;
        f_ = f_new;
        lambda_ += h;
        h_last_ = h;
        h_ = decision.h_next;
        ++accepted_;
        return StepOutcome::ok;
      }
      if constexpr (Controller::estimate == ErrorEstimate::none) {
        return StepOutcome::non_finite;
      } else {
        ++rejected_;  // the new point itself is singular: shrink and retry
        h_ = h * StepFactorLimits{}.min_factor;
        return no_value;
      }
    }
    ++rejected_;
    h_ = decision.h_next;
    return no_value;
  }

  // Two half steps against one full step from y (the current state) with f0 = f(y), on `stepper`; returns the
  // scaled error norm and the value to propagate.
  template <class Rhs>
  GRTRACE_HD double doubling_step(const Rhs& f, Stepper& stepper, const State& y, const State& f0, double h,
                                  State& y_new) {
    State y_full, y_mid, y_two;
    stepper.step(f, y, f0, h, y_full);
    stepper.step(f, y, f0, 0.5 * h, y_mid);
    const State f_mid = evaluate_rhs(f, y_mid);
    stepper.step(f, y_mid, f_mid, 0.5 * h, y_two);
    rhs_evals_ += 3 * Stepper::evals_per_step + 1;
    const State err = (y_two - y_full) / (std::pow(2.0, T::order) - 1.0);
    y_new = controller_.richardson ? State(y_two + err) : y_two;
    if (!all_finite(y_new) || !all_finite(y_full)) return std::numeric_limits<double>::infinity();
    return norm_(err, y, y_new, settings_.tolerance);
  }

  template <class Rhs>
  GRTRACE_GPU_CALLED GRTRACE_HD double initial_step(const Rhs& f) {
    const Tolerance& tol = settings_.tolerance;
    auto scaled = [&](const State& v) {
      double s = 0.0;
      for (int i = 0; i < N; ++i) {
        const double sc = tol.atol + tol.rtol * std::abs(y_[i]);
        s += (v[i] / sc) * (v[i] / sc);
      }
      return std::sqrt(s / N);
    };
    const double d0 = scaled(y_), d1 = scaled(f_);
    double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    const State f1 = evaluate_rhs(f, State(y_ + h0 * f_));
    ++rhs_evals_;
    const double d2 = scaled(State(f1 - f_)) / h0;
    const double dmax = std::max(d1, d2);
    const double h1 = dmax <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dmax, 1.0 / (T::order + 1));
    const double h = std::min(100.0 * h0, h1);
    return std::isfinite(h) && h > 0.0 ? h : 1e-6;
  }

  IntegratorSettings settings_;
  Controller controller_;
  Norm norm_;
  Stepper stepper_;
  State y_ = State::Zero(), f_ = State::Zero(), y_prev_ = State::Zero(), f_prev_ = State::Zero();
  double lambda_ = 0.0, h_ = 0.0, h_last_ = 0.0;
  int accepted_ = 0, rejected_ = 0;
  long rhs_evals_ = 0;
};

}  // namespace grtrace
