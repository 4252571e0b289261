// grtrace/trace/scene_tracer.hpp
// The general scene tracer: one integration per camera ray through ANY metric policy, ended by the horizon (for
// metrics that have one), the sky sphere, or one of the scene's objects (scene/scene_object.hpp); a group of rays
// (trace_many, what render_frame calls per tile) four at a time side by side (trace/batched_trace.hpp), each
// outcome bit for bit the ray's alone. The metric, tableau, controller and scene are template parameters, so a
// tracer instantiated for a scene contains only that scene's objects and no virtual call.
//
// Takes:   a metric, trace settings (tolerances, sky radius, horizon guard), a controller, how escaped rays are
//          continued to the sky (AngleCorrection: exact where the metric's has one or is Kerr, else flat;
//          trace/sky_continuation.hpp), and the scene.
// Returns: per ray a RayOutcome: status, scene position, direction, end state (x, k), redshift.
// Redshift (seed eq. 9): f_obs / f_src = g(e_0, k_cam) / g(u_src, k_src) with g(e_0, k_cam) = -1 by the camera's
// normalisation of the pixel momentum. u_src: the sky's and the horizon's emitters are at rest (static where the
// metric allows, else the ZAMO: observer/observers.hpp), an object's comes from its emitter_velocity(metric, x).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/trace/batched_trace.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/ray_outcome.hpp"
#include "grtrace/trace/sky_continuation.hpp"

#include <span>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace grtrace {

/// f_obs / f_src for a ray that left a camera with unit energy (g(e_0, k) = -1) and reached an emitter moving
/// with 4-velocity u at the end state y (NaN when u is NaN: no emitter can exist there).
template <MetricPolicy M>
GRTRACE_HD double redshift_at(const M& metric, const Vec4& u, const GeodesicState& y) {
  return -1.0 / u.dot(metric.metric(y.head<4>()) * y.tail<4>());
}

/// Every object of the scene checked against the metric with check_scene_object (static_asserts whose messages name
/// what an object lacks): what a scene tracer's class asserts.
template <class Metric, class SceneT>
inline constexpr bool scene_objects_checked =
    every_object_of<SceneT>([]<class O>() { return check_scene_object<O, Metric>(); });

/// A scene object seen as the tracer's event in a given metric: the object's surface(metric, y) and
/// accepts(metric, y) where it provides them (scene/scene_object.hpp), its two_sided and interior_samples as they
/// are. Holds pointers: the object and the metric must outlive it (a tracer's trace call).
template <class O, class M>
struct MetricBoundObject {
  const O* object;
  const M* metric;
  static constexpr bool two_sided = event_is_two_sided<O>();
  static constexpr int interior_samples = event_interior_samples<O>();
  GRTRACE_HD double operator()(const GeodesicState& y) const { return object->surface(*metric, y); }
  GRTRACE_HD bool accepts(const GeodesicState& y) const {
    if constexpr (requires { { object->accepts(*metric, y) } -> std::convertible_to<bool>; })
      return object->accepts(*metric, y);
    else return event_accepts(*object, y);
  }
};

/// The event a tracer integrating in `metric` checks for `object`: the object itself, or a MetricBoundObject when
/// it writes its surface with the metric at hand (the thin disk in a Cartesian chart).
template <class O, MetricPolicy M>
GRTRACE_HD decltype(auto) bind_to_metric(const O& object, const M& metric) {
  if constexpr (requires(const GeodesicState y) { { object.surface(metric, y) } -> std::convertible_to<double>; })
    return MetricBoundObject<O, M>{&object, &metric};
  else return (object);
}

/// True when every object of the scene can say how its matter moves in the metric (e.g. ThinDisk needs a
/// spherical chart): programs that choose metric and scene at run time test this before instantiating a tracer.
template <class Metric, class SceneT>
inline constexpr bool scene_fits_metric = every_object_of<SceneT>([]<class O>() { return SceneObjectIn<O, Metric>; });

/// What a scene tracer reports for a ray the tracing loop ended with r (trace/ray_outcome.hpp): the object, where,
/// the end state and the redshift against the emitter there (the object's matter, or the rest frame for the sky
/// and the horizon). An escaped ray is seen where escaped(from, at_sphere) says (trace/sky_continuation.hpp: from
/// is the last accepted step, at_sphere the sky sphere's crossing).
template <MetricPolicy Metric, class SceneT, class EscapedDirection>
GRTRACE_GPU_CALLED GRTRACE_HD RayOutcome scene_outcome(const Metric& m, const SceneT& scene, const TraceResult& r,
                                                       const EscapedDirection& escaped) {
  RayOutcome out;
  out.status = r.status;
  out.steps = r.accepted;
  if (is_failure(r.status)) return out;  // no position, no redshift
  const GeodesicState& y = r.final_state;
  const Vec4 x = y.head<4>();
  out.state = y;
  out.radius = m.radius(x);
  out.order = r.crossings;
  Vec4 u = Vec4::Zero();
  if (r.status == RayStatus::hit) {
    out.object = kFirstSceneObject + r.hit_event;
    out.where = position_direction(m, x);
    scene.visit_object(out.object, [&](const auto& o) { u = o.emitter_velocity(m, x); });
  } else {
    out.object = r.status == RayStatus::escaped ? kSkyObject : kHorizonObject;
    out.where = r.status == RayStatus::escaped ? escaped(r.step_end_state, y) : position_direction(m, x);
    // An escaped ray's order counts its crossings up to where it is seen (core/sky_direction.hpp).
    if (r.status == RayStatus::escaped && r.crossings >= 0)
      out.order += crossed_beyond_sphere(equatorial_latitude<Metric>(y), out.where);
    u = rest_emitter_velocity(m, x);
  }
  out.redshift = redshift_at(m, u, y);
  return out;
}

/// The settings a scene tracer integrates with: the exact continuation starts from the last accepted step, not
/// from the sky sphere, so refining the sphere's crossing would buy nothing there (TraceSettings::refine_escape).
template <MetricPolicy Metric>
GRTRACE_HD TraceSettings with_escape_refinement(TraceSettings s, AngleCorrection correction) {
  if (continues_exactly<Metric>(correction)) s.refine_escape = false;
  return s;
}

template <MetricPolicy Metric, ExplicitTableau T, StepController C, class SceneT>
class GeneralSceneTracer {
  static_assert(scene_objects_checked<Metric, SceneT>);

 public:
  static constexpr const char* name = "general";
  using MetricType = Metric;
  using SceneType = SceneT;

  GeneralSceneTracer(Metric metric, TraceSettings settings, C controller, AngleCorrection correction, SceneT scene)
      : tracer_(metric, with_escape_refinement<Metric>(settings, correction), controller), correction_(correction),
        scene_(std::move(scene)) {}

  RayOutcome trace(const GeodesicState& y0) const {
    return trace_noting(y0, [this](const GeodesicState& at_sphere) { note_escape(at_sphere); });
  }

  /// trace() as a GPU runs it (core/host_device.hpp): the same outcome, bit for bit in the same arithmetic, without
  /// noting an escaped ray's impact parameter for the flat continuation's estimate (a frame traced elsewhere notes
  /// its outcomes afterwards: note_escaped).
  GRTRACE_HD RayOutcome trace_quietly(const GeodesicState& y0) const {
    return trace_noting(y0, [](const GeodesicState&) {});
  }

  /// What trace() notes of each escaped ray, for outcomes traced by trace_quietly: its impact parameter when its
  /// sky is continued flat.
  void note_escaped(std::span<const RayOutcome> outcomes) const {
    for (const RayOutcome& o : outcomes)
      if (o.status == RayStatus::escaped) note_escape(o.state);
  }

  /// Many rays, kTraceLanes at a time (trace/batched_trace.hpp): out[i] is trace(y0[i]) bit for bit, for less
  /// time (optional trait of scene tracers: trace/scene_tracer_concept.hpp). Assumes out.size() == y0.size().
  void trace_many(std::span<const GeodesicState> y0, std::span<RayOutcome> out) const {
    const Metric& m = tracer_.metric();
    std::vector<TraceResult> results(y0.size());
    std::apply([&](const auto&... o) { trace_batched(tracer_, y0, std::span(results), bind_to_metric(o, m)...); },
               scene_.objects);
    const auto note = [this](const GeodesicState& at_sphere) { note_escape(at_sphere); };
    for (std::size_t i = 0; i < y0.size(); ++i) out[i] = scene_outcome(m, scene_, results[i], escaped(note));
  }

  /// trace() with an observer called on every accepted step (GeodesicTracer::trace_observed: e.g. a PathRecorder,
  /// trace/traced_path.hpp) and `extra` events after the scene's objects: a ray's path and its outcome in one
  /// integration, the outcome trace()'s bit for bit while no extra event ends the ray (one that does gives status
  /// hit with an object index past the scene's). Escaped rays are not noted for the flat continuation's estimate.
  template <class Observer, class... Extra>
  RayOutcome trace_observed(const GeodesicState& y0, Observer&& observer, const Extra&... extra) const {
    const Metric& m = tracer_.metric();
    return scene_outcome(m, scene_,
                         apply_to_objects(
                             [&](const auto&... o) {
                               return tracer_.trace_observed(y0, observer, bind_to_metric(o, m)..., extra...);
                             },
                             scene_.objects),
                         escaped([](const GeodesicState&) {}));
  }

  /// Which continuation this tracer's escaped rays get (recorded in a frame's header: trace/tracer_report.hpp).
  GRTRACE_HD SkyContinuation sky_continuation() const { return sky_continuation_of<Metric>(correction_); }

  /// For a flat continuation: the error estimate of the rays traced so far (trace/sky_continuation.hpp; recorded in
  /// a frame's header), at the largest impact parameter among them; nothing for an exact one, or a metric without
  /// an estimate. note_flat_impact is how a tracer that hands rays to this one (planar) adds its own.
  std::optional<FlatContinuationEstimate> flat_continuation_estimate() const {
    if (sky_continuation() != SkyContinuation::flat) return std::nullopt;
    const TraceSettings& s = tracer_.settings();
    return grtrace::flat_continuation_estimate(tracer_.metric(), s.escape_radius, flat_impact_.get(),
                                               s.integrator.tolerance.rtol);
  }
  void note_flat_impact(double b) const {
    if constexpr (HasMass<Metric>) flat_impact_.raise(b);
  }

  GRTRACE_HD const SceneT& scene() const { return scene_; }
  GRTRACE_HD const Metric& metric() const { return tracer_.metric(); }
  GRTRACE_HD const GeodesicTracer<Metric, T, C>& tracer() const { return tracer_; }
  GRTRACE_HD AngleCorrection correction() const { return correction_; }

 private:
  /// One ray; note(at_sphere) sees where an escaped ray crossed the sky sphere.
  template <class Note>
  GRTRACE_HD RayOutcome trace_noting(const GeodesicState& y0, const Note& note) const {
    const Metric& m = tracer_.metric();
    return scene_outcome(
        m, scene_,
        apply_to_objects([&](const auto&... o) { return tracer_.trace(y0, bind_to_metric(o, m)...); }, scene_.objects),
        escaped(note));
  }

  /// Where an escaped ray is seen: trace/sky_continuation.hpp, with this tracer's own method.
  template <class Note>
  GRTRACE_HD auto escaped(const Note& note) const {
    return [this, &note](const GeodesicState& from, const GeodesicState& at_sphere) {
      note(at_sphere);
      return escaped_direction<T>(tracer_.metric(), tracer_.settings().integrator.tolerance, correction_, from,
                                  at_sphere);
    };
  }

  /// The flat continuation's record of an escaped ray that crossed the sky sphere at y.
  void note_escape(const GeodesicState& y) const {
    // Only where an estimate can come of it: a metric without a mass has none to report.
    if constexpr (HasMass<Metric>) {
      if (sky_continuation() == SkyContinuation::flat) note_flat_impact(flat_impact_parameter(tracer_.metric(), y));
    }
  }

  GeodesicTracer<Metric, T, C> tracer_;
  AngleCorrection correction_;
  SceneT scene_;
  ConcurrentMax flat_impact_;  ///< the largest impact parameter of the rays continued flat
};

/// Deduces the metric and the scene: make_general_tracer<Tsit5, IController>(metric, settings, correction, scene).
template <ExplicitTableau T, StepController C, MetricPolicy Metric, class SceneT>
GeneralSceneTracer<Metric, T, C, SceneT> make_general_tracer(Metric metric, TraceSettings settings,
                                                              AngleCorrection correction, SceneT scene,
                                                              C controller = {}) {
  return {metric, settings, controller, correction, std::move(scene)};
}

}  // namespace grtrace
