// examples/scenes/glowing_ring.cpp
// A medium of one's own: a ring of glowing gas (a tube of Gaussian cross-section, 0.5 M wide, around the circle of
// radius --radius in the equatorial plane) turning rigidly with the Keplerian angular velocity of that circle around
// a Kerr hole (a = 0.9), optically thin. The struct below is all a medium is (medium/emitting_medium.hpp lists what
// it must and may provide); KerrMinoMediumTracer traces every pixel on Kerr's separated equations in Mino time,
// which needs the medium stationary (declared), with Verner 6(5), whose error estimate sees the light.
//   glowing_ring [--out ring.exr] [--size 256] [--radius 8] [--inclination 75]   writes the EXR and a PNG
#include "example_cli.hpp"
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string_view>

using namespace grtrace;

struct GlowingRing {
  static constexpr std::string_view kind = "glowing-ring";
  static constexpr bool stationary = true, axisymmetric = true, equator_mirror_symmetric = true;
  double radius, width;
  double outer_radius() const { return radius + 8.0 * width; }  // j < e^-32 beyond
  MediumCoefficients coefficients(const KerrMetric&, const Vec4& x, double /*nu*/) const {
    const double rho = x[1] * std::sin(x[2]) - radius, z = x[1] * std::cos(x[2]);
    return {std::exp(-(rho * rho + z * z) / (2.0 * width * width)), 0.0};  // j, alpha
  }
  Vec4 fluid_velocity(const KerrMetric& m, const Vec4& x) const {
    const Mat4 g = m.metric(x);
    const Vec4 u(1.0, 0.0, 0.0, 1.0 / (std::pow(radius, 1.5) + m.spin));  // Bardeen, Press & Teukolsky's Omega
    const double norm = u.dot(g * u);
    return norm > 0.0 ? Vec4(u / std::sqrt(norm)) : *zamo_velocity(g);  // no gas where that is not timelike
  }
};

int main(int argc, char** argv) {
  return run_example("glowing_ring", [&] {
    const ExampleArgs args =
        parse_example_args(argc, argv, {"ring.exr", 256, {{"radius", 8.0}, {"inclination", 75.0}}});
    const double radius = args.numbers.at("radius"), inclination = args.numbers.at("inclination");
    if (!(radius >= 4.0 && radius <= 100.0)) throw std::invalid_argument("--radius must lie in [4, 100] M");
    if (!(inclination > 0.0 && inclination < 180.0))
      throw std::invalid_argument("--inclination must lie in (0, 180) degrees");
    const KerrMetric metric{1.0, 0.9};
    CameraSpec spec;  // a zero angular momentum observer 100 M away, the ring filling the frame
    spec.position = Vec4(0.0, 100.0, inclination * std::numbers::pi / 180.0, 0.0);
    spec.spherical_position = true;
    spec.observer = ObserverKind::zamo;
    spec.width = spec.height = args.size;
    spec.fov_degrees = 2.0 * std::atan((radius + 4.0) / 100.0) * 180.0 / std::numbers::pi;
    const Camera camera = make_camera(metric, spec);
    TraceSettings settings;
    settings.integrator.tolerance = {1e-8, 1e-10};
    settings.escape_radius = 1000.0;
    const KerrMinoMediumTracer<Verner65, IController, GlowingRing> tracer(metric, GlowingRing{radius, 0.5}, settings,
                                                                          camera.tetrad().e[0], 1.0);
    Frame frame = render_medium_frame(camera, tracer);
    frame.image.metadata["medium"] = std::string(GlowingRing::kind);
    write_example_frame(args, frame);
  });
}
