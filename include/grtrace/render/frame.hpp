// grtrace/render/frame.hpp
// The pixel pipeline as one call: camera -> scene tracer -> shading -> Image, with the statistics, the progress
// bar and the header attributes that make a frame self-describing.
//
//   const Camera camera = make_camera(metric, spec);                                  // observer/camera_spec.hpp
//   const auto tracer = make_general_tracer<Tsit5, IController>(metric, settings, AngleCorrection::exact, scene);
//   Frame frame = render_frame(camera, tracer);                                        // all ten channels
//   write_exr("out.exr", frame.image);                                                 // render/exr_io.hpp
//
// Takes:   a Camera (observer/camera.hpp) and any SceneTracer (trace/scene_tracer_concept.hpp); RenderOptions
//          (threads, tiles, progress: render/parallel_render.hpp); optionally a vector to receive every pixel's
//          sky direction in double precision (the channels are float), e.g. for error maps.
// Returns: the Image (channels R, G, B, object, status, redshift, sky_theta, sky_phi, steps, order) and its
//          RenderStats.
//          Metadata written: tracer, mirrors (the reflections used: render/mirror_symmetry.hpp; a frame whose
//          metric, scene and camera are mirror symmetric traces only half or a quarter of its pixels, see
//          RenderStats::traced_rays; RenderOptions::mirror_symmetry = false traces every pixel),
//          object_names (by scene position), camera_position, tetrad_e0..e3,
//          fov_degrees, and the statistics (record_render_stats). Callers add their own (tool options, metric).
// Guarantees: those of render_image (no NaN colour, statuses counted, deterministic for any thread count).
#pragma once

#include "grtrace/observer/camera.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/render/mirror_symmetry.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/trace/scene_tracer_concept.hpp"
#include "grtrace/trace/sky_continuation_kind.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>
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

/// The reflections render_frame uses for this tracer and camera: none for a tracer that does not name its metric
/// and scene types (MetricType, SceneType and metric()), or when options.mirror_symmetry is off.
template <SceneTracer Tracer>
FrameMirrors frame_mirrors_of(const Tracer& tracer, const Camera& camera, const RenderOptions& options) {
  if constexpr (requires {
                  typename Tracer::MetricType;
                  typename Tracer::SceneType;
                  { tracer.metric() } -> std::convertible_to<const typename Tracer::MetricType&>;
                }) {
    if (options.mirror_symmetry)
      return frame_mirrors<typename Tracer::MetricType, typename Tracer::SceneType>(tracer.metric(), camera);
  }
  return {};
}

/// The pixels render_frame traces for a tracer and camera: the top-left width x height block (the whole frame when
/// no mirror applies; half or a quarter of it, middle row and column of odd sizes included, when one does).
struct TracedRegion {
  FrameMirrors mirrors;
  int width = 0, height = 0;
  std::size_t pixel_count() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
};

template <SceneTracer Tracer>
TracedRegion traced_region(const Tracer& tracer, const Camera& camera, const RenderOptions& options) {
  TracedRegion r{frame_mirrors_of(tracer, camera, options), camera.width(), camera.height()};
  if (r.mirrors.meridian) r.width = (r.width + 1) / 2;
  if (r.mirrors.equator) r.height = (r.height + 1) / 2;
  return r;
}

/// Traces the pixels x0 <= col < x1, y0 <= row < y1 of `camera` with `tracer` into `out` (row by row, resized to the
/// tile), each outcome tracer.trace(camera.pixel_state(col, row)) bit for bit; a tracer that traces groups of rays
/// (TracesMany, trace/scene_tracer_concept.hpp) gets them in one call, through `states`. The one place where a frame
/// meets its tracer's type: render_frame calls it through a function pointer once per tile, so that the image loop
/// (shading, mirrors, counting) is compiled once per scene type rather than once per tracer.
template <SceneTracer Tracer>
void trace_tile(const Tracer& tracer, const Camera& camera, int x0, int y0, int x1, int y1,
                std::vector<GeodesicState>& states, std::vector<RayOutcome>& out) {
  const std::size_t count = static_cast<std::size_t>(x1 - x0) * static_cast<std::size_t>(y1 - y0);
  out.resize(count);
  if constexpr (TracesMany<Tracer>) {
    states.clear();
    for (int row = y0; row < y1; ++row)
      for (int col = x0; col < x1; ++col) states.push_back(camera.pixel_state(col, row));
    tracer.trace_many(states, out);
  } else {
    std::size_t i = 0;
    for (int row = y0; row < y1; ++row)
      for (int col = x0; col < x1; ++col) out[i++] = tracer.trace(camera.pixel_state(col, row));
  }
}

/// One thread's way to each pixel's outcome, the scratch object of render_image_by_orbits: outcomes traced
/// elsewhere beforehand (a GPU: gpu/gpu_frame.cuh) are read from there; otherwise each tile's pixels are traced
/// together when the tile begins (begin_tile, trace_tile above). Either way at(col, row) is
/// tracer.trace(camera.pixel_state(col, row)), bit for bit. The tracer's type is erased here (a function pointer,
/// called once per tile), so code that reads outcomes through TileOutcomes is compiled once for all tracers.
class TileOutcomes {
 public:
  /// traced: nothing, or the outcomes of the traced region's pixels, row by row, traced_width to a row.
  template <SceneTracer Tracer>
  TileOutcomes(const Camera& camera, const Tracer& tracer, const std::vector<RayOutcome>* traced = nullptr,
               int traced_width = 0)
      : camera_(&camera),
        tracer_(&tracer),
        trace_(+[](const void* t, const Camera& c, int x0, int y0, int x1, int y1, std::vector<GeodesicState>& states,
                   std::vector<RayOutcome>& out) {
          trace_tile(*static_cast<const Tracer*>(t), c, x0, y0, x1, y1, states, out);
        }),
        traced_(traced),
        traced_width_(traced_width) {}

  void begin_tile(int x0, int y0, int x1, int y1) {
    if (traced_) return;
    x0_ = x0;
    y0_ = y0;
    width_ = x1 - x0;
    trace_(tracer_, *camera_, x0, y0, x1, y1, states_, outcomes_);
  }

  /// The outcome of pixel (col, row) of the current tile.
  const RayOutcome& at(int col, int row) const {
    if (traced_)
      return (*traced_)[static_cast<std::size_t>(row) * static_cast<std::size_t>(traced_width_) +
                        static_cast<std::size_t>(col)];
    return outcomes_[static_cast<std::size_t>(row - y0_) * static_cast<std::size_t>(width_) +
                     static_cast<std::size_t>(col - x0_)];
  }

 private:
  using TraceTileFn = void (*)(const void*, const Camera&, int, int, int, int, std::vector<GeodesicState>&,
                               std::vector<RayOutcome>&);
  const Camera* camera_;
  const void* tracer_;
  TraceTileFn trace_;
  const std::vector<RayOutcome>* traced_;
  int traced_width_;
  int x0_ = 0, y0_ = 0, width_ = 0;
  std::vector<GeodesicState> states_;
  std::vector<RayOutcome> outcomes_;
};

namespace detail {

/// render_frame's image loop for one scene type: each traced pixel's outcome (from the thread's copy of `tiles`)
/// shaded into its own pixel and, in a mirror-symmetric frame, reflected into the pixels it mirrors; the directions
/// kept when asked. Returns the loop's statistics.
template <class SceneT>
RenderStats shade_frame(Image& image, const SceneT& scene, const TracedRegion& region, const TileOutcomes& tiles,
                        const RenderOptions& options, std::vector<SkyDirection>* directions) {
  const auto make_scratch = [&tiles] { return tiles; };  // each thread its own buffers
  const FrameMirrors& mirrors = region.mirrors;
  const int width = image.width(), height = image.height();
  const auto shade = [&](int col, int row, const RayOutcome& o) {
    if (directions) (*directions)[image.index(col, row)] = o.where;  // distinct pixels: no data race
    return scene.shade(o);
  };
  if (!mirrors.any()) {
    // Every pixel traced: one shade per pixel, the loop frames had before mirrors (the mirrored loop below
    // measured up to ~5 % slower on such frames, within the noise of one run).
    return render_image(
        image, make_scratch,
        [&](int col, int row, TileOutcomes& scratch) { return shade(col, row, scratch.at(col, row)); }, options);
  }
  return render_image_by_orbits(
      image, region.width, region.height, make_scratch,
      [&](int col, int row, TileOutcomes& scratch, const auto& emit) {
        RayOutcome o = scratch.at(col, row);
        emit(col, row, shade(col, row, o));
        const int mirror_col = width - 1 - col, mirror_row = height - 1 - row;
        const bool rows = mirrors.equator && mirror_row != row, cols = mirrors.meridian && mirror_col != col;
        // Reflected in place, at most one copy: building each image as a new outcome from a reflected copy cost
        // more than the reflections (a store-forwarding stall per copy, a third of this loop's time in perf).
        if (cols) {
          RayOutcome m = o;
          reflect_in_meridian(m, mirrors.camera_phi);
          emit(mirror_col, row, shade(mirror_col, row, m));
          if (rows) {
            reflect_in_equator(m);
            emit(mirror_col, mirror_row, shade(mirror_col, mirror_row, m));
          }
        }
        if (rows) {
          reflect_in_equator(o);
          emit(col, mirror_row, shade(col, mirror_row, o));
        }
      },
      options);
}

}  // namespace detail

/// traced: nothing (the tracer traces every pixel here), or the outcomes of traced_region's pixels traced
/// elsewhere (row by row; a GPU, gpu/gpu_frame.cuh), which are then shaded, mirrored and counted as if traced here.
template <SceneTracer Tracer>
Frame render_frame(const Camera& camera, const Tracer& tracer, const RenderOptions& options = {},
                   std::vector<SkyDirection>* directions = nullptr, const std::vector<RayOutcome>* traced = nullptr) {
  Frame frame{Image(camera.width(), camera.height()), {}};
  Image& image = frame.image;
  if (directions) directions->assign(image.pixel_count(), SkyDirection{RayOutcome::nan, RayOutcome::nan});
  const auto& scene = tracer.scene();
  // A mirror-symmetric frame traces the top-left half or quarter (the middle row and column of odd sizes
  // included) and reflects each outcome into the pixels it mirrors (render/mirror_symmetry.hpp).
  const TracedRegion region = traced_region(tracer, camera, options);
  if (traced && traced->size() != region.pixel_count())
    throw std::invalid_argument("render_frame: " + std::to_string(traced->size()) +
                                " outcomes given for a traced "
                                "region of " +
                                std::to_string(region.pixel_count()) + " pixels (traced_region)");
  frame.stats = detail::shade_frame(image, scene, region, TileOutcomes(camera, tracer, traced, region.width), options,
                                    directions);
  image.metadata["tracer"] = Tracer::name;
  if constexpr (requires { tracer.sky_continuation(); })
    image.metadata["sky_continuation"] = sky_continuation_name(tracer.sky_continuation());
  // A flat continuation's estimated error over this frame's escaped rays (trace/sky_continuation.hpp), and the sky
  // radius that would bring it down to the tracer's rtol.
  if constexpr (requires { tracer.flat_continuation_estimate(); }) {
    if (const auto e = tracer.flat_continuation_estimate()) {
      image.metadata["sky_continuation_error"] = exact_number(e->error);
      image.metadata["sky_continuation_impact"] = exact_number(e->impact);
      image.metadata["sky_radius_for_rtol"] = exact_number(e->radius_for_tolerance);
    }
  }
  image.metadata["mirrors"] = region.mirrors.names();
  std::string names;
  for (const std::string& n : scene.object_names()) names += (names.empty() ? "" : ",") + n;
  image.metadata["object_names"] = names;
  record_camera(image, camera);
  record_render_stats(image, frame.stats);
  return frame;
}

/// A frame whose rays are traced elsewhere (a GPU: gpu/gpu_frame.cuh): trace(width, height) returns the outcomes of
/// the camera's top-left width x height pixels (traced_region's), row by row, as tracer.trace would give them; the
/// tracer takes their statistics back (note_escaped, where it keeps any) and render_frame shades, mirrors, counts and
/// records them. The same Frame as render_frame(camera, tracer, options, directions) when trace is the tracer's own.
template <SceneTracer Tracer, class Trace>
Frame render_frame_traced_by(const Camera& camera, const Tracer& tracer, const Trace& trace,
                             const RenderOptions& options = {}, std::vector<SkyDirection>* directions = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  const TracedRegion region = traced_region(tracer, camera, options);
  const std::vector<RayOutcome> outcomes = trace(region.width, region.height);
  if constexpr (requires { tracer.note_escaped(outcomes); }) tracer.note_escaped(outcomes);
  Frame frame = render_frame(camera, tracer, options, directions, &outcomes);
  // The frame's time is the tracing's too, wherever it ran.
  RenderStats& stats = frame.stats;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.rays_per_second = stats.seconds > 0.0 ? static_cast<double>(stats.rays) / stats.seconds : 0.0;
  record_render_stats(frame.image, stats);
  return frame;
}

}  // namespace grtrace
