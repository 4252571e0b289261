// Schwarzschild and flat-space frames (see frame_tracers.hpp).
#include "frame_tracers.hpp"

#include "grtrace/trace/straight_line.hpp"
#include "grtrace/trace/symmetric_scene_tracer.hpp"

namespace grtrace::app {

/// Flat space by straight lines; Schwarzschild by auto's choice (the planar tracer), every pixel integrated
/// (general), or the older sky-only table (symmetric: draws no objects).
void with_schwarzschild_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f) {
  if (q.metric.name == "minkowski") {
    with_standard_scene(q.scene, [&](auto scene) {
      hand_over(StraightLineTracer(MinkowskiSpherical{}, q.settings.escape_radius, q.correction, scene), f);
    });
    return;
  }
  const SchwarzschildMetric metric{q.metric.mass};
  if (q.tracer != "symmetric") return with_integrating_tracer(q, metric, camera, f);
  const bool known = dispatch_tool_method(q.tableau, q.control, [&]<class T, class C>() {
    const BackgroundScene scene = background_scene(q.scene);
    hand_over(SymmetricSceneTracer<T, C, BackgroundScene>(metric, q.settings, camera, q.correction, scene,
                                                          q.table_rays),
              f);
  });
  if (!known) check_tool_method(q.tableau, q.control);
}

}  // namespace grtrace::app
