// The named example metrics (metric/named_metrics.hpp: wormhole, sds, rn, schwarzschild-ef) rendered through the
// open scene layer, each against a closed form or an independent computation:
//  - Ellis wormhole: the throat's angular radius seen by a static camera, sin(alpha) = b0 / r(l); a radial ray
//    passes the throat with redshift 1 (ultrastatic); the other universe's sky is painted from the end state;
//  - Schwarzschild-de Sitter: the shadow's edge, sin(alpha) = b_c sqrt(f(r_o)) / r_o with the photon sphere at 3M
//    and b_c = 3 sqrt(3) M / sqrt(1 - 9 Lambda M^2); both horizons where the cubic (and g_tt) vanish;
//  - Reissner-Nordstrom from g alone (AutoMetric) against the closed-form user metric of examples/scenes;
//  - Schwarzschild in outgoing Eddington-Finkelstein coordinates: the same sky as Schwarzschild coordinates, the
//    same captured rays (which now cross r = 2M), and fixed-step RK4 carries them through instead of failing;
//  - bad input: a broken metric at the camera, and grtrace-render's parameter and sky-radius checks.
#include "reissner_nordstrom.hpp"

#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/classic_rk4.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace named_metrics_render_test {

using namespace grtrace;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = std::numbers::pi;
using Tableau = DormandPrince54;
using Control = PIController;

/// Adaptive settings: rtol (atol 1e-2 rtol) and the sky sphere's radius.
TraceSettings settings(double sky, double rtol = 1e-10) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-2 * rtol};
  s.escape_radius = sky;
  return s;
}

RenderOptions quiet() {
  RenderOptions o;
  o.progress = ProgressMode::never;
  o.threads = 2;
  return o;
}

/// A static camera at chart radius r (the wormhole's l), polar angle theta_deg, looking at the centre.
CameraSpec camera_spec(double r, double theta_deg, int width, int height, double fov) {
  CameraSpec spec;
  spec.position = Vec4(0.0, r, theta_deg * kPi / 180.0, 0.0);
  spec.width = width;
  spec.height = height;
  spec.fov_degrees = fov;
  return spec;
}

/// Angle between the optical axis and the ray of column `col` in the middle row of a `w`-pixel-wide camera.
double column_angle(const Camera& cam, int col, int w) {
  return std::atan(cam.tan_half_fov() * std::abs(2.0 * col / (w - 1) - 1.0));
}

/// Checks that along the middle row of `cam` (width w, odd) the columns for which `inside(col)` holds are exactly
/// those within `alpha` of the axis, up to the pixels whose angle lies within one pixel's angular size of alpha.
/// Returns the number of columns inside.
int expect_disc_of_angular_radius(const Camera& cam, int w, double alpha, const std::function<bool(int)>& inside) {
  int count = 0;
  for (int col = 0; col < w; ++col) {
    const double a = column_angle(cam, col, w);
    const bool in = inside(col);
    count += in ? 1 : 0;
    const double pixel = column_angle(cam, col, w) - column_angle(cam, col < (w - 1) / 2 ? col + 1 : col - 1, w);
    if (std::abs(a - alpha) > std::abs(pixel)) {
      EXPECT_EQ(in, a < alpha) << "column " << col << " at " << a << " rad, edge at " << alpha << " rad";
    }
  }
  return count;
}

// ---- 1. Ellis wormhole ----------------------------------------------------------------------------------

AutoEllisWormhole wormhole(double throat) {
  AutoEllisWormhole m;
  m.throat = throat;
  return m;
}

TEST(EllisWormholeFrame, TheThroatSubtendsTheAngleOfItsCriticalImpactParameter) {
  // Null geodesics: E = k^t, L = r^2 k^phi, (dl/dlambda)^2 = E^2 - L^2 / r(l)^2 with r(l) = sqrt(l^2 + b0^2) >= b0:
  // a ray with b = L/E < b0 never turns and passes the throat; b0 is the critical impact parameter (the throat is
  // the photon sphere). A static observer measures sin(alpha) = b / r(l) from the axis, so the throat's edge is at
  // sin(alpha) = b0 / r(l). Two cameras, two throats.
  for (const auto& [b0, l] : {std::pair{1.0, 10.0}, std::pair{2.5, 6.0}}) {
    SCOPED_TRACE("b0 = " + std::to_string(b0) + ", l = " + std::to_string(l));
    const auto m = wormhole(b0);
    const double alpha = std::asin(b0 / m.areal_radius(l));
    const int w = 201;
    const Camera cam = make_camera(m, camera_spec(l, 90.0, w, 3, 2.0 * alpha * 180.0 / kPi * 1.6));
    const auto tracer = make_general_tracer<Tableau, Control>(m, settings(100.0), AngleCorrection::flat,
                                                              background_scene(StandardSceneSpec{}));
    std::vector<RayOutcome> row(w);
    for (int col = 0; col < w; ++col) row[static_cast<std::size_t>(col)] = tracer.trace(cam.pixel_state(col, 1));
    for (const RayOutcome& o : row) {
      ASSERT_EQ(o.status, RayStatus::escaped) << "a wormhole captures nothing";
      EXPECT_NEAR(o.radius, 100.0, 1e-6) << "every ray ends on a sky sphere, one side or the other";
    }
    const int through = expect_disc_of_angular_radius(
        cam, w, alpha, [&](int col) { return row[static_cast<std::size_t>(col)].state[1] < 0.0; });
    EXPECT_GT(through, 100) << "the throat fills about 1/1.6 of the row";
    EXPECT_LT(through, w);
  }
}

TEST(EllisWormholeFrame, ARadialRayPassesTheThroatUnshifted) {
  const auto m = wormhole(1.0);
  const int w = 5;  // odd: the middle pixel looks exactly along -d_l
  const Camera cam = make_camera(m, camera_spec(10.0, 90.0, w, w, 30.0));
  const double sky = 100.0;
  const auto tracer = make_general_tracer<Tableau, Control>(m, settings(sky), AngleCorrection::flat,
                                                            background_scene(StandardSceneSpec{}));
  const GeodesicState y0 = cam.pixel_state(2, 2);
  ASSERT_LT(y0[5], 0.0) << "pixel ray traced towards the throat";
  const RayOutcome o = tracer.trace(y0);
  ASSERT_EQ(o.status, RayStatus::escaped);
  // On the other side, on its sky sphere r(l) = sky: l = -sqrt(sky^2 - b0^2), still moving away (dl < 0).
  EXPECT_NEAR(o.state[1], -std::sqrt(sky * sky - 1.0), 1e-6);
  EXPECT_LT(o.state[5], 0.0);
  EXPECT_NEAR(o.state[2], kPi / 2, 1e-9) << "a radial ray keeps its angles";
  EXPECT_NEAR(o.state[6], 0.0, 1e-12);
  EXPECT_NEAR(o.state[7], 0.0, 1e-12);
  // g_tt = 1 everywhere: static emitters and the static camera share their clocks, f_obs / f_src = 1.
  EXPECT_NEAR(o.redshift, 1.0, 1e-12);
}

TEST(EllisWormholeFrame, TheOtherUniversesSkyIsSeenThroughTheThroat) {
  // The command-line preset for the wormhole (StandardSceneSpec::far_side): the scene's sky painter sees the end
  // state (scene/scene.hpp OutcomePainter), so pixels whose ray ended at l < 0 carry the far side's colours.
  const auto m = wormhole(1.0);
  StandardSceneSpec preset;
  preset.far_side = true;
  const auto scene = background_scene(preset);
  const CheckerSky near = std::get<CheckerSky>(scene.sky.sky);
  const CheckerSky far = std::get<CheckerSky>(*scene.sky.far_side);
  const auto tracer = make_general_tracer<Tableau, Control>(m, settings(100.0, 1e-8), AngleCorrection::flat, scene);
  const Camera cam = make_camera(m, camera_spec(4.0, 80.0, 24, 24, 90.0));
  const Frame frame = render_frame(cam, tracer, quiet());
  const auto& R = frame.image.channel("R");
  const auto& G = frame.image.channel("G");
  const auto& B = frame.image.channel("B");
  auto is = [](const Rgb& c, float r, float g, float b) { return c[0] == r && c[1] == g && c[2] == b; };
  long through = 0, here = 0;
  for (int row = 0; row < 24; ++row)
    for (int col = 0; col < 24; ++col) {
      const auto i = static_cast<std::size_t>(row * 24 + col);
      const bool other = tracer.trace(cam.pixel_state(col, row)).state[1] < 0.0;
      const Rgb& a = other ? far.light : near.light;
      const Rgb& b = other ? far.dark : near.dark;
      EXPECT_TRUE(is(a, R[i], G[i], B[i]) || is(b, R[i], G[i], B[i])) << col << "," << row << " other=" << other;
      (other ? through : here) += 1;
    }
  EXPECT_GT(through, 20);
  EXPECT_GT(here, 20);
}

// The painter choice itself: a painter with the outcome form gets the outcome, a direction painter the direction.
struct SidePainter {
  Rgb operator()(double, double) const { return {9.0f, 9.0f, 9.0f}; }  // never used: the outcome form wins
  Rgb operator()(const RayOutcome& o) const { return {static_cast<float>(o.state[1]), 0.0f, 0.0f}; }
};
static_assert(OutcomePainter<SidePainter> && DirectionPainter<SidePainter>);
static_assert(ScenePainter<CheckerSky> && !OutcomePainter<CheckerSky>);

TEST(ScenePainters, AnOutcomePainterSeesTheEndStateAndADirectionPainterTheDirection) {
  RayOutcome o;
  o.status = RayStatus::escaped;
  o.object = kSkyObject;
  o.where = {1.0, 2.0};
  o.redshift = 1.0;
  o.state = GeodesicState::Zero();
  o.state[1] = -3.0;
  const auto side = make_scene(SidePainter{}, HorizonPaint{});
  EXPECT_EQ(side.shade(o).rgb[0], -3.0f);
  const auto checker = make_scene(CheckerSky{}, HorizonPaint{});
  EXPECT_EQ(checker.shade(o).rgb, CheckerSky{}(1.0, 2.0));
  AnySky any;
  any.sky = CheckerSky{};
  EXPECT_EQ(any(o), CheckerSky{}(1.0, 2.0)) << "no far side: one sky everywhere";
  any.far_side = StarFieldSky{};
  EXPECT_EQ(any(o), StarFieldSky{}(1.0, 2.0));
  o.state[1] = 3.0;
  EXPECT_EQ(any(o), CheckerSky{}(1.0, 2.0));
}

// ---- 2. Schwarzschild-de Sitter --------------------------------------------------------------------------

AutoSchwarzschildDeSitter sds(double lambda) {
  AutoSchwarzschildDeSitter m;
  m.mass = 1.0;
  m.lambda = lambda;
  return m;
}

TEST(SchwarzschildDeSitterFrame, ShadowEdgeSitsWhereThePhotonSphereSaysWithinOnePixel) {
  // f = 1 - 2M/r - Lambda r^2/3. The potential f / r^2 = 1/r^2 - 2M/r^3 - Lambda/3 peaks at r = 3M whatever Lambda,
  // so b_c^2 = 9M^2 / f(3M) = 27 M^2 / (1 - 9 Lambda M^2), and a static observer sees the edge at
  // sin(alpha) = b_c sqrt(f(r_o)) / r_o. (Without the 1 / sqrt(1 - 9 Lambda M^2) the edge would lie 3 pixels
  // further in for Lambda = 0.01: the first case tells the two apart.)
  struct Case {
    double lambda, r_o, sky;
  };
  for (const Case c : {Case{0.01, 8.0, 14.0}, Case{1e-5, 30.0, 400.0}}) {
    SCOPED_TRACE("Lambda = " + std::to_string(c.lambda));
    const auto m = sds(c.lambda);
    ASSERT_LT(c.sky, m.cosmological_horizon_radius());
    auto f = [&](double r) { return 1.0 - 2.0 / r - c.lambda * r * r / 3.0; };
    const double b_c = std::sqrt(27.0 / (1.0 - 9.0 * c.lambda));
    EXPECT_NEAR(b_c, 3.0 / std::sqrt(f(3.0)), 1e-12);
    const double alpha = std::asin(b_c * std::sqrt(f(c.r_o)) / c.r_o);
    const int w = 201;
    const Camera cam = make_camera(m, camera_spec(c.r_o, 90.0, w, 3, 2.0 * alpha * 180.0 / kPi * 1.6));
    const auto tracer = make_general_tracer<Tableau, Control>(m, settings(c.sky), AngleCorrection::flat,
                                                              background_scene(StandardSceneSpec{}));
    const int shadow = expect_disc_of_angular_radius(cam, w, alpha, [&](int col) {
      const RayOutcome o = tracer.trace(cam.pixel_state(col, 1));
      EXPECT_TRUE(o.status == RayStatus::escaped || o.status == RayStatus::captured) << col;
      return o.object == kHorizonObject;
    });
    EXPECT_GT(shadow, 100);
  }
}

TEST(SchwarzschildDeSitterFrame, BothHorizonsLieWhereTheCubicSays) {
  // Independently of the metric's closed form: the roots of g_tt(r) (the metric's own component, by bisection)
  // are the horizons; static observers (and the sky's emitters at rest) exist between them and nowhere else.
  for (double lambda : {1e-5, 1e-3, 0.01, 0.1}) {
    SCOPED_TRACE("Lambda = " + std::to_string(lambda));
    const auto m = sds(lambda);
    auto gtt = [&](double r) { return m.metric(Vec4(0.0, r, kPi / 2, 0.0))(0, 0); };
    auto root = [&](double lo, double hi) {  // g_tt changes sign on [lo, hi]
      const bool rising = gtt(lo) < 0.0;
      for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        ((gtt(mid) < 0.0) == rising ? lo : hi) = mid;
      }
      return 0.5 * (lo + hi);
    };
    const double r_b = root(2.0, 3.0), r_c = root(3.0, 2.0 * std::sqrt(3.0 / lambda));
    EXPECT_NEAR(m.black_hole_horizon_radius(), r_b, 1e-12 * r_b);
    EXPECT_NEAR(m.cosmological_horizon_radius(), r_c, 1e-12 * r_c);
    EXPECT_EQ(m.horizon_radius(), m.black_hole_horizon_radius()) << "rays are captured at the black hole's";
    for (double r : {r_b, r_c}) EXPECT_NEAR(m.horizon_cubic(r), 0.0, 1e-12 * r);
    // The cubic's sum of roots is 0 (no r^2 term): r_b + r_c + r_neg = 0, and r_b r_c r_neg = -6M / Lambda.
    const double r_neg = m.cubic_root(2);
    EXPECT_NEAR(r_b + r_c + r_neg, 0.0, 1e-9 * r_c);
    EXPECT_NEAR(r_b * r_c * r_neg, -6.0 / lambda, 1e-9 * 6.0 / lambda);
    auto at_rest = [&](double r) { return static_velocity(m.metric(Vec4(0.0, r, kPi / 2, 0.0))).has_value(); };
    EXPECT_TRUE(at_rest(r_b * (1.0 + 1e-6)));
    EXPECT_TRUE(at_rest(r_c * (1.0 - 1e-6)));
    EXPECT_FALSE(at_rest(r_c * (1.0 + 1e-6)));
    EXPECT_FALSE(at_rest(r_b * (1.0 - 1e-6)));
  }
}

// ---- 3. Reissner-Nordstrom: differentiated against closed form ------------------------------------------

TEST(ReissnerNordstromFrame, TheAutomaticMetricRendersTheClosedFormsFrame) {
  for (double q : {0.6, 0.95}) {
    SCOPED_TRACE("Q = " + std::to_string(q));
    const auto closed = ReissnerNordstromMetric::checked(1.0, q);
    AutoReissnerNordstrom automatic;
    automatic.mass = 1.0;
    automatic.charge = q;
    const Camera cam = make_camera(closed, camera_spec(40.0, 80.0, 32, 32, 60.0));
    const Camera cam_auto = make_camera(automatic, camera_spec(40.0, 80.0, 32, 32, 60.0));
    StandardSceneSpec preset;
    preset.name = "disk";
    preset.disk.r_in = 4.0;
    const auto a = make_general_tracer<Tableau, Control>(closed, settings(300.0), AngleCorrection::flat,
                                                         disk_scene(preset));
    const auto b = make_general_tracer<Tableau, Control>(automatic, settings(300.0), AngleCorrection::flat,
                                                         disk_scene(preset));
    long counts[3] = {0, 0, 0};
    double worst_sky = 0.0, worst_shift = 0.0;
    for (int row = 0; row < 32; ++row)
      for (int col = 0; col < 32; ++col) {
        ASSERT_EQ(cam.pixel_state(col, row), cam_auto.pixel_state(col, row)) << "the same camera";
        const RayOutcome p = a.trace(cam.pixel_state(col, row)), r = b.trace(cam.pixel_state(col, row));
        ASSERT_EQ(p.status, r.status) << col << "," << row;
        ASSERT_EQ(p.object, r.object) << col << "," << row;
        ++counts[std::min(p.object, 2)];
        worst_shift = std::max(worst_shift, std::abs(p.redshift - r.redshift) / std::abs(p.redshift));
        if (p.status == RayStatus::escaped) worst_sky = std::max(worst_sky, angular_distance(p.where, r.where));
      }
    EXPECT_LT(worst_sky, 1e-9);
    EXPECT_LT(worst_shift, 1e-9);
    std::printf("RN Q=%.2f: sky %ld horizon %ld disk %ld pixels; worst sky %.2e rad, worst redshift %.2e\n", q,
                counts[0], counts[1], counts[2], worst_sky, worst_shift);
    EXPECT_GT(counts[1], 10);
    EXPECT_GT(counts[2], 50);
  }
}

// ---- 4. Eddington-Finkelstein: the same sky, and the horizon crossed -----------------------------------

AutoEddingtonFinkelstein outgoing_ef() {
  AutoEddingtonFinkelstein m;
  m.mass = 1.0;
  m.outgoing = true;  // camera rays are past-directed: the outgoing chart carries them through r = 2M
  return m;
}

TEST(EddingtonFinkelsteinFrame, ShowsTheSameSkyAsSchwarzschildCoordinatesAndCrossesTheHorizon) {
  const SchwarzschildMetric schw{1.0};
  const auto ef = outgoing_ef();
  const int w = 40, h = 40;
  const Camera cs = make_camera(schw, camera_spec(20.0, 75.0, w, h, 80.0));
  const Camera ce = make_camera(ef, camera_spec(20.0, 75.0, w, h, 80.0));
  const auto scene = background_scene(StandardSceneSpec{});
  const auto ts = make_general_tracer<Tableau, Control>(schw, settings(300.0), AngleCorrection::flat, scene);
  const auto te = make_general_tracer<Tableau, Control>(ef, settings(300.0), AngleCorrection::flat, scene);
  std::vector<int> object(static_cast<std::size_t>(w * h));
  std::vector<RayOutcome> es(object.size());
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) {
      const auto i = static_cast<std::size_t>(row * w + col);
      es[i] = te.trace(ce.pixel_state(col, row));
      object[i] = ts.trace(cs.pixel_state(col, row)).object;
    }
  long escaped = 0, captured = 0, silhouette = 0;
  double worst_sky = 0.0, worst_shift = 0.0;
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) {
      const auto i = static_cast<std::size_t>(row * w + col);
      const RayOutcome& e = es[i];
      ASSERT_FALSE(is_failure(e.status)) << col << "," << row;
      if (e.object != object[i]) {
        // Only on the shadow's edge: a neighbour in the reference has the other verdict.
        bool edge = false;
        for (const auto& [dc, dr] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
          const int c = col + dc, r = row + dr;
          if (c >= 0 && c < w && r >= 0 && r < h) edge = edge || object[static_cast<std::size_t>(r * w + c)] != object[i];
        }
        EXPECT_TRUE(edge) << "verdicts differ away from the silhouette at " << col << "," << row;
        ++silhouette;
        continue;
      }
      if (e.status == RayStatus::captured) {
        ++captured;
        // Captured inside the event horizon: at the capture radius M, having crossed r = 2M with finite k.
        EXPECT_NEAR(e.radius, (1.0 + 1e-3) * ef.capture_radius(), 1e-6) << col << "," << row;
        EXPECT_LT(e.radius, ef.event_horizon_radius());
        EXPECT_TRUE(e.state.allFinite());
        continue;
      }
      ++escaped;
      const RayOutcome s = ts.trace(cs.pixel_state(col, row));
      worst_sky = std::max(worst_sky, angular_distance(s.where, e.where));
      worst_shift = std::max(worst_shift, std::abs(s.redshift - e.redshift));
    }
  std::printf("EF vs Schwarzschild: %ld escaped, %ld captured, %ld silhouette pixels; worst sky %.2e rad, "
              "worst redshift %.2e\n", escaped, captured, silhouette, worst_sky, worst_shift);
  EXPECT_GT(escaped, 800);
  EXPECT_GT(captured, 100);
  EXPECT_LE(silhouette, 4);
  EXPECT_LT(worst_sky, 1e-8);  // measured 4e-10 (both converged to rtol 1e-10; the charts differ in rounding)
  EXPECT_LT(worst_shift, 1e-9);
}

TEST(EddingtonFinkelsteinFrame, FixedStepRk4CarriesTheCapturedRaysThroughTheHorizon) {
  // The failure map's case (docs/failure-maps.md) on a small frame: classic RK4 with the fixed step h = 0.25. In
  // Schwarzschild coordinates k^t grows as 1/(1 - 2M/r) towards the horizon and every captured ray ends
  // non_finite; in the outgoing Eddington-Finkelstein chart g is regular at r = 2M and the captured rays cross it.
  // What remains is the spherical chart's polar axis, which both charts share: a ray whose orbit plane passes
  // close to the axis (|L_z| / L small: k^phi = L_z / (r sin theta)^2 grows there) near the hole is not resolved by
  // h = 0.25 and fails in both charts (measured: the EF failures all have |L_z| / L <= 0.26).
  const SchwarzschildMetric schw{1.0};
  const auto ef = outgoing_ef();
  const int w = 48, h = 24;
  CameraSpec spec = camera_spec(20.0, 90.0, w, h, 90.0);
  const Camera cs = make_camera(schw, spec), ce = make_camera(ef, spec);
  TraceSettings fixed = settings(100.0);
  fixed.initial_step = 0.25;
  fixed.max_steps = 20000;
  StandardSceneSpec checker;
  const auto reference = make_general_tracer<Tableau, Control>(schw, settings(100.0), AngleCorrection::flat,
                                                               background_scene(checker));
  const auto fs_tracer = make_general_tracer<ClassicRK4, FixedStep>(schw, fixed, AngleCorrection::flat,
                                                                    background_scene(checker));
  const auto fe_tracer = make_general_tracer<ClassicRK4, FixedStep>(ef, fixed, AngleCorrection::flat,
                                                                    background_scene(checker));
  std::array<long, kRayStatusCount> ref{}, in_schw{}, in_ef{};
  long off_axis_captured = 0;
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) {
      const GeodesicState y0 = cs.pixel_state(col, row);
      const RayStatus r = reference.trace(y0).status;
      const RayStatus s = fs_tracer.trace(y0).status;
      const RayStatus e = fe_tracer.trace(ce.pixel_state(col, row)).status;
      ++ref[static_cast<std::size_t>(r)];
      ++in_schw[static_cast<std::size_t>(s)];
      ++in_ef[static_cast<std::size_t>(e)];
      // How close the ray's orbit plane comes to the polar axis: sin(theta_min) = |L_z| / L.
      const double st = std::sin(y0[2]), r2 = y0[1] * y0[1];
      const double lz = r2 * st * st * y0[7], l = r2 * std::hypot(y0[6], st * y0[7]);
      const bool off_axis = std::abs(lz) > 0.3 * l;
      if (r == RayStatus::captured) {
        EXPECT_EQ(s, RayStatus::non_finite) << col << "," << row;
        if (off_axis) {
          ++off_axis_captured;
          EXPECT_EQ(e, RayStatus::captured) << col << "," << row << ": crosses the horizon in EF";
        }
      }
      if (e == RayStatus::non_finite) {
        EXPECT_EQ(s, RayStatus::non_finite) << col << "," << row << ": EF fails only where Schwarzschild does";
        EXPECT_FALSE(off_axis) << col << "," << row << ": EF fails only near the polar axis";
      }
      if (s == RayStatus::escaped) {
        EXPECT_EQ(e, RayStatus::escaped) << col << "," << row;
      }
    }
  auto show = [](const char* what, const std::array<long, kRayStatusCount>& c) {
    std::printf("%-28s", what);
    for (std::size_t i = 0; i < kRayStatusCount; ++i) std::printf(" %s %ld", std::string(kRayStatusNames[i]).c_str(), c[i]);
    std::printf("\n");
  };
  show("adaptive, Schwarzschild:", ref);
  show("RK4 h=0.25, Schwarzschild:", in_schw);
  show("RK4 h=0.25, EF:", in_ef);
  std::printf("captured rays off the axis (|L_z| > 0.3 L): %ld\n", off_axis_captured);
  const auto captured = static_cast<std::size_t>(RayStatus::captured);
  const auto non_finite = static_cast<std::size_t>(RayStatus::non_finite);
  EXPECT_GT(ref[captured], 50);
  EXPECT_EQ(in_schw[captured], 0) << "Schwarzschild coordinates: no captured ray survives the fixed step";
  EXPECT_GE(in_schw[non_finite], ref[captured]);
  EXPECT_GT(off_axis_captured, 50);
  EXPECT_GE(in_ef[captured], off_axis_captured);
  EXPECT_LT(in_ef[non_finite], in_schw[non_finite] / 3) << "measured 32 against 124";
}

// ---- 5. Bad input ------------------------------------------------------------------------------------------

/// Schwarzschild with a deliberate fault at the camera: a sign error in g_rr (signature (+,+,-,-)), or g_thth
/// vanishing on the sphere r = r0 (singular there).
struct BrokenSchwarzschild {
  static constexpr std::string_view name = "broken-schwarzschild";
  static constexpr Chart chart = Chart::spherical;
  bool sign_error = true;
  double r0 = 10.0;

  template <class S>
  Mat4Of<S> metric_components(const Vec4Of<S>& x) const {
    using std::sin;
    const S r = x[1], f = 1.0 - 2.0 / r, st = sin(x[2]);
    const S area = sign_error ? r * r : (r - r0) * (r - r0);
    return diagonal_metric<S>(f, (sign_error ? 1.0 : -1.0) / f, -area, -area * st * st);
  }
  double radius(const Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 2.0; }
};

TEST(NamedMetricsBadInput, ACameraWhereTheMetricIsBrokenIsRefusedWithAMessage) {
  for (bool sign_error : {true, false}) {
    AutoMetric<BrokenSchwarzschild> m;
    m.sign_error = sign_error;
    try {
      (void)make_camera(m, camera_spec(10.0, 90.0, 8, 8, 60.0));
      ADD_FAILURE() << "accepted a camera where g is " << (sign_error ? "of the wrong signature" : "singular");
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("singular or not of signature"), std::string::npos) << e.what();
    }
  }
  // The same metric away from its fault takes a camera (singular case: the fault is on r = 10 only).
  AutoMetric<BrokenSchwarzschild> m;
  m.sign_error = false;
  EXPECT_NO_THROW((void)make_camera(m, camera_spec(12.0, 90.0, 8, 8, 60.0)));
}

TEST(NamedMetricsBadInput, CheckMetricSpecRefusesWhatMakesNoSpacetime) {
  auto refused = [](MetricSpec s, const std::string& words) {
    try {
      check_metric_spec(s);
      ADD_FAILURE() << "accepted " << s.name << " (" << words << ")";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  MetricSpec s;
  s.name = "rn";
  s.charge = 1.0;
  refused(s, "--charge");
  s.name = "sds";
  for (double lambda : {0.0, -1e-3, 1.0 / 9.0, 0.2, std::nan("")}) {
    s.lambda = lambda;
    refused(s, "--lambda");
  }
  s.name = "wormhole";
  s.throat = 0.0;
  refused(s, "--throat");
}

// grtrace-render itself: the binary as in render_cli_input_test.cpp.
fs::path render_binary() {
#ifdef GRTRACE_RENDER_BINARY
  return tool_tests::tool_path(GRTRACE_RENDER_BINARY, "render", "grtrace-render");
#else
  return tool_tests::tool_path(nullptr, "render", "grtrace-render");
#endif
}

using tool_tests::ToolRun;

class NamedMetricsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    binary_ = render_binary();
    if (!fs::exists(binary_)) GTEST_SKIP() << "grtrace-render not built at " << binary_;
    fs::create_directories(base_ / "out");
  }

  /// Runs grtrace-render with args (stderr captured to a file outside the output directory).
  ToolRun run(const std::vector<std::string>& args) const { return tool_tests::run_tool(binary_, args, base_); }

  tool_tests::ScratchDir scratch_{"grtrace_named_cli"};
  fs::path binary_, base_ = scratch_.path();
};

TEST_F(NamedMetricsCli, RefusesBadMetricParametersWithExitTwoAMessageAndNoFile) {
  const std::string target = (base_ / "out" / "frame.exr").string();
  struct Bad {
    std::vector<std::string> args;
    std::string words;  ///< what the message must say
  };
  const std::vector<Bad> bad = {
      {{"--metric", "rn", "--charge", "1"}, "--charge"},
      {{"--metric", "rn", "--charge", "-1.5"}, "--charge"},
      {{"--metric", "sds", "--lambda", "0"}, "--lambda"},
      {{"--metric", "sds", "--lambda", "-1e-4"}, "--lambda"},
      {{"--metric", "sds", "--lambda", "0.1111111111111112"}, "--lambda"},  // just above 1/(9 M^2)
      {{"--metric", "sds", "--lambda", "0.5"}, "--lambda"},
      {{"--metric", "wormhole", "--throat", "0"}, "--throat"},
      {{"--metric", "wormhole", "--throat", "-1"}, "--throat"},
      // r_c = 53.74 M for Lambda = 1e-3: a sky sphere beyond it has no emitters at rest.
      {{"--metric", "sds", "--lambda", "1e-3", "--camera-r", "20", "--sky-radius", "100"}, "--sky-radius"},
      {{"--metric", "sds", "--lambda", "1e-3", "--camera-r", "20", "--sky-radius", "54"}, "--sky-radius"},
      // The camera inside the black hole's horizon of SdS / RN (r_+ = 1.6 M for Q = 0.8).
      {{"--metric", "rn", "--charge", "0.8", "--camera-r", "1.5"}, "horizon"},
      {{"--metric", "sds", "--lambda", "1e-3", "--camera-r", "2", "--sky-radius", "40"}, "horizon"},
      // Circular orbits of SdS end at the static radius (3 M / Lambda)^(1/3) = 14.42 M for Lambda = 1e-3: a disk
      // out to 20 M would have matter where none can circle (its pixels were non_finite).
      {{"--metric", "sds", "--lambda", "1e-3", "--scene", "disk", "--camera-r", "30", "--sky-radius", "50"},
       "no timelike circular orbit exists at the outer radius r = 20.000000 in this metric (they end near r = 14.42"},
  };
  for (const Bad& b : bad) {
    std::string shown;
    for (const auto& a : b.args) shown += a + " ";
    SCOPED_TRACE(shown);
    std::vector<std::string> args = b.args;
    args.insert(args.end(), {"--width", "8", "--height", "8", "--out", target});
    const ToolRun r = run(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find(b.words), std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_empty(base_ / "out")) << "left a file behind";
  }
  // Just inside the cosmological horizon is accepted.
  const ToolRun ok = run({"--metric", "sds", "--lambda", "1e-3", "--camera-r", "20", "--sky-radius", "53.5",
                          "--width", "8", "--height", "8", "--rtol", "1e-7", "--out", target});
  EXPECT_EQ(ok.status, 0) << ok.err;
}

TEST_F(NamedMetricsCli, TheWormholeSkySceneShowsTheOtherUniverseThroughTheThroat) {
  const fs::path exr = base_ / "out" / "wormhole.exr";
  const ToolRun r = run({"--metric", "wormhole", "--scene", "checker", "--camera-r", "6", "--fov", "60", "--width",
                         "15", "--height", "15", "--rtol", "1e-8", "--out", exr.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const Image image = read_exr(exr);
  // The middle pixel looks radially through the throat: the far side's green-violet checker; the corners (30
  // degrees off axis, outside the throat's 9.5-degree radius at l = 6) see this side's orange-blue one.
  StandardSceneSpec preset;
  preset.far_side = true;
  const auto scene = background_scene(preset);
  const CheckerSky near = std::get<CheckerSky>(scene.sky.sky), far = std::get<CheckerSky>(*scene.sky.far_side);
  auto pixel = [&](int col, int row) {
    const auto i = static_cast<std::size_t>(row * 15 + col);
    return Rgb{image.channel("R")[i], image.channel("G")[i], image.channel("B")[i]};
  };
  EXPECT_TRUE(pixel(7, 7) == far.light || pixel(7, 7) == far.dark);
  for (const auto& [c, w] : {std::pair{0, 0}, std::pair{14, 0}, std::pair{0, 14}, std::pair{14, 14}})
    EXPECT_TRUE(pixel(c, w) == near.light || pixel(c, w) == near.dark) << c << "," << w;
}

}  // namespace

}  // namespace named_metrics_render_test
