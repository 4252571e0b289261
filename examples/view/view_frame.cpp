// grtrace-view: the frame rendered in-process (see view_request.hpp).
#include "view_request.hpp"

#include "grtrace/render/frame.hpp"
#include "grtrace/trace/method_dispatch.hpp"
#include "grtrace/trace/auto_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <stdexcept>
#include <type_traits>

namespace grtrace::view {

/// Renders the frame in-process as grtrace-render does (--tracer auto, trace/auto_tracer.hpp): the fastest exact
/// tracer for the scene: one table of rays (planar tracer) around a Schwarzschild hole, disk included; every pixel
/// integrated for Kerr in either chart (its sky is not spherically symmetric). The image header's "tracer" says
/// which ran.
Image render_frame(const Request& q) {
  const Camera& camera = *q.camera;
  RenderOptions options;
  options.threads = q.threads;
  options.progress_label = "frame";
  std::optional<Frame> frame;
  dispatch_method(q.rays.tableau, q.rays.control, [&]<class T, class C>() {
    with_standard_scene(make_scene_spec(q), [&]<class Scene>(Scene scene) {
      auto draw = [&](const auto& tracer) { frame.emplace(grtrace::render_frame(camera, tracer, options)); };
      with_metric(q, [&](const auto& metric) {
        if constexpr (scene_fits_metric<std::remove_cvref_t<decltype(metric)>, Scene>)
          with_auto_tracer<T, C>(metric, q.rays.settings, camera, q.correction, scene, grtrace::default_table_rays,
                                 draw);
        else
          throw std::logic_error("grtrace-view: a disk scene in a chart that cannot hold it was not refused");
      });
    });
  });
  return std::move(frame->image);
}

}  // namespace grtrace::view
