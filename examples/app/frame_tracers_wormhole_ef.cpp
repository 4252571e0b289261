// Ellis wormhole and Schwarzschild in Eddington-Finkelstein coordinates (see frame_tracers.hpp).
#include "frame_tracers.hpp"

namespace grtrace::app {

void with_wormhole_ef_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f) {
  with_metric_of<AutoEllisWormhole, AutoEddingtonFinkelstein>(
      q.metric, [&](const auto& metric) { with_integrating_tracer(q, metric, camera, f); });
}

}  // namespace grtrace::app
