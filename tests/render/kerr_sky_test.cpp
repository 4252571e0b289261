// Kerr's sky continued exactly to infinity (trace/sky_continuation.hpp, exact_mino):
//  (a) at a = 0 the Mino-time continuation is Schwarzschild's elliptic integral (exact::asymptotic_direction)
//      within 1e-9 rad, from the sky sphere and from nearer in; and the flat continuation's error there is what
//      flat_continuation_error estimates (within 10 %);
//  (b) for a = 0.5, 0.9, 0.998 a frame's sky directions do not depend on the sky radius (400, 4000, 40000 M)
//      within 1e-8 rad, where the flat continuation moved them by more than 1e-6;
//  (c) the general tracer in Boyer-Lindquist and in Kerr-Schild coordinates sees the same sky as the reduced
//      tracer within 1e-7 rad;
//  (d) equatorial rays from a camera reach the sky where Iyer & Hansen's exact deflection puts them (at the tools'
//      default sky radius, 400 M) within 1e-9 rad;
//  (e) the frame's header names the continuation that ran.
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/static_frame.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/deflection.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/sky_continuation.hpp"

#include "../common/trace_settings.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace kerr_sky_test {

using namespace grtrace;

namespace {

constexpr double kPi = std::numbers::pi;

using test_settings::settings_at;

/// The frame's camera of the issue: r = 50 M, 80 degrees from the spin axis, 60 degree field, n x n pixels.
Camera camera_of(const auto& metric, int n, double theta_deg = 80.0) {
  CameraSpec cs;
  cs.position = Vec4(0.0, 50.0, theta_deg * kPi / 180.0, 0.0);
  cs.spherical_position = true;
  cs.observer = ObserverKind::zamo;
  cs.width = cs.height = n;
  cs.fov_degrees = 60.0;
  return make_camera(metric, cs);
}

/// Every pixel's outcome under a tracer (pixel centres, row by row).
template <class Tracer>
std::vector<RayOutcome> trace_pixels(const Tracer& tracer, const Camera& cam, int n) {
  std::vector<RayOutcome> out;
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) out.push_back(tracer.trace(cam.pixel_state(col + 0.5, row + 0.5)));
  return out;
}

/// The largest angle between the sky directions of pixels both frames see on the sky; counts them in *shared.
double largest_sky_difference(const std::vector<RayOutcome>& a, const std::vector<RayOutcome>& b, int* shared) {
  double worst = 0.0;
  *shared = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].object != kSkyObject || b[i].object != kSkyObject) continue;
    ++*shared;
    worst = std::max(worst, angular_distance(a[i].where, b[i].where));
  }
  return worst;
}

/// A future-directed null state at (r, theta, 0) around a unit-mass Schwarzschild hole, moving along the unit
/// direction n = (n_r, n_theta, n_phi) of the static observer's frame (observer/static_frame.hpp).
GeodesicState schwarzschild_state(double r, double theta, const Vec3& n) {
  const Vec4 x(0.0, r, theta, 0.0);
  const StaticFrame frame(SchwarzschildMetric{1.0}.metric(x));
  GeodesicState y;
  y << x, frame.e[0] + frame.spatial(n);
  return y;
}

}  // namespace

// ---- (a) a = 0: Schwarzschild's elliptic integral ---------------------------------------------------------------

TEST(KerrSky, AtZeroSpinTheMinoContinuationIsSchwarzschildsEllipticIntegral) {
  const KerrMetric kerr{1.0, 0.0};
  double worst = 0.0;
  int cases = 0;
  for (double r : {400.0, 60.0, 12.0})
    for (double theta : {0.3, 1.2, kPi / 2.0, 2.6})
      for (double tilt : {0.0, 0.4, 1.1, 1.45}) {
        // Outwards at `tilt` from the radial direction, turned out of the meridian plane by 0.7 rad.
        const Vec3 n(std::cos(tilt), std::sin(tilt) * std::cos(0.7), std::sin(tilt) * std::sin(0.7));
        const GeodesicState y = schwarzschild_state(r, theta, n);
        const auto expected = exact::asymptotic_direction(y, 1.0);
        ASSERT_TRUE(expected.has_value());
        const auto got = kerr_direction_at_infinity<Fehlberg78>(kerr, Tolerance{1e-13, 1e-15}, y);
        ASSERT_TRUE(got.has_value()) << "r = " << r << " theta = " << theta << " tilt = " << tilt;
        const double err = angular_distance(*got, *expected);
        worst = std::max(worst, err);
        ++cases;
        EXPECT_LT(err, 1e-9) << "r = " << r << " theta = " << theta << " tilt = " << tilt;
      }
  std::printf("a = 0: Mino continuation against the elliptic integral, %d states, worst %.2e rad\n", cases, worst);
}

TEST(KerrSky, FlatContinuationErrorEstimateMatchesSchwarzschildsExactSky) {
  // Outward rays on the sky sphere R with impact b << R: the flat continuation's error against the elliptic integral
  // is what flat_continuation_error estimates, (3/4) M b^3 / R^4, to its next order in b / R and M / b.
  const SchwarzschildMetric m{1.0};
  for (double R : {400.0, 4000.0})
    for (double b : {10.0, 20.0, 40.0}) {
      const double f = 1.0 - 2.0 / R, sin_tilt = b * std::sqrt(f) / R;  // b = R sin(tilt) / sqrt(f) (E = 1)
      const GeodesicState y = schwarzschild_state(R, 1.0, Vec3(std::sqrt(1.0 - sin_tilt * sin_tilt), sin_tilt, 0.0));
      const double flat = angular_distance(continued_direction(m, y, y, AngleCorrection::flat),
                                           *exact::asymptotic_direction(y, 1.0));
      const double estimate = flat_continuation_error(1.0, b, R);
      EXPECT_NEAR(flat / estimate, 1.0, 0.1) << "R = " << R << " b = " << b;
      EXPECT_NEAR(sky_radius_for_flat_error(1.0, b, estimate), R, 1e-9 * R);
    }
}

TEST(KerrSky, AFlatContinuationsFrameReportsItsEstimatedError) {
  // Schwarzschild continued flat from R = 400 M against its exact continuation, per pixel: the frame's worst error
  // is what the header's estimate (flat_continuation_error at the frame's largest escaped impact parameter) says.
  constexpr int n = 16;
  const BackgroundScene scene = background_scene({});
  const SchwarzschildMetric m{1.0};
  CameraSpec cs;
  cs.position = Vec4(0.0, 50.0, 1.4, 0.0);
  cs.spherical_position = true;
  cs.width = cs.height = n;
  cs.fov_degrees = 60.0;
  const Camera cam = make_camera(m, cs);
  const auto flat_tracer =
      make_general_tracer<Fehlberg78, IController>(m, settings_at(1e-12, 400.0), AngleCorrection::flat, scene);
  const auto flat = trace_pixels(flat_tracer, cam, n);
  const auto exact_tracer =
      make_general_tracer<Fehlberg78, IController>(m, settings_at(1e-12, 400.0), AngleCorrection::exact, scene);
  const auto exact = trace_pixels(exact_tracer, cam, n);
  int shared = 0;
  const double worst = largest_sky_difference(flat, exact, &shared);
  const auto estimate = flat_tracer.flat_continuation_estimate();
  ASSERT_TRUE(estimate.has_value());
  EXPECT_NEAR(estimate->error / worst, 1.0, 0.2) << "estimate " << estimate->error << ", measured " << worst;
  EXPECT_NEAR(sky_radius_for_flat_error(1.0, estimate->impact, 1e-12), estimate->radius_for_tolerance, 1e-6);
  const Frame frame = render_frame(cam, flat_tracer);
  EXPECT_EQ(std::stod(frame.image.metadata.at("sky_continuation_error")), estimate->error);
  std::printf("Schwarzschild, flat from 400 M: worst error %.3e rad, estimated %.3e (largest b %.2f M); sky radius "
              "for 1e-12: %.0f M\n", worst, estimate->error, estimate->impact, estimate->radius_for_tolerance);
  // Exact continuations and metrics without an estimate say nothing: de Sitter's g_tt falls without bound outside
  // (not asymptotically flat), the Ellis wormhole has no mass; Reissner-Nordstrom and Eddington-Finkelstein have one.
  EXPECT_FALSE(exact_tracer.flat_continuation_estimate().has_value());
  AutoSchwarzschildDeSitter sds;
  sds.lambda = 1e-5;
  EXPECT_FALSE(has_flat_continuation_estimate(sds, 400.0));
  EXPECT_FALSE(has_flat_continuation_estimate(AutoEllisWormhole{}, 400.0));
  EXPECT_TRUE(has_flat_continuation_estimate(AutoReissnerNordstrom{}, 400.0));
  EXPECT_TRUE(has_flat_continuation_estimate(AutoEddingtonFinkelstein{}, 400.0));
}

// ---- (b) the sky radius only bounds where objects can be ---------------------------------------------------------

TEST(KerrSky, SkyDirectionsDoNotDependOnTheSkyRadius) {
  constexpr int n = 16;
  const BackgroundScene scene = background_scene({});
  for (double spin : {0.5, 0.9, 0.998}) {
    SCOPED_TRACE("a = " + std::to_string(spin));
    const KerrMetric metric{1.0, spin};
    const Camera cam = camera_of(metric, n);
    auto frame = [&](double sky, AngleCorrection c) {
      const auto tracer = make_kerr_mino_tracer<Fehlberg78, IController>(metric, settings_at(1e-12, sky), c, scene);
      return trace_pixels(tracer, cam, n);
    };
    const auto near = frame(400.0, AngleCorrection::exact), mid = frame(4000.0, AngleCorrection::exact),
               far = frame(40000.0, AngleCorrection::exact);
    int shared = 0;
    const double d_mid = largest_sky_difference(near, mid, &shared);
    EXPECT_GT(shared, n * n / 2) << "the sky fills most of the frame";
    const double d_far = largest_sky_difference(near, far, &shared);
    EXPECT_LT(d_mid, 1e-8);
    EXPECT_LT(d_far, 1e-8);
    // The flat continuation from 400 M, against the exact sky: what the exact one removes (the test's teeth).
    const double d_flat = largest_sky_difference(frame(400.0, AngleCorrection::flat), far, &shared);
    EXPECT_GT(d_flat, 1e-6);
    std::printf("a = %.3f: sky radius 400 vs 4000 %.2e rad, vs 40000 %.2e rad (%d sky pixels); flat from 400: %.2e\n",
                spin, d_mid, d_far, shared, d_flat);
  }
}

// ---- (c) every Kerr tracer sees the same sky -------------------------------------------------------------------

TEST(KerrSky, GeneralTracersInBothChartsSeeTheReducedTracersSky) {
  constexpr int n = 16;
  const BackgroundScene scene = background_scene({});
  const double spin = 0.9;
  const KerrMetric bl{1.0, spin};
  const KerrSchildMetric ks = kerr_schild_for_camera_rays(1.0, spin);
  const auto mino = trace_pixels(
      make_kerr_mino_tracer<Fehlberg78, IController>(bl, settings_at(1e-12, 400.0), AngleCorrection::exact, scene),
      camera_of(bl, n), n);
  const auto general = trace_pixels(
      make_general_tracer<Fehlberg78, IController>(bl, settings_at(1e-12, 400.0), AngleCorrection::exact, scene),
      camera_of(bl, n), n);
  const auto general_ks = trace_pixels(
      make_general_tracer<Fehlberg78, IController>(ks, settings_at(1e-12, 400.0), AngleCorrection::exact, scene),
      camera_of(ks, n), n);
  int shared_bl = 0, shared_ks = 0;
  const double d_bl = largest_sky_difference(mino, general, &shared_bl);
  const double d_ks = largest_sky_difference(mino, general_ks, &shared_ks);
  EXPECT_GT(shared_bl, n * n / 2);
  EXPECT_GT(shared_ks, n * n / 2);
  EXPECT_LT(d_bl, 1e-7);
  EXPECT_LT(d_ks, 1e-7);
  std::printf("a = 0.9: reduced vs general Boyer-Lindquist %.2e rad (%d pixels), vs Kerr-Schild %.2e rad (%d)\n", d_bl,
              shared_bl, d_ks, shared_ks);
}

// ---- (d) Iyer & Hansen -------------------------------------------------------------------------------------------

TEST(KerrSky, EquatorialRaysReachTheSkyWhereTheExactDeflectionPutsThem) {
  const double r_cam = 50.0, sky = 400.0;
  double worst = 0.0;
  const BackgroundScene scene = background_scene({});
  for (const auto& [spin, bs] : std::vector<std::pair<double, std::vector<double>>>{
           {0.9, {3.5, 6.0, 15.0, 40.0, -7.5, -20.0}}, {0.5, {5.0, -7.0, 30.0}}, {0.998, {3.0, -8.0}}}) {
    const KerrMetric metric{1.0, spin};
    const auto mino =
        make_kerr_mino_tracer<Fehlberg78, IController>(metric, settings_at(1e-12, sky), AngleCorrection::exact, scene);
    const auto general =
        make_general_tracer<Fehlberg78, IController>(metric, settings_at(1e-12, sky), AngleCorrection::exact, scene);
    for (double b : bs) {
      // In from the camera to the turning point, out to infinity: the exact angles of both legs.
      const double swept = 2.0 * exact::equatorial_phi_to_turning_point(b, spin) -
                           exact::equatorial_phi_from_infinity(b, 1.0 / r_cam, spin);
      const SkyDirection expected{kPi / 2.0, azimuth_in_range(swept)};
      const GeodesicState y0 = kerr_equatorial_photon(metric, b, r_cam);  // trace/deflection.hpp
      for (const RayOutcome& o : {mino.trace(y0), general.trace(y0)}) {
        ASSERT_EQ(o.object, kSkyObject) << "a = " << spin << " b = " << b;
        const double err = angular_distance(o.where, expected);
        worst = std::max(worst, err);
        EXPECT_LT(err, 1e-9) << "a = " << spin << " b = " << b;
      }
    }
  }
  std::printf("equatorial rays against Iyer & Hansen at sky radius 400: worst %.2e rad\n", worst);
}

// ---- (e) the header says which continuation ran -------------------------------------------------------------------

TEST(KerrSky, TheFrameHeaderNamesTheContinuation) {
  const BackgroundScene scene = background_scene({});
  const KerrMetric metric{1.0, 0.9};
  const Camera cam = camera_of(metric, 4);
  auto header = [&](const auto& tracer) { return render_frame(cam, tracer).image.metadata.at("sky_continuation"); };
  EXPECT_EQ(header(make_kerr_mino_tracer<Fehlberg78, IController>(metric, settings_at(1e-9, 400.0),
                                                                 AngleCorrection::exact, scene)),
            sky_continuation_name(SkyContinuation::exact_mino));
  EXPECT_EQ(header(make_general_tracer<Fehlberg78, IController>(metric, settings_at(1e-9, 400.0), AngleCorrection::flat,
                                                               scene)),
            sky_continuation_name(SkyContinuation::flat));
  EXPECT_EQ(sky_continuation_of<KerrSchildMetric>(AngleCorrection::exact), SkyContinuation::exact_mino);
  EXPECT_EQ(sky_continuation_of<SchwarzschildMetric>(AngleCorrection::exact), SkyContinuation::exact_elliptic);
  EXPECT_EQ(sky_continuation_of<KerrMetric>(AngleCorrection::none), SkyContinuation::sky_sphere);
}

}  // namespace kerr_sky_test
