// examples/render/render_request.hpp
// What grtrace-render was asked to do (parsed and checked in grtrace_render.cpp before any work). The frames are
// drawn by the application layer (grtrace/app/frame_tracer.hpp), where every tracer the tool offers is compiled
// once; this program instantiates none.
#pragma once

#include "command_line.hpp"

#include "grtrace/app/frame_tracer.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/render/flight.hpp"
#include "grtrace/render/flight_files.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"

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
  std::optional<FlightFrameRange> range;  ///< --frame-range: only these frames (nothing: all)
  std::function<bool(int)> skip;                              ///< frame i is already on disk, written whole
  std::function<void(int, Frame&, const TracerReport&)> sink;  ///< writes frame i (on the flight's writer thread)
  FlightStats* stats = nullptr;                              ///< receives the flight's statistics
};

struct Request {
  StandardSceneSpec scene;
  MetricSpec metric;
  std::string tableau, control, tracer, correction_name, out;
  std::string device = "cpu";  ///< cpu or cuda (app::choose_device's answer to --device)
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

/// What the application layer draws the frames with (grtrace/app/frame_tracer.hpp).
inline app::FrameRequest frame_request(const Request& q) {
  app::FrameRequest f;
  f.metric = q.metric;
  f.scene = q.scene;
  f.tableau = q.tableau;
  f.control = q.control;
  f.tracer = q.tracer;
  f.settings = q.settings;
  f.correction = q.correction;
  f.table_rays = q.table_nodes;
  f.device = q.device;
  return f;
}

}  // namespace grtrace::render_tool
