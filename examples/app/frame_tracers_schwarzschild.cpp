// Schwarzschild and flat-space frames (see frame_tracers.hpp).
#include "frame_tracers.hpp"

#include "grtrace/trace/straight_line.hpp"

namespace grtrace::app {

/// Flat space by straight lines; Schwarzschild by auto's choice (the planar tracer) or every pixel integrated
/// (general).
void with_schwarzschild_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f) {
  if (q.metric.name == "minkowski") {
    with_standard_scene(q.scene, [&](auto scene) {
      hand_over(StraightLineTracer(MinkowskiSpherical{}, q.settings.escape_radius, q.correction, scene), f);
    });
    return;
  }
  with_integrating_tracer(q, SchwarzschildMetric{q.metric.mass}, camera, f);
}

}  // namespace grtrace::app
