// Frames of emitting media, with one declared method (kMediaMethod: Verner 6(5), whose error estimate sees the
// light's integral, which Fehlberg 7(8)'s, the tools' default, does not: trace/emission_system.hpp), on the CPU:
//   --scene accretion: SphericalAccretion (medium/spherical_accretion.hpp) onto a Schwarzschild hole (one metric:
//     each is another instantiation of the tracers; check_request refuses the others): one table of rays
//     (SphericalMediumTracer: tracer auto or planar) or every pixel integrated (GeneralMediumTracer: general);
//   --scene torus: PolishDoughnut (medium/polish_doughnut.hpp) around Kerr in Boyer-Lindquist coordinates, every
//     pixel integrated on Kerr's separated equations in Mino time (KerrMinoMediumTracer), geometric units;
//   --scene riaf: RiafFlow (medium/riaf.hpp) around Kerr in Boyer-Lindquist coordinates, every pixel integrated
//     as the torus's, its intensity in cgs, its flux in janskys and its pixel in microarcseconds at the source's
//     distance.
// Every pixel integrated splits the intensity by image order (the table does not: trace/medium_tracers.hpp);
// and the frames of the thin disk drawn by its light (--scene disk --disk-light: render/disk_light_frame.hpp, every
// ray's crossings in closed form), whose intensity is split by image order.
#include "frame_tracers.hpp"
#include "grtrace/core/physical_units.hpp"
#include "grtrace/medium/polish_doughnut.hpp"
#include "grtrace/medium/riaf.hpp"
#include "grtrace/medium/spherical_accretion.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/render/disk_light_frame.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/render/scale_bar.hpp"
#include "grtrace/spectra/kerr_disk_map.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

namespace grtrace::app {

namespace {

static_assert(kToolMethods[kMediaMethod].tableau == Verner65::name &&
                  kToolMethods[kMediaMethod].control == IController::name,
              "medium_frames.cpp instantiates media with Verner65 + IController: keep kMediaMethod pointing at it");

/// The renderer of one medium tracer, which it owns (built in place: the table tracer holds an atomic).
template <class Tracer>
class MediumFrameRenderer final : public FrameRenderer {
 public:
  template <class Make>
  MediumFrameRenderer(const CheckedRequest& checked, const Make& make) : FrameRenderer(checked), tracer_(make()) {}

  RenderResult render(const RenderControl& control) const override {
    RenderOptions options = render_options(checked_, control);
    options.mirror_symmetry = false;  // render_medium_frame traces every pixel (a look-up each with the table)
    FrameFacts facts;
    long fallbacks_before = 0;  // the general tracer has none: it is the fallback
    if constexpr (requires { tracer_.fallback_rays(); }) fallbacks_before = tracer_.fallback_rays();
    const auto t0 = std::chrono::steady_clock::now();
    Frame frame = render_medium_frame(camera(), tracer_, options);
    facts.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    facts.tracer.name = Tracer::name;
    if constexpr (requires { tracer_.table_rays(); }) {
      facts.tracer.table_rays = tracer_.table_rays();
      facts.tracer.table_steps = tracer_.table_steps();
    }
    if constexpr (requires { tracer_.fallback_rays(); })
      facts.tracer.fallback_rays = tracer_.fallback_rays() - fallbacks_before;
    facts.flux = medium_frame_flux(camera(), frame.image);
    if constexpr (splits_by_order<Tracer>()) facts.flux_by_order = flux_by_order(camera(), frame.image);
    if (scale_) {  // physical units: the camera far away (check_request), its angles scaled by r / D
      const double r_cam = checked_.request.camera.r;
      facts.flux_jy = scale_->janskys(*facts.flux, r_cam);
      facts.microarcseconds_per_pixel = scale_->microarcseconds_at_telescope(camera_pixel_pitch(camera()), r_cam);
      draw_scale_bar(frame.image, *facts.microarcseconds_per_pixel);  // into the picture (R, G, B) only
    }
    return finish_render(checked_, std::move(frame), facts, setup_seconds_, {});
  }

  void set_setup_seconds(double s) { setup_seconds_ = s; }
  void set_scale(const SourceScale& s) { scale_ = s; }

 private:
  Tracer tracer_;
  std::optional<SourceScale> scale_;
};

template <class Make>
std::unique_ptr<FrameRenderer> own_medium_tracer(const CheckedRequest& checked, const Make& make,
                                                 std::optional<SourceScale> scale = {}) {
  using Tracer = std::remove_cvref_t<decltype(make())>;
  const auto t0 = std::chrono::steady_clock::now();
  auto renderer = std::make_unique<MediumFrameRenderer<Tracer>>(checked, make);
  renderer->set_setup_seconds(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  if (scale) renderer->set_scale(*scale);
  return renderer;
}

/// The renderer of a disk drawn by its light: the disk's rays and light, made once.
class DiskLightRenderer final : public FrameRenderer {
 public:
  explicit DiskLightRenderer(const CheckedRequest& checked)
      : FrameRenderer(checked),
        rays_(disk_light_rays(checked.request, checked.scene.disk, checked.settings.escape_radius)),
        light_(disk_light_of(checked.request)) {}

  RenderResult render(const RenderControl& control) const override {
    RenderOptions options = render_options(checked_, control);
    options.mirror_symmetry = false;  // render_disk_light_frame traces every pixel
    FrameFacts facts;
    const auto t0 = std::chrono::steady_clock::now();
    DiskLightFrame f = render_disk_light_frame(camera(), rays_, light_, options);
    facts.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    facts.tracer.name = "kerr-closed-form";
    facts.flux_by_order = flux_by_order(camera(), f.frame.image);
    facts.flux = medium_frame_flux(camera(), f.frame.image);
    facts.uncovered_rays = f.uncovered;
    return finish_render(checked_, std::move(f.frame), facts, setup_seconds_, {});
  }

 private:
  KerrDiskRays rays_;
  DiskLight light_;
};

SphericalAccretion accretion_of(const CheckedRequest& checked) {
  const RenderRequest& q = checked.request;
  SphericalAccretion gas;
  gas.gas = q.accretion_gas == "rest" ? SphericalAccretion::Gas::at_rest : SphericalAccretion::Gas::free_fall;
  gas.power = q.accretion_power;
  gas.outer = 2.0 * checked.settings.escape_radius;  // beyond the sky sphere: no edge on any ray
  return gas;
}

}  // namespace

std::unique_ptr<FrameRenderer> make_disk_light_renderer(const CheckedRequest& checked) {
  return std::make_unique<DiskLightRenderer>(checked);
}

std::unique_ptr<FrameRenderer> make_medium_renderer(const CheckedRequest& checked) {
  const RenderRequest& q = checked.request;
  if (q.scene == "torus") {  // Kerr in Boyer-Lindquist coordinates (check_request)
    const KerrMetric metric{q.metric.mass, q.metric.spin};
    return own_medium_tracer(checked, [&] {
      return KerrMinoMediumTracer<Verner65, IController, PolishDoughnut<KerrMetric>>(
          metric, polish_doughnut(q), checked.settings, checked.camera.tetrad().e[0], 1.0);
    });
  }
  if (q.scene == "riaf") {  // Kerr in Boyer-Lindquist coordinates (check_request)
    const KerrMetric metric{q.metric.mass, q.metric.spin};
    const RiafParameters p = riaf_parameters(q);
    return own_medium_tracer(
        checked,
        [&] {
          return KerrMinoMediumTracer<Verner65, IController, RiafFlow<KerrMetric>>(
              metric, RiafFlow<KerrMetric>(metric, p), checked.settings, checked.camera.tetrad().e[0],
              q.frequency_ghz * 1e9);
        },
        source_scale(q));
  }
  // accretion: Schwarzschild (check_request).
  const SphericalAccretion gas = accretion_of(checked);
  const SchwarzschildMetric metric{q.metric.mass};
  if (q.tracer == "general") {
    return own_medium_tracer(checked, [&] {
      return GeneralMediumTracer<SchwarzschildMetric, Verner65, IController, SphericalAccretion>(
          metric, gas, checked.settings, checked.camera.tetrad().e[0], 1.0);
    });
  }
  return own_medium_tracer(checked, [&] {
    return SphericalMediumTracer<SchwarzschildMetric, Verner65, IController, SphericalAccretion>(
        metric, gas, checked.settings, checked.camera, 1.0, q.table_rays);
  });
}

}  // namespace grtrace::app
