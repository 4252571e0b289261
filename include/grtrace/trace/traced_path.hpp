// grtrace/trace/traced_path.hpp
// A traced geodesic as a sampled path, and the tracer observer that records it: what grtrace-view draws, what
// grtrace-geodesic writes and what the Python module's trace_ray returns (the viz frontend names these types
// grtrace::viz::TracedPath, ...: grtrace/viz/traced_path.hpp).
//
// Takes:   a metric (for to_cartesian and g), and the integrator the tracer hands to its observer on every
//          accepted step (GeodesicTracer::trace_observed calls observer(integrator, theta_end)).
// Returns: a TracedPath with
//          * samples: `samples_per_step` points per accepted step from the integrator's dense output, so a
//            polyline through them is a smooth curve, not the chord of each step. The last sample of every step
//            is the accepted state itself (theta = 1, or theta_end on the step that met the surface ending
//            the ray). Each sample carries its chart state, Cartesian embedding, lambda, the step size h of
//            the step it lies on, the step index and (if the recorder was given an observer) a redshift.
//          * steps: one record per accepted step (and the start): lambda, h, state, embedding, g(k, k); the
//            last one is `located` when the trace ended on a surface inside that step (its state then comes
//            from the dense output at the crossing, not from the step itself).
// Assumes: the tracer calls the observer once per accepted step, in order (GeodesicTracer does).
//
// The "redshift" of a sample is f_obs / f_static(x): the frequency the observer (4-velocity u_obs at the
// start event, e.g. the camera's e_0) measures, divided by the frequency a static observer at the sample
// measures, g(u_obs, k0) / g(u_static(x), k(x)) with u_static = (1/sqrt(g_00), 0, 0, 0). Where the ray meets
// a static emitter this is the frame's redshift channel; NaN where no static observer exists (g_00 <= 0).
#pragma once

#include "grtrace/core/memory_limit.hpp"
#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace grtrace {

namespace path_detail {
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace path_detail

struct PathSample {
  Vec3 position = Vec3::Zero();                    ///< Cartesian embedding, metric.to_cartesian(x)
  GeodesicState state = GeodesicState::Zero();     ///< chart coordinates (x^mu, k^mu)
  double lambda = 0.0;                             ///< affine parameter (proper time for timelike paths)
  double h = 0.0;                                  ///< size of the accepted step this sample lies on
  int step = 0;                                    ///< accepted-step index (0: the start point)
  double redshift = path_detail::kNaN;                          ///< f_obs / f_static(x), NaN unless recorded
};

struct StepRecord {
  double lambda = 0.0;
  double h = 0.0;                                  ///< 0 for the start record
  GeodesicState state = GeodesicState::Zero();
  Vec3 position = Vec3::Zero();
  double norm = 0.0;                               ///< g(k, k): 0 for light, 1 for a 4-velocity
  bool located = false;  ///< the end of the last step, cut at the surface that ended the trace (dense output)
};

/// An 8-bit sRGB colour (the frame's preview colour of a pixel).
using PathRgb8 = std::array<std::uint8_t, 3>;

/// The bytes of a path's arrays with `samples` samples and `steps` step records.
inline double path_bytes(std::size_t samples, std::size_t steps) {
  return static_cast<double>(samples) * sizeof(PathSample) + static_cast<double>(steps) * sizeof(StepRecord);
}

struct TracedPath {
  std::vector<PathSample> samples;
  std::vector<StepRecord> steps;
  RayStatus status = RayStatus::max_steps;
  std::optional<PathRgb8> color;                       ///< the colour of its pixel in the frame (bundle rays)
  int pixel_x = -1, pixel_y = -1;                  ///< frame pixel (column, row from the top) for bundle rays
};

/// Tracer observer that fills a TracedPath. Keep it alive (and the path) for the duration of the trace.
template <MetricPolicy Metric>
class PathRecorder {
 public:
  /// samples_per_step >= 1 points per accepted step; observer_velocity: 4-velocity at the start event that
  /// defines the redshift array (nothing: no redshift is recorded).
  PathRecorder(const Metric& metric, TracedPath& out, int samples_per_step = 8,
               std::optional<Vec4> observer_velocity = std::nullopt)
      : metric_(&metric), out_(&out), samples_per_step_(samples_per_step), observer_(observer_velocity) {
    if (samples_per_step < 1) throw std::invalid_argument("PathRecorder: samples_per_step must be >= 1");
  }

  template <class Integrator>
  void operator()(const Integrator& integ, double theta_end) {
    const double h = integ.last_step();
    if (out_->steps.empty()) start(integ.previous_state(), integ.previous_lambda(), h);
    // Checked where the arrays grow (a doubling, so rarely): a ray of 1e5 steps at 1000 samples a step would hold
    // 15 GB. MemoryLimitError (core/memory_limit.hpp) says what to lower.
    if (out_->samples.size() + static_cast<std::size_t>(samples_per_step_) > out_->samples.capacity())
      check_memory(path_bytes(2 * (out_->samples.size() + static_cast<std::size_t>(samples_per_step_)),
                              2 * out_->steps.size() + 1),
                   "a traced path of " + std::to_string(out_->steps.size()) + " steps at " +
                       std::to_string(samples_per_step_) + " samples a step (fewer samples a step or a shorter ray)");
    const int step = static_cast<int>(out_->steps.size());
    for (int i = 1; i <= samples_per_step_; ++i) {
      const double theta = theta_end * static_cast<double>(i) / static_cast<double>(samples_per_step_);
      const bool end_of_step = i == samples_per_step_;
      const GeodesicState y = end_of_step && theta_end == 1.0 ? GeodesicState(integ.state()) : integ.dense(theta);
      out_->samples.push_back(sample(y, integ.previous_lambda() + theta * h, h, step));
      if (end_of_step) {
        out_->steps.push_back(record(y, integ.previous_lambda() + theta * h, h));
        out_->steps.back().located = theta_end != 1.0;
      }
    }
  }

 private:
  void start(const GeodesicState& y0, double lambda0, double h_first) {
    if (observer_) {
      const Vec4 x0 = y0.head<4>(), k0 = y0.tail<4>();
      observer_energy_ = inner_product(*metric_, x0, *observer_, k0);
    }
    out_->samples.push_back(sample(y0, lambda0, h_first, 0));
    out_->steps.push_back(record(y0, lambda0, 0.0));
  }

  PathSample sample(const GeodesicState& y, double lambda, double h, int step) const {
    PathSample s;
    s.state = y;
    s.position = metric_->to_cartesian(y.head<4>());
    s.lambda = lambda;
    s.h = h;
    s.step = step;
    if (observer_) s.redshift = redshift(y);
    return s;
  }

  StepRecord record(const GeodesicState& y, double lambda, double h) const {
    const Vec4 x = y.head<4>(), k = y.tail<4>();
    return {lambda, h, y, metric_->to_cartesian(x), inner_product(*metric_, x, k, k)};
  }

  double redshift(const GeodesicState& y) const {
    const Vec4 x = y.head<4>(), k = y.tail<4>();
    const Mat4 g = metric_->metric(x);
    if (!(g(0, 0) > 0.0)) return path_detail::kNaN;
    const double static_energy = g.row(0).dot(k) / std::sqrt(g(0, 0));
    return observer_energy_ / static_energy;
  }

  const Metric* metric_;
  TracedPath* out_;
  int samples_per_step_;
  std::optional<Vec4> observer_;
  double observer_energy_ = path_detail::kNaN;
};

/// Ends a recorded path: its status, and the start point kept when the ray ended before its first accepted step
/// (e.g. it started on a surface), so that every path has at least one point.
template <MetricPolicy Metric>
void finish_path(TracedPath& path, const Metric& metric, const GeodesicState& y0, RayStatus status) {
  path.status = status;
  if (!path.steps.empty()) return;
  StepRecord r;
  r.state = y0;
  r.position = metric.to_cartesian(y0.head<4>());
  r.norm = inner_product(metric, Vec4(y0.head<4>()), Vec4(y0.tail<4>()), Vec4(y0.tail<4>()));
  path.steps.push_back(r);
  PathSample s;
  s.state = y0;
  s.position = r.position;
  path.samples.push_back(s);
}

/// Traces one geodesic with `tracer` and records it (status included). Extra arguments are the tracer's events.
template <class Tracer, class... Events>
TracedPath trace_path(const Tracer& tracer, const GeodesicState& y0, int samples_per_step,
                      std::optional<Vec4> observer_velocity, const Events&... events) {
  TracedPath path;
  PathRecorder recorder(tracer.metric(), path, samples_per_step, observer_velocity);
  const auto result = tracer.trace_observed(y0, recorder, events...);
  finish_path(path, tracer.metric(), y0, result.status);
  return path;
}

}  // namespace grtrace
