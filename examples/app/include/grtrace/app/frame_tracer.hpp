// grtrace/app/frame_tracer.hpp
// The rendering tools' frames, compiled once: names become types here and nowhere else. A FrameRequest names the
// metric, the preset scene, the method (grtrace/app/tool_methods.hpp), the tracer and its settings; the
// application layer (the static library grtrace_app that grtrace-render, grtrace-view and their tests link) builds
// the one concrete scene tracer it names and hands it over as a FrameTracer: one virtual call per frame, below which
// everything (the pixel loop, shading, mirror images, the trace loop) is the concrete tracer's own inlined code.
//
//   app::FrameRequest q;                    // the seed's main frame, rkf78 + I, tracer auto
//   const Camera camera = ...;              // observer/camera_spec.hpp
//   Frame frame = app::render_frame(q, camera);
//
// Takes:   a FrameRequest (checked by check_frame_request: what can draw what is the library's answer, not a string
//          compare in a tool), a camera; for flights the cameras and the skip/sink of render/flight.hpp.
// Returns: the Frame render_frame (render/frame.hpp) returns for the concrete tracer, bit for bit; the tracer's
//          report (trace/tracer_report.hpp).
// Why the boundary is the frame and not the tile: the frame loop's per-pixel work (shading, mirror reflections)
//          stays inlined into each tracer's own loop, so a frame costs what it cost when every tool instantiated its
//          tracers itself; the compile-time saving comes from instantiating each tracer once, in one place.
#pragma once

#include "grtrace/core/sky_direction.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/render/flight.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/trace/critical_angle_grid.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/tracer_report.hpp"

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace grtrace::app {

/// What a frame is drawn with: everything the tools choose by name.
struct FrameRequest {
  MetricSpec metric;                 ///< metric/named_metrics.hpp
  StandardSceneSpec scene;           ///< scene/standard_scenes.hpp
  std::string tableau = "rkf78";     ///< with control: one of kToolMethods
  std::string control = "i";
  /// auto (the fastest tracer whose assumptions hold: trace/auto_tracer.hpp), general (every pixel integrated),
  /// planar (auto's choice around a static spherical hole, asked for by name). Flat space (minkowski) always draws
  /// straight lines.
  std::string tracer = "auto";
  TraceSettings settings;
  AngleCorrection correction = AngleCorrection::exact;
  int table_rays = grtrace::default_table_rays;  ///< planar tracer: table rays per side
  /// Where the rays are traced: cpu, or cuda (the GPU backend: every pixel integrated, the default method only;
  /// tracer auto means kerr-mino for Kerr in Boyer-Lindquist coordinates and general otherwise). Tools turn the
  /// user's auto into one of them with choose_device.
  std::string device = "cpu";
};

inline constexpr std::array<std::string_view, 3> kDeviceNames = {"auto", "cpu", "cuda"};

/// The GPU this build can trace on: whether the CUDA backend was compiled in, and the first CUDA device's name or
/// why there is none. Asked once per process.
struct GpuStatus {
  bool built = false;
  bool present = false;
  std::string name;     ///< e.g. "NVIDIA H100 80GB HBM3"
  std::string why_not;  ///< when not present
};
const GpuStatus& gpu_status();

/// Why the GPU cannot draw the request (a method, tracer or metric it does not run, then no backend or no device),
/// in words that say what to use instead; nothing when it can.
std::optional<std::string> gpu_refusal(const FrameRequest& q);

/// Whether auto may pick the GPU: the CUDA backend passes its device checks (tests/gpu, cmake/gpu-check.sh on an
/// H200: the same statuses, redshifts and sky directions as the CPU's trace; docs/benchmarks.md, "GPU").
inline constexpr bool kAutoPicksGpu = true;

/// True when the CPU draws the request with its table tracer (--tracer auto on a static spherical metric with a
/// horizon, Schwarzschild or Reissner-Nordstrom, whose preset scenes lie in the equatorial plane): one table of rays
/// for the whole frame, faster on the CPU than any GPU integrating every pixel (15 ms against 18 ms of kernel alone
/// for the main frame, docs/benchmarks.md "GPU"), so auto keeps it there.
bool cpu_table_tracer_draws(const FrameRequest& q);

/// The device the request runs on when the user asks for `asked`: cpu; cuda (std::invalid_argument saying what to
/// change when gpu_refusal refuses); auto: cuda where kAutoPicksGpu, the CPU's table tracer does not draw it and
/// gpu_refusal has nothing against it, else cpu. Refuses names outside kDeviceNames.
std::string choose_device(std::string_view asked, const FrameRequest& q);

/// The name a frame's header and the JSON line give the device (cpu or cuda): "cpu", or the GPU's model.
std::string device_name(std::string_view device);

inline constexpr std::array<std::string_view, 3> kTracerNames = {"auto", "general", "planar"};

/// Refuses (std::invalid_argument, saying what to change) a request whose tracer cannot draw its metric, scene or
/// method, or whose method is not offered (check_tool_method). Checked before any work.
void check_frame_request(const FrameRequest& q);

/// The scene tracer a request names, as the frame loop sees it. Lives only inside a with_frame_tracer call.
class FrameTracer {
 public:
  virtual ~FrameTracer() = default;
  /// render_frame (render/frame.hpp) with the concrete tracer.
  virtual Frame render(const Camera& camera, const RenderOptions& options,
                       std::vector<SkyDirection>* directions) const = 0;
  /// tracer_report (trace/tracer_report.hpp) of the concrete tracer: its name, table and fallback counts.
  virtual TracerReport report() const = 0;

 protected:
  FrameTracer() = default;
  FrameTracer(const FrameTracer&) = default;
  FrameTracer& operator=(const FrameTracer&) = default;
};

/// render_frame and tracer_report for a FrameTracer: what render_flight (render/flight.hpp) calls on it.
Frame render_frame(const Camera& camera, const FrameTracer& tracer, const RenderOptions& options = {},
                   std::vector<SkyDirection>* directions = nullptr);
TracerReport tracer_report(const FrameTracer& tracer);

using FrameTracerUser = std::function<void(const FrameTracer&)>;

/// Builds the tracer the request names for this camera (the planar tracer's table covers the camera's pixels) and
/// calls f once with it. Throws std::invalid_argument for a request check_frame_request refuses.
void with_frame_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f);

/// One frame: with_frame_tracer + render_frame; *report (if given) receives the tracer's report.
Frame render_frame(const FrameRequest& q, const Camera& camera, const RenderOptions& options = {},
                   std::vector<SkyDirection>* directions = nullptr, TracerReport* report = nullptr);

using FlightSkip = std::function<bool(int)>;
using FlightSink = std::function<void(int, Frame&&, const TracerReport&)>;

/// A flight (render/flight.hpp) drawn with the request's tracer, built per camera.
FlightStats render_flight(const FrameRequest& q, const std::vector<Camera>& cameras, const FlightSkip& skip,
                          const FlightSink& sink, const RenderOptions& options = {});

}  // namespace grtrace::app
