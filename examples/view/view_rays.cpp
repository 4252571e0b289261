// grtrace-view: the bundle's rays (see view_request.hpp).
#include "view_request.hpp"

#include "grtrace/app/tool_methods.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/viz/bundles.hpp"

#include <algorithm>
#include <type_traits>

namespace grtrace::view {

namespace {

/// Calls f(GeodesicTracer, events...) with the scene's objects as events (a disk for the disk scene).
template <class F>
void with_scene_tracer(const Request& q, F&& f) {
  app::dispatch_tool_method(q.rays.tableau, q.rays.control, [&]<class T, class C>() {
    with_metric(q, [&](const auto& metric) {
      using M = std::remove_cvref_t<decltype(metric)>;
      const GeodesicTracer<M, T, C> tracer(metric, q.rays.settings);
      // The disk as the general scene tracer sees it in this metric (bind_to_metric: z = 0 in Kerr-Schild).
      if (q.scene == "disk") return f(tracer, bind_to_metric(make_scene_spec(q).disk, metric));
      f(tracer);
    });
  });
}


}  // namespace

std::vector<viz::TracedPath> trace_bundle(const Request& q, std::span<const std::array<int, 2>> pixels,
                                          const viz::Rgb8Image& frame) {
  std::vector<viz::TracedPath> paths;
  if (q.bundle == "beam") {
    // The beam lies in the disk's plane, so the disk is no surface for it: only the horizon and the sky end it.
    const auto states = viz::parallel_fan(q.mass, q.bundle_size[0], q.beam_width, beam_start_radius(q));
    with_scene_tracer(q, [&](const auto& tracer, const auto&...) {
      for (const auto& y0 : states) paths.push_back(viz::trace_path(tracer, y0, q.samples_per_step, std::nullopt));
    });
  } else if (!pixels.empty()) {
    const Camera& camera = *q.camera;
    with_scene_tracer(q, [&](const auto& tracer, const auto&... events) {
      paths = viz::trace_pixels(tracer, [&](int x, int y) { return camera.pixel_state(x, y); }, pixels,
                                q.samples_per_step, camera.tetrad().e[0], frame.empty() ? nullptr : &frame,
                                events...);
    });
  }
  return paths;
}

}  // namespace grtrace::view
