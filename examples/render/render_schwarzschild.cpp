// grtrace-render: Schwarzschild and flat-space frames (see render_request.hpp).
#include "render_request.hpp"

#include "grtrace/trace/straight_line.hpp"
#include "grtrace/trace/symmetric_scene_tracer.hpp"

namespace grtrace::render_tool {

/// Flat space by straight lines; Schwarzschild by auto's choice (one table of rays for the frame: the planar tracer,
/// trace/auto_tracer.hpp), every pixel integrated (--tracer general), or the older sky-only table (--tracer
/// symmetric).
std::optional<Frame> render_schwarzschild(const Request& q, SkyDirections* directions, TracerReport& table) {
  const RenderOptions options = q.render_options();
  const Camera& cam = *q.camera;
  if (q.tracer == "straight-line")
    return with_standard_scene(q.scene, [&](auto scene) -> std::optional<Frame> {
      const StraightLineTracer tracer(MinkowskiSpherical{}, q.settings.escape_radius, q.correction, scene);
      if (q.flight.cameras.empty()) return render_frame(cam, tracer, options, directions);
      const FlightStats stats = render_flight(
          q.flight.cameras, [&](const Camera&, auto&& f) { f(tracer); }, q.flight.skip,
          [&](int i, Frame&& frame, const TracerReport& r) { q.flight.sink(i, frame, r); }, options);
      if (q.flight.stats) *q.flight.stats = stats;
      return std::nullopt;
    });
  const SchwarzschildMetric metric{q.metric.mass};
  if (q.tracer != "symmetric") return render_general(q, metric, directions, &table);
  std::optional<Frame> frame;
  dispatch_method(q.tableau, q.control, [&]<class T, class C>() {
    const BackgroundScene scene = background_scene(q.scene);  // the symmetric tracer draws no objects
    const SymmetricSceneTracer<T, C, BackgroundScene> tracer(metric, q.settings, cam, q.correction, scene,
                                                             q.table_nodes);
    table = tracer_report(tracer);
    frame.emplace(render_frame(cam, tracer, options, directions));
  });
  return frame;
}

}  // namespace grtrace::render_tool
