// grtrace-view: the frame rendered in-process (see view_request.hpp).
#include "view_request.hpp"

#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/trace/method_dispatch.hpp"
#include "grtrace/trace/auto_tracer.hpp"

namespace grtrace::view {

/// Renders the frame in-process as grtrace-render does (--tracer auto, trace/auto_tracer.hpp): the fastest exact
/// tracer for the scene: one table of rays (planar tracer) around a Schwarzschild hole, disk included; every pixel
/// integrated for Kerr (its sky is not spherically symmetric). The image header's "tracer" says which ran.
Image render_frame(const Request& q) {
  const Camera& camera = *q.camera;
  RenderOptions options;
  options.threads = q.threads;
  options.progress_label = "frame";
  std::optional<Frame> frame;
  dispatch_method(q.rays.tableau, q.rays.control, [&]<class T, class C>() {
    with_standard_scene(make_scene_spec(q), [&]<class Scene>(Scene scene) {
      auto draw = [&](const auto& tracer) { frame.emplace(grtrace::render_frame(camera, tracer, options)); };
      if (q.kerr)
        with_auto_tracer<T, C>(KerrMetric{q.mass, q.spin}, q.rays.settings, camera, q.correction, scene, 2048, draw);
      else
        with_auto_tracer<T, C>(SchwarzschildMetric{q.mass}, q.rays.settings, camera, q.correction, scene, 2048, draw);
    });
  });
  return std::move(frame->image);
}

}  // namespace grtrace::view
