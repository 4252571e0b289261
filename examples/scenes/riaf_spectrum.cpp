// examples/scenes/riaf_spectrum.cpp
// The millimetre spectrum of Sgr A* (or M87*) from its hot accretion flow (medium/riaf.hpp: thermal synchrotron
// light, its absorption, a = 0.9): one frame at eight observing frequencies from 43 GHz to 1 THz in one pass, each
// pixel's ray traced once and the flow asked for all eight at every stage (KerrMinoMediumTracer with eight bands,
// trace/emission_system.hpp). Writes the EXR (intensity_<f>GHz and optical_depth_<f>GHz for each, the 230 GHz image
// as R, G, B), its PNG, and NAME-spectrum.png: the flux in janskys against frequency, both on logarithmic axes; the
// JSON line lists the fluxes.
//   riaf_spectrum [--out spectrum.exr] [--size 128] [--inclination 17] [--m87 0|1]
#include "example_cli.hpp"
#include "grtrace/core/number_text.hpp"
#include "grtrace/core/physical_units.hpp"
#include "grtrace/medium/riaf.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/spectra/line_profile_output.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

using namespace grtrace;

namespace {

constexpr std::array<double, 8> kGhz{43, 86, 140, 230, 345, 490, 690, 1000};

/// The spectrum on logarithmic axes: frequency (GHz) across, flux (Jy) up, a decade a tick.
LineChart spectrum_chart(const std::array<double, kGhz.size()>& jy) {
  line_chart_detail::Plot plot;  // its canvas, lines and digits
  using P = line_chart_detail::Plot;
  const double x_lo = std::log10(30.0), x_hi = std::log10(1500.0);
  const auto [lo, hi] = std::minmax_element(jy.begin(), jy.end());
  const double y_lo = std::floor(std::log10(*lo)), y_hi = std::max(y_lo + 1.0, std::ceil(std::log10(*hi)));
  const auto x_of = [&](double ghz) {
    return P::left + (std::log10(ghz) - x_lo) / (x_hi - x_lo) * (P::W - P::left - P::right);
  };
  const auto y_of = [&](double f) {
    return P::H - P::bottom - (std::log10(f) - y_lo) / (y_hi - y_lo) * (P::H - P::bottom - P::top);
  };
  const std::array<std::uint8_t, 3> axis{160, 160, 160}, curve{255, 150, 40};
  plot.line(P::left, P::H - P::bottom, P::W - P::right, P::H - P::bottom, axis);
  plot.line(P::left, P::top, P::left, P::H - P::bottom, axis);
  for (const double ghz : {50.0, 100.0, 200.0, 500.0, 1000.0}) {
    plot.line(x_of(ghz), P::H - P::bottom, x_of(ghz), P::H - P::bottom + 6, axis);
    plot.text(static_cast<int>(x_of(ghz)) - 6, P::H - P::bottom + 9, shortest_number_text(ghz));
  }
  for (double d = y_lo; d <= y_hi + 1e-9; d += 1.0) {
    plot.line(P::left - 6, y_of(std::pow(10.0, d)), P::left, y_of(std::pow(10.0, d)), axis);
    plot.text(4, static_cast<int>(y_of(std::pow(10.0, d))) - 4, shortest_number_text(std::pow(10.0, d)));
  }
  for (std::size_t i = 0; i < jy.size(); ++i) {
    if (i + 1 < jy.size()) plot.line(x_of(kGhz[i]), y_of(jy[i]), x_of(kGhz[i + 1]), y_of(jy[i + 1]), curve);
    for (int d = -3; d <= 3; ++d)
      plot.line(x_of(kGhz[i]) - 3, y_of(jy[i]) + d, x_of(kGhz[i]) + 3, y_of(jy[i]) + d, curve);
  }
  return {P::W, P::H, std::move(plot.rgb)};
}

}  // namespace

int main(int argc, char** argv) {
  return run_example("riaf_spectrum", [&] {
    ExampleArgs defaults{"spectrum.exr", 128, {{"inclination", 17.0}, {"m87", 0.0}}};
    defaults.more_pictures = {"-spectrum"};
    const ExampleArgs args = parse_example_args(argc, argv, defaults);
    const double inclination = args.numbers.at("inclination");
    if (!(inclination > 0.0 && inclination < 180.0))
      throw std::invalid_argument("--inclination must lie in (0, 180) degrees");
    const bool m87 = args.numbers.at("m87") != 0.0;
    const KerrMetric metric{1.0, 0.9};
    const RiafFlow<KerrMetric> flow(metric, m87 ? RiafParameters::m87() : RiafParameters::sgr_a());
    const SourceScale scale = m87 ? SourceScale::m87() : SourceScale::sgr_a();
    const double r_cam = 1000.0;  // far enough for the angles seen at Earth (to r / D), near enough to trace fast
    CameraSpec spec;
    spec.position = Vec4(0.0, r_cam, inclination * std::numbers::pi / 180.0, 0.0);
    spec.spherical_position = true;
    spec.width = spec.height = args.size;
    spec.fov_degrees = 2.0 * std::atan(30.0 / r_cam) * 180.0 / std::numbers::pi;  // 60 M across
    const Camera camera = make_camera(metric, spec);
    TraceSettings settings;
    settings.integrator.tolerance = {1e-8, 1e-10};
    settings.escape_radius = 2000.0;
    std::array<double, kGhz.size()> hz;
    std::vector<std::string> names(kGhz.size());
    for (std::size_t i = 0; i < kGhz.size(); ++i) {
      hz[i] = kGhz[i] * 1e9;
      names[i] = shortest_number_text(kGhz[i]) + "GHz";
    }
    const KerrMinoMediumTracer<Verner65, IController, RiafFlow<KerrMetric>, kGhz.size()> tracer(
        metric, flow, settings, camera.tetrad().e[0], hz);
    Frame frame = render_medium_spectrum(camera, tracer, names, 3);  // the picture at 230 GHz
    std::array<double, kGhz.size()> jy;
    std::string fluxes;
    for (std::size_t i = 0; i < kGhz.size(); ++i) {
      jy[i] = scale.janskys(medium_frame_flux(camera, frame.image, "intensity_" + names[i]), r_cam);
      frame.image.metadata["flux_jy_" + names[i]] = exact_number(jy[i]);
      fluxes += (i ? ", \"" : "\"") + names[i] + "\": " + shortest_number_text(jy[i]);
    }
    frame.image.metadata["medium"] = std::string(RiafFlow<KerrMetric>::kind);
    write_example_image(args, frame.image, {spectrum_chart(jy)});
    std::printf("{\"out\": \"%s\", \"seconds\": %.3f, \"failures\": %ld, \"flux_jy\": {%s}}\n", args.out.c_str(),
                frame.stats.seconds, frame.stats.failures(), fluxes.c_str());
  });
}
