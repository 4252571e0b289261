// examples/scenes/kerr_torus.cpp
// A thick torus of glowing gas around a Kerr hole (a = 0.9): a Polish doughnut of constant angular momentum
// (medium/polish_doughnut.hpp), inner edge 6 M, pressure maximum 10 M, emitting and absorbing in proportion to its
// density (a grey source function). Every pixel's ray is integrated with its light on Kerr's separated equations in
// Mino time (KerrMinoMediumTracer), with Verner 6(5), whose error estimate sees the light's integral; the
// approaching side is Doppler-brightened, the far side is lensed over the hole, and steps end on the torus's
// surface (its boundary), where the density has a kink.
//   kerr_torus [--out torus.exr] [--size 256] [--opacity 0.3] [--inclination 75]   writes the EXR and a PNG
#include "example_cli.hpp"
#include "grtrace/medium/polish_doughnut.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <numbers>
#include <stdexcept>

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("kerr_torus", [&] {
    const ExampleArgs args =
        parse_example_args(argc, argv, {"torus.exr", 256, {{"opacity", 0.3}, {"inclination", 75.0}}});
    const double opacity = args.numbers.at("opacity"), inclination = args.numbers.at("inclination");
    if (!(opacity >= 0.0)) throw std::invalid_argument("--opacity must be >= 0 (alpha = opacity * density)");
    if (!(inclination > 0.0 && inclination < 180.0))
      throw std::invalid_argument("--inclination must lie in (0, 180) degrees");
    const KerrMetric metric{1.0, 0.9};
    const PolishDoughnut<KerrMetric> torus(metric, 6.0, 10.0, 3.0, 1.0, opacity);
    CameraSpec spec;  // a zero angular momentum observer 100 M away, the torus (out to 33 M) filling the frame
    spec.position = Vec4(0.0, 100.0, inclination * std::numbers::pi / 180.0, 0.0);
    spec.spherical_position = true;
    spec.observer = ObserverKind::zamo;
    spec.width = spec.height = args.size;
    spec.fov_degrees = 36.0;
    const Camera camera = make_camera(metric, spec);
    TraceSettings settings;
    settings.integrator.tolerance = {1e-8, 1e-10};
    settings.escape_radius = 1000.0;
    const KerrMinoMediumTracer<Verner65, IController, PolishDoughnut<KerrMetric>> tracer(metric, torus, settings,
                                                                                         camera.tetrad().e[0], 1.0);
    Frame frame = render_medium_frame(camera, tracer);
    frame.image.metadata["medium"] = std::string(PolishDoughnut<KerrMetric>::kind);
    write_example_frame(args, frame);
  });
}
