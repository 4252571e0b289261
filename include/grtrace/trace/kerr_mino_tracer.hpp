// grtrace/trace/kerr_mino_tracer.hpp
// The reduced Kerr scene tracer: every camera ray integrated, as by GeneralSceneTracer, but on Kerr's separated
// equations in Mino time (trace/kerr_mino_system.hpp: five variables, a few polynomials and one sincos per
// right-hand side) instead of the geodesic equation of KerrMetric (eight variables, ~115 flops). Same tableaux,
// controllers, events, guards and outcome (trace_geodesic_system, scene_outcome), so it reports what the general
// tracer reports for the same scene (tests/kerr_mino_test.cpp compares them pixel by pixel).
//
// Takes:   a KerrMetric (Boyer-Lindquist), trace settings (the same meaning as for the general tracer, applied to
//          the reduced variables: rtol on u = 1/r, theta, phi and their Mino-time derivatives), an adaptive
//          controller, the angle correction, and a scene whose objects are all stationary
//          (scene/scene_object.hpp: the tracer does not follow t).
// Returns: per ray a RayOutcome; its end state's t is NaN (not followed), everything else in Boyer-Lindquist.
// Assumes: null camera rays from outside r_+ (a camera in the Boyer-Lindquist chart always is).
// Sky:     an escaped ray is carried on from its last accepted step to u = 1/r = 0, where its (theta, phi) are its
//          direction at infinity (trace/sky_continuation.hpp, exact_mino); the sky sphere only bounds where objects
//          can be, and its crossing (on the step's interpolant) gives the sky's redshift.
// trace/auto_tracer.hpp picks it for KerrMetric scenes it can draw.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/kerr_mino_system.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/sky_continuation.hpp"

#include <span>
#include <tuple>
#include <utility>

namespace grtrace {

/// True when the reduced Kerr tracer can draw every object of the scene: each is stationary (optional object trait,
/// scene/scene_object.hpp); a scene without objects always.
template <class SceneT>
inline constexpr bool kerr_mino_supports_scene =
    every_object_of<SceneT>([]<class O>() { return object_is_stationary<O>(); });

/// One ray of a Kerr metric on the separated equations: the TraceResult of GeodesicTracer<KerrMetric>::trace for
/// the same ray and events (within the integration's tolerance), lambda in Mino time, t not followed (NaN).
template <ExplicitTableau T, StepController C, class... Events>
GRTRACE_HD TraceResult trace_kerr_mino(const KerrMinoSystem& system, const TraceSettings& settings, const C& controller,
                                       const GeodesicState& y0, const Events&... events) {
  return trace_geodesic_system<T>(system, settings, controller, system.initial_state(y0),
                                  system.metric.horizon_radius(), false, NullObserver{}, events...);
}

/// The same, the ray's system built here (a caller that needs the system afterwards builds it and passes it).
template <ExplicitTableau T, StepController C, class... Events>
GRTRACE_HD TraceResult trace_kerr_mino(const KerrMetric& metric, const TraceSettings& settings, const C& controller,
                                       const GeodesicState& y0, const Events&... events) {
  return trace_kerr_mino<T>(KerrMinoSystem(metric, y0), settings, controller, y0, events...);
}

template <ExplicitTableau T, StepController C, class SceneT>
class KerrMinoSceneTracer {
  static_assert(kerr_mino_supports_scene<SceneT>,
                "the reduced Kerr tracer does not follow t: every object must be stationary (declare `static "
                "constexpr bool stationary = true;` if yours is); other objects need GeneralSceneTracer");
  static_assert(C::estimate != ErrorEstimate::none,
                "the reduced Kerr tracer integrates in Mino time, not in the affine parameter: a fixed step would "
                "mean something else there; use an adaptive controller (i, pi, doubling)");
  static_assert(scene_objects_checked<KerrMetric, SceneT>);

 public:
  static constexpr const char* name = "kerr-mino";
  using MetricType = KerrMetric;
  using SceneType = SceneT;

  KerrMinoSceneTracer(KerrMetric metric, TraceSettings settings, C controller, AngleCorrection correction,
                      SceneT scene)
      : metric_(metric), settings_(with_escape_refinement<KerrMetric>(settings, correction)),
        controller_(controller), correction_(correction), scene_(std::move(scene)) {}

  GRTRACE_HD RayOutcome trace(const GeodesicState& y0) const {
    const KerrMinoSystem system(metric_, y0);
    const TraceResult r = apply_to_objects(
        [&](const auto&... o) {
          return trace_kerr_mino<T>(system, settings_, controller_, y0, bind_to_metric(o, metric_)...);
        },
        scene_.objects);
    // The continuation starts from the last accepted step (which may lie beyond u = 0: it is then taken back),
    // with the ray's own constants of motion; from the sky sphere's crossing if that step is not usable.
    return scene_outcome(metric_, scene_, r, [&](const GeodesicState& from, const GeodesicState& at_sphere) {
      if (correction_ == AngleCorrection::exact) {
        const Tolerance& tol = settings_.integrator.tolerance;
        for (const GeodesicState* y : {&from, &at_sphere})
          if (auto d = kerr_direction_at_infinity<T>(system, tol, system.initial_state(*y))) return *d;
      }
      return continued_direction(metric_, at_sphere, at_sphere, correction_);
    });
  }

  /// trace() as a GPU runs it (the general tracer's name for it: trace/scene_tracer.hpp); this tracer notes nothing.
  GRTRACE_HD RayOutcome trace_quietly(const GeodesicState& y0) const { return trace(y0); }
  void note_escaped(std::span<const RayOutcome>) const {}

  /// Which continuation this tracer's escaped rays get (recorded in a frame's header: trace/tracer_report.hpp).
  GRTRACE_HD SkyContinuation sky_continuation() const { return sky_continuation_of<KerrMetric>(correction_); }

  GRTRACE_HD const SceneT& scene() const { return scene_; }
  GRTRACE_HD const KerrMetric& metric() const { return metric_; }
  GRTRACE_HD AngleCorrection correction() const { return correction_; }

 private:
  KerrMetric metric_;
  TraceSettings settings_;
  C controller_;
  AngleCorrection correction_;
  SceneT scene_;
};

/// Deduces the scene: make_kerr_mino_tracer<RKF78, IController>(metric, settings, correction, scene).
template <ExplicitTableau T, StepController C, class SceneT>
KerrMinoSceneTracer<T, C, SceneT> make_kerr_mino_tracer(KerrMetric metric, TraceSettings settings,
                                                        AngleCorrection correction, SceneT scene, C controller = {}) {
  return {metric, settings, controller, correction, std::move(scene)};
}

}  // namespace grtrace
