// grtrace/trace/straight_line.hpp
// Flat spacetime is never integrated: a light ray is a straight line X(s) = X0 + s K in the Cartesian embedding,
// where it leaves the sky sphere is a quadratic equation, and a scene object (scene/scene_object.hpp) is met
// where its function first reaches 0 along the line: sampled at `line_samples` points (or the object's own
// interior_samples, if larger) between the camera and the sky sphere, then located by the Illinois method on the
// exact line (integrate/event_locator.hpp). Objects receive states in the metric's own chart (Cartesian for
// MinkowskiMetric, spherical for MinkowskiSpherical), exactly as the integrating tracer would give them.
// Assumes: the camera is inside the sky sphere; an object thinner than the sample spacing along a ray can be
// missed (raise line_samples or give the object interior_samples).
#pragma once

#include "grtrace/integrate/event_locator.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"  // event traits: two_sided, interior_samples, accepts
#include "grtrace/trace/ray_outcome.hpp"
#include "grtrace/trace/scene_tracer.hpp"      // redshift_at

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace grtrace {

template <FlatMetric Metric, class SceneT>
class StraightLineTracer {
  static_assert(scene_objects_checked<Metric, SceneT>);

 public:
  static constexpr const char* name = "straight-line";
  using MetricType = Metric;
  using SceneType = SceneT;

  StraightLineTracer(Metric metric, double sky_radius, AngleCorrection correction, SceneT scene,
                     int line_samples = 256)
      : metric_(metric), sky_radius_(sky_radius), correction_(correction), scene_(std::move(scene)),
        line_samples_(line_samples) {
    if (!(sky_radius > 0.0) || !std::isfinite(sky_radius))
      throw std::invalid_argument("straight-line tracer: the sky radius must be a positive finite number");
    if (line_samples < 1) throw std::invalid_argument("straight-line tracer: line_samples must be at least 1");
  }

  /// Takes a state in the metric's chart; the camera is inside the sky sphere.
  RayOutcome trace(const GeodesicState& y) const {
    const Vec3 p = metric_.to_cartesian(y.head<4>());
    const Vec3 v = embedded_velocity_of(metric_, y);
    // |p + s v| = R for the positive root s.
    const double a = v.squaredNorm(), b = p.dot(v), c = p.squaredNorm() - sky_radius_ * sky_radius_;
    const double s_exit = (-b + std::sqrt(b * b - a * c)) / a;
    auto state_at = [&](double s) { return chart_state(y[0] + s * y[4], p + s * v, y[4], v); };

    // The earliest object along the line, as a fraction of the way to the sky sphere.
    double theta_first = std::numeric_limits<double>::infinity();
    int first = -1;
    const GeodesicState y0 = state_at(0.0), y1 = state_at(s_exit);
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (locate(std::get<I>(scene_.objects), static_cast<int>(I), y0, y1, s_exit, state_at, theta_first, first), ...);
    }(std::make_index_sequence<static_cast<std::size_t>(SceneT::object_count)>{});

    RayOutcome out;
    out.steps = 0;
    // A line crosses the equatorial plane (z = 0) at most once: before its end if it ends off the plane on the
    // other side (a hit on the plane is not a crossing before it: trace/ray_outcome.hpp).
    auto order_at_end = [&](double s) {
      const Vec3 end = p + s * v;
      return p.z() * end.z() < 0.0 && std::abs(end.z()) > kOnEquatorialPlane * end.norm() ? 1 : 0;
    };
    if (first >= 0) {
      out.order = order_at_end(theta_first * s_exit);
      const GeodesicState hit = state_at(theta_first * s_exit);
      out.status = RayStatus::hit;
      out.object = kFirstSceneObject + first;
      out.state = hit;
      out.radius = metric_.radius(hit.head<4>());
      out.where = position_direction(metric_, hit.head<4>());
      Vec4 u = Vec4::Zero();
      scene_.visit_object(out.object, [&](const auto& o) { u = o.emitter_velocity(metric_, hit.head<4>()); });
      out.redshift = redshift_at(metric_, u, hit);
      return out;
    }
    out.status = RayStatus::escaped;
    out.object = kSkyObject;
    out.order = order_at_end(s_exit);
    out.state = y1;
    out.radius = sky_radius_;
    out.where = sky_direction_of(correction_ == AngleCorrection::none ? Vec3(p + s_exit * v) : v);
    const Vec3 end = p + s_exit * v;  // a line going on towards the plane crosses it beyond the sphere
    out.order += crossed_beyond_sphere(end.z() / end.norm(), out.where);
    out.redshift = redshift_at(metric_, rest_emitter_velocity(metric_, y1.head<4>()), y1);
    return out;
  }

  const SceneT& scene() const { return scene_; }
  /// The straight line is the ray: exact for any correction but none (trace/sky_continuation.hpp).
  SkyContinuation sky_continuation() const { return sky_continuation_of<Metric>(correction_); }
  const Metric& metric() const { return metric_; }

 private:
  /// (t, X | k^t, V) of the embedding as a state of the metric's chart.
  static GeodesicState chart_state(double t, const Vec3& x, double kt, const Vec3& v) {
    if constexpr (Metric::chart == Chart::spherical) return spherical_state_from_cartesian(t, x, kt, v);
    else {
      GeodesicState s;
      s << t, x, kt, v;
      return s;
    }
  }

  template <class Object, class StateAt>
  void locate(const Object& o, int index, const GeodesicState& y0, const GeodesicState& y1, double s_exit,
              const StateAt& state_at, double& theta_first, int& first) const {
    const double g0 = o(y0), g1 = o(y1);
    const bool two_sided = event_is_two_sided<Object>();
    if (two_sided && g0 == 0.0) return;  // starting on a two-sided surface does not count (as in GeodesicTracer)
    const double side = two_sided && g0 < 0.0 ? -1.0 : 1.0;
    auto g = [&](double theta) { return side * o(state_at(theta * s_exit)); };
    const int samples = std::max(line_samples_, event_interior_samples<Object>());
    if (auto c = locate_first_crossing(g, side * g0, side * g1, samples);
        c && c->theta < theta_first && event_accepts(o, state_at(c->theta * s_exit))) {
      theta_first = c->theta;
      first = index;
    }
  }

  Metric metric_;
  double sky_radius_;
  AngleCorrection correction_;
  SceneT scene_;
  int line_samples_;
};

}  // namespace grtrace
