// grtrace-view's tracing (see view_request.hpp), all through the application library: the frame
// (app::FrameRenderer, as grtrace-render draws it), the bundle's and the picked rays (app::RayTracer), the orbit.
#include "grtrace/app/medium_view.hpp"
#include "grtrace/viz/bundles.hpp"
#include "grtrace/viz/pick.hpp"
#include "view_request.hpp"

#include <cmath>
#include <numbers>

namespace grtrace::view {

viz::TracedPath trace_orbit(const Request& q) {
  const auto tracer = app::RayTracer::create(*q.orbit_checked);
  const double sign = q.orbit.dphi_dtau >= 0.0 ? 1.0 : -1.0;
  app::PathOptions options;
  options.samples_per_step = q.samples_per_step;
  options.scene_objects = false;
  options.phi_advance = sign * 2.0 * std::numbers::pi * q.orbit.revolutions;
  return tracer->trace(viz::orbit_initial_state(q.orbit), options).path;
}

std::vector<viz::TracedPath> trace_bundle(const Request& q, std::span<const std::array<int, 2>> pixels,
                                          const viz::Rgb8Image& frame) {
  std::vector<viz::TracedPath> paths;
  const auto tracer = app::RayTracer::create(*q.checked);
  app::PathOptions options;
  options.samples_per_step = q.samples_per_step;
  if (q.bundle == "beam") {
    // The beam lies in the disk's plane, so the disk is no surface for it: only the horizon and the sky end it.
    options.scene_objects = false;
    for (const auto& y0 : viz::parallel_fan(q.mass, q.bundle_size[0], q.beam_width, beam_start_radius(q)))
      paths.push_back(tracer->trace(y0, options).path);
  } else {
    const Camera& camera = q.camera();
    options.observer_velocity = camera.tetrad().e[0];
    for (const auto& p : pixels) {
      paths.push_back(tracer->trace(camera.pixel_state(p[0], p[1]), options).path);
      viz::mark_pixel(paths.back(), p, frame.empty() ? nullptr : &frame);
    }
  }
  return paths;
}

app::RenderResult render_frame(const Request& q) {
  app::RenderControl control;
  control.label = "frame";
  return app::FrameRenderer::create(*q.checked)->render(control);
}

viz::RayPick pick_ray(const Request& q, std::array<int, 2> pixel, const viz::Rgb8Image& frame) {
  const auto tracer = app::RayTracer::create(*q.checked);
  const Camera& camera = q.camera();
  const GeodesicState y0 = camera.pixel_state(pixel[0], pixel[1]);
  app::PathOptions options;
  options.samples_per_step = q.samples_per_step;
  options.observer_velocity = camera.tetrad().e[0];
  app::TracedRay ray = tracer->trace(y0, options);
  viz::RayPick pick;
  pick.pixel = pixel;
  pick.path = std::move(ray.path);
  viz::mark_pixel(pick.path, pixel, frame.empty() ? nullptr : &frame);
  pick.outcome = ray.outcome;
  pick.object_name = std::move(ray.object);
  if (app::is_medium_scene(q.scene))
    pick.light = app::medium_light_along(*q.checked, pick.path, *options.observer_velocity);
  return pick;
}

}  // namespace grtrace::view
