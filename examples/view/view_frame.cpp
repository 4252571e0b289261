// grtrace-view: the frame rendered in-process (see view_request.hpp).
#include "view_request.hpp"

#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/trace/method_dispatch.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/symmetric_scene_tracer.hpp"

namespace grtrace::view {

/// Renders the frame in-process as grtrace-render does (--tracer auto): the general scene tracer for the disk
/// scene, the symmetric-sky tracer (one table of rays for the frame) otherwise.
Image render_frame(const Request& q) {
  const Camera& camera = *q.camera;
  Image image(q.width, q.height);
  const Shading shading = make_shading(q);
  RenderOptions options;
  options.threads = q.threads;
  options.progress_label = "frame";
  const SchwarzschildMetric metric{q.mass};
  dispatch_method(q.rays.tableau, q.rays.control, [&]<class T, class C>() {
    auto render_with = [&](const auto& tracer) {
      render_image(image, [&](int x, int y) { return shade(tracer.trace(camera.pixel_state(x, y)), shading); }, options);
    };
    if (q.scene == SceneKind::disk)
      render_with(GeneralSceneTracer<T, C, ThinDisk>(metric, q.rays.settings, C{}, q.correction, shading.disk));
    else
      render_with(SymmetricSceneTracer<T, C>(metric, q.rays.settings, camera, q.correction));
  });
  return image;
}

}  // namespace grtrace::view
