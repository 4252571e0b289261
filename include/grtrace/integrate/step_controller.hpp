// grtrace/integrate/step_controller.hpp
// Step-size controllers as policies. Each names the error estimate it needs and turns an error norm
// (<= 1 means acceptable) into accept/reject and the next step size.
//
//   FixedStep     no estimate; every step is accepted with the same h.
//   StepDoubling  the seed report's scheme (sec. 3.1.3): two steps of h/2 against one of h; the difference
//                 divided by 2^p - 1 estimates the error of the pair (Richardson). Optionally the
//                 extrapolated value is propagated (order p + 1). Any tableau works.
//   IController   elementary controller on an embedded pair: h_new = h * safety * err^(-1/k).
//   PIController  Gustafsson's PI controller (Gustafsson 1991; Hairer & Wanner II, sec. IV.2):
//                 h_new = h * safety * err^(-alpha) * err_prev^(beta), alpha = 0.7/k, beta = 0.4/k.
// k = (order of the error estimate) + 1; supplied by the integrator.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/inverse_root.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace grtrace {

enum class ErrorEstimate { none, step_doubling, embedded };

struct StepDecision {
  bool accept;
  double h_next;
};

/// Bounds shared by the adaptive controllers: how much a step may shrink or grow at once.
struct StepFactorLimits {
  double safety = 0.9;
  double min_factor = 0.2;
  double max_factor = 5.0;

  GRTRACE_HD double clamp(double factor) const { return std::clamp(factor, min_factor, max_factor); }
};

struct FixedStep {
  static constexpr std::string_view name = "fixed";
  static constexpr ErrorEstimate estimate = ErrorEstimate::none;
  GRTRACE_HD StepDecision decide(double /*err*/, double h, int /*k*/) { return {true, h}; }
  GRTRACE_HD void reset() {}
};

namespace controller_detail {
/// x^k for a small positive integer k, by multiplication.
constexpr GRTRACE_HD double integer_power(double x, int k) {
  double p = 1.0;
  for (int i = 0; i < k; ++i) p *= x;
  return p;
}

/// True when safety * err^(-1/k) is certainly above lim.max_factor, i.e. the law's pow would be clamped anyway:
/// err < (safety / max_factor)^k, with a relative margin of 1e-9 that pow's rounding (< 1 ulp) cannot cross, so
/// skipping pow never changes a decision. Steps held down by h_max (small err) are common; pow is not cheap.
inline GRTRACE_HD bool grows_by_max_factor(const StepFactorLimits& lim, double err, int k) {
  return err < integer_power(lim.safety / lim.max_factor, k) * (1.0 - 1e-9);
}

/// The elementary (I) law. A non-finite error (NaN stage) shrinks by the largest allowed factor.
/// err^(-1/k) is inverse_root (core/inverse_root.hpp), not std::pow: it lies on the chain from one step to the next
/// and costs half of pow's latency (within 4 ulp of the exact root, so step sizes agree with pow's to round-off).
inline GRTRACE_HD StepDecision elementary(const StepFactorLimits& lim, double err, double h, int k) {
  if (!std::isfinite(err)) return {false, h * lim.min_factor};
  if (err <= 1.0) {
    const double factor = grows_by_max_factor(lim, err, k) ? lim.max_factor : lim.safety * inverse_root(err, k);
    return {true, h * lim.clamp(factor)};
  }
  return {false, h * lim.clamp(std::min(lim.safety * inverse_root(err, k), lim.safety))};
}
}  // namespace controller_detail

struct IController {
  static constexpr std::string_view name = "i";
  static constexpr ErrorEstimate estimate = ErrorEstimate::embedded;
  StepFactorLimits limits{};
  GRTRACE_HD StepDecision decide(double err, double h, int k) {
    return controller_detail::elementary(limits, err, h, k);
  }
  GRTRACE_HD void reset() {}
};

struct StepDoubling {
  static constexpr std::string_view name = "doubling";
  static constexpr ErrorEstimate estimate = ErrorEstimate::step_doubling;
  StepFactorLimits limits{};
  bool richardson = false;  ///< propagate the extrapolated value instead of the two half steps
  GRTRACE_HD StepDecision decide(double err, double h, int k) {
    return controller_detail::elementary(limits, err, h, k);
  }
  GRTRACE_HD void reset() {}
};

struct PIController {
  static constexpr std::string_view name = "pi";
  static constexpr ErrorEstimate estimate = ErrorEstimate::embedded;
  StepFactorLimits limits{};
  double alpha_times_k = 0.7;
  double beta_times_k = 0.4;
  double err_prev = 1.0;        ///< error norm of the last accepted step
  bool rejected_last = false;   ///< after a rejection the step may not grow (Hairer's DOPRI5 rule)

  GRTRACE_HD StepDecision decide(double err, double h, int k) {
    if (!std::isfinite(err) || err > 1.0) {
      rejected_last = true;
      return controller_detail::elementary(limits, err, h, k);
    }
    const double e = std::max(err, 1e-10);
    double factor = limits.safety * std::pow(e, -alpha_times_k / k) * std::pow(err_prev, beta_times_k / k);
    factor = limits.clamp(factor);
    if (rejected_last) factor = std::min(factor, 1.0);
    err_prev = std::max(err, 1e-4);
    rejected_last = false;
    return {true, h * factor};
  }
  GRTRACE_HD void reset() {
    err_prev = 1.0;
    rejected_last = false;
  }
};

template <class C>
concept StepController = requires(C c, double e, double h, int k) {
  { C::name } -> std::convertible_to<std::string_view>;
  { C::estimate } -> std::convertible_to<ErrorEstimate>;
  { c.decide(e, h, k) } -> std::same_as<StepDecision>;
  c.reset();
};

}  // namespace grtrace
