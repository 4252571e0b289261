// grtrace/integrate/event_locator.hpp
// Locates where a scalar event function first becomes <= 0 inside an accepted step, on the dense output,
// so that a surface is hit where it is and not one step late.
//
// Takes:   g(theta) (the event function composed with the step's interpolant), its values at both ends,
//          and how many interior samples to look at (to catch a surface entered and left within one step).
// Returns: the smallest theta in (0, 1] with g(theta) <= 0 to within `theta_tol`, or nothing.
// Method:  bracket by sampling, then the Illinois variant of regula falsi (Dowell & Jarratt 1971):
//          superlinear, and never leaves the bracket.
// The interpolant is only as accurate as its own order (cubic Hermite for tableaux without a continuous
// extension), so refine_crossing() then moves the crossing onto the integration's own step map (see
// ControlledIntegrator::step_from_previous) with a secant iteration started from the interpolant's answer.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/optional.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace grtrace {

struct EventCrossing {
  double theta;  ///< step fraction of the crossing
  double value;  ///< g at theta (<= 0 up to the tolerance)
};

template <class G>
GRTRACE_GPU_CALLED GRTRACE_HD Optional<EventCrossing> locate_first_crossing(const G& g, double g0, double g1,
                                                                            int interior_samples = 0,
                                                                            double theta_tol = 1e-13) {
  if (!(g0 > 0.0)) return EventCrossing{0.0, g0};  // already inside at the start of the step
  double a = 0.0, ga = g0, b = 1.0, gb = g1;
  bool bracketed = false;
  const int pieces = interior_samples + 1;
  for (int j = 1; j <= pieces; ++j) {
    const double t = static_cast<double>(j) / pieces;
    const double gt = j == pieces ? g1 : g(t);
    if (gt <= 0.0 || !std::isfinite(gt)) {
      b = t;
      gb = gt;
      bracketed = true;
      break;
    }
    a = t;
    ga = gt;
  }
  if (!bracketed) return no_value;
  if (!std::isfinite(gb)) {  // cannot interpolate through a non-finite value: bisect it away first
    for (int i = 0; i < 60 && !std::isfinite(gb); ++i) {
      const double m = 0.5 * (a + b);
      const double gm = g(m);
      if (std::isfinite(gm) && gm > 0.0) { a = m; ga = gm; }
      else { b = m; gb = gm; }
    }
    if (!std::isfinite(gb)) return EventCrossing{b, gb};
  }
  int side = 0;
  for (int it = 0; it < 100 && b - a > theta_tol; ++it) {
    double m = (a * gb - b * ga) / (gb - ga);
    if (!(m > a && m < b)) m = 0.5 * (a + b);
    const double gm = g(m);
    if (gm <= 0.0) {
      b = m;
      gb = gm;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = m;
      ga = gm;
      if (side == +1) gb *= 0.5;
      side = +1;
    }
    if (gm == 0.0) break;
  }
  return EventCrossing{b, gb};
}

/// What a probe of refine_crossing returns: g at the probed point and what was computed there (a plain struct, not
/// std::pair, whose constructors are not callable on a GPU).
template <class Payload>
struct Probed {
  double g;
  Payload payload;
};

/// A crossing refined on an accurate but costly probe of the step, with what the probe returned there.
template <class Payload>
struct RefinedCrossing {
  double theta;         ///< step fraction of the probed point (the crossing is at theta + pending)
  double value;         ///< g at theta (near 0; either sign)
  Payload payload;      ///< what the probe computed at theta (e.g. the state there)
  int probes;           ///< probe calls spent
  bool converged;       ///< the last secant correction was below linear_limit
  double pending = 0.;  ///< that last correction, not probed: apply it to the payload to first order
};

/// Refines a crossing found on a step's interpolant with a probe that is more accurate but costs a step each
/// (the event function on the integrator's step map): a secant iteration on theta started from the
/// interpolant's crossing, whose first correction uses the interpolant's slope there.
/// Takes:   probe(theta) -> Probed<Payload> (g and what was computed), for theta in (0, 1];
///          theta0, the interpolant's crossing in (0, 1]; slope0, dg/dtheta of the interpolant at theta0;
///          linear_limit: a correction this small (as a step fraction) is not probed but returned as `pending`,
///          for the caller to apply with the payload's derivative, if it is also accurate: a secant iterate
///          is off by about |g''/2g'| times the product of the last two corrections (the first correction,
///          with the interpolant's slope, counts as its own predecessor), and that product must not exceed
///          linear_limit^2. With the default 1e-7 both the iterate's error (~1e-14 of the step) and the
///          first-order Taylor error ~ (linear_limit h)^2 |y''| / 2 stay below round-off of y on any step whose
///          h^2 |y''| does not exceed about |y|. max_probes >= 1.
/// Returns: the last probed point and the correction still pending on it, when the iteration converges; else
///          the probed point with the smallest |g| and no pending correction. Nothing if the probe gave a
///          non-finite g at theta0. Never probes outside (0, 1]: an iterate beyond 1 is clamped to 1, one at or
///          below 0 halves the current theta.
/// Assumes: the probe and the interpolant differ by little more than the interpolant's error, so the crossing
///          sought is the one next to theta0. The secant then converges superlinearly: one probe with a
///          tableau's own (order >= 4) interpolant, two with cubic Hermite.
template <class Probe>
GRTRACE_HD auto refine_crossing(const Probe& probe, double theta0, double slope0, double linear_limit = 1e-7,
                                int max_probes = 8) -> Optional<RefinedCrossing<decltype(probe(0.0).payload)>> {
  using Payload = decltype(probe(0.0).payload);
  auto [g0, p0] = probe(theta0);
  if (!std::isfinite(g0)) return no_value;
  RefinedCrossing<Payload> best{theta0, g0, std::move(p0), 1, false};
  double t = theta0, g = g0, slope = slope0;
  double last_correction = std::numeric_limits<double>::quiet_NaN();  // none yet
  bool last_is_best = true;
  while (true) {
    if (g == 0.0 && last_is_best) {
      best.converged = true;
      break;
    }
    if (!(std::isfinite(slope) && slope != 0.0)) break;
    double t_next = t - g / slope;
    if (!std::isfinite(t_next)) break;
    // The step being refined is [0, 1]: a crossing the secant puts outside lies at its edge, or the slope is off.
    if (t_next > 1.0) t_next = 1.0;
    if (t_next <= 0.0) t_next = 0.5 * t;
    const double correction = std::abs(t_next - t);
    const double previous = std::isnan(last_correction) ? correction : last_correction;
    if (correction <= linear_limit && correction * previous <= linear_limit * linear_limit && last_is_best) {
      best.converged = true;
      best.pending = t_next - t;
      break;
    }
    last_correction = correction;
    if (best.probes >= max_probes) break;
    auto [g_next, p_next] = probe(t_next);
    ++best.probes;
    if (!std::isfinite(g_next)) break;
    slope = (g_next - g) / (t_next - t);
    t = t_next;
    g = g_next;
    last_is_best = std::abs(g) <= std::abs(best.value);
    if (last_is_best) {
      best.theta = t;
      best.value = g;
      best.payload = std::move(p_next);
    }
  }
  return best;
}

}  // namespace grtrace
