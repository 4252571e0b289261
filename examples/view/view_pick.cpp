// grtrace-view: picked pixels (see view_request.hpp).
#include "view_request.hpp"

#include "grtrace/app/tool_methods.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/viz/pick.hpp"

#include <stdexcept>
#include <type_traits>

namespace grtrace::view {

/// Traces one pixel with the general scene tracer of the request (every pixel integrated, the scene's objects as
/// events), whatever tracer drew the frame: the path drawn and the outcome listed are that one integration's.
viz::RayPick pick_ray(const Request& q, std::array<int, 2> pixel, const viz::Rgb8Image& frame) {
  const Camera& camera = *q.camera;
  viz::RayPick pick;
  app::dispatch_tool_method(q.rays.tableau, q.rays.control, [&]<class T, class C>() {
    with_standard_scene(make_scene_spec(q), [&]<class Scene>(Scene scene) {
      with_metric(q, [&](const auto& metric) {
        if constexpr (scene_fits_metric<std::remove_cvref_t<decltype(metric)>, Scene>) {
          const auto tracer = make_general_tracer<T, C>(metric, q.rays.settings, q.correction, scene);
          pick = viz::pick_ray(tracer, [&](int x, int y) { return camera.pixel_state(x, y); }, pixel,
                               q.samples_per_step, camera.tetrad().e[0], frame.empty() ? nullptr : &frame);
        } else {
          throw std::logic_error("grtrace-view: a disk scene in a chart that cannot hold it was not refused");
        }
      });
    });
  });
  return pick;
}

}  // namespace grtrace::view
