// Kerr frames in Boyer-Lindquist coordinates (see frame_tracers.hpp).
#include "frame_tracers.hpp"

namespace grtrace::app {

void with_kerr_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f) {
  with_metric_of<KerrMetric>(q.metric, [&](const auto& metric) { with_integrating_tracer(q, metric, camera, f); });
}

}  // namespace grtrace::app
