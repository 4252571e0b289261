// examples/scenes/star_beside_hole.cpp
// A glowing star beside a Schwarzschild black hole. The star is one struct of our own (glowing_star.hpp: its shape,
// how its matter moves, its colour); everything else is the library's. The hole bends the star's light around
// both sides: the direct image, and on the far side of the shadow the thin secondary image.
//   star_beside_hole [--out star.exr] [--size 512]       writes star.exr (all data channels) and star.png
#include "glowing_star.hpp"

#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>

int main(int argc, char** argv) {
  using namespace grtrace;
  std::string out = "star.exr";
  int size = 512;
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
      else throw std::invalid_argument("usage: star_beside_hole [--out FILE.exr] [--size 8..4096]");
    }
    const SchwarzschildMetric metric{1.0};
    CameraSpec spec;  // static observer at r = 30 M, a little above the plane, looking at the hole
    spec.position = Vec4(0.0, 30.0, 1.48, 0.0);
    spec.width = spec.height = size;
    spec.fov_degrees = 60.0;
    const Camera camera = make_camera(metric, spec);
    const GlowingStar star;  // at (-12, 6, 0): behind the hole, off to one side
    check_star(metric, star, spec.position);

    TraceSettings settings;
    settings.integrator.tolerance = {1e-9, 1e-11};
    settings.escape_radius = 400.0;
    const auto tracer = make_general_tracer<Tsitouras54, IController>(metric, settings, AngleCorrection::exact,
                                                                      make_scene(StarFieldSky{}, HorizonPaint{}, star));
    const Frame frame = render_frame(camera, tracer);
    const std::string png = out.substr(0, out.size() - 4) + ".png";
    write_exr(out, frame.image);
    write_png_preview(png, frame.image);
    std::cout << "{\"out\":\"" << out << "\",\"png\":\"" << png << "\",\"seconds\":" << frame.stats.seconds
              << ",\"star_pixels\":" << frame.stats.count(RayStatus::hit)
              << ",\"failed\":" << frame.stats.failures() << "}\n";
  } catch (const std::invalid_argument& e) {  // bad input: nothing was traced or written
    std::cerr << "star_beside_hole: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "star_beside_hole: " << e.what() << "\n";
    return 1;
  }
}
