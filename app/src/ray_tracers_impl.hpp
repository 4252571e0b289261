// make_ray_tracer's definition (private to grtrace_app_rays): single rays of a checked request, each with its path
// and its outcome from one integration (grtrace-view's bundles and picks, the Python module's trace_ray). Included by
// the units that instantiate it (ray_tracers_*.cpp), for the metrics they name.
#pragma once

#include "frame_tracers.hpp"

#include "grtrace/app/tool_methods.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/traced_path.hpp"

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace grtrace::app {

/// Ends a path once phi (x^3 of a spherical chart) has passed `end`, in the sense `sign`; positive before. With no
/// advance asked for it never ends one (always +1: the same instantiation serves every path).
struct PhiAdvanceEvent {
  double end = 0.0;
  double sign = 0.0;  ///< 0: inactive
  double operator()(const GeodesicState& y) const { return sign == 0.0 ? 1.0 : sign * (end - y[3]); }
};

/// The rays of one metric, method and scene: the scene's general tracer, and (for a scene with objects) the same
/// tracer without them, for paths that only the horizon and the sky end (a beam in the disk's plane, an orbit).
template <MetricPolicy M, class T, class C, class Scene>
class RayTracerOf final : public RayTracer {
 public:
  RayTracerOf(const M& metric, const CheckedRequest& checked, const Scene& scene)
      : with_objects_(make_general_tracer<T, C>(metric, checked.settings, checked.correction, scene)),
        bare_(make_general_tracer<T, C>(metric, checked.settings, checked.correction,
                                        BackgroundScene{scene.sky, scene.horizon, {}, scene.colour_by_redshift,
                                                        scene.failure})) {}

  TracedRay trace(const GeodesicState& y0, const PathOptions& o) const override {
    if (o.samples_per_step < 1 || o.samples_per_step > 1000)
      throw RequestError("samples_per_step must be 1 .. 1000, got " + std::to_string(o.samples_per_step));
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
    if (!is_failure(ray.outcome.status)) {
      const auto index = static_cast<std::size_t>(ray.outcome.object);
      ray.object = ray.outcome.object >= 0 && index < names.size() ? names[index]
                                                                   : "object " + std::to_string(ray.outcome.object);
    }
    return ray;
  }

  std::vector<std::string> object_names() const override { return with_objects_.scene().object_names(); }

 private:
  GeneralSceneTracer<M, T, C, Scene> with_objects_;
  GeneralSceneTracer<M, T, C, BackgroundScene> bare_;
};

template <MetricPolicy M>
std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest& checked, const M& metric) {
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

}  // namespace grtrace::app
