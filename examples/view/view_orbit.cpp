// grtrace-view: the timelike orbit (see view_request.hpp).
#include "view_request.hpp"

#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/app/tool_methods.hpp"

namespace grtrace::view {

viz::TracedPath trace_orbit(const Request& q) {
  viz::TracedPath path;
  app::dispatch_tool_method(q.orbit_method.tableau, q.orbit_method.control, [&]<class T, class C>() {
    const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{q.mass}, q.orbit_method.settings);
    path = viz::trace_orbit(tracer, q.orbit, q.samples_per_step);
  });
  return path;
}

}  // namespace grtrace::view
