// examples/scenes/star_beside_hole.cpp
// A glowing star beside a Schwarzschild black hole. The star is one struct of our own (glowing_star.hpp: its shape,
// how its matter moves, its colour); everything else is the library's. The hole bends the star's light around
// both sides: the direct image, and on the far side of the shadow the thin secondary image.
//   star_beside_hole [--out star.exr] [--size 512]       writes star.exr (all data channels) and star.png
#include "example_cli.hpp"
#include "glowing_star.hpp"

#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/trace/scene_tracer.hpp"

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("star_beside_hole", [&] {
    const ExampleArgs args = parse_example_args(argc, argv, {"star.exr", 512, {}});
    const SchwarzschildMetric metric{1.0};
    CameraSpec spec;  // static observer at r = 30 M, a little above the plane, looking at the hole
    spec.position = Vec4(0.0, 30.0, 1.48, 0.0);
    spec.width = spec.height = args.size;
    spec.fov_degrees = 60.0;
    const Camera camera = make_camera(metric, spec);
    const GlowingStar star;  // at (-12, 6, 0): behind the hole, off to one side
    check_star(metric, star, spec.position);

    TraceSettings settings;
    settings.integrator.tolerance = {1e-9, 1e-11};
    settings.escape_radius = 400.0;
    const auto tracer = make_general_tracer<Tsitouras54, IController>(metric, settings, AngleCorrection::exact,
                                                                      make_scene(StarFieldSky{}, HorizonPaint{}, star));
    write_example_frame(args, render_frame(camera, tracer));
  });
}
