// Single rays (grtrace/app/front_door.hpp, RayTracer) in the metrics with closed-form accelerations: Schwarzschild,
// flat space, Kerr in Boyer-Lindquist and Kerr-Schild coordinates; and RayTracer::create, which reaches every unit.
#include "ray_tracers_impl.hpp"

namespace grtrace::app {

template std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest&, const SchwarzschildMetric&);
template std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest&, const MinkowskiSpherical&);
template std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest&, const KerrMetric&);
template std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest&, const KerrSchildMetric&);

std::unique_ptr<RayTracer> RayTracer::create(const CheckedRequest& checked) {
  return with_named_metric(checked.request.metric,
                           [&](const auto& metric) { return make_ray_tracer(checked, metric); });
}

}  // namespace grtrace::app
