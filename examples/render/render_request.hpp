// examples/render/render_request.hpp
// What grtrace-render was asked to do (parsed and checked in grtrace_render.cpp before any work), and the frame
// rendered for it. The (metric x tableau x controller x scene) instantiations are split over translation units
// by metric so that they compile in parallel:
//   render_schwarzschild.cpp  schwarzschild (general, planar and symmetric-sky tracers), minkowski (straight lines)
//   render_kerr.cpp           kerr in Boyer-Lindquist and Kerr-Schild charts
//   render_rn_sds.cpp         Reissner-Nordstrom, Schwarzschild-de Sitter (automatic Christoffels)
//   render_wormhole_ef.cpp    Ellis wormhole, Schwarzschild in Eddington-Finkelstein coordinates
#pragma once

#include "command_line.hpp"

#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/render/flight.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/trace/method_dispatch.hpp"
#include "grtrace/trace/auto_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <functional>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <string>
#include <utility>
#include <vector>

namespace grtrace::render_tool {


/// --flight: one frame per camera along a path (render/flight.hpp); empty cameras: a single frame (Request::camera).
struct FlightRequest {
  std::string name;                ///< --flight: seed | circular | orbit | infall | csv ("" = one frame)
  std::vector<Camera> cameras;
  std::vector<double> tau;         ///< each frame's proper time on the path
  double dtau = 0.0;               ///< proper time between frames (csv: as given)
  std::function<bool(int)> skip;                              ///< frame i is already on disk, written whole
  std::function<void(int, Frame&, const TracerReport&)> sink;  ///< writes frame i (on the flight's writer thread)
  FlightStats* stats = nullptr;                              ///< receives the flight's statistics
};

struct Request {
  StandardSceneSpec scene;
  MetricSpec metric;
  std::string tableau, control, tracer, correction_name, out;
  TraceSettings settings;
  AngleCorrection correction = AngleCorrection::exact;
  std::optional<Camera> camera;
  int threads = 0;
  int table_nodes = grtrace::default_table_rays;
  bool error_map = false;
  bool mirror_symmetry = true;  ///< false: --no-mirrors (trace every pixel of a mirror-symmetric frame)
  FlightRequest flight;

  /// The render loop's options this request asks for (threads, mirror symmetry).
  RenderOptions render_options() const {
    RenderOptions options;
    options.threads = threads;
    options.mirror_symmetry = mirror_symmetry;
    return options;
  }
};

/// Sky direction of every pixel in double precision (the EXR channels are float), kept for --error-map.
using SkyDirections = std::vector<SkyDirection>;

/// The frame for any metric through the tracer asked for: --tracer general, or auto / planar: the fastest whose
/// assumptions hold (trace/auto_tracer.hpp; --tracer planar was refused up front where it does not apply). Every
/// (tableau, controller) pair and both preset scene types are instantiated for Metric. A scene whose objects do
/// not fit the metric's chart (the thin disk needs a spherical chart, or a Cartesian one that names its spherical
/// chart) is refused with a message.
/// With q.flight.cameras: every frame of the flight through q.flight's skip and sink, and nothing returned.
template <MetricPolicy Metric>
std::optional<Frame> render_general(const Request& q, const Metric& metric, SkyDirections* directions,
                                    TracerReport* table = nullptr) {
  const RenderOptions options = q.render_options();
  std::optional<Frame> frame;
  dispatch_method(q.tableau, q.control, [&]<class T, class C>() {
    with_standard_scene(q.scene, [&]<class Scene>(Scene scene) {
      if constexpr (scene_fits_metric<Metric, Scene>) {
        if (!q.flight.cameras.empty()) {
          auto sink = [&](int i, Frame&& f, const TracerReport& r) { q.flight.sink(i, f, r); };
          const FlightStats stats =
              q.tracer == "general"
                  ? render_flight(
                        q.flight.cameras,
                        [&](const Camera&, auto&& f) { f(make_general_tracer<T, C>(metric, q.settings, q.correction, scene)); },
                        q.flight.skip, sink, options)
                  : render_flight(q.flight.cameras,
                                  auto_tracer_per_camera<T, C>(metric, q.settings, q.correction, scene, q.table_nodes),
                                  q.flight.skip, sink, options);
          if (q.flight.stats) *q.flight.stats = stats;
          return;
        }
        auto draw = [&](const auto& tracer) {
          frame.emplace(render_frame(*q.camera, tracer, options, directions));
          if (table) *table = tracer_report(tracer);
        };
        if (q.tracer == "general") draw(make_general_tracer<T, C>(metric, q.settings, q.correction, scene));
        else with_auto_tracer<T, C>(metric, q.settings, *q.camera, q.correction, scene, q.table_nodes, draw);
      } else {
        throw tools::UsageError("--scene " + q.scene.name + " cannot be drawn in the " + std::string(Metric::name) +
                                " chart (its objects need a spherical chart, or a Cartesian one that names its "
                                "spherical chart)");
      }
    });
  });
  return frame;
}

/// render_general for the named metric when it is one of Metrics (this translation unit's share of the metrics).
template <class... Metrics>
std::optional<Frame> render_one_of(const Request& q, SkyDirections* directions, TracerReport* table = nullptr) {
  return with_named_metric(q.metric, [&](const auto& metric) -> std::optional<Frame> {
    using M = std::remove_cvref_t<decltype(metric)>;
    if constexpr ((std::is_same_v<M, Metrics> || ...)) return render_general(q, metric, directions, table);
    else throw std::logic_error("grtrace-render: metric " + q.metric.name + " dispatched to the wrong unit");
  });
}

// Each returns the frame, or nothing for a flight (q.flight.cameras: the frames went to q.flight.sink).
std::optional<Frame> render_schwarzschild(const Request& q, SkyDirections* directions, TracerReport& table);
std::optional<Frame> render_kerr(const Request& q, SkyDirections* directions);
std::optional<Frame> render_rn_sds(const Request& q, SkyDirections* directions, TracerReport& table);
std::optional<Frame> render_wormhole_ef(const Request& q, SkyDirections* directions);

}  // namespace grtrace::render_tool
