// grtrace-view: the frame rendered in-process (see view_request.hpp), by the application layer that draws
// grtrace-render's frames (grtrace/app/frame_tracer.hpp): the same tracers, compiled once.
#include "view_request.hpp"

#include "grtrace/app/frame_tracer.hpp"

namespace grtrace::view {

/// The request's frame as grtrace-render draws it with --tracer auto (trace/auto_tracer.hpp): one table of rays
/// (planar tracer) around a Schwarzschild hole, disk included; Kerr's separated equations (kerr-mino) in
/// Boyer-Lindquist coordinates with an adaptive controller; every pixel integrated otherwise. On the device
/// app::choose_device's auto picks (the CPU until the GPU backend passes its device checks). The image header's
/// "tracer" and "device" say which ran.
app::FrameRequest frame_request(const Request& q) {
  app::FrameRequest f;
  f.metric.name = q.kerr ? "kerr" : "schwarzschild";
  f.metric.mass = q.mass;
  f.metric.spin = q.kerr ? q.spin : 0.0;
  f.metric.chart = q.kerr ? q.chart : "bl";
  f.metric.slicing = q.ks_slicing;
  f.scene = make_scene_spec(q);
  f.tableau = q.rays.tableau;
  f.control = q.rays.control;
  f.settings = q.rays.settings;
  f.correction = q.correction;
  f.device = app::choose_device("auto", f);
  return f;
}

Image render_frame(const Request& q) {
  RenderOptions options;
  options.threads = q.threads;
  options.progress_label = "frame";
  return app::render_frame(frame_request(q), *q.camera, options).image;
}

}  // namespace grtrace::view
