// Cameras, tetrads and the scene tracers against closed-form physics.
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/static_frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/straight_line.hpp"
#include "grtrace/trace/symmetric_scene_tracer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace camera_scene_test {

namespace {

using namespace grtrace;
constexpr double kPi = std::numbers::pi;

Camera static_camera(double mass, double r, int w, int h, double fov, Vec3 beta = Vec3::Zero()) {
  const SchwarzschildMetric m{mass};
  const Vec4 x(0.0, r, kPi / 2, 0.0);
  const StaticFrame frame(m.metric(x));
  const Tetrad t = make_tetrad(m.metric(x), frame.velocity(beta), frame.spatial(Vec3(-1, 0, 0)),
                               frame.spatial(Vec3(0, -1, 0)));
  return Camera(x, t, w, h, fov);
}

TraceSettings accurate(double sky) {
  TraceSettings s;
  s.integrator.tolerance = {1e-10, 1e-12};
  s.escape_radius = sky;
  return s;
}

const BackgroundScene kChecker = background_scene(StandardSceneSpec{});

auto general_tracer(double sky) {
  return make_general_tracer<DormandPrince54, PIController>(SchwarzschildMetric{1.0}, accurate(sky),
                                                            AngleCorrection::exact, kChecker);
}

TEST(Tetrad, IsOrthonormalAndRightHandedForRandomObservers) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const SchwarzschildMetric m{1.0};
    const Vec4 x(0.0, 2.5 + 50.0 * (u(rng) + 1.0), 0.2 + 1.3 * (u(rng) + 1.0), 3.0 * u(rng));
    const StaticFrame frame(m.metric(x));
    const Vec3 beta = 0.9 * Vec3(u(rng), u(rng), u(rng)) / std::sqrt(3.0);
    const Vec3 look(u(rng), u(rng), u(rng)), up(u(rng), u(rng), u(rng));
    if (look.cross(up).norm() < 0.1) continue;
    const Tetrad t = make_tetrad(m.metric(x), frame.velocity(beta), frame.spatial(look), frame.spatial(up));
    const Mat4 gram = tetrad_gram(m.metric(x), t);
    EXPECT_LT((gram - Vec4(1, -1, -1, -1).asDiagonal().toDenseMatrix()).cwiseAbs().maxCoeff(), 1e-11);
    Mat4 e;
    for (int a = 0; a < 4; ++a) e.col(a) = t.e[static_cast<std::size_t>(a)];
    EXPECT_GT(e.determinant(), 0.0);
  }
}

TEST(Tetrad, DefaultCameraLooksAtTheHoleWithPhiToTheRight) {
  const Camera cam = static_camera(1.0, 20.0, 3, 3, 90.0);
  const auto& e = cam.tetrad().e;
  EXPECT_LT(e[1][1], 0.0) << "forward is -d/dr";
  EXPECT_LT(e[2][2], 0.0) << "up is -d/dtheta (north)";
  EXPECT_GT(e[3][3], 0.0) << "right is +d/dphi";
  // Row 0 is the top: its pixels look north of the centre (k^theta of the backward ray < 0 means towards theta=0).
  EXPECT_LT(cam.pixel_momentum(1, 0)[2], 0.0);
  EXPECT_GT(cam.pixel_momentum(2, 1)[3], 0.0) << "the right column looks towards +phi";
}

TEST(Tetrad, RefusesBadObservers) {
  const SchwarzschildMetric m{1.0};
  const Vec4 x(0.0, 10.0, kPi / 2, 0.0);
  const StaticFrame frame(m.metric(x));
  EXPECT_THROW(frame.velocity(Vec3(0.6, 0.6, 0.6)), std::invalid_argument);
  EXPECT_THROW(make_tetrad(m.metric(x), frame.velocity(Vec3::Zero()), frame.spatial(Vec3(1, 0, 0)),
                           frame.spatial(Vec3(2, 0, 0))),
               std::invalid_argument);
  const Vec4 null_velocity = frame.e[0] + frame.e[1];
  EXPECT_THROW(make_tetrad(m.metric(x), null_velocity, frame.spatial(Vec3(0, 1, 0)), frame.spatial(Vec3(0, 0, 1))),
               std::invalid_argument);
  const Tetrad ok = make_tetrad(m.metric(x), frame.velocity(Vec3::Zero()), frame.spatial(Vec3(-1, 0, 0)),
                                frame.spatial(Vec3(0, -1, 0)));
  EXPECT_THROW(Camera(x, ok, 10, 10, 180.0), std::invalid_argument);
  EXPECT_THROW(Camera(x, ok, 0, 10, 90.0), std::invalid_argument);
}

TEST(Camera, PixelMomentumIsNullWithUnitEnergy) {
  const Camera cam = static_camera(1.0, 15.0, 33, 17, 70.0, Vec3(0.1, -0.3, 0.5));
  const SchwarzschildMetric m{1.0};
  const Mat4 g = m.metric(cam.position());
  for (int row = 0; row < 17; row += 4)
    for (int col = 0; col < 33; col += 4) {
      const Vec4 k = cam.pixel_momentum(col, row);
      EXPECT_NEAR(k.dot(g * k), 0.0, 1e-12);
      EXPECT_NEAR(cam.tetrad().e[0].dot(g * k), -1.0, 1e-12) << "unit energy, past-directed";
    }
}

// Angular radius of the shadow seen by a static observer: sin a = (3 sqrt 3 / r_o) sqrt(1 - 2 / r_o).
class Shadow : public ::testing::TestWithParam<double> {};

TEST_P(Shadow, EdgeSitsWhereTheFormulaPutsItWithinOnePixel) {
  const double r_o = GetParam();
  const double a = std::asin(3.0 * std::sqrt(3.0) / r_o * std::sqrt(1.0 - 2.0 / r_o));
  const double fov = 2.0 * a * 180.0 / kPi * 1.6;  // the shadow fills ~60% of the width
  const int w = 201, h = 3;                        // odd: the middle row and column are on the axis
  const Camera cam = static_camera(1.0, r_o, w, h, fov);
  const SymmetricSceneTracer<DormandPrince54, PIController, BackgroundScene> symmetric(
      SchwarzschildMetric{1.0}, accurate(400.0), cam, AngleCorrection::exact, kChecker, 256);
  const auto general = general_tracer(400.0);
  for (int which = 0; which < 2; ++which) {
    int last_inside = -1;
    for (int col = (w - 1) / 2; col < w; ++col) {
      const GeodesicState y = cam.pixel_state(col, 1);
      const RayOutcome o = which == 0 ? symmetric.trace(y) : general.trace(y);
      if (o.object == kHorizonObject) last_inside = col;
    }
    ASSERT_GE(last_inside, (w - 1) / 2);
    ASSERT_LT(last_inside, w - 1);
    auto angle = [&](int col) { return std::atan(cam.tan_half_fov() * std::abs(2.0 * col / (w - 1) - 1.0)); };
    EXPECT_LE(angle(last_inside), a) << "tracer " << which;
    EXPECT_GE(angle(last_inside + 1), a) << "tracer " << which;
  }
}

INSTANTIATE_TEST_SUITE_P(StaticCameras, Shadow, ::testing::Values(10.0, 20.0, 50.0));

TEST(Scene, FrameIsMirrorSymmetricAndRedshiftOfStaticEmittersIsExact) {
  const double r_o = 12.0, sky = 300.0;
  const int w = 41, h = 21;
  const Camera cam = static_camera(1.0, r_o, w, h, 100.0);
  const auto tracer = general_tracer(sky);
  const double guard = 2.0 * (1.0 + 1e-3);
  int captured = 0, escaped = 0;
  for (int row = 0; row < h; row += 2)
    for (int col = 0; col < w / 2; col += 2) {
      const RayOutcome left = tracer.trace(cam.pixel_state(col, row));
      const RayOutcome right = tracer.trace(cam.pixel_state(w - 1 - col, row));
      ASSERT_EQ(left.status, right.status);
      EXPECT_NEAR(left.where.theta, right.where.theta, 1e-7);
      EXPECT_NEAR(std::remainder(left.where.phi + right.where.phi, 2 * kPi), 0.0, 1e-7) << "phi mirrors to -phi";
      const double r_src = left.status == RayStatus::captured ? guard : sky;
      EXPECT_NEAR(left.redshift, std::sqrt(1.0 - 2.0 / r_src) / std::sqrt(1.0 - 2.0 / r_o), 1e-8);
      (left.status == RayStatus::captured ? captured : escaped)++;
    }
  EXPECT_GT(captured, 5);
  EXPECT_GT(escaped, 5);
}

TEST(Minkowski, SkyDirectionIsTheCameraFrameDirection) {
  const Camera cam = static_camera(0.0, 10.0, 31, 17, 120.0);
  const StraightLineTracer tracer(MinkowskiSpherical{}, 1000.0, AngleCorrection::exact, kChecker);
  for (int row = 0; row < 17; ++row)
    for (int col = 0; col < 31; ++col) {
      const Vec3 d = cam.pixel_direction(col, row);  // (forward, up, right) = (-x, +z, +y) at (r, 90 deg, 0)
      const Vec3 world(-d[0], d[2], d[1]);
      const RayOutcome o = tracer.trace(cam.pixel_state(col, row));
      const exact::SkyDirection expected{std::acos(world.z()), std::atan2(world.y(), world.x())};
      EXPECT_LT(exact::angular_distance(o.where, expected), 1e-12);
      EXPECT_NEAR(o.redshift, 1.0, 1e-14);
    }
}

TEST(Minkowski, MovingCameraShowsAberrationAndDoppler) {
  const double beta = 0.6, gamma = 1.0 / std::sqrt(1.0 - beta * beta);
  // Moving forward (towards the centre, -r) at 0.6 c.
  const Camera cam = static_camera(0.0, 10.0, 41, 3, 150.0, Vec3(-beta, 0.0, 0.0));
  const StraightLineTracer tracer(MinkowskiSpherical{}, 1000.0, AngleCorrection::exact, kChecker);
  for (int col = 0; col < 41; ++col) {
    const Vec3 d = cam.pixel_direction(col, 1);
    const double cos_camera = d[0];  // angle from the direction of motion, in the camera frame
    const RayOutcome o = tracer.trace(cam.pixel_state(col, 1));
    // Rest-frame angle of the sky point from the direction of motion (-x): cos a = -(sky direction).x
    const double cos_rest = -std::sin(o.where.theta) * std::cos(o.where.phi);
    EXPECT_NEAR(cos_rest, (cos_camera - beta) / (1.0 - beta * cos_camera), 1e-12) << "aberration";
    EXPECT_NEAR(o.redshift, 1.0 / (gamma * (1.0 - beta * cos_camera)), 1e-12) << "Doppler factor";
  }
}

}  // namespace

}  // namespace camera_scene_test
