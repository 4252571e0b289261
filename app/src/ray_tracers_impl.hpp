// make_ray_tracer's definition (private to grtrace_app_rays): single rays of a checked request, each with its path
// and its outcome from one integration (grtrace-view's bundles and picks, the Python module's trace_ray). Included by
// the units that instantiate it (ray_tracers_*.cpp), for the metrics they name.
#pragma once

#include "frame_tracers.hpp"
#include "grtrace/app/tool_methods.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/straight_line.hpp"
#include "grtrace/trace/traced_path.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace grtrace::app {

/// Refuses a path with fewer than one or more than 1000 samples a step.
inline void check_samples_per_step(const PathOptions& o) {
  if (o.samples_per_step < 1 || o.samples_per_step > 1000)
    throw RequestError("samples_per_step must be 1 .. 1000, got " + std::to_string(o.samples_per_step));
}

/// Ends a path once phi (x^3 of a spherical chart) has passed `end`, in the sense `sign`; positive before. With no
/// advance asked for it never ends one (always +1: the same instantiation serves every path).
struct PhiAdvanceEvent {
  double end = 0.0;
  double sign = 0.0;  ///< 0: inactive
  double operator()(const GeodesicState& y) const { return sign == 0.0 ? 1.0 : sign * (end - y[3]); }
};

/// A path that ends on a surface (status hit) ends on the crossing the tracer located (the outcome's state, refined
/// to the tolerance), not on the tableau's interpolant there, which is of lower order than the steps.
template <MetricPolicy M>
void end_on_the_crossing(TracedRay& ray, const M& metric) {
  if (ray.outcome.status != RayStatus::hit || ray.path.steps.empty() || !ray.path.steps.back().located) return;
  const GeodesicState& y = ray.outcome.state;
  const Vec3 position = metric.to_cartesian(y.head<4>());
  ray.path.samples.back().state = y;
  ray.path.samples.back().position = position;
  ray.path.steps.back().state = y;
  ray.path.steps.back().position = position;
}

/// The rays of one metric, method and scene: the scene's general tracer, and (for a scene with objects) the same
/// tracer without them, for paths that only the horizon and the sky end (a beam in the disk's plane, an orbit).
template <MetricPolicy M, class T, class C, class Scene>
class RayTracerOf final : public RayTracer {
 public:
  RayTracerOf(const M& metric, const CheckedRequest& checked, const Scene& scene)
      : with_objects_(make_general_tracer<T, C>(metric, checked.settings, checked.correction, scene)),
        bare_(make_general_tracer<T, C>(
            metric, checked.settings, checked.correction,
            BackgroundScene{scene.sky, scene.horizon, {}, scene.colour_by_redshift, scene.failure})) {}

  TracedRay trace(const GeodesicState& y0, const PathOptions& o) const override {
    check_samples_per_step(o);
    PhiAdvanceEvent stop;
    if (o.phi_advance) {
      if constexpr (M::chart != Chart::spherical) {
        throw RequestError("phi_advance ends a path in a spherical chart; the " + std::string(M::name) +
                           " chart is Cartesian");
      } else {
        if (!std::isfinite(*o.phi_advance) || *o.phi_advance == 0.0)
          throw RequestError("phi_advance must be a finite, non-zero angle (radians)");
        stop = {y0[3] + *o.phi_advance, *o.phi_advance > 0.0 ? 1.0 : -1.0};
      }
    }
    TracedRay ray;
    ray.cartesian = M::chart == Chart::cartesian;
    const M& metric = with_objects_.metric();
    PathRecorder recorder(metric, ray.path, o.samples_per_step, o.observer_velocity);
    std::vector<std::string> names;
    if (o.scene_objects || std::is_same_v<Scene, BackgroundScene>) {
      ray.outcome = with_objects_.trace_observed(y0, recorder, stop);
      names = with_objects_.scene().object_names();
    } else {
      ray.outcome = bare_.trace_observed(y0, recorder, stop);
      names = bare_.scene().object_names();
    }
    finish_path(ray.path, metric, y0, ray.outcome.status);
    end_on_the_crossing(ray, metric);
    ray.object = outcome_object_name(ray.outcome, names);
    return ray;
  }

  std::vector<std::string> object_names() const override { return with_objects_.scene().object_names(); }

 private:
  GeneralSceneTracer<M, T, C, Scene> with_objects_;
  GeneralSceneTracer<M, T, C, BackgroundScene> bare_;
};

/// Rays in flat space: straight lines, never integrated (the straight-line tracer's outcome, trace/straight_line.hpp,
/// and the line itself sampled evenly in the affine parameter: 16 x samples_per_step points, as one step).
template <MetricPolicy M, class Scene>
class StraightRayTracerOf final : public RayTracer {
  static_assert(M::chart == Chart::spherical, "StraightRayTracerOf samples lines in a spherical chart");

 public:
  StraightRayTracerOf(const M& metric, const CheckedRequest& checked, const Scene& scene)
      : metric_(metric),
        with_objects_(metric, checked.settings.escape_radius, checked.correction, scene),
        bare_(metric, checked.settings.escape_radius, checked.correction,
              BackgroundScene{scene.sky, scene.horizon, {}, scene.colour_by_redshift, scene.failure}) {}

  TracedRay trace(const GeodesicState& y0, const PathOptions& o) const override {
    check_samples_per_step(o);
    if (o.phi_advance) throw RequestError("phi_advance ends integrated paths; flat space draws straight lines");
    TracedRay ray;
    const bool objects = o.scene_objects || std::is_same_v<Scene, BackgroundScene>;
    ray.outcome = objects ? with_objects_.trace(y0) : bare_.trace(y0);
    const std::vector<std::string> names =
        objects ? with_objects_.scene().object_names() : bare_.scene().object_names();
    // The line in Cartesian coordinates: X(lambda) = X0 + K lambda, t(lambda) = t0 + k^t lambda.
    const Vec4 x0 = y0.head<4>(), k0 = y0.tail<4>();
    const double r0 = x0[1], st = std::sin(x0[2]), ct = std::cos(x0[2]), sp = std::sin(x0[3]), cp = std::cos(x0[3]);
    const Vec3 X0 = metric_.to_cartesian(x0);
    const Vec3 K(k0[1] * st * cp + r0 * k0[2] * ct * cp - r0 * k0[3] * st * sp,
                 k0[1] * st * sp + r0 * k0[2] * ct * sp + r0 * k0[3] * st * cp, k0[1] * ct - r0 * k0[2] * st);
    double lambda_end = 0.0;
    if (!is_failure(ray.outcome.status))
      lambda_end = k0[0] != 0.0 ? (ray.outcome.state[0] - x0[0]) / k0[0]
                                : (metric_.to_cartesian(ray.outcome.state.head<4>()) - X0).norm() / K.norm();
    const double energy = o.observer_velocity ? inner_product(metric_, x0, *o.observer_velocity, k0) : 0.0;
    const int n = 16 * o.samples_per_step;
    double phi = x0[3];
    for (int i = 0; i <= n; ++i) {
      const double lambda = lambda_end * static_cast<double>(i) / n;
      const Vec3 X = X0 + K * lambda;
      const double r = X.norm(), rho = std::hypot(X[0], X[1]);
      // phi continued from the previous sample (atan2 gives it modulo 2 pi).
      phi += std::remainder(std::atan2(X[1], X[0]) - phi, 2.0 * std::numbers::pi);
      const double kr = X.dot(K) / r;
      GeodesicState y;
      y << x0[0] + k0[0] * lambda, r, std::atan2(rho, X[2]), phi, k0[0], kr,
          rho > 0.0 ? (X[2] * kr - K[2] * r) / (r * rho) : 0.0,
          rho > 0.0 ? (X[0] * K[1] - X[1] * K[0]) / (rho * rho) : 0.0;
      PathSample p;
      p.state = i == 0 ? y0 : y;
      p.position = X;
      p.lambda = lambda;
      p.h = lambda_end;
      p.step = i == 0 ? 0 : 1;
      if (o.observer_velocity) p.redshift = energy / k0[0];  // a static observer's energy is k^t all along
      ray.path.samples.push_back(p);
      if (i == 0 || i == n)
        ray.path.steps.push_back(
            {lambda, i == 0 ? 0.0 : lambda_end, p.state, X,
             inner_product(metric_, Vec4(p.state.head<4>()), Vec4(p.state.tail<4>()), Vec4(p.state.tail<4>()))});
    }
    ray.path.status = ray.outcome.status;
    ray.object = outcome_object_name(ray.outcome, names);
    return ray;
  }

  std::vector<std::string> object_names() const override { return with_objects_.scene().object_names(); }

 private:
  M metric_;
  StraightLineTracer<M, Scene> with_objects_;
  StraightLineTracer<M, BackgroundScene> bare_;
};

template <MetricPolicy M>
std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest& checked, const M& metric) {
  if constexpr (FlatMetric<M>) {
    std::unique_ptr<RayTracer> out;
    with_standard_scene(checked.scene, [&]<class Scene>(Scene scene) {
      out = std::make_unique<StraightRayTracerOf<M, Scene>>(metric, checked, scene);
    });
    return out;
  } else {
    const MethodRequest& m = checked.request.method;
    std::unique_ptr<RayTracer> out;
    const bool known = dispatch_tool_method(m.tableau, m.control, [&]<class T, class C>() {
      with_standard_scene(checked.scene, [&]<class Scene>(Scene scene) {
        if constexpr (scene_fits_metric<M, Scene>) {
          out = std::make_unique<RayTracerOf<M, T, C, Scene>>(metric, checked, scene);
        } else {
          throw RequestError("--scene " + checked.request.scene + " cannot be drawn in the " + std::string(M::name) +
                             " chart");
        }
      });
    });
    if (!known) check_tool_method(m.tableau, m.control);  // throws: says what to choose
    return out;
  }
}

}  // namespace grtrace::app
