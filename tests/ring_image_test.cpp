// The photon ring by order (spectra/ring_image.hpp) against the theory of the photon ring: each ring e^-gamma as
// wide as the one before, near the critical curve, with gamma the closed-form Lyapunov exponent of the photon
// orbit there (exact::photon_orbit_lyapunov; Johnson et al. 2020), more closely as the order grows; the fluxes
// likewise for Schwarzschild. The ring image's pixels against each order's flux, against the cuts, against the
// line profile's mesh and against the map sampled at pixel centres (orientation), and the pixel clipping exactly.
#include "grtrace/spectra/ring_image.hpp"

#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/disk_light_frame.hpp"
#include "grtrace/spectra/kerr_disk_map.hpp"
#include "grtrace/spectra/line_profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace {

using namespace grtrace;
constexpr double kPi = std::numbers::pi;

KerrMetric kerr(double spin) {
  KerrMetric m;
  m.spin = spin;
  m.mass = 1.0;
  return m;
}

TEST(PhotonRing, LyapunovExponentIsPiForSchwarzschildAndEquatorialOrbits) {
  EXPECT_NEAR(exact::photon_orbit_lyapunov(3.0, 0.0), kPi, 1e-14);
  // Continuous at a -> 0 (the orbits spread over 3 M -+ 2a / sqrt(3)): pi to first order in a.
  for (double r : {3.0 - 1e-6, 3.0, 3.0 + 1e-6}) EXPECT_NEAR(exact::photon_orbit_lyapunov(r, 1e-6), kPi, 1e-5) << r;
  // At the ends of the range, the equatorial circular orbits, chi = 3/4 and xi^2 = 3 r^2 + a^2 for every spin, so
  // gamma = pi there too; in between the orbits are less unstable (gamma < pi), the same for a and -a.
  for (double a : {0.3, 0.9, 0.998, -0.7}) {
    const double r1 = exact::photon_orbit_radius(a, exact::Orbit::prograde);
    const double r2 = exact::photon_orbit_radius(a, exact::Orbit::retrograde);
    EXPECT_NEAR(exact::photon_orbit_lyapunov(r1, a), kPi, 1e-12) << a;
    EXPECT_NEAR(exact::photon_orbit_lyapunov(r2, a), kPi, 1e-12) << a;
    const double mid = exact::photon_orbit_lyapunov(0.5 * (r1 + r2), a);
    EXPECT_LT(mid, kPi - 0.02) << a;
    EXPECT_NEAR(exact::photon_orbit_lyapunov(0.5 * (r1 + r2), -a), mid, 1e-12) << a;
  }
  EXPECT_THROW(exact::photon_orbit_lyapunov(2.0, 0.5), std::invalid_argument);
  EXPECT_THROW(exact::photon_orbit_lyapunov(3.1, 0.0), std::invalid_argument);
}

/// The radius of the spherical photon orbit whose point of the critical curve (far observer at inclination i) lies
/// at angle phi about (centre, 0), in the upper half (beta >= 0; the curve is symmetric in beta), by bisection.
double orbit_at_angle(double spin, double inclination, double centre, double phi) {
  if (phi > kPi) phi = 2.0 * kPi - phi;
  const auto curve = exact::critical_curve(spin, inclination, 400);
  double r1 = 1e9, r2 = 0.0;
  for (const auto& p : curve) r1 = std::min(r1, p.r), r2 = std::max(r2, p.r);
  const double si = std::sin(inclination), ci = std::cos(inclination);
  auto angle = [&](double r) {
    const auto [xi, eta] = exact::spherical_photon_orbit(r, spin);
    const double beta2 = eta + spin * spin * ci * ci - xi * xi * ci * ci / (si * si);
    return std::atan2(std::sqrt(std::max(0.0, beta2)), -xi / si - centre);
  };
  // alpha = -xi / sin i grows with r for a > 0: the angle about the centre falls from pi (r1) to 0 (r2)
  double lo = r1, hi = r2;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (angle(mid) > phi ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Hole {
  double spin, inclination_degrees, r_in;
};

// Each ring's width on a cut, near the critical curve, against the one before: w_{n+1} / w_n -> e^-gamma. At n = 1
// -> 2 the first ring is still shaped by the disk's extent (off by up to ~70 % here); the departure falls by a
// factor ~e^-gamma each order, so n = 2 -> 3 is within 8 % and at least six times nearer than n = 1 -> 2. (A gamma
// wrong by 5 % would move e^-gamma by 13-15 %.)
TEST(PhotonRing, EachRingIsNarrowerByTheLyapunovFactor) {
  for (const Hole h : {Hole{0.0, 17.0, 6.0}, Hole{0.5, 60.0, 4.233}, Hole{0.9, 17.0, 2.321}, Hole{0.9, 60.0, 2.321}}) {
    const double inc = h.inclination_degrees * kPi / 180.0;
    const KerrDiskMap map(kerr(h.spin), 1e7, inc, h.r_in, 1000.0);
    DiskLight light;
    light.transparent = true;
    const RingGeometry g = measure_rings(map, light, 16);
    double worst12 = 0.0, worst23 = 0.0;
    for (std::size_t c = 0; c < g.cut_angle.size(); ++c) {
      const double phi = g.cut_angle[c];
      double gamma = kPi;
      if (h.spin != 0.0) {
        const double r = orbit_at_angle(h.spin, inc, g.centre_alpha, phi);
        gamma = exact::photon_orbit_lyapunov(r, h.spin);
        // The cut's critical radius (the rays' capture edge) is the closed-form curve's point at its angle.
        const auto [xi, eta] = exact::spherical_photon_orbit(r, h.spin);
        const double si = std::sin(inc), ci = std::cos(inc);
        const double beta = std::sqrt(std::max(0.0, eta + h.spin * h.spin * ci * ci - xi * xi * ci * ci / (si * si)));
        EXPECT_NEAR(g.critical_radius[c], std::hypot(-xi / si - g.centre_alpha, beta), 1e-5) << h.spin << " " << phi;
      } else {
        EXPECT_NEAR(g.critical_radius[c], 3.0 * std::sqrt(3.0), 1e-5);
      }
      const auto& w = g.cut_width[c];
      ASSERT_GT(w[3], 0.0) << "order 3 not found on the cut at " << phi;
      const double dev12 = std::abs(w[2] / w[1] * std::exp(gamma) - 1.0);
      const double dev23 = std::abs(w[3] / w[2] * std::exp(gamma) - 1.0);
      EXPECT_LT(dev23, 0.08) << "a = " << h.spin << ", i = " << h.inclination_degrees << ", phi = " << phi;
      EXPECT_LT(dev23, dev12 / 6.0) << "a = " << h.spin << ", i = " << h.inclination_degrees << ", phi = " << phi;
      worst12 = std::max(worst12, dev12), worst23 = std::max(worst23, dev23);
    }
    std::printf("  a = %.1f, i = %2.0f: |w2/w1 e^gamma - 1| <= %.3f, |w3/w2 e^gamma - 1| <= %.4f\n", h.spin,
                h.inclination_degrees, worst12, worst23);
  }
}

// The rings' fluxes: for Schwarzschild seen nearly face-on every point of the n-th ring has its like in the next,
// e^-pi as wide with the same g and radius, so F_{n+1} / F_n -> e^-pi (the channel >= 3 holds n = 3, 4, 5:
// e^-pi / (1 - e^-pi) of F_2 in the limit). For Kerr the ratio lies between the smallest and largest e^-gamma of
// the critical curve.
TEST(PhotonRing, FluxesFallByTheLyapunovFactor) {
  {
    const KerrDiskMap map(kerr(0.0), 1e7, 5.0 * kPi / 180.0, 6.0, 1000.0);
    DiskLight light;
    light.transparent = true;
    light.redshift_power = 3.0;
    const RingGeometry g = measure_rings(map, light, 64);
    const double q = std::exp(-kPi);
    const double dev12 = std::abs(g.flux[2] / g.flux[1] / q - 1.0);
    const double dev23 = std::abs(g.flux[3] / g.flux[2] / (q / (1.0 - q)) - 1.0);
    std::printf("  Schwarzschild, 5 deg: F2/F1 = %.5f, F>=3/F2 = %.5f (e^-pi = %.5f)\n", g.flux[2] / g.flux[1],
                g.flux[3] / g.flux[2], q);
    EXPECT_LT(dev23, 0.03);
    EXPECT_LT(dev23, dev12 / 6.0);
  }
  for (const Hole h : {Hole{0.5, 60.0, 4.233}, Hole{0.9, 60.0, 2.321}}) {
    const double inc = h.inclination_degrees * kPi / 180.0;
    const KerrDiskMap map(kerr(h.spin), 1e7, inc, h.r_in, 1000.0);
    DiskLight light;
    light.transparent = true;
    light.redshift_power = 3.0;
    const RingGeometry g = measure_rings(map, light, 64);
    double lo = 1.0, hi = 0.0;
    for (const auto& p : exact::critical_curve(h.spin, inc, 200)) {
      const double q = std::exp(-exact::photon_orbit_lyapunov(p.r, h.spin));
      lo = std::min(lo, q), hi = std::max(hi, q);
    }
    const double ratio = g.flux[3] / g.flux[2];
    std::printf("  a = %.1f, i = %2.0f: F>=3/F2 = %.5f in e^-gamma's [%.5f, %.5f]\n", h.spin, h.inclination_degrees,
                ratio, lo, hi);
    EXPECT_GT(ratio, lo);
    EXPECT_LT(ratio, hi / (1.0 - hi));
  }
}

// One triangle with a linear weight over a 4 x 4 grid: the pixels sum to its integral, a pixel wholly inside gets
// its area times the weight at its centre.
TEST(RingImage, PixelClippingIsExactForALinearWeight) {
  const ring_detail::PixelSink sink{4, 4, 2.0, 2.0, 1.0, 2.0, 4.0};
  ring_detail::PixelSink::Row row;
  row.first = 0;
  row.rows = 4;
  for (auto& s : row.sum) s.assign(16, 0.0);
  const std::array<disk_mesh::ScreenPoint, 3> xy{{{-1.9, -1.7}, {1.8, -1.2}, {-0.4, 1.95}}};
  auto w = [](const disk_mesh::ScreenPoint& p) { return 2.0 + 0.3 * p.alpha - 0.7 * p.beta; };
  sink.deposit(1, xy, {}, {w(xy[0]), w(xy[1]), w(xy[2])}, row);
  const double area = 0.5 * std::abs((xy[1].alpha - xy[0].alpha) * (xy[2].beta - xy[0].beta) -
                                     (xy[2].alpha - xy[0].alpha) * (xy[1].beta - xy[0].beta));
  const double integral = area * (w(xy[0]) + w(xy[1]) + w(xy[2])) / 3.0;
  double sum = 0.0;
  for (double v : row.sum[1]) sum += v;
  EXPECT_NEAR(sum, integral, 1e-13 * integral);
  EXPECT_NEAR(row.flux[1], integral, 1e-13 * integral);
  // pixel (row 2, column 1): alpha in [-1, 0], beta in [-1, 0], inside the triangle
  EXPECT_NEAR(row.sum[1][2 * 4 + 1], w({-0.5, -0.5}), 1e-13);
  EXPECT_EQ(row.sum[0][2 * 4 + 1], 0.0);
}

// A ring image: each order's pixels sum to its flux; the cut-traced orders' flux equals the cuts' own (the same
// integrals), the meshed n = 1 the cuts' n = 1 (two methods) within 1e-3; order 0 and 1 against the line profile's
// mesh (energy bins instead of pixels, g^4) within 1e-3; the pixels far from any edge equal the intensity sampled
// at their centres (the image's orientation: alpha to the right, beta up, the top row first).
TEST(RingImage, PixelsHoldEachOrdersFlux) {
  const KerrDiskMap map(kerr(0.9), 1e7, 60.0 * kPi / 180.0, 2.321, 30.0);
  RingImageSpec spec;
  spec.width = 160;
  spec.height = 120;
  spec.half_width = 40.0;
  spec.redshift_power = 4.0;
  const RingImage image = ring_image(map, spec);
  const double pixel_area = image.pixel * image.pixel;
  for (std::size_t o = 0; o < RingImage::kOrderChannels; ++o) {
    double sum = 0.0;
    for (double v : image.intensity[o]) sum += v;
    EXPECT_NEAR(sum * pixel_area, image.flux[o], 1e-12 * image.flux[o]) << o;
    EXPECT_GT(image.flux[o], 0.0) << o;
  }
  EXPECT_NEAR(image.flux[2], image.rings.flux[2], 1e-12 * image.flux[2]);
  EXPECT_NEAR(image.flux[3], image.rings.flux[3], 1e-12 * image.flux[3]);

  DiskLight light;
  light.transparent = true;
  light.redshift_power = 4.0;
  const RingGeometry all = measure_rings(map, light, 720);
  EXPECT_NEAR(image.flux[1], all.flux[1], 1e-3 * all.flux[1]);
  EXPECT_NEAR(image.flux[2], all.flux[2], 1e-4 * all.flux[2]);

  LineProfileSpec line;
  line.transparent = true;
  line.bins = 50;
  const LineProfile profile = line_profile(map, line);
  EXPECT_NEAR(image.flux[0], profile.total_by_order[0], 1e-3 * profile.total_by_order[0]);
  EXPECT_NEAR(image.flux[1], profile.total_by_order[1], 1e-3 * profile.total_by_order[1]);
  std::printf("  flux by order: %.6e %.6e %.6e %.6e (line profile: %.6e %.6e %.6e %.6e)\n", image.flux[0],
              image.flux[1], image.flux[2], image.flux[3], profile.total_by_order[0], profile.total_by_order[1],
              profile.total_by_order[2], profile.total_by_order[3]);

  // A camera's disk-light frame of the same field (render/disk_light_frame.hpp), one ray through each pixel's
  // centre: its flux in the camera's sky times r_o^2 is the same integral by the midpoint rule, so it approaches the
  // mesh's where an order's image is many pixels wide (n = 0, 1) and only samples the thinner rings.
  {
    CameraSpec cs;
    cs.position = Vec4(0.0, 1e7, 60.0 * kPi / 180.0, 0.0);
    cs.width = 1280;
    cs.height = 960;
    cs.fov_degrees = 2.0 * std::atan(spec.half_width / 1e7) * 180.0 / kPi;
    const Camera camera = make_camera(kerr(0.9), cs);
    const KerrDiskRays rays(kerr(0.9), 2.321, 30.0, +1, 1e8);
    const DiskLightFrame frame = render_disk_light_frame(camera, rays, light);
    const std::array<double, 4> flux = flux_by_order(camera, frame.frame.image);
    std::printf("  a camera's frame, %d x %d: %.6e %.6e %.6e %.6e (%ld rays not followed)\n", cs.width, cs.height,
                flux[0] * 1e14, flux[1] * 1e14, flux[2] * 1e14, flux[3] * 1e14, frame.uncovered);
    // Measured: n = 0 1e-4, n = 1 4e-4, n = 2 1.2e-2 (at 640 x 480: 2.4e-3, 1.0e-2, 0.18).
    EXPECT_NEAR(flux[0] * 1e14, image.flux[0], 1e-3 * image.flux[0]);
    EXPECT_NEAR(flux[1] * 1e14, image.flux[1], 3e-3 * image.flux[1]);
    EXPECT_NEAR(flux[2] * 1e14, image.flux[2], 5e-2 * image.flux[2]);  // 0.02-0.07 M wide: 1/2 - 1 pixel
    // The rays the closed form leaves are vortical (eta <= 0: they never reach the plane), so dark is exact there.
    const Image& im = frame.frame.image;
    long vortical = 0;
    for (int row = 0; row < cs.height; ++row)
      for (int col = 0; col < cs.width; ++col)
        if (im.channel("status")[im.index(col, row)] == static_cast<float>(RayStatus::max_steps)) {
          const KerrNullGeodesic ray(kerr(0.9), camera.pixel_state(col, row), 1e8, 1.0);
          vortical += ray.eta() <= 0.0 ? 1 : 0;
        }
    EXPECT_EQ(vortical, frame.uncovered);
    EXPECT_GT(frame.uncovered, 0);
  }

  int compared = 0;
  for (int r = 0; r < spec.height; r += 7)
    for (int c = 0; c < spec.width; c += 7) {
      const double alpha = -spec.half_width + image.pixel * (c + 0.5);
      const double beta = 0.5 * image.pixel * spec.height - image.pixel * (r + 0.5);
      // the pixel's corners and centre all see order 0 alone, on the disk
      bool plain = true;
      double centre = 0.0;
      for (const auto& [da, db] : {std::pair{0.0, 0.0}, std::pair{-0.5, -0.5}, std::pair{0.5, -0.5},
                                   std::pair{-0.5, 0.5}, std::pair{0.5, 0.5}}) {
        const DiskRaySample s = map.sample(alpha + da * image.pixel, beta + db * image.pixel);
        plain = plain && s.where[0] == DiskRaySample::on_disk && s.where[1] != DiskRaySample::on_disk;
        if (da == 0.0 && db == 0.0 && plain) centre = std::pow(s.redshift[0], 4.0) * spec.emissivity(s.radius[0]);
      }
      if (!plain) continue;
      const double v = image.intensity[0][static_cast<std::size_t>(r * spec.width + c)];
      EXPECT_NEAR(v, centre, 2e-2 * centre) << "pixel (" << r << ", " << c << ")";
      ++compared;
    }
  EXPECT_GT(compared, 40);
}

TEST(RingImage, RefusesBadInput) {
  const KerrDiskMap map(kerr(0.5), 1e7, 1.0, 6.0, 30.0);
  auto refused = [&](auto change, const char* what) {
    RingImageSpec spec;
    spec.width = spec.height = 8;
    change(spec);
    try {
      (void)ring_image(map, spec);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("ring image: "), std::string::npos) << e.what();
    }
  };
  refused([](RingImageSpec& s) { s.width = 0; }, "width 0");
  refused([](RingImageSpec& s) { s.half_width = -1.0; }, "negative field");
  refused([](RingImageSpec& s) { s.ring_cuts = 1; }, "one cut");
  refused([](RingImageSpec& s) { s.redshift_power = std::numeric_limits<double>::infinity(); }, "infinite power");
  refused([](RingImageSpec& s) { s.emissivity.r_break = 0.0; }, "break at 0");
  DiskLight light;
  EXPECT_THROW((void)measure_rings(map, light, 1), std::invalid_argument);
}

}  // namespace
