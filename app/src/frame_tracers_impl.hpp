// make_frame_renderer's definition (private to grtrace_app): included only by the units that instantiate it for
// their metrics (frame_tracers.hpp lists them), so that no other unit compiles a tracer.
#pragma once

#include "frame_tracers.hpp"
#include "gpu_tracers.hpp"
#include "grtrace/app/tool_methods.hpp"
#include "grtrace/trace/auto_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/straight_line.hpp"

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace grtrace::app {

/// The frame renderer of one concrete scene tracer, which it owns (built in place by a maker: the planar tracer can
/// be neither copied nor moved). Traces on the CPU or, for the tracers gpu_traces lists, on the GPU.
template <SceneTracer Tracer>
class FrameTracerOf final : public FrameRenderer {
 public:
  template <class Make>
  FrameTracerOf(const CheckedRequest& checked, const Make& make, bool on_gpu)
      : FrameRenderer(checked), tracer_(make()), on_gpu_(on_gpu) {}

  RenderResult render(const RenderControl& control) const override {
    const RenderOptions options = render_options(checked_, control);
    const Camera& cam = camera();
    FrameFacts facts;
    const long fallbacks_before = fallback_count();
    std::vector<SkyDirection> directions;
    std::vector<SkyDirection>* const where = checked_.request.error_map ? &directions : nullptr;
    const auto t0 = std::chrono::steady_clock::now();
    Frame frame = trace_frame(cam, options, where, facts);
    facts.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    facts.tracer = tracer_report(tracer_);
    facts.tracer.fallback_rays = fallback_count() - fallbacks_before;  // this frame's, if rendered again
    facts.mirrors = frame_mirrors_of(tracer_, cam, options).names();
    if constexpr (requires { tracer_.flat_continuation_estimate(); }) {
      if (const auto e = tracer_.flat_continuation_estimate())
        facts.continuation_error = ContinuationEstimate{e->error, e->impact, e->radius_for_tolerance};
    }
    return finish_render(checked_, std::move(frame), facts, setup_seconds_, directions);
  }

  void set_setup_seconds(double s) { setup_seconds_ = s; }

 private:
  long fallback_count() const {
    if constexpr (requires { tracer_.fallback_rays(); }) return tracer_.fallback_rays();
    else return 0;
  }

  Frame trace_frame(const Camera& cam, const RenderOptions& options, std::vector<SkyDirection>* directions,
                    FrameFacts& facts) const {
    if constexpr (kAppHasCuda && gpu_traces<Tracer>) {
      if (on_gpu_) {
        GpuSeconds seconds;
        Frame frame = render_frame_traced_by(
            cam, tracer_, [&](int width, int height) { return trace_on_gpu(cam, tracer_, width, height, &seconds); },
            options, directions);
        facts.device = "cuda";
        facts.gpu_trace_seconds = seconds.kernel;
        facts.gpu_seconds = seconds.total;
        return frame;
      }
    }
    if (on_gpu_) throw std::logic_error("grtrace_app: a tracer the GPU does not run was sent to the GPU");
    return grtrace::render_frame(cam, tracer_, options, directions);
  }

  Tracer tracer_;
  bool on_gpu_;
};

/// The renderer of the tracer `make` builds, its build timed (the planar tracer's table is the frame's setup).
template <class Make>
std::unique_ptr<FrameRenderer> own_tracer(const CheckedRequest& checked, const Make& make, bool on_gpu = false) {
  using Tracer = std::remove_cvref_t<decltype(make())>;
  const auto t0 = std::chrono::steady_clock::now();
  auto renderer = std::make_unique<FrameTracerOf<Tracer>>(checked, make, on_gpu);
  renderer->set_setup_seconds(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  return renderer;
}

template <MetricPolicy M>
std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest& checked, const M& metric) {
  const RenderRequest& q = checked.request;
  std::unique_ptr<FrameRenderer> out;
  if constexpr (FlatMetric<M>) {  // flat space: straight lines, whatever method was named
    with_standard_scene(checked.scene, [&](auto scene) {
      out = own_tracer(checked, [&] {
        return StraightLineTracer(metric, checked.settings.escape_radius, checked.correction, scene);
      });
    });
    return out;
  } else {
    const bool known = dispatch_tool_method(q.method.tableau, q.method.control, [&]<class T, class C>() {
      with_standard_scene(checked.scene, [&]<class Scene>(Scene scene) {
        if constexpr (scene_fits_metric<M, Scene>) {
          // On the GPU (device cuda, checked: the GPU's method, no planar tracer) auto means kerr-mino where it
          // applies and general otherwise.
          const bool on_gpu = q.device == "cuda";
          const bool mino = q.tracer == "kerr-mino" || (on_gpu && kerr_mino_tracer_applies<M, Scene, C>);
          if (q.tracer == "general" || (on_gpu && !kerr_mino_tracer_applies<M, Scene, C>)) {
            out = own_tracer(
                checked, [&] { return make_general_tracer<T, C>(metric, checked.settings, checked.correction, scene); },
                on_gpu);
          } else if (mino && kerr_closed_form_tracer_applies<M, Scene, C>) {
            // kerr-mino asked for (or on the GPU) where auto's choice is the closed form; elsewhere auto's choice
            // below is kerr-mino itself where it applies.
            if constexpr (kerr_mino_tracer_applies<M, Scene, C>) {
              out = own_tracer(
                  checked,
                  [&] { return make_kerr_mino_tracer<T, C>(metric, checked.settings, checked.correction, scene); },
                  on_gpu);
            }
          } else {
            // check_tracer refused a reduced tracer the metric or control cannot have; this is the scene's part.
            if ((q.tracer == "kerr-mino" && !kerr_mino_tracer_applies<M, Scene, C>) ||
                (q.tracer == "kerr-closed-form" && !kerr_closed_form_tracer_applies<M, Scene, C>) ||
                (q.tracer == "planar" && !planar_tracer_applies<M, Scene, C>))
              throw RequestError("--tracer " + q.tracer + " cannot draw --scene " + q.scene + "; use auto or general");
            with_auto_tracer_maker<T, C>(metric, checked.settings, checked.camera, checked.correction, scene,
                                         q.table_rays,
                                         [&](const auto& make) { out = own_tracer(checked, make, on_gpu); });
          }
        } else {
          throw RequestError("--scene " + q.scene + " cannot be drawn in the " + std::string(M::name) +
                             " chart (its objects need a spherical chart, or a Cartesian one that names its "
                             "spherical chart)");
        }
      });
    });
    if (!known) check_tool_method(q.method.tableau, q.method.control);  // throws: says what to choose
    return out;
  }
}

}  // namespace grtrace::app
