// examples/scenes/spherical_accretion.cpp
// Gas falling onto a Schwarzschild hole, glowing as it falls: the image of Narayan, Johnson & Gammie (2019), an
// optically thin emitter j ~ r^-2 (medium/spherical_accretion.hpp) whose light every ray collects all along its
// path (trace/emission_system.hpp). The shadow's edge is the photon ring at b = 3 sqrt(3) M, brightest where rays
// linger near the photon sphere; the infalling gas is redshifted, so the inside of the shadow is dim, not black.
// The gas and the hole are spherically symmetric, so one table of rays draws the frame (trace/medium_tracers.hpp),
// integrated with Verner 6(5), whose error estimate sees the light (trace/emission_system.hpp).
// A medium of one's own is one struct of the same shape (emitting_medium.hpp lists what it provides).
//   spherical_accretion [--out accretion.exr] [--size 256] [--at-rest 0]   writes the EXR ("intensity" channel) and a PNG
#include "example_cli.hpp"

#include "grtrace/medium/spherical_accretion.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/medium_tracers.hpp"

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
    settings.integrator.tolerance = {1e-10, 1e-12};
    settings.escape_radius = 2000.0;
    // The gas and the hole are spherically symmetric: one table of rays (2048) serves every pixel, each a look-up
    // (trace/medium_tracers.hpp); GeneralMediumTracer would integrate every pixel's ray instead, to the same image.
    const SphericalMediumTracer<SchwarzschildMetric, Verner65, IController, SphericalAccretion> tracer(
        metric, gas, settings, camera, 1.0);
    Frame frame = render_medium_frame(camera, tracer);  // channels intensity, optical_depth; the PNG's colours
    frame.image.metadata["medium"] = std::string(SphericalAccretion::kind);
    frame.image.metadata["gas"] = gas.gas == SphericalAccretion::Gas::at_rest ? "at_rest" : "free_fall";
    write_example_frame(args, frame);
  });
}
