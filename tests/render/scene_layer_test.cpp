// The open scene layer: scene tracing generic in the metric, objects by concept, the frame pipeline as
// library code. Each test checks physics against a closed form or an independent computation:
//  - the generic tracer with SchwarzschildMetric against the Schwarzschild-only formulas it replaced (static
//    emitter sqrt(1 - 2M/r) k^t, Keplerian u^t = 1/sqrt(1 - 3M/r), elliptic continuation), main and disk frames;
//  - Schwarzschild written in another chart (isotropic coordinates, a metric of this file) gives the same sky;
//  - a user's star: image position and angular radius in flat space, the static-emitter redshift in Schwarzschild;
//  - a user's metric (Reissner-Nordstrom, examples/scenes): Q = 0 is Schwarzschild, horizon, shadow size;
//  - two objects of one kind get distinct positions and names; flat space is traced by straight lines through
//    the same objects, and a moving sphere's outline stays a circle (Terrell-Penrose) with the Doppler factor;
//  - observers: the ZAMO equals the static observer for a static metric; bad objects are refused.
#include "glowing_star.hpp"
#include "moving_sphere.hpp"
#include "reissner_nordstrom.hpp"

#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/straight_line.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace scene_layer_test {

using namespace grtrace;

namespace {

constexpr double kPi = std::numbers::pi;
using Tableau = DormandPrince54;
using Control = PIController;

TraceSettings settings(double sky, double rtol = 1e-10) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-2 * rtol};
  s.escape_radius = sky;
  return s;
}

RenderOptions quiet() {
  RenderOptions o;
  o.progress = ProgressMode::never;
  return o;
}

CameraSpec camera_spec(double r, double theta_deg, int size, double fov) {
  CameraSpec spec;
  spec.position = Vec4(0.0, r, theta_deg * kPi / 180.0, 0.0);
  spec.width = spec.height = size;
  spec.fov_degrees = fov;
  return spec;
}

// ---- 1. The generic tracer reproduces the Schwarzschild-only formulas it replaced --------------------------

/// What the scene tracer computed before it was generic, written out with Schwarzschild's closed forms.
struct SchwarzschildReference {
  GeodesicTracer<SchwarzschildMetric, Tableau, Control> tracer;
  std::optional<ThinDisk> disk;

  RayOutcome trace(const GeodesicState& y0) const {
    const double M = tracer.metric().mass;
    const TraceResult r = disk ? tracer.trace(y0, *disk) : tracer.trace(y0);
    RayOutcome o;
    o.status = r.status;
    const GeodesicState& y = r.final_state;
    auto static_energy = [&] { return std::sqrt(1.0 - 2.0 * M / y[1]) * y[4]; };
    if (r.status == RayStatus::escaped) {
      o.object = kSkyObject;
      o.where = exact::asymptotic_direction(r.step_end_state, M).value();
      o.redshift = -1.0 / static_energy();
    } else if (r.status == RayStatus::captured) {
      o.object = kHorizonObject;
      o.redshift = -1.0 / static_energy();
    } else if (r.status == RayStatus::hit) {
      o.object = kFirstSceneObject;
      const double rr = y[1], ut = 1.0 / std::sqrt(1.0 - 3.0 * M / rr), omega = std::sqrt(M / (rr * rr * rr));
      const Vec4 u(ut, 0.0, 0.0, ut * omega);
      o.redshift = -1.0 / u.dot(tracer.metric().metric(y.head<4>()) * y.tail<4>());
    }
    return o;
  }
};

template <class Tracer>
void expect_same_as_reference(const Tracer& tracer, const SchwarzschildReference& reference, const Camera& cam,
                              long& hits) {
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const GeodesicState y0 = cam.pixel_state(col, row);
      const RayOutcome a = tracer.trace(y0), b = reference.trace(y0);
      ASSERT_EQ(a.status, b.status) << col << "," << row;
      ASSERT_EQ(a.object, b.object) << col << "," << row;
      EXPECT_NEAR(a.redshift, b.redshift, 1e-9 * std::abs(b.redshift)) << col << "," << row;
      if (a.status == RayStatus::escaped) {
        EXPECT_LT(angular_distance(a.where, b.where), 1e-9) << col << "," << row;
      }
      hits += a.status == RayStatus::hit;
    }
}

TEST(GenericTracer, ReproducesTheSchwarzschildMainFrame) {
  const SchwarzschildMetric m{1.0};
  const Camera cam = make_camera(m, camera_spec(200.0, 90.0, 48, 90.0));
  const auto tracer = make_general_tracer<Tableau, Control>(m, settings(400.0), AngleCorrection::exact,
                                                            background_scene(StandardSceneSpec{}));
  const SchwarzschildReference reference{{m, settings(400.0)}, std::nullopt};
  long hits = 0;
  expect_same_as_reference(tracer, reference, cam, hits);
}

TEST(GenericTracer, ReproducesTheSchwarzschildDiskFrame) {
  const SchwarzschildMetric m{1.0};
  const Camera cam = make_camera(m, camera_spec(50.0, 80.0, 40, 60.0));
  StandardSceneSpec preset;
  preset.name = "disk";
  const auto tracer = make_general_tracer<Tableau, Control>(m, settings(400.0), AngleCorrection::exact,
                                                            disk_scene(preset));
  const SchwarzschildReference reference{{m, settings(400.0)}, preset.disk};
  long hits = 0;
  expect_same_as_reference(tracer, reference, cam, hits);
  EXPECT_GT(hits, 100);  // the disk is in the picture
}

// ---- 2. Same physics in another chart ------------------------------------------------------------------

/// Schwarzschild in isotropic coordinates (t, rho, theta, phi): ds^2 = A dt^2 - B (drho^2 + rho^2 dOmega^2) with
/// A = ((1 - m)/(1 + m))^2, B = (1 + m)^4, m = M / (2 rho); r = rho (1 + m)^2, horizon at rho = M/2.
struct IsotropicSchwarzschild {
  static constexpr std::string_view name = "schwarzschild-isotropic";
  static constexpr Chart chart = Chart::spherical;
  double mass = 1.0;

  double areal_radius(double rho) const { return rho * std::pow(1.0 + mass / (2.0 * rho), 2); }
  Mat4 metric(const Vec4& x) const {
    const double rho = x[1], m = mass / (2.0 * rho), s = std::sin(x[2]);
    const double A = std::pow((1.0 - m) / (1.0 + m), 2), B = std::pow(1.0 + m, 4);
    return Vec4(A, -B, -B * rho * rho, -B * rho * rho * s * s).asDiagonal();
  }
  Christoffel christoffel(const Vec4& x) const {
    const double rho = x[1], m = mass / (2.0 * rho), s = std::sin(x[2]), c = std::cos(x[2]);
    const double A = std::pow((1.0 - m) / (1.0 + m), 2), B = std::pow(1.0 + m, 4);
    const double dA = 4.0 * (1.0 - m) * m / (rho * std::pow(1.0 + m, 3)), dB = -4.0 * std::pow(1.0 + m, 3) * m / rho;
    Christoffel G;
    for (auto& g : G) g.setZero();
    G[0](0, 1) = G[0](1, 0) = dA / (2.0 * A);
    G[1](0, 0) = dA / (2.0 * B);
    G[1](1, 1) = dB / (2.0 * B);
    G[1](2, 2) = -(rho + rho * rho * dB / (2.0 * B));
    G[1](3, 3) = G[1](2, 2) * s * s;
    G[2](1, 2) = G[2](2, 1) = G[3](1, 3) = G[3](3, 1) = 1.0 / rho + dB / (2.0 * B);
    G[2](3, 3) = -s * c;
    G[3](2, 3) = G[3](3, 2) = c / s;
    return G;
  }
  Vec4 acceleration(const Vec4& x, const Vec4& k) const { return acceleration_from_christoffel(christoffel(x), k); }
  double radius(const Vec4& x) const { return x[1]; }
  double horizon_radius() const { return mass / 2.0; }
  Vec3 to_cartesian(const Vec4& x) const { return spherical_to_cartesian(x); }
  /// Optional trait: the exact continuation, through the chart change to Schwarzschild coordinates
  /// (r = rho (1 + m)^2, dr/drho = (1 - m)(1 + m); the angles and t are shared).
  std::optional<SkyDirection> asymptotic_direction(const GeodesicState& y) const {
    const double m = mass / (2.0 * y[1]);
    GeodesicState z = y;
    z[1] = areal_radius(y[1]);
    z[5] = (1.0 - m) * (1.0 + m) * y[5];
    return exact::asymptotic_direction(z, mass);
  }
};

TEST(GenericTracer, SchwarzschildInIsotropicCoordinatesShowsTheSameSky) {
  const SchwarzschildMetric schw{1.0};
  const IsotropicSchwarzschild iso{1.0};
  // The same event: areal radius 20 M, i.e. rho with rho (1 + 1/(2 rho))^2 = 20.
  auto rho_of = [](double r) { return 0.5 * (r - 1.0 + std::sqrt(r * (r - 2.0))); };  // inverse of r(rho), M = 1
  const double r_cam = 20.0, rho_cam = rho_of(r_cam);
  ASSERT_NEAR(iso.areal_radius(rho_cam), r_cam, 1e-12);
  const Camera cam_s = make_camera(schw, camera_spec(r_cam, 70.0, 32, 100.0));
  CameraSpec spec_i = camera_spec(rho_cam, 70.0, 32, 100.0);
  const Camera cam_i = make_camera(iso, spec_i);
  const double sky = 300.0, rho_sky = rho_of(sky);
  const auto scene = background_scene(StandardSceneSpec{});
  const auto ts = make_general_tracer<Tableau, Control>(schw, settings(sky), AngleCorrection::exact, scene);
  const auto ti = make_general_tracer<Tableau, Control>(iso, settings(rho_sky), AngleCorrection::exact, scene);
  long escaped = 0, captured = 0;
  for (int row = 0; row < 32; ++row)
    for (int col = 0; col < 32; ++col) {
      const RayOutcome a = ts.trace(cam_s.pixel_state(col, row)), b = ti.trace(cam_i.pixel_state(col, row));
      ASSERT_EQ(a.object, b.object) << col << "," << row;
      if (a.status != RayStatus::escaped) {
        ++captured;
        continue;
      }
      ++escaped;
      EXPECT_LT(angular_distance(a.where, b.where), 1e-7) << col << "," << row;
      EXPECT_NEAR(a.redshift, b.redshift, 1e-9) << col << "," << row;  // static emitters on the same sphere
    }
  EXPECT_GT(escaped, 200);
  EXPECT_GT(captured, 20);
}

// ---- 3. A user's object: the glowing star ----------------------------------------------------------------

TEST(GlowingStarScene, InFlatSpaceItsImageIsWhereAndAsLargeAsGeometrySays) {
  // Camera at r = 30 on the x axis looking at the origin; the star (radius 2) on the axis at x = 10: distance 20,
  // angular radius asin(2/20), centred in the frame. Traced by the integrating tracer with M = 0 (no horizon is
  // then traced at all) and by straight lines: the same pixels.
  const MinkowskiSpherical flat;
  const int n = 81;
  const double fov = 20.0;
  const Camera cam = make_camera(flat, camera_spec(30.0, 90.0, n, fov));
  GlowingStar star;
  star.centre = Vec3(10.0, 0.0, 0.0);
  star.radius = 2.0;
  const auto scene = make_scene(StarFieldSky{}, HorizonPaint{}, star);
  const auto general = make_general_tracer<Tableau, Control>(flat, settings(100.0), AngleCorrection::flat, scene);
  const StraightLineTracer straight(flat, 100.0, AngleCorrection::flat, scene, 1024);
  const double alpha = std::asin(2.0 / 20.0);
  const double step = 2.0 * std::tan(fov * kPi / 360.0) / (n - 1);  // tan-plane size of one pixel
  for (const auto* name : {"general", "straight"}) {
    int first = -1, last = -1;
    for (int col = 0; col < n; ++col) {
      const GeodesicState y0 = cam.pixel_state(col, (n - 1) / 2);
      const RayOutcome o = std::string(name) == "general" ? general.trace(y0) : straight.trace(y0);
      if (o.object == kFirstSceneObject) {
        if (first < 0) first = col;
        last = col;
        EXPECT_NEAR(o.redshift, 1.0, 1e-12) << "static star, static camera, flat space";
      }
    }
    ASSERT_GE(first, 0) << name;
    EXPECT_EQ(first + last, n - 1) << name << ": the image is centred";
    const double half_width = 0.5 * (last - first) * step;  // tan of the angular radius, to within a pixel
    EXPECT_NEAR(std::atan(half_width), alpha, std::atan(step)) << name;
  }
}

TEST(GlowingStarScene, AStaticStarIsRedshiftedByTheRatioOfLapses) {
  // f_obs / f_src = sqrt(1 - 2M/r_src) / sqrt(1 - 2M/r_cam) for a static star and a static camera.
  const SchwarzschildMetric m{1.0};
  const Camera cam = make_camera(m, camera_spec(30.0, 85.0, 40, 60.0));
  const GlowingStar star;
  check_star(m, star, cam.position());
  const auto tracer = make_general_tracer<Tableau, Control>(m, settings(400.0), AngleCorrection::exact,
                                                            make_scene(StarFieldSky{}, HorizonPaint{}, star));
  const Frame frame = render_frame(cam, tracer, quiet());
  EXPECT_EQ(frame.image.metadata.at("object_names"), "sky,horizon,star");
  long pixels = 0;
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const RayOutcome o = tracer.trace(cam.pixel_state(col, row));
      if (o.object != kFirstSceneObject) continue;
      ++pixels;
      EXPECT_NEAR(star(o.state), 0.0, 1e-6) << "the hit lies on the star's surface";
      const double expected = std::sqrt(1.0 - 2.0 / o.radius) / std::sqrt(1.0 - 2.0 / 30.0);
      EXPECT_NEAR(o.redshift, expected, 1e-9) << col << "," << row;
    }
  EXPECT_GT(pixels, 3);
}

TEST(GlowingStarScene, TwoStarsGetTheirOwnPositionsAndNames) {
  const SchwarzschildMetric m{1.0};
  const Camera cam = make_camera(m, camera_spec(30.0, 90.0, 48, 70.0));
  GlowingStar left, right;
  left.centre = Vec3(0.0, 8.0, 0.0);
  right.centre = Vec3(0.0, -8.0, 0.0);
  left.radius = right.radius = 2.0;
  const auto tracer = make_general_tracer<Tableau, Control>(m, settings(400.0), AngleCorrection::exact,
                                                            make_scene(StarFieldSky{}, HorizonPaint{}, left, right));
  EXPECT_EQ(tracer.scene().object_names(), (std::vector<std::string>{"sky", "horizon", "star-1", "star-2"}));
  long on_left = 0, on_right = 0;
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const RayOutcome o = tracer.trace(cam.pixel_state(col, row));
      if (o.object == kFirstSceneObject) {
        ++on_left;
        EXPECT_NEAR(left(o.state), 0.0, 1e-6);
      } else if (o.object == kFirstSceneObject + 1) {
        ++on_right;
        EXPECT_NEAR(right(o.state), 0.0, 1e-6);
      }
    }
  EXPECT_GT(on_left, 5);
  EXPECT_GT(on_right, 5);
}

TEST(GlowingStarScene, BadStarsAreRefusedWithWhatToChange) {
  const SchwarzschildMetric m{1.0};
  const Vec4 camera(0.0, 30.0, kPi / 2, 0.0);
  auto refused = [&](GlowingStar s, const std::string& words) {
    try {
      check_star(m, s, camera);
      ADD_FAILURE() << "accepted a star that should be refused (" << words << ")";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  GlowingStar s;
  s.centre = Vec3(1.0, 0.0, 0.0);
  refused(s, "horizon");
  s = GlowingStar{};
  s.centre = Vec3(30.0, 0.0, 0.5);
  refused(s, "camera is inside");
  s = GlowingStar{};
  s.radius = -1.0;
  refused(s, "radius must be > 0");
  s.radius = std::nan("");
  refused(s, "finite");
}

// ---- 4. A user's metric: Reissner-Nordstrom --------------------------------------------------------------

TEST(ReissnerNordstrom, WithoutChargeItIsSchwarzschild) {
  const SchwarzschildMetric schw{1.0};
  const auto rn = ReissnerNordstromMetric::checked(1.0, 0.0);
  const Camera cam = make_camera(schw, camera_spec(40.0, 80.0, 32, 60.0));
  StandardSceneSpec preset;
  preset.name = "disk";
  const auto a = make_general_tracer<Tableau, Control>(schw, settings(300.0), AngleCorrection::flat, disk_scene(preset));
  const auto b = make_general_tracer<Tableau, Control>(rn, settings(300.0), AngleCorrection::flat, disk_scene(preset));
  for (int row = 0; row < 32; ++row)
    for (int col = 0; col < 32; ++col) {
      const RayOutcome p = a.trace(cam.pixel_state(col, row)), q = b.trace(cam.pixel_state(col, row));
      ASSERT_EQ(p.object, q.object) << col << "," << row;
      EXPECT_NEAR(p.redshift, q.redshift, 1e-9 * std::abs(p.redshift)) << col << "," << row;
      if (p.status == RayStatus::escaped) {
        EXPECT_LT(angular_distance(p.where, q.where), 1e-9);
      }
    }
}

TEST(ReissnerNordstrom, HorizonAndChristoffelsFollowFromTheMetric) {
  for (double q : {0.0, 0.5, 0.9, 0.999}) {
    const auto rn = ReissnerNordstromMetric::checked(1.0, q);
    EXPECT_NEAR(rn.horizon_radius(), 1.0 + std::sqrt(1.0 - q * q), 1e-15);
    EXPECT_NEAR(rn.f(rn.horizon_radius()), 0.0, 1e-12) << "g_tt vanishes on the horizon";
    // Christoffels against central differences of g: Gamma^a_bc = 1/2 g^ad (d_b g_dc + d_c g_db - d_d g_bc).
    const Vec4 x(0.0, 7.3, 1.1, 0.4);
    std::array<Mat4, 4> dg;
    for (int d = 0; d < 4; ++d) {
      const double h = 1e-6;
      dg[static_cast<std::size_t>(d)] = (rn.metric(x + h * Vec4::Unit(d)) - rn.metric(x - h * Vec4::Unit(d))) / (2 * h);
    }
    const Mat4 gi = rn.metric(x).inverse();
    const Christoffel G = rn.christoffel(x);
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int c = 0; c < 4; ++c) {
          double v = 0.0;
          for (int d = 0; d < 4; ++d) {
            const auto D = static_cast<std::size_t>(d), B = static_cast<std::size_t>(b), C = static_cast<std::size_t>(c);
            v += 0.5 * gi(a, d) * (dg[B](d, c) + dg[C](d, b) - dg[D](b, c));
          }
          EXPECT_NEAR(G[static_cast<std::size_t>(a)](b, c), v, 1e-7) << a << b << c << " Q=" << q;
        }
  }
}

TEST(ReissnerNordstrom, ShadowEdgeSitsWhereThePhotonSphereSaysWithinOnePixel) {
  for (double q : {0.6, 0.95}) {
    const auto rn = ReissnerNordstromMetric::checked(1.0, q);
    const double r_o = 30.0, r_ph = rn.photon_sphere(), b_c = r_ph / std::sqrt(rn.f(r_ph));
    const double alpha = std::asin(b_c * std::sqrt(rn.f(r_o)) / r_o);
    const int w = 201;
    CameraSpec spec = camera_spec(r_o, 90.0, 3, 2.0 * alpha * 180.0 / kPi * 1.6);
    spec.width = w;
    const Camera cam = make_camera(rn, spec);
    const auto tracer = make_general_tracer<Tableau, Control>(rn, settings(400.0), AngleCorrection::flat,
                                                              background_scene(StandardSceneSpec{}));
    int last_inside = -1;
    for (int col = (w - 1) / 2; col < w; ++col)
      if (tracer.trace(cam.pixel_state(col, 1)).object == kHorizonObject) last_inside = col;
    ASSERT_GE(last_inside, (w - 1) / 2);
    auto angle = [&](int col) { return std::atan(cam.tan_half_fov() * std::abs(2.0 * col / (w - 1) - 1.0)); };
    EXPECT_LE(angle(last_inside), alpha) << "Q = " << q;
    EXPECT_GE(angle(last_inside + 1), alpha) << "Q = " << q;
  }
}

TEST(ReissnerNordstrom, NakedSingularitiesAndNonsenseAreRefused) {
  for (double q : {1.0, -1.0, 1.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(ReissnerNordstromMetric::checked(1.0, q), std::invalid_argument) << q;
  }
}

// ---- 5. Flat space: straight lines through the same objects ------------------------------------------------

TEST(TerrellRotation, AMovingSphereKeepsACircularOutlineAndShowsTheDopplerFactor) {
  MovingSphere sphere;
  sphere.velocity = Vec3(0.0, 0.9, 0.0);
  sphere.centre_at_zero = Vec3(10.0, 9.0, 0.0);  // seen straight ahead: it was at (10, 0, 0) at t = -10
  sphere.check();
  const MinkowskiMetric flat;
  CameraSpec spec;
  spec.position = Vec4::Zero();
  spec.look = Vec3(1.0, 0.0, 0.0);
  spec.up = Vec3(0.0, 0.0, 1.0);
  spec.width = spec.height = 101;
  spec.fov_degrees = 50.0;
  const Camera cam = make_camera(flat, spec);
  const StraightLineTracer tracer(flat, 40.0, AngleCorrection::flat, make_scene(CheckerSky{}, HorizonPaint{}, sphere),
                                  1024);
  const double gamma = sphere.gamma();
  std::vector<Vec3> edge;
  Vec3 mean = Vec3::Zero();
  long hits = 0;
  for (int row = 0; row < 101; ++row)
    for (int col = 0; col < 101; ++col) {
      const RayOutcome o = tracer.trace(cam.pixel_state(col, row));
      if (o.object != kFirstSceneObject) continue;
      ++hits;
      const Vec3 d = cam.pixel_direction(col, row);
      mean += d;
      // Doppler: g = 1 / (gamma (1 - v . n)), n the photon's direction of travel (minus the traced spatial k).
      const Vec3 n = -o.state.tail<3>().normalized();
      EXPECT_NEAR(o.redshift, 1.0 / (gamma * (1.0 - sphere.velocity.dot(n))), 1e-12);
      EXPECT_NEAR(sphere(o.state), 0.0, 1e-9) << "the hit lies on the moving sphere";
      const bool border = col == 0 || row == 0 || col == 100 || row == 100 ||
                          tracer.trace(cam.pixel_state(col + 1, row)).object != kFirstSceneObject ||
                          tracer.trace(cam.pixel_state(col - 1, row)).object != kFirstSceneObject;
      if (border) edge.push_back(d);
    }
  ASSERT_GT(hits, 500);
  const Vec3 centre = mean.normalized();
  EXPECT_GT(centre[0], 0.999) << "seen straight ahead, where it was when the light left";
  // Every edge pixel at the same angle from the centre (within a pixel's angular size: a circle, not an ellipse
  // flattened by 1/gamma = 0.44 as the Lorentz contraction alone would suggest).
  double lo = 10.0, hi = 0.0;
  for (const Vec3& d : edge) {
    const double a = std::acos(std::clamp(d.dot(centre), -1.0, 1.0));
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  const double pixel = 2.0 * std::tan(25.0 * kPi / 180.0) / 100.0;
  EXPECT_LT(hi - lo, 2.5 * pixel) << "outline radius from " << lo << " to " << hi;
}

TEST(Observers, TheZamoOfAStaticMetricIsTheStaticObserver) {
  const SchwarzschildMetric m{1.0};
  CameraSpec spec = camera_spec(7.0, 60.0, 5, 60.0);
  spec.velocity = Vec3(0.3, -0.2, 0.4);
  const Camera a = make_camera(m, spec);
  spec.observer = ObserverKind::zamo;
  const Camera b = make_camera(m, spec);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT((a.tetrad().e[i] - b.tetrad().e[i]).norm(), 1e-14) << i;
  spec.position[1] = 1.5;
  EXPECT_THROW(make_camera(m, spec), std::invalid_argument) << "inside the horizon";
}

// ---- 6. The example programs refuse bad input before any work ---------------------------------------------

/// The exit status of `command` (shell words); its output is not looked at.
int run_quietly(const std::string& command) { return grtrace::tool_tests::run_command(command).status; }

TEST(ExamplePrograms, RefuseBadInputWithExitTwoAndWriteNothing) {
#ifdef GRTRACE_EXAMPLE_DIR
  const std::filesystem::path dir(GRTRACE_EXAMPLE_DIR);
  const grtrace::tool_tests::ScratchDir scratch("grtrace_scene_layer");
  const std::filesystem::path out = scratch / "bad.exr";
  const std::string o = " --size 16 --out " + out.string();
  EXPECT_EQ(run_quietly((dir / "reissner_nordstrom").string() + " --charge 1" + o), 2);
  EXPECT_EQ(run_quietly((dir / "reissner_nordstrom").string() + " --charge nan" + o), 2);
  EXPECT_EQ(run_quietly((dir / "reissner_nordstrom").string() + " --charge 0.5x" + o), 2);
  EXPECT_EQ(run_quietly((dir / "terrell_rotation").string() + " --beta 1" + o), 2);
  EXPECT_EQ(run_quietly((dir / "star_beside_hole").string() + " --size 0 --out " + out.string()), 2);
  EXPECT_EQ(run_quietly((dir / "star_beside_hole").string() + " --out x.png"), 2);
  EXPECT_EQ(run_quietly((dir / "terrell_rotation").string() + " --size 16 --out /nonexistent-dir/t.exr"), 2);
  EXPECT_FALSE(std::filesystem::exists(out));
#else
  GTEST_SKIP() << "example programs not built";
#endif
}

}  // namespace

}  // namespace scene_layer_test
