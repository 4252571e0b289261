// examples/scenes/spherical_accretion.cpp
// Gas falling onto a Schwarzschild hole, glowing as it falls: the image of Narayan, Johnson & Gammie (2019), an
// optically thin emitter j ~ r^-2 (medium/spherical_accretion.hpp) whose light every ray collects all along its
// path (trace/emission_system.hpp). The shadow's edge is the photon ring at b = 3 sqrt(3) M, brightest where rays
// linger near the photon sphere; the infalling gas is redshifted, so the inside of the shadow is dim, not black.
// A medium of one's own is one struct of the same shape (emitting_medium.hpp lists what it provides).
//   spherical_accretion [--out accretion.exr] [--size 256] [--at-rest 0]   writes the EXR ("intensity" channel) and a PNG
#include "example_cli.hpp"

#include "grtrace/medium/spherical_accretion.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/emission_system.hpp"

#include <algorithm>
#include <cmath>

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("spherical_accretion", [&] {
    const ExampleArgs args = parse_example_args(argc, argv, {"accretion.exr", 256, {{"at-rest", 0.0}}});
    const SchwarzschildMetric metric{1.0};
    SphericalAccretion gas;  // j = r^-2 out to r = 1e6: beyond the sky sphere, so the medium is smooth on every ray
    gas.gas = args.numbers.at("at-rest") != 0.0 ? SphericalAccretion::Gas::at_rest : SphericalAccretion::Gas::free_fall;
    gas.outer = 1e6;
    CameraSpec spec;  // a static camera 1000 M away, the shadow (radius 5.2 M) filling about half the frame
    spec.position = Vec4(0.0, 1000.0, std::numbers::pi / 2, 0.0);
    spec.spherical_position = true;
    spec.width = spec.height = args.size;
    spec.fov_degrees = 1.2;
    const Camera camera = make_camera(metric, spec);
    TraceSettings settings;
    settings.integrator.tolerance = {1e-8, 1e-10};
    settings.escape_radius = 2000.0;
    Frame frame{Image(args.size, args.size), {}};
    std::vector<float> intensity(static_cast<std::size_t>(args.size) * static_cast<std::size_t>(args.size));
    frame.stats = render_image(frame.image, [&](int x, int y) {
      const EmissionResult r = trace_emission_seen_by<Fehlberg78, IController>(
          metric, gas, settings, camera.pixel_state(x, y), camera.tetrad().e[0], 1.0);
      intensity[static_cast<std::size_t>(y) * static_cast<std::size_t>(args.size) + static_cast<std::size_t>(x)] =
          static_cast<float>(r.intensity);
      PixelSample s;
      s.status = r.trace.status;
      s.steps = r.trace.accepted;
      return s;
    });
    // The PNG: intensity over the frame's brightest pixel, gamma 2.2, in the colours of hot gas.
    const float peak = *std::max_element(intensity.begin(), intensity.end());
    frame.image.add_channel("intensity") = intensity;
    std::vector<float>&red = frame.image.channel("R"), &green = frame.image.channel("G"), &blue = frame.image.channel("B");
    for (std::size_t i = 0; i < intensity.size(); ++i) {
      const float v = std::pow(intensity[i] / peak, 1.0f / 2.2f);
      red[i] = v;
      green[i] = v * v;
      blue[i] = v * v * v * v;
    }
    frame.image.metadata["medium"] = std::string(SphericalAccretion::kind);
    frame.image.metadata["gas"] = gas.gas == SphericalAccretion::Gas::at_rest ? "at_rest" : "free_fall";
    write_example_frame(args, frame);
  });
}
