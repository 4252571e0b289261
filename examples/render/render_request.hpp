// examples/render/render_request.hpp
// What grtrace-render was asked to do (parsed and checked in grtrace_render.cpp before any work), and the frame
// rendered for it. The (metric x tableau x controller x scene) instantiations are split over translation units
// by metric so that they compile in parallel:
//   render_schwarzschild.cpp  schwarzschild (general and symmetric-sky tracers), minkowski (straight lines)
//   render_kerr.cpp           kerr in Boyer-Lindquist and Kerr-Schild charts
//   render_rn_sds.cpp         Reissner-Nordstrom, Schwarzschild-de Sitter (automatic Christoffels)
//   render_wormhole_ef.cpp    Ellis wormhole, Schwarzschild in Eddington-Finkelstein coordinates
#pragma once

#include "command_line.hpp"

#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/trace/method_dispatch.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <optional>
#include <stdexcept>
#include <type_traits>
#include <string>
#include <utility>
#include <vector>

namespace grtrace::render_tool {

struct Request {
  StandardSceneSpec scene;
  MetricSpec metric;
  std::string tableau, control, tracer, correction_name, out;
  TraceSettings settings;
  AngleCorrection correction = AngleCorrection::exact;
  std::optional<Camera> camera;
  int threads = 0;
  int table_nodes = 1024;
  bool error_map = false;
};

struct TableStats {
  long rays = 0, steps = 0;
};

/// Sky direction of every pixel in double precision (the EXR channels are float), kept for --error-map.
using SkyDirections = std::vector<SkyDirection>;

/// The frame through the general scene tracer for any metric: every (tableau, controller) pair and both preset
/// scene types are instantiated for Metric. A scene whose objects do not fit the metric's chart (the thin disk
/// needs a spherical chart) is refused with a message.
template <MetricPolicy Metric>
Frame render_general(const Request& q, const Metric& metric, SkyDirections* directions) {
  RenderOptions options;
  options.threads = q.threads;
  std::optional<Frame> frame;
  dispatch_method(q.tableau, q.control, [&]<class T, class C>() {
    with_standard_scene(q.scene, [&]<class Scene>(Scene scene) {
      if constexpr (scene_fits_metric<Metric, Scene>) {
        frame.emplace(render_frame(*q.camera, make_general_tracer<T, C>(metric, q.settings, q.correction, scene),
                                   options, directions));
      } else {
        throw tools::UsageError("--scene " + q.scene.name + " cannot be drawn in the " + std::string(Metric::name) +
                                " chart (the thin disk needs a spherical chart: use --chart bl)");
      }
    });
  });
  return std::move(*frame);
}

/// render_general for the named metric when it is one of Metrics (this translation unit's share of the metrics).
template <class... Metrics>
Frame render_one_of(const Request& q, SkyDirections* directions) {
  return with_named_metric(q.metric, [&](const auto& metric) -> Frame {
    using M = std::remove_cvref_t<decltype(metric)>;
    if constexpr ((std::is_same_v<M, Metrics> || ...)) return render_general(q, metric, directions);
    else throw std::logic_error("grtrace-render: metric " + q.metric.name + " dispatched to the wrong unit");
  });
}

Frame render_schwarzschild(const Request& q, SkyDirections* directions, TableStats& table);
Frame render_kerr(const Request& q, SkyDirections* directions);
Frame render_rn_sds(const Request& q, SkyDirections* directions);
Frame render_wormhole_ef(const Request& q, SkyDirections* directions);

}  // namespace grtrace::render_tool
