// Frames of emitting media, with one declared method (kMediaMethod: Verner 6(5), whose error estimate sees the
// light's integral, which Fehlberg 7(8)'s, the tools' default, does not: trace/emission_system.hpp), on the CPU:
//   --scene accretion: SphericalAccretion (medium/spherical_accretion.hpp) onto a Schwarzschild hole (one metric:
//     each is another instantiation of the tracers; check_request refuses the others): one table of rays
//     (SphericalMediumTracer: tracer auto or planar) or every pixel integrated (GeneralMediumTracer: general);
//   --scene torus: PolishDoughnut (medium/polish_doughnut.hpp) around Kerr in Boyer-Lindquist coordinates, every
//     pixel integrated on Kerr's separated equations in Mino time (KerrMinoMediumTracer), geometric units;
//   --scene riaf: RiafFlow (medium/riaf.hpp) around Kerr in Boyer-Lindquist coordinates, every pixel integrated
//     as the torus's, its intensity in cgs, its flux in janskys and its pixel in microarcseconds at the source's
//     distance; at several frequencies (up to kMaxFrequencies) in one pass, by one tracer of that many bands (a
//     channel and a flux each; not split by order).
// Every pixel integrated at one frequency splits the intensity by image order (the table does not:
// trace/medium_tracers.hpp);
// and the frames of the thin disk drawn by its light (--scene disk --disk-light: render/disk_light_frame.hpp, every
// ray's crossings in closed form), whose intensity is split by image order.
#include "frame_tracers.hpp"
#include "grtrace/app/medium_view.hpp"
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

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

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
    std::vector<std::string> bands;  // several frequencies: their names, the tracer's first bands
    for (const double f : checked_.request.frequencies_ghz) bands.push_back(frequency_band_name(f));
    constexpr bool spectral = !std::is_same_v<decltype(tracer_.trace(GeodesicState{})), MediumSample>;
    Frame frame = [&] {
      if constexpr (spectral) return render_medium_spectrum(camera(), tracer_, bands, 0, options);
      else return render_medium_frame(camera(), tracer_, options);
    }();
    facts.trace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    facts.tracer.name = Tracer::name;
    if constexpr (requires { tracer_.table_rays(); }) {
      facts.tracer.table_rays = tracer_.table_rays();
      facts.tracer.table_steps = tracer_.table_steps();
    }
    if constexpr (requires { tracer_.fallback_rays(); })
      facts.tracer.fallback_rays = tracer_.fallback_rays() - fallbacks_before;
    facts.flux = medium_frame_flux(camera(), frame.image);
    if constexpr (spectral) {
      for (const std::string& b : bands)
        facts.band_fluxes.push_back({b, medium_frame_flux(camera(), frame.image, "intensity_" + b), {}});
    } else if constexpr (splits_by_order<Tracer>()) {
      facts.flux_by_order = flux_by_order(camera(), frame.image);
    }
    if (scale_) {  // physical units: the camera far away (check_request), its angles scaled by r / D
      const double r_cam = checked_.request.camera.r;
      facts.flux_jy = scale_->janskys(*facts.flux, r_cam);
      for (RenderReport::BandFlux& b : facts.band_fluxes) b.flux_jy = scale_->janskys(b.flux, r_cam);
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

namespace {

/// Calls f(medium, metric, nu, horizon radius) with the request's medium (a medium's scene: check_request): the one
/// place the media are built from a request, for their frames, volumes and light along a path. nu: the first
/// observing frequency in Hz (1 for a medium without units).
template <class F>
auto with_medium(const CheckedRequest& checked, const F& f) {
  const RenderRequest& q = checked.request;
  if (q.scene == "torus" || q.scene == "riaf") {
    const KerrMetric metric{q.metric.mass, q.metric.spin};
    if (q.scene == "torus") return f(polish_doughnut(q), metric, 1.0, metric.outer_horizon());
    return f(RiafFlow<KerrMetric>(metric, riaf_parameters(q)), metric, q.frequencies_ghz.front() * 1e9,
             metric.outer_horizon());
  }
  if (q.scene != "accretion")
    throw RequestError("--scene " + q.scene + " has no emitting medium (accretion, riaf or torus have one)");
  const SchwarzschildMetric metric{q.metric.mass};
  return f(accretion_of(checked), metric, 1.0, 2.0 * q.metric.mass);
}

/// Whether x lies in the gas, outside the horizon.
template <class Medium, class Metric>
bool in_gas(const Medium& medium, const Metric& metric, const Vec4& x, double r_h) {
  return metric.radius(x) > r_h && medium_contains(medium, metric, x);
}

/// j at x for light leaving radially outwards in the fluid's frame (signature + - - -: g(u, u) = 1).
template <class Medium, class Metric>
double radial_emission(const Medium& medium, const Metric& metric, const Vec4& x, double nu) {
  const Mat4 g = metric.metric(x);
  const Vec4 u = medium_fluid_velocity(medium, metric, x, g);
  const Vec4 e_r(0.0, 1.0, 0.0, 0.0);
  const Vec4 n = e_r - u.dot(g * e_r) * u;  // orthogonal to u, spacelike
  const double nn = -n.dot(g * n);
  const Vec4 k = nn > 0.0 ? Vec4(u + n / std::sqrt(nn)) : u;
  return medium_coefficients(medium, metric, x, k, u, nu, g).emission;
}

}  // namespace

MediumVolume medium_volume(const CheckedRequest& checked, int n, double half_width) {
  if (n < 2 || n > 256) throw RequestError("medium_volume: 2 to 256 points a side, got " + std::to_string(n));
  return with_medium(checked, [&](const auto& medium, const auto& metric, double nu, double r_h) {
    MediumVolume v;
    v.n = n;
    v.kind = std::string(std::remove_cvref_t<decltype(medium)>::kind);
    v.half_width =
        half_width > 0.0 ? half_width
                         : std::max(std::min(medium.outer_radius(), 40.0 * checked.request.metric.mass), 4.0 * r_h);
    const double h = v.spacing();
    const auto side = static_cast<std::size_t>(n);
    v.emission.assign(side * side * side, 0.0f);
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const double px = -v.half_width + i * h, py = -v.half_width + j * h, pz = -v.half_width + k * h;
          const double r = std::sqrt(px * px + py * py + pz * pz);
          if (!(r > r_h)) continue;  // inside the horizon
          const Vec4 x(0.0, r, std::acos(std::clamp(pz / r, -1.0, 1.0)), std::atan2(py, px));
          if (!in_gas(medium, metric, x, r_h)) continue;
          const auto at =
              static_cast<std::size_t>(i) + side * (static_cast<std::size_t>(j) + side * static_cast<std::size_t>(k));
          v.emission[at] = static_cast<float>(radial_emission(medium, metric, x, nu));
        }
      }
    }
    for (const float e : v.emission)
      if (std::isfinite(e)) v.peak = std::max(v.peak, static_cast<double>(e));
    return v;
  });
}

std::vector<double> medium_light_along(const CheckedRequest& checked, const TracedPath& path,
                                       const Vec4& camera_velocity) {
  return with_medium(checked, [&](const auto& medium, const auto& metric, double nu, double r_h) {
    std::vector<double> light(path.samples.size(), 0.0);
    if (path.samples.empty()) return light;
    const double e_cam = camera_photon_energy(metric, path.samples.front().state, camera_velocity);
    // At a sample: the light's and the depth's rates per unit of the affine parameter, 0 outside the gas.
    const auto rates = [&](const GeodesicState& y) -> std::array<double, 2> {
      const Vec4 x = y.template head<4>(), k = y.template tail<4>();
      if (!in_gas(medium, metric, x, r_h)) return {0.0, 0.0};
      const LocalLight<1> l = local_light(metric, medium, x, k, e_cam, std::array<double, 1>{nu});
      return {l.emission_rate(0), l.depth_rate(0)};
    };
    std::array<double, 2> before = rates(path.samples.front().state);
    double tau = 0.0, intensity = 0.0;
    for (std::size_t i = 1; i < path.samples.size(); ++i) {
      const std::array<double, 2> now = rates(path.samples[i].state);
      const double dl = std::abs(path.samples[i].lambda - path.samples[i - 1].lambda);
      const double tau_now = tau + 0.5 * (before[1] + now[1]) * dl;
      intensity += 0.5 * (before[0] * std::exp(-tau) + now[0] * std::exp(-tau_now)) * dl;
      tau = tau_now;
      before = now;
      light[i] = intensity;
    }
    return light;
  });
}

std::unique_ptr<FrameRenderer> make_disk_light_renderer(const CheckedRequest& checked) {
  return std::make_unique<DiskLightRenderer>(checked);
}

std::unique_ptr<FrameRenderer> make_medium_renderer(const CheckedRequest& checked) {
  const RenderRequest& q = checked.request;
  const Vec4 u_cam = checked.camera.tetrad().e[0];
  return with_medium(
      checked, [&](const auto& medium, const auto& metric, double nu, double) -> std::unique_ptr<FrameRenderer> {
        using Medium = std::remove_cvref_t<decltype(medium)>;
        using Metric = std::remove_cvref_t<decltype(metric)>;
        if constexpr (std::is_same_v<Medium, SphericalAccretion>) {  // Schwarzschild (check_request)
          if (q.tracer == "general") {
            return own_medium_tracer(checked, [&] {
              return GeneralMediumTracer<Metric, Verner65, IController, Medium>(metric, medium, checked.settings, u_cam,
                                                                                nu);
            });
          }
          return own_medium_tracer(checked, [&] {
            return SphericalMediumTracer<Metric, Verner65, IController, Medium>(metric, medium, checked.settings,
                                                                                checked.camera, nu, q.table_rays);
          });
        } else if constexpr (std::is_same_v<Medium, RiafFlow<KerrMetric>>) {  // Kerr, Boyer-Lindquist (check_request)
          if (q.frequencies_ghz.size() == 1) {
            return own_medium_tracer(
                checked,
                [&] {
                  return KerrMinoMediumTracer<Verner65, IController, Medium>(metric, medium, checked.settings, u_cam,
                                                                             nu);
                },
                source_scale(q));
          }
          // Several: one tracer of kMaxFrequencies bands (one instantiation), the last frequency repeated in the rest.
          std::array<double, kMaxFrequencies> hz;
          for (std::size_t b = 0; b < kMaxFrequencies; ++b)
            hz[b] = q.frequencies_ghz[std::min(b, q.frequencies_ghz.size() - 1)] * 1e9;
          return own_medium_tracer(
              checked,
              [&] {
                return KerrMinoMediumTracer<Verner65, IController, Medium, kMaxFrequencies>(
                    metric, medium, checked.settings, u_cam, hz);
              },
              source_scale(q));
        } else {  // the torus: Kerr, Boyer-Lindquist (check_request)
          return own_medium_tracer(checked, [&] {
            return KerrMinoMediumTracer<Verner65, IController, Medium>(metric, medium, checked.settings, u_cam, nu);
          });
        }
      });
}

}  // namespace grtrace::app
