// grtrace/render/frame.hpp
// The pixel pipeline as one call: camera -> scene tracer -> shading -> Image, with the statistics, the progress
// bar and the header attributes that make a frame self-describing.
//
//   const Camera camera = make_camera(metric, spec);                                  // observer/camera_spec.hpp
//   const auto tracer = make_general_tracer<Tsit5, IController>(metric, settings, AngleCorrection::exact, scene);
//   Frame frame = render_frame(camera, tracer);                                        // all nine channels
//   write_exr("out.exr", frame.image);                                                 // render/exr_io.hpp
//
// Takes:   a Camera (observer/camera.hpp) and any SceneTracer (trace/scene_tracer_concept.hpp); RenderOptions
//          (threads, tiles, progress: render/parallel_render.hpp); optionally a vector to receive every pixel's
//          sky direction in double precision (the channels are float), e.g. for error maps.
// Returns: the Image (channels R, G, B, object, status, redshift, sky_theta, sky_phi, steps) and its RenderStats.
//          Metadata written: tracer, object_names (by scene position), camera_position, tetrad_e0..e3,
//          fov_degrees, and the statistics (record_render_stats). Callers add their own (tool options, metric).
// Guarantees: those of render_image (no NaN colour, statuses counted, deterministic for any thread count).
#pragma once

#include "grtrace/observer/camera.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/trace/scene_tracer_concept.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace grtrace {

struct Frame {
  Image image;
  RenderStats stats;
};

/// "%.17g": a number that reads back to the same double.
inline std::string exact_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

inline std::string exact_vector(const Vec4& v) {
  return exact_number(v[0]) + "," + exact_number(v[1]) + "," + exact_number(v[2]) + "," + exact_number(v[3]);
}

/// Writes the camera's event, tetrad and field of view into the image header (grtrace-view --frame reads them).
inline void record_camera(Image& image, const Camera& camera) {
  image.metadata["camera_position"] = exact_vector(camera.position());
  for (int a = 0; a < 4; ++a)
    image.metadata["tetrad_e" + std::to_string(a)] = exact_vector(camera.tetrad().e[static_cast<std::size_t>(a)]);
  image.metadata["fov_degrees"] = exact_number(camera.fov_degrees());
}

template <SceneTracer Tracer>
Frame render_frame(const Camera& camera, const Tracer& tracer, const RenderOptions& options = {},
                   std::vector<SkyDirection>* directions = nullptr) {
  Frame frame{Image(camera.width(), camera.height()), {}};
  Image& image = frame.image;
  if (directions) directions->assign(image.pixel_count(), SkyDirection{RayOutcome::nan, RayOutcome::nan});
  const auto& scene = tracer.scene();
  frame.stats = render_image(
      image,
      [&](int col, int row) {
        const RayOutcome o = tracer.trace(camera.pixel_state(col, row));
        if (directions) (*directions)[image.index(col, row)] = o.where;  // distinct pixels: no data race
        return scene.shade(o);
      },
      options);
  image.metadata["tracer"] = Tracer::name;
  std::string names;
  for (const std::string& n : scene.object_names()) names += (names.empty() ? "" : ",") + n;
  image.metadata["object_names"] = names;
  record_camera(image, camera);
  record_render_stats(image, frame.stats);
  return frame;
}

}  // namespace grtrace
