// grtrace/trace/scene_tracer.hpp
// The general scene tracer: one integration per camera ray through Schwarzschild, ended by the horizon guard,
// the sky sphere, or one of the scene's objects. Objects are template parameters (events: g(y) -> double, see
// trace/geodesic_tracer.hpp; each names its SceneObjectId and its emitter's 4-velocity), so a tracer
// instantiated for a scene contains only that scene's objects.
//
// Redshift (seed eq. 9): f_obs / f_src = g(e_0, k_cam) / g(u_src, k_src), with g(e_0, k_cam) = -1 from the
// camera's normalisation; static emitters for the horizon and the sky, the object's own emitter otherwise.
#pragma once

#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <cmath>
#include <tuple>

namespace grtrace {

/// g(u_static, k) for a static emitter at the state's radius, with u_static = d_t / sqrt(g_tt).
inline double static_emitter_energy(const SchwarzschildMetric& m, const GeodesicState& y) {
  const double f = 1.0 - 2.0 * m.mass / y[1];
  return std::sqrt(f) * y[4];
}

template <ExplicitTableau T, StepController C, class... Objects>
class GeneralSceneTracer {
 public:
  static constexpr const char* name = "general";

  GeneralSceneTracer(SchwarzschildMetric metric, TraceSettings settings, C controller, AngleCorrection correction,
                     Objects... objects)
      : tracer_(metric, settings, controller), correction_(correction), objects_(objects...) {}

  RayOutcome trace(const GeodesicState& y0) const {
    const TraceResult r = std::apply([&](const auto&... o) { return tracer_.trace(y0, o...); }, objects_);
    const SchwarzschildMetric& m = tracer_.metric();
    const double camera_energy = -1.0;  // g(e_0, k) at the camera, by construction of the pixel momentum
    RayOutcome out;
    out.status = r.status;
    out.steps = r.accepted;
    const GeodesicState& y = r.final_state;
    switch (r.status) {
      case RayStatus::escaped:
        out.object = SceneObjectId::sky;
        // The exact continuation holds from any point of the outgoing leg: start it from the last accepted step
        // (integrator error only), not from the crossing located on the interpolant (Hermite error for most
        // tableaux). The other corrections are defined at the sky sphere itself.
        out.where = corrected_sky_direction(correction_ == AngleCorrection::exact ? r.step_end_state : y, correction_,
                                            m.mass);
        out.redshift = camera_energy / static_emitter_energy(m, y);
        break;
      case RayStatus::captured:
        out.object = SceneObjectId::horizon;
        out.where = chart_angles(y);
        out.radius = y[1];
        out.redshift = camera_energy / static_emitter_energy(m, y);
        break;
      case RayStatus::hit:
        out.where = chart_angles(y);
        out.radius = y[1];
        visit_object(r.hit_event, [&](const auto& o) {
          out.object = o.id;
          const Vec4 u = o.emitter_velocity(y[1]);
          out.redshift = camera_energy / u.dot(m.metric(y.head<4>()) * y.tail<4>());
        });
        break;
      default: break;  // failed: no position, no redshift
    }
    return out;
  }

  const GeodesicTracer<SchwarzschildMetric, T, C>& tracer() const { return tracer_; }

 private:
  template <class F>
  void visit_object(int index, F&& f) const {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      ((static_cast<int>(I) == index ? f(std::get<I>(objects_)) : void()), ...);
    }(std::index_sequence_for<Objects...>{});
  }

  GeodesicTracer<SchwarzschildMetric, T, C> tracer_;
  AngleCorrection correction_;
  std::tuple<Objects...> objects_;
};

}  // namespace grtrace
