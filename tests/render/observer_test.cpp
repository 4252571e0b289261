// Observers and cameras: the tetrad is orthonormal (g(e_a, e_b) = eta_ab) and right-handed, moving observers
// get the boosted 4-velocity, the pixel momentum is exactly seed eq. (5)-(6) (null, unit energy in the camera
// frame, past-directed; row 0 at the top, column 0 at the left), and every bad input is refused.
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/observer/static_frame.hpp"
#include "grtrace/observer/tetrad.hpp"

#include <Eigen/Geometry>  // cross
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace observer_test {

using namespace grtrace;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

Mat4 eta() { return Vec4(1.0, -1.0, -1.0, -1.0).asDiagonal(); }

Mat4 as_matrix(const Tetrad& t) {
  Mat4 m;
  for (int a = 0; a < 4; ++a) m.col(a) = t.e[static_cast<std::size_t>(a)];
  return m;
}

/// Components of a coordinate vector in the static orthonormal frame (t, r, theta, phi hats).
Vec4 static_components(const StaticFrame& f, const Mat4& g, const Vec4& v) {
  const Mat4 n = eta();
  Vec4 c;
  for (int a = 0; a < 4; ++a) c[a] = n(a, a) * f.e[static_cast<std::size_t>(a)].dot(g * v);
  return c;
}

struct Event {
  SchwarzschildMetric metric{1.0};
  Vec4 x{0.0, 10.0, 1.1, 0.3};
  Mat4 g = metric.metric(x);
  StaticFrame frame{g};

  Tetrad tetrad(const Vec3& beta, const Vec3& look, const Vec3& up) const {
    return make_tetrad(g, frame.velocity(beta), frame.spatial(look), frame.spatial(up));
  }
};

/// Expects `f` to throw std::invalid_argument whose message contains `word`.
template <class F>
void expect_refused(F&& f, const std::string& word) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected a refusal mentioning '" << word << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Tetrad, StaticObserverIsOrthonormalAndRightHanded) {
  const Event s;
  const Tetrad t = s.tetrad(Vec3::Zero(), Vec3(-1, 0, 0), Vec3(0, -1, 0));
  EXPECT_LT((tetrad_gram(s.g, t) - eta()).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_GT(as_matrix(t).determinant(), 0.0);
  // Default camera: forward = -r hat, up = -theta hat (north), hence right = forward x up = +phi hat.
  EXPECT_LT((static_components(s.frame, s.g, t.e[0]) - Vec4(1, 0, 0, 0)).norm(), 1e-13);
  EXPECT_LT((static_components(s.frame, s.g, t.e[1]) - Vec4(0, -1, 0, 0)).norm(), 1e-13);
  EXPECT_LT((static_components(s.frame, s.g, t.e[2]) - Vec4(0, 0, -1, 0)).norm(), 1e-13);
  EXPECT_LT((static_components(s.frame, s.g, t.e[3]) - Vec4(0, 0, 0, 1)).norm(), 1e-13);
}

TEST(Tetrad, RightIsForwardCrossUpForEveryStaticOrientation) {
  // In the static orthonormal frame (r, theta, phi) is a right-handed triple; a static camera's right vector
  // must be forward x up there.
  const Event s;
  const Vec3 looks[] = {{-1, 0, 0}, {0.3, 1, -2}, {0, 0, 1}, {1, 1, 1}, {0, -1, 0}};
  const Vec3 ups[] = {{0, -1, 0}, {1, 0, 0}, {0.2, 0.3, -0.7}};
  for (const Vec3& look : looks)
    for (const Vec3& up : ups) {
      if (look.normalized().cross(up.normalized()).norm() < 1e-6) continue;
      const Tetrad t = s.tetrad(Vec3::Zero(), look, up);
      const Vec3 f = static_components(s.frame, s.g, t.e[1]).tail<3>();
      const Vec3 u = static_components(s.frame, s.g, t.e[2]).tail<3>();
      const Vec3 r = static_components(s.frame, s.g, t.e[3]).tail<3>();
      EXPECT_LT((f - look.normalized()).norm(), 1e-13);
      EXPECT_LT((r - f.cross(u)).norm(), 1e-13);
      EXPECT_GT(u.dot(up), 0.0);
    }
}

TEST(Tetrad, MovingObserversAreOrthonormalAndRightHanded) {
  const Event s;
  const Vec3 betas[] = {{0.3, -0.2, 0.5}, {-0.9, 0.1, 0.0}, {0.0, 0.0, 0.99}, {0.5, 0.5, 0.5}, {0, 0, 0.9999}};
  const Vec3 looks[] = {{-1, 0, 0}, {0.3, 1, -2}, {0, 0, 1}, {1, 1, 1}};
  const Vec3 ups[] = {{0, -1, 0}, {1, 0, 0}, {0.2, 0.3, -0.7}};
  for (const Vec3& beta : betas)
    for (const Vec3& look : looks)
      for (const Vec3& up : ups) {
        if (look.normalized().cross(up.normalized()).norm() < 1e-6) continue;
        SCOPED_TRACE("beta " + std::to_string(beta[0]) + "," + std::to_string(beta[1]) + "," +
                     std::to_string(beta[2]));
        const Vec4 u = s.frame.velocity(beta);
        const Tetrad t = s.tetrad(beta, look, up);
        const double gamma = 1.0 / std::sqrt(1.0 - beta.squaredNorm());
        EXPECT_LT((tetrad_gram(s.g, t) - eta()).cwiseAbs().maxCoeff(), 1e-10 * gamma * gamma);
        EXPECT_GT(as_matrix(t).determinant(), 0.0);
        // The boost: static-frame components gamma (1, beta).
        Vec4 expected;
        expected << gamma, gamma * beta;
        EXPECT_LT((static_components(s.frame, s.g, u) - expected).norm(), 1e-12 * gamma);
        EXPECT_LT((t.e[0] - u).norm(), 1e-12 * u.norm());
        // forward lies in span(e_0, look) on the look side; up in span(e_0, e_1, up) on the up side.
        const Vec4 l = s.frame.spatial(look), w = s.frame.spatial(up);
        EXPECT_LT(t.e[1].dot(s.g * l), 0.0);
        EXPECT_LT(t.e[2].dot(s.g * w), 0.0);
        const Vec4 along_e0 = t.e[0].dot(s.g * l) * t.e[0], along_e1 = t.e[1].dot(s.g * l) * t.e[1];
        const Vec4 l_rest = l - along_e0 + along_e1;  // nothing left: look is in span(e_0, e_1)
        EXPECT_LT(l_rest.norm(), 1e-12 * (l.norm() + along_e0.norm() + along_e1.norm()));
      }
}

TEST(Tetrad, RefusesBadVelocitiesAndDirections) {
  const Event s;
  const Vec4 look = s.frame.spatial(Vec3(-1, 0, 0)), up = s.frame.spatial(Vec3(0, -1, 0));
  const Vec4 u = s.frame.e[0];
  // spacelike, null, past-directed, zero 4-velocities
  expect_refused([&] { make_tetrad(s.g, s.frame.e[1], look, up); }, "timelike");
  const Vec4 null = s.frame.e[0] + s.frame.e[3];
  ASSERT_NEAR(null.dot(s.g * null), 0.0, 1e-15);
  expect_refused([&] { make_tetrad(s.g, null, look, up); }, "timelike");
  expect_refused([&] { make_tetrad(s.g, -u, look, up); }, "future");
  expect_refused([&] { make_tetrad(s.g, Vec4::Zero(), look, up); }, "timelike");
  // non-finite input anywhere
  expect_refused([&] { make_tetrad(s.g, Vec4(kNaN, 0, 0, 0), look, up); }, "finite");
  expect_refused([&] { make_tetrad(s.g, u, Vec4(0, kInf, 0, 0), up); }, "finite");
  expect_refused([&] { make_tetrad(s.g, u, look, Vec4(0, 0, kNaN, 0)); }, "finite");
  Mat4 bad = s.g;
  bad(2, 2) = kNaN;
  expect_refused([&] { make_tetrad(bad, u, look, up); }, "finite");
  // look parallel (or anti-parallel) to up, nearly parallel, or along the 4-velocity
  expect_refused([&] { make_tetrad(s.g, u, look, 2.0 * look); }, "--up");
  expect_refused([&] { make_tetrad(s.g, u, look, -look); }, "--up");
  expect_refused([&] { make_tetrad(s.g, u, look, look + 1e-14 * up); }, "--up");
  expect_refused([&] { make_tetrad(s.g, u, u, up); }, "look");
  expect_refused([&] { make_tetrad(s.g, u, Vec4::Zero(), up); }, "look");
  expect_refused([&] { make_tetrad(s.g, u, look, Vec4::Zero()); }, "--up");
}

TEST(StaticFrame, RefusesSpeedOfLightAndBeyondAndInsideTheHorizon) {
  const Event s;
  expect_refused([&] { (void)s.frame.velocity(Vec3(1.0, 0.0, 0.0)); }, "below 1");
  expect_refused([&] { (void)s.frame.velocity(Vec3(0.6, 0.0, 0.8)); }, "below 1");
  expect_refused([&] { (void)s.frame.velocity(Vec3(0.0, -3.0, 0.0)); }, "below 1");
  expect_refused([&] { (void)s.frame.velocity(Vec3(kNaN, 0.0, 0.0)); }, "below 1");
  EXPECT_NO_THROW((void)s.frame.velocity(Vec3(0.0, 0.0, 0.999999)));
  expect_refused([&] { StaticFrame f(s.metric.metric(Vec4(0.0, 1.5, 1.0, 0.0))); }, "horizon");
}

TEST(Camera, PixelMomentumIsSeedEquationFiveAndSix) {
  const Event s;
  const Tetrad t = s.tetrad(Vec3(0.2, -0.1, 0.4), Vec3(-1, 0.2, 0), Vec3(0, -1, 0));
  const int W = 7, H = 4;
  const double fov = 70.0;
  const Camera cam(s.x, t, W, H, fov);
  const double th = std::tan(fov * std::numbers::pi / 360.0);
  for (int row = 0; row < H; ++row)
    for (int col = 0; col < W; ++col) {
      const double y = H - 1 - row;  // image row 0 is the top: the seed's y counts upwards
      const double r = th * (2.0 * col / (W - 1) - 1.0);
      const double u = th * (2.0 * y / (H - 1) - 1.0) * H / W;
      const Vec4 expected = (t.e[1] + u * t.e[2] + r * t.e[3]) / std::sqrt(1.0 + u * u + r * r) - t.e[0];
      const Vec4 k = cam.pixel_momentum(col, row);
      EXPECT_LT((k - expected).norm(), 1e-14 * expected.norm()) << col << "," << row;
      // null, unit energy in the camera frame, past-directed
      const double scale = k.cwiseAbs().dot(s.g.cwiseAbs() * k.cwiseAbs());
      EXPECT_LT(std::abs(k.dot(s.g * k)), 1e-14 * scale);
      EXPECT_NEAR(t.e[0].dot(s.g * k), -1.0, 1e-13);
      EXPECT_LT(k[0], 0.0);
      const GeodesicState y0 = cam.pixel_state(col, row);
      EXPECT_EQ(y0.head<4>(), s.x);
      EXPECT_EQ(y0.tail<4>(), k);
    }
}

TEST(Camera, RowZeroIsTheTopAndColumnZeroTheLeft) {
  const Event s;
  const Tetrad t = s.tetrad(Vec3::Zero(), Vec3(-1, 0, 0), Vec3(0, -1, 0));
  const Camera cam(s.x, t, 64, 48, 90.0);
  auto seen = [&](int col, int row) {  // the spatial direction the pixel looks along, static frame (r, th, ph)
    const Vec4 k = cam.pixel_momentum(col, row);
    return Vec3(static_components(s.frame, s.g, k).tail<3>());
  };
  const Vec3 top_left = seen(0, 0), bottom_right = seen(63, 47);
  EXPECT_LT(top_left[1], 0.0);      // towards the north pole (-theta): up
  EXPECT_LT(top_left[2], 0.0);      // towards -phi: left
  EXPECT_GT(bottom_right[1], 0.0);  // south: down
  EXPECT_GT(bottom_right[2], 0.0);  // +phi: right
  EXPECT_LT(top_left[0], 0.0);      // all towards the hole (-r)
  // The corner rays make the angle atan(tan(F/2) sqrt(1 + (H/W)^2)) with the forward direction.
  const double corner = std::atan(std::sqrt(1.0 + 0.75 * 0.75));
  EXPECT_NEAR(std::acos(-top_left[0] / top_left.norm()), corner, 1e-13);
  // The middle of the left edge is exactly fov/2 to the left.
  const Camera odd(s.x, t, 65, 49, 90.0);
  const Vec4 k = odd.pixel_momentum(0, 24);
  const Vec3 d = static_components(s.frame, s.g, k).tail<3>();
  EXPECT_NEAR(d[1], 0.0, 1e-15);
  EXPECT_NEAR(std::atan2(-d[2], -d[0]), std::numbers::pi / 4, 1e-14);
}

TEST(Camera, RefusesBadSizesAndFieldsOfView) {
  const Event s;
  const Tetrad t = s.tetrad(Vec3::Zero(), Vec3(-1, 0, 0), Vec3(0, -1, 0));
  expect_refused([&] { Camera c(s.x, t, 0, 10, 90.0); }, "width");
  expect_refused([&] { Camera c(s.x, t, 10, 0, 90.0); }, "height");
  expect_refused([&] { Camera c(s.x, t, -3, 10, 90.0); }, "width");
  for (double fov : {0.0, 180.0, -10.0, 200.0, kNaN, kInf})
    expect_refused([&] { Camera c(s.x, t, 10, 10, fov); }, "fov");
  EXPECT_NO_THROW(Camera(s.x, t, 1, 1, 179.9));
  EXPECT_NO_THROW(Camera(s.x, t, 3, 2, 0.01));
}

}  // namespace observer_test
