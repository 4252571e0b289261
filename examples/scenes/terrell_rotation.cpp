// examples/scenes/terrell_rotation.cpp
// Flat space, never integrated: a checkered sphere (moving_sphere.hpp) passes the camera at 0.9 c. Rays are straight
// lines (trace/straight_line.hpp) through the same scene-object concept as in curved space. The sphere's outline
// stays a circle, but it is seen turned: the camera sees its back (Terrell-Penrose rotation), and each part is
// brightened or dimmed by its Doppler factor.
//   terrell_rotation [--beta 0.9] [--out terrell.exr] [--size 512]     writes terrell.exr and terrell.png
#include "example_cli.hpp"
#include "moving_sphere.hpp"

#include "grtrace/metric/minkowski.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/trace/straight_line.hpp"

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("terrell_rotation", [&] {
    const ExampleArgs args = parse_example_args(argc, argv, {"terrell.exr", 512, {{"beta", 0.9}}});
    MovingSphere sphere;
    sphere.velocity = Vec3(0.0, args.numbers.at("beta"), 0.0);
    // Seen straight ahead: the light that arrives at t = 0 left the centre's position at t = -10, (10, 0, 0).
    sphere.centre_at_zero = Vec3(10.0, 10.0 * sphere.velocity.y(), 0.0);
    sphere.check();
    CameraSpec spec;  // static camera at the origin looking along +x, z up
    spec.position = Vec4::Zero();
    spec.look = Vec3(1.0, 0.0, 0.0);
    spec.up = Vec3(0.0, 0.0, 1.0);
    spec.width = spec.height = args.size;
    spec.fov_degrees = 50.0;
    const MinkowskiMetric flat;
    const Camera camera = make_camera(flat, spec);
    const StraightLineTracer tracer(flat, 40.0, AngleCorrection::flat,
                                    make_scene(CheckerSky{12}, HorizonPaint{}, sphere), 512);
    write_example_frame(args, render_frame(camera, tracer));
  });
}
