// grtrace/trace/auto_tracer.hpp
// "auto": the fastest scene tracer whose assumptions hold, decided where the facts are known (from the types at
// compile time, from the metric's values at run time) so that every program picks the same way: grtrace-render,
// grtrace-view and a user's own.
//
//   straight-line  the metric declares itself flat (FlatMetric, metric/metric_traits.hpp): nothing to integrate
//   planar         a static spherically symmetric metric with a horizon (StaticSphericalMetric), a scene whose
//                  objects lie in the equatorial plane (planar_supports_scene), an adaptive step controller:
//                  one table of rays for the frame (trace/planar_scene_tracer.hpp)
//   kerr-closed-form  KerrMetric (Boyer-Lindquist), a scene whose objects lie in the equatorial plane
//                  (planar_supports_scene; the sky alone too), an adaptive step controller: every pixel from the
//                  ray's separated integrals, nothing integrated (trace/kerr_closed_form_tracer.hpp)
//   kerr-mino      KerrMetric (Boyer-Lindquist), a scene of stationary objects (kerr_mino_supports_scene), an
//                  adaptive step controller: every pixel integrated on Kerr's separated equations in Mino time
//                  (trace/kerr_mino_tracer.hpp)
//   general        anything else: every pixel integrated (trace/scene_tracer.hpp)
//
// Takes:   the tableau and controller (template arguments), the metric, trace settings, the camera (the planar
//          table covers its pixels), the angle correction, the scene, the number of table rays per side, and f.
// Returns: whatever f(tracer) returns, f called once with the chosen tracer (a const reference; its static `name`
//          says which it is). The planar tracer's table is built before f is called.
// Assumes: for the planar tracer, horizon guard < camera radius < sky radius (checked: std::invalid_argument).
#pragma once

#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/metric/static_spherical.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/trace/kerr_closed_form_tracer.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"
#include "grtrace/trace/planar_scene_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/straight_line.hpp"

#include <type_traits>
#include <utility>

namespace grtrace {

/// True when the reduced Kerr tracer can draw this scene in this metric with this controller.
template <class Metric, class SceneT, class C>
inline constexpr bool kerr_mino_tracer_applies =
    std::is_same_v<Metric, KerrMetric> && kerr_mino_supports_scene<SceneT> && C::estimate != ErrorEstimate::none;

/// True when the closed-form Kerr tracer can draw this scene in this metric with this controller (the
/// controller is its fallback's: trace/kerr_closed_form_tracer.hpp).
template <class Metric, class SceneT, class C>
inline constexpr bool kerr_closed_form_tracer_applies =
    std::is_same_v<Metric, KerrMetric> && planar_supports_scene<SceneT> && C::estimate != ErrorEstimate::none;

/// True when the planar tracer can draw this scene in this metric with this controller (its run-time condition,
/// a horizon, is checked by with_auto_tracer).
template <class Metric, class SceneT, class C>
inline constexpr bool planar_tracer_applies = [] {
  if constexpr (StaticSphericalMetric<Metric> && planar_supports_scene<SceneT>) return C::estimate != ErrorEstimate::none;
  else return false;
}();

/// with_auto_tracer's choice as a maker: calls f(make) once, make() building the chosen tracer and returning it by
/// value (a prvalue: it can initialise a tracer in place, e.g. inside an owner on the heap, although the planar
/// tracer can be neither copied nor moved). Everything else as with_auto_tracer.
template <ExplicitTableau T, StepController C, MetricPolicy Metric, class SceneT, class F>
decltype(auto) with_auto_tracer_maker(const Metric& metric, const TraceSettings& settings, const Camera& camera,
                                      AngleCorrection correction, const SceneT& scene, int table_rays, F&& f) {
  if constexpr (FlatMetric<Metric>) {
    return f([&] { return StraightLineTracer(metric, settings.escape_radius, correction, scene); });
  } else {
    if constexpr (planar_tracer_applies<Metric, SceneT, C>) {
      if (metric.horizon_radius() > 0.0)
        return f([&] {
          return PlanarSceneTracer<Metric, T, C, SceneT>(metric, settings, camera, correction, scene, table_rays);
        });
    }
    if constexpr (kerr_closed_form_tracer_applies<Metric, SceneT, C>) {
      return f([&] { return make_kerr_closed_form_tracer<T, C>(metric, settings, correction, scene); });
    } else if constexpr (kerr_mino_tracer_applies<Metric, SceneT, C>) {
      return f([&] { return make_kerr_mino_tracer<T, C>(metric, settings, correction, scene); });
    } else {
      return f([&] { return make_general_tracer<T, C>(metric, settings, correction, scene); });
    }
  }
}

template <ExplicitTableau T, StepController C, MetricPolicy Metric, class SceneT, class F>
decltype(auto) with_auto_tracer(const Metric& metric, const TraceSettings& settings, const Camera& camera,
                                AngleCorrection correction, const SceneT& scene, int table_rays, F&& f) {
  return with_auto_tracer_maker<T, C>(metric, settings, camera, correction, scene, table_rays,
                                      [&](const auto& make) -> decltype(auto) {
                                        const auto tracer = make();
                                        return f(tracer);
                                      });
}

}  // namespace grtrace
