// grtrace/observer/worldline.hpp
// A massive body's path (a timelike geodesic) sampled at evenly spaced proper times, and how long it takes to
// reach a place on it: the camera path of a flight (render/flight.hpp), or any orbit a user wants to sample.
//
//   sample_worldline<T, C>(metric, start, dtau, count)   states at tau = 0, dtau, ..., (count - 1) dtau
//   proper_time_until<T, C>(metric, start, event)         tau where event(y) first reaches 0 (or nothing)
//   revolution_event(start) / radius_event(metric, r)    the events a flight's automatic length uses
//
// Method:  the geodesic equation in (x, u) with the affine parameter = proper time (g(u, u) = 1 at the start and
//          conserved by the flow), integrated with the tableau T and controller C (defaults: Tsitouras 5(4), PI,
//          rtol = atol = 1e-12). A sample is not read off an interpolant: the step that contains tau_k is re-taken
//          from its start with the length that ends at tau_k (ControlledIntegrator::step_from_previous), so every
//          sample is as accurate as the integration itself, and a sampled path does not depend on where the
//          controller happened to put its steps beyond the integration error.
// Ends early (Worldline::stopped = captured, fewer samples) when the body reaches the stop radius: by default the
// metric's horizon guard (just outside the horizon in a Schwarzschild-type chart, which cannot carry a body further;
// inside it in Kerr-Schild's ingoing chart, where a falling camera crosses it); step failures end it with their status. Polar-axis crossings are re-charted as for rays (wrap_polar_axis).
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"
#include "grtrace/integrate/step_controller.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/observer/timelike_start.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/traced_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

namespace grtrace {

/// One sample of a worldline: proper time since the start, the event and the 4-velocity there.
struct WorldlineSample {
  double tau = 0.0;
  Vec4 x = Vec4::Zero();
  Vec4 u = Vec4::Zero();
};

struct Worldline {
  std::vector<WorldlineSample> samples;
  /// Why the samples end before the count asked for, or nothing when all were taken: captured (the body reached
  /// the stop radius), step_underflow / non_finite (the integration failed), max_steps (the step budget ran out).
  std::optional<RayStatus> stopped;
  bool complete() const { return !stopped; }
};

struct WorldlineSettings {
  IntegratorSettings integrator{Tolerance{1e-12, 1e-12}};
  /// The body stops (status captured) at this radius; <= 0: (1 + horizon_epsilon) r_cap, the metric's capture
  /// radius for the body (metric/metric_traits.hpp capture_radius_of: inside the event horizon in a chart that
  /// carries a falling body across it, Kerr-Schild's ingoing slicing).
  double stop_radius = 0.0;
  double horizon_epsilon = 1e-3;
  long max_steps = 10'000'000;
};

namespace detail {
template <MetricPolicy M>
double worldline_stop_radius(const M& metric, const TimelikeStart& start, const WorldlineSettings& s) {
  return s.stop_radius > 0.0 ? s.stop_radius : (1.0 + s.horizon_epsilon) * capture_radius_of(metric, start.state());
}
}  // namespace detail

/// Samples the timelike geodesic from `start` at tau_k = k dtau, k = 0 .. count - 1.
/// Takes:   the metric, a start with g(u, u) = 1 (observer/timelike_start.hpp), dtau > 0, count >= 1.
/// Returns: the samples taken (all count of them unless the body stopped first: see Worldline::stopped).
/// Throws:  std::invalid_argument for dtau <= 0, count < 1, or a start that is not unit timelike (1e-9).
template <ExplicitTableau T = Tsitouras54, StepController C = PIController, MetricPolicy M>
Worldline sample_worldline(const M& metric, const TimelikeStart& start, double dtau, int count,
                           const WorldlineSettings& settings = {}) {
  if (!(dtau > 0.0) || !std::isfinite(dtau)) throw std::invalid_argument("worldline: the proper-time step must be > 0");
  if (count < 1) throw std::invalid_argument("worldline: at least one sample");
  if (!(std::abs(inner_product(metric, start.x, start.u, start.u) - 1.0) < 1e-9) || !(start.u[0] > 0.0))
    throw std::invalid_argument("worldline: the start's 4-velocity must be future-directed with g(u, u) = 1");
  Worldline w;
  w.samples.reserve(static_cast<std::size_t>(count));
  w.samples.push_back({0.0, start.x, start.u});
  if (count == 1) return w;
  // The tracers' geodesic system (trace/geodesic_system.hpp): its right-hand side is GeodesicEquation's, bit for bit,
  // and a program that also traces rays with this method (the orbit paths below, the tools' flights) then compiles
  // one integrator step per metric instead of two.
  const MetricGeodesicSystem<M> rhs(metric, start.state());
  const double r_stop = detail::worldline_stop_radius(metric, start, settings);
  ControlledIntegrator<T, C, 8> integ(settings.integrator, C{});
  integ.start(rhs, start.state(), 0.0);
  int k = 1;
  for (long step = 0; step < settings.max_steps; ++step) {
    const StepOutcome outcome = integ.advance(rhs);
    if (outcome != StepOutcome::ok) {
      w.stopped = outcome == StepOutcome::step_underflow ? RayStatus::step_underflow : RayStatus::non_finite;
      return w;
    }
    // Every sample time inside this step, from the step's own map (not the interpolant).
    while (k < count && static_cast<double>(k) * dtau <= integ.lambda()) {
      const double tau = static_cast<double>(k) * dtau;
      const double theta = std::clamp((tau - integ.previous_lambda()) / integ.last_step(), 0.0, 1.0);
      GeodesicState y = theta == 1.0 ? integ.state() : integ.step_from_previous(rhs, theta);
      if constexpr (M::chart == Chart::spherical) wrap_polar_axis(y);
      if (!(metric.radius(y.template head<4>()) > r_stop)) {
        w.stopped = RayStatus::captured;
        return w;
      }
      w.samples.push_back({tau, y.template head<4>(), y.template tail<4>()});
      ++k;
    }
    if (k == count) return w;
    if (!(metric.radius(integ.state().template head<4>()) > r_stop)) {
      w.stopped = RayStatus::captured;
      return w;
    }
    if constexpr (M::chart == Chart::spherical) {
      GeodesicState y = integ.state();
      if (wrap_polar_axis(y)) integ.reseat(rhs, y);
    }
  }
  w.stopped = RayStatus::max_steps;
  return w;
}

/// An event (positive before, <= 0 at and after) that ends a path after one full turn in phi from the start's phi,
/// in the start's sense of rotation (dphi/dtau's sign).
struct RevolutionEvent {
  double phi_end;
  double sign;
  double operator()(const GeodesicState& y) const { return sign * (phi_end - y[3]); }
};
inline RevolutionEvent revolution_event(const TimelikeStart& start) {
  const double sign = start.u[3] >= 0.0 ? 1.0 : -1.0;
  return {start.x[3] + sign * 2.0 * std::numbers::pi, sign};
}

/// An event that ends a path where it first comes within radius r of the centre (the metric's radius(x)).
template <MetricPolicy M>
struct RadiusEvent {
  const M* metric;
  double r;
  double operator()(const GeodesicState& y) const { return metric->radius(y.template head<4>()) - r; }
};
template <MetricPolicy M>
RadiusEvent<M> radius_event(const M& metric, double r) {
  return {&metric, r};
}

/// The proper time from `start` until event(y) first reaches 0, or nothing when the body stops first (the stop
/// radius of settings, an integration failure, max_steps).
template <ExplicitTableau T = Tsitouras54, StepController C = PIController, MetricPolicy M, class Event>
std::optional<double> proper_time_until(const M& metric, const TimelikeStart& start, const Event& event,
                                        const WorldlineSettings& settings = {}) {
  TraceSettings s;
  s.integrator = settings.integrator;
  s.max_steps = static_cast<int>(std::min<long>(settings.max_steps, std::numeric_limits<int>::max()));
  s.escape_radius = std::numeric_limits<double>::max();
  const double r_capture = capture_radius_of(metric, start.state());  // the tracer's guard is (1 + eps) r_capture
  s.horizon_epsilon =
      settings.stop_radius > 0.0 && r_capture > 0.0 ? settings.stop_radius / r_capture - 1.0 : settings.horizon_epsilon;
  const GeodesicTracer<M, T, C> tracer(metric, s);
  const TraceResult r = tracer.trace(start.state(), event);
  if (r.status != RayStatus::hit) return std::nullopt;
  return r.lambda;
}

/// Takes a metric and a sampled worldline (a camera flight: one sample per frame); returns it as a TracedPath with
/// one sample per worldline sample, in order: position = the metric's Cartesian embedding of x, state = (x, u),
/// lambda = tau, h = the proper time to the next sample (the last one repeats its predecessor's), step = the
/// sample's (frame's) index; one step record per sample with g(u, u). Status: why the worldline stopped, or
/// max_steps when it took every sample asked for (its count ran out, nothing ended it).
template <MetricPolicy M>
TracedPath worldline_path(const M& metric, const Worldline& worldline) {
  TracedPath path;
  const auto& w = worldline.samples;
  for (std::size_t i = 0; i < w.size(); ++i) {
    PathSample s;
    s.state = make_state(w[i].x, w[i].u);
    s.position = metric.to_cartesian(w[i].x);
    s.lambda = w[i].tau;
    s.h = i + 1 < w.size() ? w[i + 1].tau - w[i].tau : i > 0 ? w[i].tau - w[i - 1].tau : 0.0;
    s.step = static_cast<int>(i);
    path.samples.push_back(s);
    path.steps.push_back({s.lambda, s.h, s.state, s.position, inner_product(metric, w[i].x, w[i].u, w[i].u)});
  }
  path.status = worldline.stopped.value_or(RayStatus::max_steps);
  return path;
}

}  // namespace grtrace
