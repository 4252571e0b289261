// grtrace/trace/kerr_closed_form_tracer.hpp
// The closed-form Kerr scene tracer: every pixel of a Kerr (Boyer-Lindquist) frame whose objects lie in the
// equatorial plane, from the ray's separated integrals (exact/kerr_null_geodesic.hpp: Gralla & Lupsasca 2020)
// instead of an integration: where it crosses the plane (every order), where it ends, where it is seen on the sky.
//
// Takes:   a KerrMetric, trace settings (the sky sphere's and the horizon guard's radii, and for the fallback the
//          tolerance), the angle correction, and a scene whose objects are all equatorial (scene/scene_object.hpp:
//          `static constexpr bool equatorial = true;`, e.g. ThinDisk).
// Returns: per ray a RayOutcome like the reduced Kerr tracer's (trace/kerr_mino_tracer.hpp), which the frames are
//          tested to equal: the first crossing of the equatorial plane an object accepts, its state (x, k) and
//          redshift against the object's matter; else the end on the sky sphere or the horizon guard, the redshift
//          against an emitter at rest there, and for an escaped ray its direction at infinity (AngleCorrection::
//          exact; the sky sphere's point or the flat continuation under the other corrections). t is NaN (not
//          followed), steps 0 (nothing integrated).
// Per ray: the constants of motion, the radial potential's roots, the polar motion's period; then each crossing
//          n = 0, 1, ... before the end at a Mino time known at once, its radius by one Jacobi function; phi (two
//          Pi integrals) at the hit alone where every object declares itself axisymmetric (scene/scene_object.hpp),
//          at every crossing otherwise.
// Assumes: rays the closed form does not cover (exact/kerr_null_geodesic.hpp: vortical rays, a camera inside the
//          potential's barrier or on the axis) are traced by the reduced Kerr tracer instead: exact to its
//          tolerance, slower; fallback_rays() counts them.
// The tracer's type names the scene only: the fallback's method (tableau, controller) is held behind a small
// interface, called for those few rays alone (136 of a 1024^2 disk frame). So a program that offers several methods
// (the tools' declared list) instantiates this tracer, and the frame loop around it, once per scene, not once per
// method; the hot path has no virtual call.
// trace/auto_tracer.hpp picks it for KerrMetric scenes whose objects are all equatorial.
#pragma once

#include "grtrace/exact/kerr_null_geodesic.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"
#include "grtrace/trace/planar_scene_tracer.hpp"  // planar_supports_scene
#include "grtrace/trace/ray_outcome.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <atomic>
#include <memory>
#include <numbers>
#include <optional>
#include <tuple>
#include <type_traits>
#include <utility>

namespace grtrace {

template <class SceneT>
class KerrClosedFormTracer {
  static_assert(planar_supports_scene<SceneT>,
                "the closed-form Kerr tracer intersects objects that lie in the equatorial plane (declare "
                "`static constexpr bool equatorial = true;` if yours does); other objects need KerrMinoSceneTracer");

 public:
  static constexpr const char* name = "kerr-closed-form";
  using MetricType = KerrMetric;
  using SceneType = SceneT;

  /// The tracer of the rays the closed form does not cover: a KerrMinoSceneTracer of some method.
  struct Fallback {
    virtual ~Fallback() = default;
    virtual RayOutcome trace(const GeodesicState& y0) const = 0;
  };

  template <ExplicitTableau T, StepController C>
  KerrClosedFormTracer(KerrMetric metric, const TraceSettings& settings, C controller, AngleCorrection correction,
                       SceneT scene, std::type_identity<T>)
      : metric_(metric),
        correction_(correction),
        escape_radius_(settings.escape_radius),
        guard_radius_((1.0 + settings.horizon_epsilon) * metric.horizon_radius()),
        scene_(scene),
        fallback_(
            std::make_unique<const FallbackOf<T, C>>(metric, settings, controller, correction, std::move(scene))) {}

  RayOutcome trace(const GeodesicState& y0) const {
    const KerrNullGeodesic ray(metric_, y0, escape_radius_, guard_radius_);
    if (!ray.supported()) {
      fallbacks_.fetch_add(1, std::memory_order_relaxed);
      return fallback_->trace(y0);
    }
    const double end = ray.end_mino_time();
    int n = 0;
    for (; ray.crossing_mino_time(n) < end; ++n) {
      std::optional<RayOutcome> hit;
      if constexpr (kAxisymmetric) {
        // phi (two Pi integrals) only where an object takes the crossing: most crossings miss the objects.
        GeodesicState y = ray.crossing_state_without_phi(n);
        if (accepted(y)) {
          y[3] = ray.crossing_phi(n, y[1]);
          hit = hit_at(y);
        }
      } else {
        hit = hit_at(ray.crossing_state(n));
      }
      if (hit) {
        hit->order = n;
        return *hit;
      }
    }
    RayOutcome out;
    out.steps = 0;
    out.order = n;  // every crossing before the end
    if (!ray.escapes() || correction_ != AngleCorrection::exact) {
      out.state = ray.state_at(end);
      out.radius = out.state[1];
      out.redshift = redshift_at(metric_, rest_emitter_velocity(metric_, out.state.template head<4>()), out.state);
    }
    if (!ray.escapes()) {
      out.status = RayStatus::captured;
      out.object = kHorizonObject;
      out.where = position_direction(metric_, out.state.template head<4>());
      return out;
    }
    out.status = RayStatus::escaped;
    out.object = kSkyObject;
    if (correction_ != AngleCorrection::exact) {
      out.where = continued_direction(metric_, out.state, out.state, correction_);
      out.order += crossed_beyond_sphere(0.5 * std::numbers::pi - out.state[2], out.where);  // up to where it is seen
      return out;
    }
    // The direction at infinity needs no state on the sky sphere (NaN, as the table tracers leave it); the sphere's
    // redshift, against an emitter at rest there (static: far outside the ergosphere), only its theta:
    // -1 / (u . k) = -sqrt(g_tt) / E with E = p_t of y0's k.
    double theta = 0.0, phi = 0.0;
    ray.direction_at_infinity(theta, phi);
    out.where = SkyDirection{theta, azimuth_in_range(phi)};
    out.radius = escape_radius_;
    // cos(theta) there is the sine of the latitude: crossed_beyond_sphere reads its sign and whether it is beyond
    // kOnEquatorialPlane (1e-9, where the two agree to 1e-27), and g_tt reads it as it is: no acos, no sincos.
    const double cos_end = ray.cos_theta_at(end);
    out.order += crossed_beyond_sphere(cos_end, out.where);  // up to where it is seen
    const SinCos end_angle{std::sqrt((1.0 - cos_end) * (1.0 + cos_end)), cos_end};
    const double g_tt = KerrBLComponents(metric_.mass, metric_.spin, escape_radius_, end_angle).g_tt;
    out.redshift = -std::sqrt(g_tt) / ray.energy();
    return out;
  }

  const SceneT& scene() const { return scene_; }
  const KerrMetric& metric() const { return metric_; }
  /// Which continuation escaped rays get: the closed form's direction at infinity under AngleCorrection::exact.
  SkyContinuation sky_continuation() const { return sky_continuation_of<KerrMetric>(correction_); }
  /// Pixels traced by the reduced Kerr tracer instead (see the top of this file), since construction.
  long fallback_rays() const { return fallbacks_.load(std::memory_order_relaxed); }

 private:
  template <ExplicitTableau T, StepController C>
  struct FallbackOf final : Fallback {
    KerrMinoSceneTracer<T, C, SceneT> mino;
    FallbackOf(KerrMetric metric, const TraceSettings& settings, C controller, AngleCorrection correction, SceneT scene)
        : mino(metric, settings, controller, correction, std::move(scene)) {}
    RayOutcome trace(const GeodesicState& y0) const override { return mino.trace(y0); }
  };

  static constexpr bool kAxisymmetric = every_object_of<SceneT>([]<class O>() { return object_is_axisymmetric<O>(); });

  // Whether an object accepts the crossing state y.
  bool accepted(const GeodesicState& y) const {
    return std::apply([&](const auto&... o) { return (bind_to_metric(o, metric_).accepts(y) || ...); },
                      scene().objects);
  }

  // The outcome of the first object (in scene order) that accepts the crossing state y, if any.
  std::optional<RayOutcome> hit_at(const GeodesicState& y) const {
    std::optional<RayOutcome> hit;
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      ((!hit && bind_to_metric(std::get<I>(scene().objects), metric_).accepts(y)
            ? void(hit = outcome_of(kFirstSceneObject + static_cast<int>(I), std::get<I>(scene().objects), y))
            : void()),
       ...);
    }(std::make_index_sequence<SceneT::object_count>{});
    return hit;
  }

  template <class O>
  RayOutcome outcome_of(int position, const O& object, const GeodesicState& y) const {
    RayOutcome out;
    out.status = RayStatus::hit;
    out.object = position;
    out.steps = 0;
    out.state = y;
    out.radius = y[1];
    out.where = position_direction(metric_, y.template head<4>());
    out.redshift = redshift_at(metric_, object.emitter_velocity(metric_, y.template head<4>()), y);
    return out;
  }

  KerrMetric metric_;
  AngleCorrection correction_;
  double escape_radius_, guard_radius_;
  SceneT scene_;
  std::unique_ptr<const Fallback> fallback_;
  mutable std::atomic<long> fallbacks_{0};
};

/// Deduces the scene; T and C are the fallback's method: make_kerr_closed_form_tracer<RKF78, IController>(metric,
/// settings, correction, scene).
template <ExplicitTableau T, StepController C, class SceneT>
KerrClosedFormTracer<SceneT> make_kerr_closed_form_tracer(KerrMetric metric, const TraceSettings& settings,
                                                          AngleCorrection correction, SceneT scene, C controller = {}) {
  return KerrClosedFormTracer<SceneT>(metric, settings, controller, correction, std::move(scene),
                                      std::type_identity<T>{});
}

}  // namespace grtrace
