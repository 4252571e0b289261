// grtrace/render/flight.hpp
// A camera flight: one frame per camera along a path, through the same pixel pipeline as a single frame
// (render/frame.hpp), with one progress bar over the whole sequence.
//
//   const TimelikeStart start = seed_orbit_start(metric);                              // observer/timelike_start.hpp
//   const Worldline path = sample_worldline(metric, start, dtau, 300);                  // observer/worldline.hpp
//   const auto cameras = flight_cameras(metric, path, CameraView{...});
//   render_flight(cameras, auto_tracer_per_camera<Tsitouras54, IController>(metric, settings, correction, scene),
//                 [](int) { return false; },                                            // nothing to skip
//                 [](int i, Frame&& frame, const TracerReport& tracer) { /* write frame i */ });
//
// Takes:   the cameras; with_tracer(camera, f), which builds the scene tracer for a camera and calls f(tracer)
//          once (auto_tracer_per_camera: the fastest exact tracer, trace/auto_tracer.hpp, per frame; the planar
//          tracer's table depends on the camera's radius and angle range, so it is built per frame); skip(i):
//          true for a frame already on disk (resumed flights: render/flight_files.hpp); sink(i, frame, report):
//          receives each rendered frame, in order, with what its tracer reported (trace/tracer_report.hpp).
//          The sink runs on a thread of its own while the next frame is traced (writing a frame, mostly EXR and
//          PNG compression, costs about half as much as tracing it), one call at a time; an exception it throws
//          stops the flight and propagates from render_flight.
// Returns: FlightStats: frames rendered and skipped, rays and their statuses summed over the rendered frames.
// Guarantees: frame i is exactly render_frame(cameras[i], tracer) for the tracer with_tracer builds (the flight
//          adds no state between frames: tests/render/flight_test.cpp compares bit for bit).
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/worldline.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/render/progress_bar.hpp"
#include "grtrace/trace/auto_tracer.hpp"
#include "grtrace/trace/tracer_report.hpp"

#include <array>
#include <optional>
#include <chrono>
#include <exception>
#include <thread>
#include <utility>
#include <vector>

namespace grtrace {

struct FlightStats {
  int frames = 0;    ///< cameras in the flight
  int rendered = 0;  ///< frames traced in this call
  int skipped = 0;   ///< frames skip() declared done
  long rays = 0;     ///< pixels rendered (rendered frames only)
  long traced_rays = 0;  ///< of those, pixels traced (the rest reflected: render/mirror_symmetry.hpp)
  std::array<long, kRayStatusCount> status_counts{};
  double seconds = 0.0;  ///< wall time of the whole call, the sink's included
  long count(RayStatus s) const { return status_counts[static_cast<std::size_t>(s)]; }
};

/// One camera per sample of the worldline, each pointed by `view` (make_moving_camera: its look rule).
template <MetricPolicy M>
std::vector<Camera> flight_cameras(const M& metric, const Worldline& path, const CameraView& view) {
  std::vector<Camera> cameras;
  cameras.reserve(path.samples.size());
  for (const WorldlineSample& s : path.samples) cameras.push_back(make_moving_camera(metric, s.x, s.u, view));
  return cameras;
}

/// with_auto_tracer (trace/auto_tracer.hpp) as a with_tracer for render_flight. Keeps references to the metric
/// and the scene: both must outlive the flight.
template <ExplicitTableau T, StepController C, MetricPolicy M, class SceneT>
auto auto_tracer_per_camera(const M& metric, const TraceSettings& settings, AngleCorrection correction,
                            const SceneT& scene, int table_rays) {
  return [&metric, &scene, settings, correction, table_rays](const Camera& camera, auto&& f) {
    with_auto_tracer<T, C>(metric, settings, camera, correction, scene, table_rays, f);
  };
}

/// The flight loop for any kind of frame: render_one(camera, options) draws one camera's frame (any type R, moved
/// to the sink), stats_of(r) gives its RenderStats (summed into the FlightStats), sink(i, r) receives it on the
/// writer thread while the next frame is traced. What render_flight runs, for callers whose frames carry more than a
/// Frame (the application library's reports).
template <class RenderOne, class StatsOf, class Skip, class Sink>
FlightStats render_frames(const std::vector<Camera>& cameras, RenderOne&& render_one, StatsOf&& stats_of, Skip&& skip,
                          Sink&& sink, RenderOptions options = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  FlightStats stats;
  stats.frames = static_cast<int>(cameras.size());
  std::vector<bool> to_render(cameras.size());
  long total_pixels = 0;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    to_render[i] = !skip(static_cast<int>(i));
    if (to_render[i]) total_pixels += static_cast<long>(cameras[i].width()) * cameras[i].height();
    else ++stats.skipped;
  }
  ProgressBar own_bar(options.shared_progress ? 0L : total_pixels, "flight",
                      options.shared_progress ? ProgressMode::never : options.progress);
  if (!options.shared_progress) options.shared_progress = &own_bar;
  // One frame is written (by the sink, on `writer`) while the next is traced.
  std::thread writer;
  std::exception_ptr write_error;
  auto wait_for_writer = [&] {
    if (writer.joinable()) writer.join();
    if (write_error) std::rethrow_exception(std::exchange(write_error, nullptr));
  };
  try {
    for (std::size_t i = 0; i < cameras.size(); ++i) {
      if (!to_render[i]) continue;
      auto frame = render_one(cameras[i], std::as_const(options));
      const RenderStats& frame_stats = stats_of(std::as_const(frame));
      ++stats.rendered;
      stats.rays += frame_stats.rays;
      stats.traced_rays += frame_stats.traced_rays;
      for (std::size_t s = 0; s < kRayStatusCount; ++s) stats.status_counts[s] += frame_stats.status_counts[s];
      wait_for_writer();
      writer = std::thread([&sink, &write_error, index = static_cast<int>(i), f = std::move(frame)]() mutable {
        try {
          sink(index, std::move(f));
        } catch (...) {
          write_error = std::current_exception();
        }
      });
    }
    wait_for_writer();
  } catch (...) {
    if (writer.joinable()) writer.join();  // never leave a running thread behind (std::terminate)
    throw;
  }
  own_bar.finish();
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return stats;
}

template <class WithTracer, class Skip, class Sink>
FlightStats render_flight(const std::vector<Camera>& cameras, WithTracer&& with_tracer, Skip&& skip, Sink&& sink,
                          RenderOptions options = {}) {
  struct TracedFrame {
    Frame frame;
    TracerReport report;
  };
  return render_frames(
      cameras,
      [&](const Camera& camera, const RenderOptions& o) {
        std::optional<TracedFrame> traced;
        with_tracer(camera, [&](const auto& tracer) {
          traced.emplace(TracedFrame{render_frame(camera, tracer, o), tracer_report(tracer)});
        });
        return std::move(*traced);
      },
      [](const TracedFrame& t) -> const RenderStats& { return t.frame.stats; }, skip,
      [&](int i, TracedFrame&& t) { sink(i, std::move(t.frame), std::as_const(t.report)); }, std::move(options));
}

}  // namespace grtrace
