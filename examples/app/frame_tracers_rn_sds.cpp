// Reissner-Nordstrom and Schwarzschild-de Sitter frames, automatic Christoffels (see frame_tracers.hpp).
#include "frame_tracers.hpp"

namespace grtrace::app {

void with_rn_sds_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f) {
  with_metric_of<AutoReissnerNordstrom, AutoSchwarzschildDeSitter>(
      q.metric, [&](const auto& metric) { with_integrating_tracer(q, metric, camera, f); });
}

}  // namespace grtrace::app
