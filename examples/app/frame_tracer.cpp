// The frame tracers' front door: the checks, the dispatch by metric to the units that instantiate the tracers,
// and the frame and flight loops over a FrameTracer, compiled once (grtrace/app/frame_tracer.hpp).
#include "frame_tracers.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grtrace::app {

namespace {

/// The named metrics the planar table tracer draws: static, spherically symmetric, with a horizon (Reissner-Nordstrom's
/// |Q| < M, check_metric_spec, always gives it one).
bool planar_tracer_metric(const MetricSpec& metric) { return metric.name == "schwarzschild" || metric.name == "rn"; }

}  // namespace

void check_frame_request(const FrameRequest& q) {
  check_tool_method(q.tableau, q.control);
  if (q.device != "cpu" && q.device != "cuda")
    throw std::invalid_argument("grtrace_app: device '" + q.device + "' (choose_device gives cpu or cuda)");
  if (q.device == "cuda")
    if (const auto refusal = gpu_refusal(q)) throw std::invalid_argument("--device cuda: " + *refusal);
  // The older sky-and-horizon table is the library's (trace/symmetric_scene_tracer.hpp), no longer the tools': the
  // planar tracer draws every frame it drew, more accurately (tests/render/planar_tracer_test.cpp,
  // DrawsEveryFrameTheSymmetricTracerDrew).
  if (q.tracer == "symmetric")
    throw std::invalid_argument("--tracer symmetric is retired: the planar tracer draws every frame it drew, with a "
                                "smaller error; use --tracer planar (or auto, which picks it)");
  bool known_tracer = false;
  for (std::string_view name : kTracerNames) known_tracer = known_tracer || name == q.tracer;
  if (!known_tracer)
    throw std::invalid_argument("unknown --tracer '" + q.tracer + "'; choose auto, general or planar");
  if (q.tracer == "planar" && !planar_tracer_metric(q.metric))
    throw std::invalid_argument("--tracer planar needs a static spherically symmetric metric with a horizon "
                                "(--metric schwarzschild or rn); use general");
  if (q.tracer == "planar" && q.control == "fixed")
    throw std::invalid_argument("--tracer planar integrates its table in swept angle, where a fixed --step would mean "
                                "something else; use --control i, pi or doubling, or --tracer general");
}

std::optional<std::string> gpu_refusal(const FrameRequest& q) {
  if (q.tableau != kGpuTableau || q.control != kGpuControl)
    return "the GPU traces with --tableau " + std::string(kGpuTableau) + " --control " + std::string(kGpuControl) +
           " only; use those, or --device cpu for the other methods";
  if (q.tracer == "planar")
    return "--tracer planar is the CPU's table tracer (the GPU integrates every pixel); use --tracer general or auto, "
           "or --device cpu";
  if (q.metric.name == "minkowski") return "flat space is drawn with straight lines, on the CPU; use --device cpu";
  const GpuStatus& gpu = gpu_status();
  if (!gpu.built || !gpu.present) return gpu.why_not + "; use --device cpu";
  return std::nullopt;
}

bool cpu_table_tracer_draws(const FrameRequest& q) {
  return q.tracer == "planar" || (q.tracer == "auto" && planar_tracer_metric(q.metric));
}

std::string choose_device(std::string_view asked, const FrameRequest& q) {
  if (asked == "cpu") return "cpu";
  if (std::find(kDeviceNames.begin(), kDeviceNames.end(), asked) == kDeviceNames.end())
    throw std::invalid_argument("unknown --device '" + std::string(asked) + "'; choose auto, cpu or cuda");
  // Where auto keeps the CPU anyway, the driver is not asked (its start costs a tenth of a second where there is a
  // GPU, and nothing is gained).
  if (asked == "auto" && (!kAutoPicksGpu || cpu_table_tracer_draws(q))) return "cpu";
  const auto refusal = gpu_refusal(q);
  if (asked == "cuda" && refusal) throw std::invalid_argument("--device cuda: " + *refusal);
  return refusal ? "cpu" : "cuda";
}

std::string device_name(std::string_view device) { return device == "cuda" ? gpu_status().name : "cpu"; }

#if !defined(GRTRACE_APP_CUDA)
// A build without the CUDA backend (no CUDA compiler found, or GRTRACE_CUDA=OFF); with it, the backend's own unit
// (frame_tracers_gpu_exact.cu) asks the driver.
const GpuStatus& gpu_status() {
  static const GpuStatus status{false, false, "",
                                "this build has no CUDA backend (configured without a CUDA compiler, or with "
                                "-DGRTRACE_CUDA=OFF)"};
  return status;
}
#endif

void with_frame_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f) {
  check_frame_request(q);
  const std::string& metric = q.metric.name;
  if (metric == "schwarzschild" || metric == "minkowski") return with_schwarzschild_tracer(q, camera, f);
  if (metric == "kerr") {
    if (q.metric.chart == "ks") return with_kerr_schild_tracer(q, camera, f);
    return with_kerr_tracer(q, camera, f);
  }
  if (metric == "rn" || metric == "sds") return with_rn_sds_tracer(q, camera, f);
  if (metric == "wormhole" || metric == "schwarzschild-ef") return with_wormhole_ef_tracer(q, camera, f);
  check_metric_spec(q.metric);  // throws: names the metrics there are
  throw std::logic_error("grtrace_app: metric '" + metric + "' has no frame tracer");
}

Frame render_frame(const Camera& camera, const FrameTracer& tracer, const RenderOptions& options,
                   std::vector<SkyDirection>* directions) {
  return tracer.render(camera, options, directions);
}

TracerReport tracer_report(const FrameTracer& tracer) { return tracer.report(); }

Frame render_frame(const FrameRequest& q, const Camera& camera, const RenderOptions& options,
                   std::vector<SkyDirection>* directions, TracerReport* report) {
  std::optional<Frame> frame;
  with_frame_tracer(q, camera, [&](const FrameTracer& tracer) {
    frame.emplace(tracer.render(camera, options, directions));
    if (report) *report = tracer.report();
  });
  return std::move(*frame);
}

FlightStats render_flight(const FrameRequest& q, const std::vector<Camera>& cameras, const FlightSkip& skip,
                          const FlightSink& sink, const RenderOptions& options) {
  check_frame_request(q);
  return grtrace::render_flight(
      cameras,
      [&](const Camera& camera, auto&& f) {
        with_frame_tracer(q, camera, [&](const FrameTracer& tracer) { f(tracer); });
      },
      skip, [&](int i, Frame&& frame, const TracerReport& report) { sink(i, std::move(frame), report); }, options);
}

}  // namespace grtrace::app
