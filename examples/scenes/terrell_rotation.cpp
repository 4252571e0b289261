// examples/scenes/terrell_rotation.cpp
// Flat space, never integrated: a checkered sphere (moving_sphere.hpp) passes the camera at 0.9 c. Rays are straight
// lines (trace/straight_line.hpp) through the same scene-object concept as in curved space. The sphere's outline
// stays a circle, but it is seen turned: the camera sees its back (Terrell-Penrose rotation), brightened on the
// approaching side and dimmed on the receding side by the Doppler factor.
//   terrell_rotation [--beta 0.9] [--out terrell.exr] [--size 512]     writes terrell.exr and terrell.png
#include "moving_sphere.hpp"

#include "grtrace/metric/minkowski.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/trace/straight_line.hpp"

#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>

int main(int argc, char** argv) {
  using namespace grtrace;
  std::string out = "terrell.exr";
  int size = 512;
  MovingSphere sphere;
  auto number = [](const std::string& v) {  // the whole text must be a number
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0') throw std::invalid_argument("'" + v + "' is not a number");
    return d;
  };
  try {
    for (int i = 1; i < argc; i += 2) {
      const std::string key = argv[i], value = i + 1 < argc ? argv[i + 1] : "";
      if (key == "--out" && value.ends_with(".exr")) out = value;
      else if (key == "--size" && number(value) >= 8 && number(value) <= 4096) size = static_cast<int>(number(value));
      else if (key == "--beta") sphere.velocity = Vec3(0.0, number(value), 0.0);
      else throw std::invalid_argument("usage: terrell_rotation [--beta B] [--out FILE.exr] [--size 8..4096]");
    }
    // Seen straight ahead: the light that arrives at t = 0 left the centre's position at t = -10, (10, 0, 0).
    sphere.centre_at_zero = Vec3(10.0, 10.0 * sphere.velocity.y(), 0.0);
    sphere.check();
    CameraSpec spec;  // static camera at the origin looking along +x, z up
    spec.position = Vec4::Zero();
    spec.look = Vec3(1.0, 0.0, 0.0);
    spec.up = Vec3(0.0, 0.0, 1.0);
    spec.width = spec.height = size;
    spec.fov_degrees = 50.0;
    const MinkowskiMetric flat;
    const Camera camera = make_camera(flat, spec);
    const StraightLineTracer tracer(flat, 40.0, AngleCorrection::flat,
                                    make_scene(CheckerSky{12}, HorizonPaint{}, sphere), 512);
    const Frame frame = render_frame(camera, tracer);
    const std::string png = out.substr(0, out.size() - 4) + ".png";
    write_exr(out, frame.image);
    write_png_preview(png, frame.image);
    std::cout << "{\"out\":\"" << out << "\",\"png\":\"" << png << "\",\"seconds\":" << frame.stats.seconds
              << ",\"sphere_pixels\":" << frame.stats.count(RayStatus::hit) << "}\n";
  } catch (const std::invalid_argument& e) {  // bad input: nothing was traced or written
    std::cerr << "terrell_rotation: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "terrell_rotation: " << e.what() << "\n";
    return 1;
  }
}
