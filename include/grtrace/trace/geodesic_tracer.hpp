// grtrace/trace/geodesic_tracer.hpp
// Traces one geodesic (null or timelike) through a metric with a chosen tableau and step controller.
//
// Takes:   the initial state (x^mu, k^mu), settings, and any number of user events: callables
//          g(const GeodesicState&) -> double that are positive outside a surface and <= 0 on or inside it.
// Returns: a TraceResult with the status (captured, escaped, hit, max_steps, step_underflow, non_finite),
//          the final state (on the surface that ended the ray, located on the dense output), the counts of
//          accepted/rejected steps and right-hand-side evaluations, and the drift of g(k, k).
// Assumes: the ray starts outside the horizon guard and inside the escape sphere (else it ends at once).
// Termination surfaces are events like any other: horizon guard r = (1 + eps) r_h, escape sphere r = R.
// An observer, if given, sees every accepted step (and the last, cut at the surface) with the integrator's
// dense output, so paths can be drawn as smooth curves.
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"
#include "grtrace/integrate/event_locator.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <utility>

namespace grtrace {

struct TraceSettings {
  IntegratorSettings integrator{};
  double initial_step = 0.0;      ///< <= 0: chosen automatically (adaptive) ; the step itself for FixedStep
  int max_steps = 100000;         ///< accepted steps before the ray ends as max_steps
  double escape_radius = 1000.0;  ///< the ray has escaped when radius(x) >= this
  double horizon_epsilon = 1e-3;  ///< captured when r <= (1 + eps) r_h (Schwarzschild coordinates never cross r_h)
  /// Constraint guard: the ray ends as non_finite when |g(k,k) - g(k0,k0)| exceeds this fraction of the size of
  /// g(k,k)'s terms (sum |g_mn k^m k^n|). The numbers then no longer describe a geodesic (typically a fixed step
  /// too large near the horizon, where k^t grows without bound). <= 0 switches the guard off.
  double constraint_tolerance = 1e-2;
};

struct TraceResult {
  RayStatus status = RayStatus::max_steps;
  GeodesicState final_state = GeodesicState::Zero();
  GeodesicState step_end_state = GeodesicState::Zero();  ///< end of the last accepted step (y0 if none)
  double lambda = 0.0;           ///< affine parameter at the end
  int accepted = 0;
  int rejected = 0;
  long rhs_evals = 0;
  double constraint_drift = 0;   ///< g(k,k) at the end minus g(k,k) at the start
  int hit_event = -1;            ///< index of the user event that ended the ray (status hit)
  int chart_wraps = 0;           ///< times the ray crossed the polar axis of a spherical chart (see wrap_polar_axis)
};

/// Relative violation of the geodesic's constraint g(k,k) = const: |g(k,k) - norm0| / sum |g_mn k^m k^n|.
template <MetricPolicy Metric>
double constraint_violation(const Metric& metric, const GeodesicState& y, double norm0) {
  const Vec4 x = y.head<4>(), k = y.tail<4>();
  const Mat4 g = metric.metric(x);
  const double size = k.cwiseAbs().dot(g.cwiseAbs() * k.cwiseAbs());
  const double v = std::abs(k.dot(g * k) - norm0) / size;
  return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
}

/// Spherical charts cover the sphere once with theta in [0, pi]. A ray through (or numerically across) the axis
/// comes out with theta < 0 or > pi; the same event and direction are theta' = -theta (or 2 pi - theta),
/// phi' = phi + pi, k^theta' = -k^theta. Returns true when it changed y.
inline bool wrap_polar_axis(GeodesicState& y) {
  constexpr double pi = std::numbers::pi;
  if (y[2] >= 0.0 && y[2] <= pi) return false;
  y[2] = y[2] < 0.0 ? -y[2] : 2.0 * pi - y[2];
  y[3] += pi;
  y[6] = -y[6];
  return true;
}

/// Optional: how many interior points of each step an event samples (to catch a surface entered and left
/// within one step). Events declare `static constexpr int interior_samples = n;`; default 0.
template <class E>
constexpr int event_interior_samples() {
  if constexpr (requires { E::interior_samples; }) return E::interior_samples;
  else return 0;
}

/// Optional: `static constexpr bool two_sided = true;` makes any sign change of g a crossing (a surface with no
/// inside, such as a thin disk: g = cos theta); the ray may start on either side.
template <class E>
constexpr bool event_is_two_sided() {
  if constexpr (requires { E::two_sided; }) return E::two_sided;
  else return false;
}

/// Optional: `bool accepts(const GeodesicState&) const` filters located crossings (e.g. the disk's plane is
/// crossed but outside its radii); a refused crossing does not end the ray.
template <class E>
bool event_accepts(const E& e, const GeodesicState& y) {
  if constexpr (requires { { e.accepts(y) } -> std::convertible_to<bool>; }) return e.accepts(y);
  else return true;
}

struct NullObserver {
  template <class Integrator>
  void operator()(const Integrator&, double /*theta_end*/) const {}
};

template <MetricPolicy Metric, ExplicitTableau Tableau, StepController Controller = PIController>
class GeodesicTracer {
 public:
  using Integrator = ControlledIntegrator<Tableau, Controller, 8>;

  GeodesicTracer(Metric metric, TraceSettings settings, Controller controller = {})
      : metric_(metric), settings_(settings), controller_(controller) {}

  const Metric& metric() const { return metric_; }
  const TraceSettings& settings() const { return settings_; }
  const Controller& controller() const { return controller_; }

  template <class... Events>
  TraceResult trace(const GeodesicState& y0, const Events&... events) const {
    return trace_observed(y0, NullObserver{}, events...);
  }

  template <class Observer, class... Events>
  TraceResult trace_observed(const GeodesicState& y0, Observer&& observer, const Events&... events) const {
    const GeodesicEquation<Metric> rhs{&metric_};
    const double r_guard = (1.0 + settings_.horizon_epsilon) * metric_.horizon_radius();
    const double r_escape = settings_.escape_radius;
    auto horizon = [&](const GeodesicState& y) { return metric_.radius(y.head<4>()) - r_guard; };
    auto escape = [&](const GeodesicState& y) { return r_escape - metric_.radius(y.head<4>()); };
    const auto all = std::tie(horizon, escape, events...);
    constexpr std::size_t K = 2 + sizeof...(Events);
    constexpr std::array<int, K> samples = {0, 0, event_interior_samples<Events>()...};
    constexpr std::array<bool, K> two_sided = {false, false, event_is_two_sided<Events>()...};

    TraceResult result;
    const double norm0 = inner_product(metric_, y0.head<4>(), y0.tail<4>(), y0.tail<4>());
    auto finish = [&](RayStatus status, const GeodesicState& y, double lambda, const Integrator& integ) {
      result.status = status;
      result.final_state = y;
      result.step_end_state = integ.accepted() > 0 ? integ.state() : y;
      result.lambda = lambda;
      result.accepted = integ.accepted();
      result.rejected = integ.rejected();
      result.rhs_evals = integ.rhs_evals();
      result.constraint_drift = inner_product(metric_, y.head<4>(), y.tail<4>(), y.tail<4>()) - norm0;
      return result;
    };
    const double guard = settings_.constraint_tolerance;
    auto violated = [&](const GeodesicState& y) { return guard > 0.0 && constraint_violation(metric_, y, norm0) > guard; };

    std::array<double, K> g_prev{};
    for_each_event(all, [&](std::size_t i, const auto& e) { g_prev[i] = e(y0); });

    Integrator integ(settings_.integrator, controller_);
    if (!y0.allFinite()) return finish(RayStatus::non_finite, y0, 0.0, integ);
    for (std::size_t i = 0; i < K; ++i)
      if (!two_sided[i] && !(g_prev[i] > 0.0)) return finish(status_of(i, result), y0, 0.0, integ);

    integ.start(rhs, y0, settings_.initial_step);
    for (int step = 0; step < settings_.max_steps; ++step) {
      const StepOutcome outcome = integ.advance(rhs);
      if (outcome != StepOutcome::ok) {
        // An underflow where the right-hand side itself is not finite (e.g. a start on the polar axis of a
        // spherical chart, where cot(theta) diverges) is a non-finite ray, not a step-size problem.
        const bool rhs_finite = outcome == StepOutcome::step_underflow && rhs(integ.state()).allFinite();
        return finish(rhs_finite ? RayStatus::step_underflow : RayStatus::non_finite, integ.state(), integ.lambda(),
                      integ);
      }
      // The earliest surface crossed inside this step ends the ray.
      double theta_first = std::numeric_limits<double>::infinity();
      std::size_t first = K;
      for_each_event(all, [&](std::size_t i, const auto& e) {
        const double g1 = e(integ.state());
        // Two-sided surfaces are seen from the side the step starts on (a start exactly on it does not count).
        const double side = two_sided[i] && g_prev[i] < 0.0 ? -1.0 : 1.0;
        if ((two_sided[i] && g_prev[i] == 0.0) || (side * g1 > 0.0 && samples[i] == 0)) {
          g_prev[i] = g1;
          return;
        }
        auto g_of_theta = [&](double t) { return side * e(integ.dense(t)); };
        if (auto c = locate_first_crossing(g_of_theta, side * g_prev[i], side * g1, samples[i]);
            c && c->theta < theta_first && event_accepts(e, integ.dense(c->theta))) {
          theta_first = c->theta;
          first = i;
        }
        g_prev[i] = g1;
      });
      if (first < K) {
        const GeodesicState y_hit = integ.dense(theta_first);
        observer(integ, theta_first);
        const double lambda_hit = integ.previous_lambda() + theta_first * integ.last_step();
        if (violated(y_hit)) return finish(RayStatus::non_finite, y_hit, lambda_hit, integ);
        return finish(status_of(first, result), y_hit, lambda_hit, integ);
      }
      if (violated(integ.state())) return finish(RayStatus::non_finite, integ.state(), integ.lambda(), integ);
      observer(integ, 1.0);
      if constexpr (Metric::chart == Chart::spherical) {
        GeodesicState y = integ.state();
        if (wrap_polar_axis(y)) {
          ++result.chart_wraps;
          integ.reseat(rhs, y);
          for_each_event(all, [&](std::size_t i, const auto& e) { g_prev[i] = e(y); });
        }
      }
    }
    return finish(RayStatus::max_steps, integ.state(), integ.lambda(), integ);
  }

 private:
  template <class Tuple, class F>
  static void for_each_event(const Tuple& events, F&& f) {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (f(I, std::get<I>(events)), ...);
    }(std::make_index_sequence<std::tuple_size_v<Tuple>>{});
  }

  static RayStatus status_of(std::size_t event_index, TraceResult& result) {
    if (event_index == 0) return RayStatus::captured;
    if (event_index == 1) return RayStatus::escaped;
    result.hit_event = static_cast<int>(event_index) - 2;
    return RayStatus::hit;
  }

  Metric metric_;
  TraceSettings settings_;
  Controller controller_;
};

}  // namespace grtrace
