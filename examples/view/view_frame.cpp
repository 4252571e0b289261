// grtrace-view: the frame rendered in-process (see view_request.hpp).
#include "view_request.hpp"

#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/trace/method_dispatch.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/symmetric_scene_tracer.hpp"

namespace grtrace::view {

/// Renders the frame in-process as grtrace-render does (--tracer auto): the general scene tracer for a scene with
/// objects (the disk), the symmetric-sky tracer (one table of rays for the frame) otherwise.
Image render_frame(const Request& q) {
  const Camera& camera = *q.camera;
  RenderOptions options;
  options.threads = q.threads;
  options.progress_label = "frame";
  const SchwarzschildMetric metric{q.mass};
  std::optional<Frame> frame;
  dispatch_method(q.rays.tableau, q.rays.control, [&]<class T, class C>() {
    with_standard_scene(make_scene_spec(q), [&]<class Scene>(Scene scene) {
      if (q.kerr)  // Kerr: the general tracer for every scene (no table: the sky is not spherically symmetric)
        frame.emplace(grtrace::render_frame(
            camera, make_general_tracer<T, C>(KerrMetric{q.mass, q.spin}, q.rays.settings, q.correction, scene),
            options));
      else {
        if constexpr (Scene::object_count == 0)
          frame.emplace(grtrace::render_frame(
              camera, SymmetricSceneTracer<T, C, Scene>(metric, q.rays.settings, camera, q.correction, scene),
              options));
        else
          frame.emplace(grtrace::render_frame(
              camera, make_general_tracer<T, C>(metric, q.rays.settings, q.correction, scene), options));
      }
    });
  });
  return std::move(frame->image);
}

}  // namespace grtrace::view
