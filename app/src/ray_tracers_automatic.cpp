// Single rays (grtrace/app/front_door.hpp, RayTracer) in the metrics differentiated by dual numbers
// (metric/auto_metric.hpp): Reissner-Nordstrom, Schwarzschild-de Sitter, the Ellis wormhole, Eddington-Finkelstein.
#include "ray_tracers_impl.hpp"

namespace grtrace::app {

template std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest&, const AutoReissnerNordstrom&);
template std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest&, const AutoSchwarzschildDeSitter&);
template std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest&, const AutoEllisWormhole&);
template std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest&, const AutoEddingtonFinkelstein&);

}  // namespace grtrace::app
