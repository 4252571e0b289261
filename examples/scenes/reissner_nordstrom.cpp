// examples/scenes/reissner_nordstrom.cpp
// A metric the library does not ship, rendered by the same scene tracer: a charged black hole (Reissner-Nordstrom,
// written in reissner_nordstrom.hpp) with a thin Keplerian disk. The disk's orbits come from the metric itself
// (metric/circular_orbits.hpp), so nothing in the library knows this metric exists.
//   reissner_nordstrom [--charge 0.8] [--out rn.exr] [--size 512]     writes rn.exr and rn.png
#include "example_cli.hpp"
#include "reissner_nordstrom.hpp"

#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/scene/thin_disk.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <numbers>
#include <string>

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("reissner_nordstrom", [&] {
    const ExampleArgs args = parse_example_args(argc, argv, {"rn.exr", 512, {{"charge", 0.8}}});
    const auto metric = ReissnerNordstromMetric::checked(1.0, args.numbers.at("charge"));
    CameraSpec spec;  // static observer at r = 50 M, 10 degrees above the disk's plane
    spec.position = Vec4(0.0, 50.0, 80.0 * std::numbers::pi / 180.0, 0.0);
    spec.width = spec.height = args.size;
    spec.fov_degrees = 40.0;
    const Camera camera = make_camera(metric, spec);
    ThinDisk disk;
    disk.r_in = 5.0;
    disk.r_out = 20.0;
    check_disk_orbits(metric, disk);

    TraceSettings settings;
    settings.integrator.tolerance = {1e-9, 1e-11};
    settings.escape_radius = 400.0;
    const auto tracer = make_general_tracer<Tsitouras54, IController>(metric, settings, AngleCorrection::flat,
                                                                      make_scene(StarFieldSky{}, HorizonPaint{}, disk));
    Frame frame = render_frame(camera, tracer);
    frame.image.metadata["metric"] = std::string(ReissnerNordstromMetric::name);
    frame.image.metadata["charge"] = exact_number(metric.charge);
    write_example_frame(args, frame);
  });
}
