// tests/benchmarks/peers/gyoto_sphere.cpp
// grtrace's half of a comparison with GYOTO (Vincent, Paumard, Gourgoulhon & Perrin 2011; Debian's gyoto 1.4.4):
// the scene GYOTO calls a FixedStar, a ball of glowing, absorbing gas at rest at a fixed point near a Kerr hole,
// with a uniform emission coefficient j = 1 and absorption coefficient alpha in its own frame (GYOTO's UniformSphere
// with IsotropicEmittedIntensity, OpticallyThin and a flat PowerLaw opacity), seen by a zero angular momentum
// observer through GYOTO's screen: its rectilinear pixel grid, axes and orientation. Each pixel is one ray, traced
// on Kerr's separated equations in Mino time (KerrMinoMediumTracer's ray, Verner 6(5) with the I controller, the
// tools' media method; a ray that never comes within the ball's outer radius is answered in closed form), so that
// pixel (i, j) of both programs is the same ray. Writes the intensity as a FITS image
// laid out as GYOTO writes its own (NAXIS1 = i, NAXIS2 = j), and prints the time the frame took.
// tests/benchmarks/peers/gyoto_compare.sh runs both programs on the same scene and compares them.
//
//   gyoto_sphere --out ball.fits [--size 128] [--rtol 1e-8] [--threads 0] [--spin 0.9] [--distance 1000]
//                [--inclination 100] [--fov 0.03] [--ball 6,1.4,-0.3] [--ball-radius 2.5] [--opacity 0.3]
//
// GYOTO's screen (lib/Screen.C, getRayCoord, 1.4.4): the observer at r = Distance, theta = pi - Inclination,
// phi = -pi/2 - Argument (0 here); pixel (i, j), 1-based, at x = -d (i - (N + 1) / 2), y = d (j - (N + 1) / 2) with
// d = 2 tan(FieldOfView / 2) / N (AngleKind Rectilinear); the photon arrives moving along
// p = (e_r - x e_phi - y e_theta) / sqrt(1 + x^2 + y^2) in the observer's frame (ObserverKind ZAMO, whose triad is
// -e_phi, -e_theta, -e_r, rotated by pi - PALN about the line of sight), with unit energy. grtrace traces it back:
// k = -(u + p).
#include "command_line.hpp"
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/spherical_chart.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

using namespace grtrace;

namespace {

/// GYOTO's FixedStar: a ball of radius R in the chart's Cartesian embedding (x = r sin(theta) cos(phi), ...,
/// r Boyer-Lindquist's), at rest (moving along the Killing time), glowing with j = 1 and absorbing with alpha.
struct UniformBall {
  static constexpr std::string_view kind = "uniform-ball";
  static constexpr bool stationary = true;
  Vec3 centre;
  double radius = 1.0;
  double absorption = 0.0;

  MediumCoefficients coefficients(const KerrMetric&, const Vec4&, double) const { return {1.0, absorption}; }
  Vec4 fluid_velocity(const KerrMetric& m, const Vec4& x) const { return rest_emitter_velocity(m, x); }
  double outer_radius() const { return centre.norm() + radius; }
  double inner_radius() const { return centre.norm() - radius; }
  /// Its surface, where j and alpha jump: the tracer ends a step there.
  double boundary(const KerrMetric&, const Vec4& x) const {
    return (spherical_to_cartesian(x) - centre).norm() - radius;
  }
};

/// A FITS file (NOST 100-2.0) of one 2-D image of doubles, as GYOTO writes its own: NAXIS1 = i, NAXIS2 = j.
void write_fits(std::ostream& os, int n, const std::vector<double>& image) {
  std::string header;
  const auto card = [&](const std::string& text) {
    std::string c = text;
    c.resize(80, ' ');
    header += c;
  };
  const auto value = [&](const std::string& key, const std::string& v) {
    std::string k = key;
    k.resize(8, ' ');
    std::string field = v;
    if (field.size() < 20) field.insert(0, 20 - field.size(), ' ');
    card(k + "= " + field);
  };
  value("SIMPLE", "T");
  value("BITPIX", "-64");
  value("NAXIS", "2");
  value("NAXIS1", std::to_string(n));
  value("NAXIS2", std::to_string(n));
  value("QUANT_1", "'Intensity'");
  card("END");
  header.resize((header.size() + 2879) / 2880 * 2880, ' ');
  os.write(header.data(), static_cast<std::streamsize>(header.size()));
  std::string data;
  for (const double v : image) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int b = 7; b >= 0; --b) data.push_back(static_cast<char>((bits >> (8 * b)) & 0xffu));  // big-endian
  }
  data.resize((data.size() + 2879) / 2880 * 2880, '\0');
  os.write(data.data(), static_cast<std::streamsize>(data.size()));
}

int run(int argc, char** argv) {
  tools::CommandLine cli("gyoto_sphere",
                         "GYOTO's FixedStar scene (a uniform glowing ball near a Kerr hole) through GYOTO's screen, "
                         "traced by grtrace; writes a FITS image as GYOTO does.");
  cli.option("out", "ball.fits", "output FITS image (intensity, GYOTO's layout)")
      .option("size", "128", "pixels a side (GYOTO's Resolution), 8 .. 4096")
      .option("rtol", "1e-8", "relative tolerance of the step control (atol 1e-3 of it)")
      .option("threads", "0", "OpenMP threads (0: all)")
      .option("tracer", "kerr-mino",
              "kerr-mino (Kerr's separated equations in Mino time) | general (the geodesic "
              "equation in Boyer-Lindquist coordinates): the same rays, an independent check")
      .option("spin", "0.9", "a / M of the Kerr hole, in (-1, 1)")
      .option("distance", "1000", "the observer's Boyer-Lindquist r (GYOTO's Distance, geometrical)")
      .option("inclination", "100", "GYOTO's Inclination in degrees (theta = 180 - it)")
      .option("fov", "0.03", "GYOTO's FieldOfView in radians")
      .option("ball", "6,1.4,-0.3", "the ball's centre r, theta, phi (GYOTO's Position)")
      .option("ball-radius", "2.5", "the ball's radius (GYOTO's Radius)")
      .option("opacity", "0.3", "alpha in the gas's frame, per M (GYOTO's Opacity, a PowerLaw of exponent 0)");
  if (!cli.parse(argc, argv)) return 0;
  const std::string out = cli.text("out");
  const long size = cli.integer("size");
  const double rtol = cli.number("rtol"), spin = cli.number("spin"), distance = cli.number("distance");
  const double inclination = cli.number("inclination") * std::numbers::pi / 180.0, fov = cli.number("fov");
  const std::vector<double> ball = cli.numbers("ball", 3);
  const double ball_radius = cli.number("ball-radius"), opacity = cli.number("opacity");
  const long threads = cli.integer("threads");
  const std::string tracer = cli.text("tracer");
  if (tracer != "kerr-mino" && tracer != "general")
    throw std::invalid_argument("--tracer must be kerr-mino or general, got '" + tracer + "'");
  if (!(size >= 8 && size <= 4096)) throw std::invalid_argument("--size must be 8 .. 4096, got " + cli.text("size"));
  if (!(rtol >= 1e-14 && rtol <= 1e-2)) throw std::invalid_argument("--rtol must lie in [1e-14, 1e-2]");
  if (!(std::abs(spin) < 1.0)) throw std::invalid_argument("--spin must lie in (-1, 1)");
  if (!(distance >= 20.0 && distance <= 1e6)) throw std::invalid_argument("--distance must lie in [20, 1e6] M");
  if (!(inclination > 0.0 && inclination < std::numbers::pi))
    throw std::invalid_argument("--inclination must lie in (0, 180) degrees (off the axis)");
  if (!(fov > 0.0 && fov < 3.0)) throw std::invalid_argument("--fov must lie in (0, 3) radians");
  if (!(ball_radius > 0.0) || !(opacity >= 0.0) || !std::isfinite(opacity))
    throw std::invalid_argument("--ball-radius must be > 0 and --opacity >= 0");
  if (threads < 0) throw std::invalid_argument("--threads must be >= 0");
  tools::check_command_output(cli, "out", out, {});

  const KerrMetric metric{1.0, spin};
  UniformBall medium;
  medium.centre = spherical_to_cartesian(Vec4(0.0, ball[0], ball[1], ball[2]));
  medium.radius = ball_radius;
  medium.absorption = opacity;
  // Its gas must be at rest: outside the ergosphere everywhere.
  const double r_inner = medium.centre.norm() - ball_radius;
  if (!(r_inner > 2.0)) throw std::invalid_argument("--ball: the ball must lie outside r = 2 M (gas at rest there)");
  if (!(distance > medium.outer_radius())) throw std::invalid_argument("--distance: the observer is inside the ball");

  const Vec4 x_cam(0.0, distance, std::numbers::pi - inclination, -std::numbers::pi / 2.0);
  const Mat4 g = metric.metric(x_cam);
  const Vec4 u = *zamo_velocity(g);
  const Vec4 e_r = Vec4(0, 1, 0, 0) / std::sqrt(-g(1, 1)), e_theta = Vec4(0, 0, 1, 0) / std::sqrt(-g(2, 2)),
             e_phi = Vec4(0, 0, 0, 1) / std::sqrt(-g(3, 3));
  TraceSettings settings;
  settings.integrator.tolerance = {rtol, 1e-3 * rtol};
  settings.escape_radius = 1.1 * distance;

  // The frame tracers' rays (trace/medium_tracers.hpp), the camera's E = 1 by construction.
  const KerrMinoMediumTracer<Verner65, IController, UniformBall> mino(metric, medium, settings, u, 1.0);
  const GeneralMediumTracer<KerrMetric, Verner65, IController, UniformBall> general(metric, medium, settings, u, 1.0);
  const int n = static_cast<int>(size);
  const double d = 2.0 * std::tan(0.5 * fov) / n;
  std::vector<double> image(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0.0);
  long failed = 0;
#ifdef _OPENMP
  if (threads > 0) omp_set_num_threads(static_cast<int>(threads));
#endif
  const auto start = std::chrono::steady_clock::now();
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1) reduction(+ : failed)
#endif
  for (int j = 1; j <= n; ++j) {
    for (int i = 1; i <= n; ++i) {
      const double x = -d * (i - 0.5 * (n + 1)), y = d * (j - 0.5 * (n + 1));
      const Vec4 p = (e_r - x * e_phi - y * e_theta) / std::sqrt(1.0 + x * x + y * y);
      const GeodesicState y0 = make_state(x_cam, Vec4(-(u + p)));
      const MediumSample r = tracer == "general" ? general.trace(y0) : mino.trace(y0);
      const RayStatus st = r.status;
      const bool ok =
          std::isfinite(r.intensity) && (st == RayStatus::escaped || st == RayStatus::captured || st == RayStatus::hit);
      if (!ok) ++failed;
      image[static_cast<std::size_t>(j - 1) * static_cast<std::size_t>(n) + static_cast<std::size_t>(i - 1)] =
          ok ? r.intensity : 0.0;
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_file_atomically(out, [&](std::ostream& os) { write_fits(os, n, image); });
  double flux = 0.0;
  for (const double v : image) flux += v;
  int used = 1;
#ifdef _OPENMP
  used = omp_get_max_threads();
#endif
  std::printf(
      "{\"out\": \"%s\", \"pixels\": %ld, \"threads\": %d, \"seconds\": %.4f, \"us_per_pixel_thread\": %.3f, "
      "\"failed\": %ld, \"sum\": %.12g}\n",
      out.c_str(), size * size, used, seconds, 1e6 * seconds * used / static_cast<double>(size * size), failed, flux);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const tools::UsageError& e) {
    std::cerr << "gyoto_sphere: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "gyoto_sphere: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "gyoto_sphere: " << e.what() << "\n";
    return 1;
  }
}
