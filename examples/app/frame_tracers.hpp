// The application layer's instantiations (private to grtrace_app): one function per group of metrics, each in its
// own translation unit so that they compile in parallel (with the CUDA backend, gpu_tracers.hpp):
//   frame_tracers_schwarzschild.cpp  schwarzschild (auto/planar, general), minkowski (straight lines)
//   frame_tracers_kerr.cpp           kerr in Boyer-Lindquist coordinates (auto/kerr-mino, general)
//   frame_tracers_kerr_schild.cpp    kerr in Cartesian Kerr-Schild coordinates (general)
//   frame_tracers_rn_sds.cpp         Reissner-Nordstrom, Schwarzschild-de Sitter (auto/planar, general)
//   frame_tracers_wormhole_ef.cpp    Ellis wormhole, Schwarzschild in Eddington-Finkelstein coordinates (general)
#pragma once

#include "grtrace/app/frame_tracer.hpp"
#include "grtrace/app/tool_methods.hpp"
#include "gpu_tracers.hpp"
#include "grtrace/trace/auto_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <stdexcept>
#include <string>
#include <type_traits>

namespace grtrace::app {

/// The FrameTracer of a concrete scene tracer, by reference (the tracer lives in with_frame_tracer's frame), tracing
/// on the CPU or, for the tracers gpu_traces lists, on the GPU; the header says which ("device").
template <SceneTracer Tracer>
class FrameTracerOf final : public FrameTracer {
 public:
  FrameTracerOf(const Tracer& tracer, bool on_gpu) : tracer_(&tracer), on_gpu_(on_gpu) {}
  Frame render(const Camera& camera, const RenderOptions& options,
               std::vector<SkyDirection>* directions) const override {
    if constexpr (kAppHasCuda && gpu_traces<Tracer>) {
      if (on_gpu_) {
        GpuSeconds seconds;
        Frame frame = render_frame_traced_by(
            camera, *tracer_,
            [&](int width, int height) { return trace_on_gpu(camera, *tracer_, width, height, &seconds); },
            options, directions);
        frame.image.metadata["device"] = device_name("cuda");
        frame.image.metadata["gpu_trace_seconds"] = exact_number(seconds.kernel);
        frame.image.metadata["gpu_seconds"] = exact_number(seconds.total);
        return frame;
      }
    }
    if (on_gpu_) throw std::logic_error("grtrace_app: a tracer the GPU does not run was sent to the GPU");
    Frame frame = grtrace::render_frame(camera, *tracer_, options, directions);
    frame.image.metadata["device"] = device_name("cpu");
    return frame;
  }
  TracerReport report() const override { return grtrace::tracer_report(*tracer_); }

 private:
  const Tracer* tracer_;
  bool on_gpu_;
};

/// Calls f with the concrete tracer wrapped.
template <class Tracer>
void hand_over(const Tracer& tracer, const FrameTracerUser& f, bool on_gpu = false) {
  f(FrameTracerOf<Tracer>(tracer, on_gpu));
}

/// The tracer q names for Metric (auto or general) with every offered method and both preset scene types, on the
/// device q names.
template <MetricPolicy Metric>
void with_integrating_tracer(const FrameRequest& q, const Metric& metric, const Camera& camera,
                             const FrameTracerUser& f) {
  const bool known = dispatch_tool_method(q.tableau, q.control, [&]<class T, class C>() {
    with_standard_scene(q.scene, [&]<class Scene>(Scene scene) {
      if constexpr (scene_fits_metric<Metric, Scene>) {
        // On the GPU (device cuda, checked by check_frame_request: the GPU's method, no planar tracer) auto means
        // kerr-mino where it applies and general otherwise; the same call sites as the CPU's, so no tracer is
        // instantiated twice (FrameTracerOf sends the frame to the GPU's kernels, gpu_tracers.hpp).
        const bool on_gpu = q.device == "cuda";
        const auto call = [&](const auto& tracer) { hand_over(tracer, f, on_gpu); };
        if (q.tracer == "general" || (on_gpu && !kerr_mino_tracer_applies<Metric, Scene, C>))
          call(make_general_tracer<T, C>(metric, q.settings, q.correction, scene));
        else with_auto_tracer<T, C>(metric, q.settings, camera, q.correction, scene, q.table_rays, call);
      } else {
        throw std::invalid_argument("--scene " + q.scene.name + " cannot be drawn in the " +
                                    std::string(Metric::name) +
                                    " chart (its objects need a spherical chart, or a Cartesian one that names its "
                                    "spherical chart)");
      }
    });
  });
  if (!known) check_tool_method(q.tableau, q.control);  // throws: says what to choose
}

void with_schwarzschild_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f);
void with_kerr_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f);
void with_kerr_schild_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f);
void with_rn_sds_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f);
void with_wormhole_ef_tracer(const FrameRequest& q, const Camera& camera, const FrameTracerUser& f);

/// Calls f(metric) for the named metric when it is one of Metrics (the calling unit's share).
template <class... Metrics, class F>
void with_metric_of(const MetricSpec& spec, F&& f) {
  with_named_metric(spec, [&](const auto& metric) {
    using M = std::remove_cvref_t<decltype(metric)>;
    if constexpr ((std::is_same_v<M, Metrics> || ...)) f(metric);
    else throw std::logic_error("grtrace_app: metric " + spec.name + " dispatched to the wrong unit");
  });
}

}  // namespace grtrace::app
