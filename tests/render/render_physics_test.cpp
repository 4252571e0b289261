// Physics of rendered frames, checked against closed forms (reference/schwarzschild.md, special relativity):
//  - the shadow's angular radius for static cameras, sin a = (3 sqrt 3 M / r_o) sqrt(1 - 2M/r_o), within one
//    pixel in the "object" channel (general and symmetric-sky tracers);
//  - left-right and up-down mirror symmetry of a symmetric frame;
//  - flat space: every pixel's sky direction is its camera-frame direction (1e-12); a moving camera shows
//    aberration cos a_sky = (cos a_cam - beta) / (1 - beta cos a_cam) and the Doppler factor exactly;
//  - static emitters (horizon guard, sky sphere): f_obs / f_src = sqrt(1 - 2M/r) / sqrt(1 - 2M/r_o);
//  - Keplerian disk: hits on theta = pi/2 within its radii, redshift from the conserved E and L_z;
//  - a failed ray is a flat colour with NaN data, counted, never a NaN colour.
// Images are small (<= 48 x 48) so that the suite runs in a few seconds.
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/static_frame.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/straight_line.hpp"
#include "grtrace/trace/symmetric_scene_tracer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace render_physics_test {

using namespace grtrace;

namespace {

constexpr double pi = std::numbers::pi;
using Tableau = DormandPrince54;
using Control = PIController;

struct TestCamera {
  double r = 20.0, theta_deg = 90.0, phi_deg = 0.0;
  Vec3 beta = Vec3::Zero(), look = Vec3(-1, 0, 0), up = Vec3(0, -1, 0);
  int width = 32, height = 32;
  double fov = 90.0;
};

Camera make_camera(const SchwarzschildMetric& m, const TestCamera& c) {
  const Vec4 x(0.0, c.r, c.theta_deg * pi / 180.0, c.phi_deg * pi / 180.0);
  const Mat4 g = m.metric(x);
  const StaticFrame f(g);
  return Camera(x, make_tetrad(g, f.velocity(c.beta), f.spatial(c.look), f.spatial(c.up)), c.width, c.height, c.fov);
}

TraceSettings settings(double sky_radius = 400.0, double rtol = 1e-10, double atol = 1e-12) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, atol};
  s.escape_radius = sky_radius;
  return s;
}

BackgroundScene scene_named(const std::string& name) {
  StandardSceneSpec spec;
  spec.name = name;
  return background_scene(spec);
}

auto general_tracer(const SchwarzschildMetric& m, const TraceSettings& s, const std::string& scene = "checker") {
  return make_general_tracer<Tableau, Control>(m, s, AngleCorrection::exact, scene_named(scene));
}

auto symmetric_tracer(const SchwarzschildMetric& m, const TraceSettings& s, const Camera& cam, int nodes) {
  return SymmetricSceneTracer<Tableau, Control, BackgroundScene>(m, s, cam, AngleCorrection::exact,
                                                                 scene_named("checker"), nodes);
}

/// The library's frame pipeline (render/frame.hpp), quietly.
template <class Tracer>
Image render(const Tracer& tracer, const Camera& cam, RenderStats* stats = nullptr) {
  RenderOptions options;
  options.progress = ProgressMode::never;
  Frame frame = render_frame(cam, tracer, options);
  if (stats) *stats = frame.stats;
  return std::move(frame.image);
}

/// Cartesian unit vectors of the spherical chart at (theta, phi).
struct Basis {
  Vec3 r, th, ph;
  Basis(double theta, double phi) {
    const double st = std::sin(theta), ct = std::cos(theta), sp = std::sin(phi), cp = std::cos(phi);
    r = Vec3(st * cp, st * sp, ct);
    th = Vec3(ct * cp, ct * sp, -st);
    ph = Vec3(-sp, cp, 0.0);
  }
};

Vec3 unit(const exact::SkyDirection& d) {
  return Vec3(std::sin(d.theta) * std::cos(d.phi), std::sin(d.theta) * std::sin(d.phi), std::cos(d.theta));
}

/// Components V^a = eta_aa g(e_a, V) of a coordinate vector in the camera's tetrad.
Vec4 in_tetrad(const Tetrad& t, const Mat4& g, const Vec4& v) {
  Vec4 c;
  for (int a = 0; a < 4; ++a) c[a] = (a == 0 ? 1.0 : -1.0) * t.e[static_cast<std::size_t>(a)].dot(g * v);
  return c;
}

double wrapped(double angle) { return std::remainder(angle, 2.0 * pi); }

double shadow_angle(double r_o) { return std::asin(3.0 * std::sqrt(3.0) / r_o * std::sqrt(1.0 - 2.0 / r_o)); }

/// Every pixel clearly inside the predicted shadow (by more than one pixel) is horizon, every pixel clearly
/// outside is sky; and the shadow's radius from its pixel count matches the prediction within one pixel.
void check_shadow(const Image& image, const Camera& cam, double a, const std::string& what) {
  SCOPED_TRACE(what);
  const double pitch = 2.0 * cam.tan_half_fov() / (cam.width() - 1);  // pixel size in the tangent plane
  long horizon = 0, misplaced = 0;
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const PixelSample p = image.sample(col, row);
      const double alpha = std::acos(cam.pixel_direction(col, row)[0]);
      const double one_pixel = pitch * std::cos(alpha) * std::cos(alpha);
      if (p.object == kHorizonObject) {
        ++horizon;
        EXPECT_EQ(p.status, RayStatus::captured);
      } else {
        EXPECT_EQ(p.object, kSkyObject);
        EXPECT_EQ(p.status, RayStatus::escaped);
      }
      const bool inside = alpha < a - one_pixel, outside = alpha > a + one_pixel;
      if ((inside && p.object != kHorizonObject) || (outside && p.object != kSkyObject)) {
        ++misplaced;
        ADD_FAILURE() << "pixel " << col << "," << row << " at " << alpha << " rad, shadow edge at " << a;
      }
    }
  EXPECT_EQ(misplaced, 0);
  const double radius_pixels = std::sqrt(static_cast<double>(horizon) / pi);
  const double predicted = std::tan(a) / pitch;
  EXPECT_NEAR(radius_pixels, predicted, 1.0) << "shadow radius in pixels";
}

}  // namespace

// ---- shadow --------------------------------------------------------------------------------------------

class ShadowSize : public ::testing::TestWithParam<double> {};

TEST_P(ShadowSize, MatchesTheStaticObserverFormulaWithinOnePixel) {
  const double r_o = GetParam();
  const double a = shadow_angle(r_o);
  const SchwarzschildMetric m{1.0};
  TestCamera spec;
  spec.r = r_o;
  spec.width = spec.height = 48;
  spec.fov = 2.0 * std::atan(2.2 * std::tan(a)) * 180.0 / pi;  // the shadow fills ~45% of the frame's width
  const Camera cam = make_camera(m, spec);
  const TraceSettings s = settings(4.0 * r_o + 100.0);
  check_shadow(render(general_tracer(m, s), cam), cam, a, "general tracer");
  check_shadow(render(symmetric_tracer(m, s, cam, 256), cam), cam, a, "symmetric-sky tracer");
}

INSTANTIATE_TEST_SUITE_P(StaticCameras, ShadowSize, ::testing::Values(10.0, 20.0, 50.0));

TEST(ShadowSize, ReferenceAnglesFromTheTable) {
  EXPECT_NEAR(shadow_angle(10.0), 0.4833612822, 1e-10);
  EXPECT_NEAR(shadow_angle(100.0), 0.0514619964, 1e-10);
}

// ---- symmetry ------------------------------------------------------------------------------------------

TEST(MirrorSymmetry, StaticCameraLookingAtTheHoleSeesAMirrorSymmetricFrame) {
  // Camera in the equatorial plane at phi = 0 looking at the hole, up = north: left-right mirror is phi -> -phi,
  // up-down mirror is theta -> pi - theta. The data channels must show both.
  const SchwarzschildMetric m{1.0};
  TestCamera spec;
  spec.r = 15.0;
  spec.width = 32;
  spec.height = 24;
  const Camera cam = make_camera(m, spec);
  const Image image = render(general_tracer(m, settings(100.0)), cam);
  const double tol = 1e-5;  // float channels; rays near the shadow edge amplify round-off of the mirrored pixel
  long compared = 0;
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const PixelSample p = image.sample(col, row);
      const PixelSample lr = image.sample(cam.width() - 1 - col, row);
      const PixelSample ud = image.sample(col, cam.height() - 1 - row);
      for (const PixelSample* q : {&lr, &ud}) {
        EXPECT_EQ(p.object, q->object) << col << "," << row;
        EXPECT_EQ(p.status, q->status) << col << "," << row;
        EXPECT_NEAR(p.redshift, q->redshift, 1e-6f * std::abs(p.redshift)) << col << "," << row;
      }
      if (p.status != RayStatus::escaped) continue;
      ++compared;
      EXPECT_NEAR(p.sky_theta, lr.sky_theta, tol) << col << "," << row;
      EXPECT_NEAR(wrapped(p.sky_phi + lr.sky_phi), 0.0, tol) << col << "," << row;
      EXPECT_NEAR(p.sky_theta, pi - static_cast<double>(ud.sky_theta), tol) << col << "," << row;
      EXPECT_NEAR(wrapped(p.sky_phi - ud.sky_phi), 0.0, tol) << col << "," << row;
    }
  EXPECT_GT(compared, cam.width() * cam.height() / 2);
}

// ---- flat space ----------------------------------------------------------------------------------------

TEST(Minkowski, EverySkyDirectionIsTheCameraFrameDirection) {
  const SchwarzschildMetric flat{0.0};  // M = 0: Minkowski in spherical coordinates
  TestCamera spec;
  spec.r = 20.0;
  spec.theta_deg = 70.0;
  spec.phi_deg = 30.0;
  spec.look = Vec3(-1.0, 0.3, 0.2);
  spec.up = Vec3(0.1, -1.0, 0.0);
  spec.width = 33;
  spec.height = 21;
  spec.fov = 120.0;
  const Camera cam = make_camera(flat, spec);
  const Vec4 x = cam.position();
  const Mat4 g = flat.metric(x);
  const StaticFrame frame(g);
  const Basis b(x[2], x[3]);
  auto cartesian = [&](const Vec4& v) {  // static-frame spatial vector -> Cartesian
    Vec3 c = Vec3::Zero();
    const Vec3 axes[] = {b.r, b.th, b.ph};
    for (int i = 0; i < 3; ++i) c -= frame.e[static_cast<std::size_t>(i + 1)].dot(g * v) * axes[i];
    return c;
  };
  const Tetrad& t = cam.tetrad();
  for (AngleCorrection correction : {AngleCorrection::flat, AngleCorrection::exact}) {
    const StraightLineTracer tracer(MinkowskiSpherical{}, 1000.0, correction, scene_named("checker"));
    double worst = 0.0;
    for (int row = 0; row < cam.height(); ++row)
      for (int col = 0; col < cam.width(); ++col) {
        const Vec3 d = cam.pixel_direction(col, row);
        const Vec3 expected = cartesian(d[0] * t.e[1] + d[1] * t.e[2] + d[2] * t.e[3]).normalized();
        const RayOutcome o = tracer.trace(cam.pixel_state(col, row));
        ASSERT_EQ(o.status, RayStatus::escaped);
        worst = std::max(worst, (unit(o.where) - expected).norm());
        EXPECT_NEAR(o.redshift, 1.0, 1e-14);  // static camera, static sky, flat space: no shift
      }
    EXPECT_LT(worst, 1e-12);
  }
}

TEST(Minkowski, MovingCameraShowsAberrationAndTheDopplerFactor) {
  const SchwarzschildMetric flat{0.0};
  const Vec3 velocities[] = {{-0.6, 0.0, 0.0}, {0.0, 0.0, 0.8}, {0.3, -0.4, 0.5}, {0.95, 0.0, 0.0}};
  for (const Vec3& beta_vec : velocities) {
    SCOPED_TRACE("beta " + std::to_string(beta_vec[0]) + "," + std::to_string(beta_vec[1]) + "," +
                 std::to_string(beta_vec[2]));
    TestCamera spec;
    spec.r = 20.0;
    spec.theta_deg = 60.0;
    spec.phi_deg = -20.0;
    spec.beta = beta_vec;
    spec.width = 25;
    spec.height = 19;
    spec.fov = 150.0;
    const Camera cam = make_camera(flat, spec);
    const Vec4 x = cam.position();
    const Mat4 g = flat.metric(x);
    const StaticFrame frame(g);
    const Basis b(x[2], x[3]);
    const double beta = beta_vec.norm(), gamma = 1.0 / std::sqrt(1.0 - beta * beta);
    // Direction of motion: in the sky's (static, Cartesian) frame and in the camera frame (where the static
    // observer moves with -beta along it).
    const Vec3 motion_sky = (beta_vec[0] * b.r + beta_vec[1] * b.th + beta_vec[2] * b.ph).normalized();
    const Vec3 motion_cam = -in_tetrad(cam.tetrad(), g, frame.e[0]).tail<3>().normalized();
    const StraightLineTracer tracer(MinkowskiSpherical{}, 1000.0, AngleCorrection::exact, scene_named("checker"));
    double worst_angle = 0.0, worst_doppler = 0.0, worst_plane = 0.0;
    for (int row = 0; row < cam.height(); ++row)
      for (int col = 0; col < cam.width(); ++col) {
        const Vec3 d = cam.pixel_direction(col, row);  // (forward, up, right), unit
        const double cos_cam = d.dot(motion_cam);
        const RayOutcome o = tracer.trace(cam.pixel_state(col, row));
        ASSERT_EQ(o.status, RayStatus::escaped);
        const Vec3 n = unit(o.where);
        const double cos_sky = n.dot(motion_sky);
        worst_angle = std::max(worst_angle, std::abs(cos_sky - (cos_cam - beta) / (1.0 - beta * cos_cam)));
        const double doppler = 1.0 / (gamma * (1.0 - beta * cos_cam));  // = gamma (1 + beta cos a_sky)
        worst_doppler = std::max(worst_doppler, std::abs(o.redshift / doppler - 1.0));
        worst_doppler = std::max(worst_doppler, std::abs(o.redshift / (gamma * (1.0 + beta * cos_sky)) - 1.0));
        // The aberration moves directions only towards or away from the motion: the sky direction's part
        // across the motion has the camera direction's transverse azimuth (checked via the static frame).
        const Vec3 d_static = [&] {
          const Tetrad& t = cam.tetrad();
          const Vec4 v = d[0] * t.e[1] + d[1] * t.e[2] + d[2] * t.e[3];  // camera-frame spatial direction
          // Its projection orthogonal to the motion is the same geometric vector in both frames.
          Vec3 c = Vec3::Zero();
          const Vec3 axes[] = {b.r, b.th, b.ph};
          for (int i = 0; i < 3; ++i) c -= frame.e[static_cast<std::size_t>(i + 1)].dot(g * v) * axes[i];
          return c;
        }();
        const Vec3 tn = n - n.dot(motion_sky) * motion_sky, td = d_static - d_static.dot(motion_sky) * motion_sky;
        if (tn.norm() > 1e-6 && td.norm() > 1e-6) worst_plane = std::max(worst_plane, (tn.normalized() - td.normalized()).norm());
      }
    EXPECT_LT(worst_angle, 1e-12);
    EXPECT_LT(worst_doppler, 1e-12);
    EXPECT_LT(worst_plane, 1e-10);
  }
}

// ---- redshift ------------------------------------------------------------------------------------------

TEST(Redshift, StaticEmittersMatchTheGravitationalFormula) {
  const SchwarzschildMetric m{1.0};
  TestCamera spec;
  spec.r = 8.0;
  spec.width = 24;
  spec.height = 20;
  spec.fov = 120.0;
  const Camera cam = make_camera(m, spec);
  const double sky = 60.0;
  const TraceSettings s = settings(sky);
  const double f_o = std::sqrt(1.0 - 2.0 / spec.r);
  const double guard = (1.0 + s.horizon_epsilon) * 2.0;
  const auto general = general_tracer(m, s, "redshift");
  const auto symmetric = symmetric_tracer(m, s, cam, 256);
  long captured = 0, escaped = 0;
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const GeodesicState y0 = cam.pixel_state(col, row);
      const RayOutcome o = general.trace(y0), q = symmetric.trace(y0);
      ASSERT_FALSE(is_failure(o.status));
      ASSERT_EQ(o.status, q.status) << col << "," << row;
      const double r_src = o.status == RayStatus::captured ? guard : sky;
      const double expected = std::sqrt(1.0 - 2.0 / r_src) / f_o;
      EXPECT_NEAR(o.redshift / expected, 1.0, 1e-8) << col << "," << row;
      EXPECT_NEAR(q.redshift / expected, 1.0, 1e-12) << col << "," << row;
      (o.status == RayStatus::captured ? captured : escaped) += 1;
      if (o.status == RayStatus::captured) {
        EXPECT_NEAR(o.radius, guard, 1e-9);  // located on the guard sphere, not a step late
        EXPECT_EQ(o.object, kHorizonObject);
      }
    }
  EXPECT_GT(captured, 20);
  EXPECT_GT(escaped, 20);
  // Through the whole pipeline into the image's float channel.
  const Image image = render(general, cam);
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const PixelSample p = image.sample(col, row);
      const double r_src = p.object == kHorizonObject ? guard : sky;
      EXPECT_NEAR(p.redshift, std::sqrt(1.0 - 2.0 / r_src) / f_o, 1e-6);
    }
}

TEST(Redshift, KeplerianDiskHitsThePlaneWithTheConservedQuantityRedshift) {
  const SchwarzschildMetric m{1.0};
  TestCamera spec;
  spec.r = 30.0;
  spec.theta_deg = 60.0;
  spec.width = 32;
  spec.height = 24;
  spec.fov = 70.0;
  const Camera cam = make_camera(m, spec);
  ThinDisk disk;
  disk.r_in = 6.0;
  disk.r_out = 20.0;
  const auto tracer = make_general_tracer<Tableau, Control>(m, settings(100.0), AngleCorrection::exact,
                                                            make_scene(StarFieldSky{}, HorizonPaint{}, disk));
  const Mat4 g0 = m.metric(cam.position());
  long hits = 0;
  double left = 0.0, right = 0.0;
  long n_left = 0, n_right = 0;
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const GeodesicState y0 = cam.pixel_state(col, row);
      const RayOutcome o = tracer.trace(y0);
      ASSERT_FALSE(is_failure(o.status));
      if (o.status != RayStatus::hit) continue;
      ++hits;
      EXPECT_EQ(o.object, kFirstSceneObject);
      EXPECT_NEAR(o.where.theta, pi / 2, 1e-9);
      EXPECT_GE(o.radius, disk.r_in);
      EXPECT_LE(o.radius, disk.r_out);
      // Conserved along the ray: k_t = g_tt k^t and k_phi = g_phiphi k^phi. The emitter u = u^t (1, 0, 0, Omega)
      // sees g(u, k) = u^t (k_t + Omega k_phi); the camera sees g(e_0, k) = -1.
      const double kt = g0(0, 0) * y0[4], kphi = g0(3, 3) * y0[7];
      const double r = o.radius, omega = std::sqrt(1.0 / (r * r * r)), ut = 1.0 / std::sqrt(1.0 - 3.0 / r);
      const double expected = -1.0 / (ut * (kt + omega * kphi));
      EXPECT_NEAR(o.redshift / expected, 1.0, 1e-7) << col << "," << row;
      (col < cam.width() / 2 ? left : right) += o.redshift;
      (col < cam.width() / 2 ? n_left : n_right) += 1;
    }
  EXPECT_GT(hits, cam.width() * cam.height() / 10);
  // Prograde (+phi) rotation with +phi to the right: the left side approaches the camera (bluer).
  ASSERT_GT(n_left, 0);
  ASSERT_GT(n_right, 0);
  EXPECT_GT(left / static_cast<double>(n_left), right / static_cast<double>(n_right));
}

// ---- failures ------------------------------------------------------------------------------------------

TEST(FailedRays, GetAFlatVisibleColourNaNDataAndAreCounted) {
  const SchwarzschildMetric m{1.0};
  TestCamera spec;
  spec.width = 12;
  spec.height = 10;
  const Camera cam = make_camera(m, spec);
  TraceSettings s = settings();
  s.max_steps = 3;
  const auto tracer = general_tracer(m, s);
  RenderStats stats;
  const Image image = render(tracer, cam, &stats);
  EXPECT_EQ(stats.count(RayStatus::max_steps), 120);
  EXPECT_EQ(stats.bad_colour, 0);
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const PixelSample p = image.sample(col, row);
      EXPECT_EQ(p.status, RayStatus::max_steps);
      EXPECT_EQ(p.rgb, tracer.scene().failure);
      EXPECT_TRUE(std::isnan(p.redshift));
      EXPECT_TRUE(std::isnan(p.sky_theta));
      EXPECT_TRUE(std::isnan(p.sky_phi));
      EXPECT_EQ(p.steps, 3);
    }
  for (RayStatus st : {RayStatus::max_steps, RayStatus::step_underflow, RayStatus::non_finite})
    for (std::string_view name : kStandardSceneNames) {
      RayOutcome o;
      o.status = st;
      o.object = kFirstSceneObject;  // even where the scene has an object there
      StandardSceneSpec preset;
      preset.name = std::string(name);
      with_standard_scene(preset, [&](const auto& scene) {
        const PixelSample p = scene.shade(o);
        EXPECT_TRUE(std::isfinite(p.rgb[0]) && std::isfinite(p.rgb[1]) && std::isfinite(p.rgb[2]));
        EXPECT_EQ(p.rgb, scene.failure);
        EXPECT_TRUE(std::isnan(p.redshift));
      });
    }
}

}  // namespace render_physics_test
