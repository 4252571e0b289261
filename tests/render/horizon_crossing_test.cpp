// A camera that falls through the horizon (with a horizon-penetrating chart a radial infall continues through the
// horizon), in Kerr-Schild's ingoing slicing (kerr_schild_for_flights):
//   - the camera's path is the exact radial fall from rest (the cycloid of Misner, Thorne & Wheeler 25.4) on both
//     sides of r = 2M, and E, L_z and g(u, u) stay constant through the Kerr horizon;
//   - outside the horizon the Kerr-Schild flight's cameras are the Schwarzschild flight's, mapped between charts;
//   - every pixel of a camera inside the photon sphere or inside the horizon ends as Schwarzschild's geometry says it
//     must: a ray traced back from the camera reaches the sky exactly when its photon came from our universe
//     (E > 0: the others come through the other universe's horizon) with impact parameter b = L / E below
//     3 sqrt(3) M and, outside the horizon, left its last turning point outwards; the rest are captured. No ray
//     fails, none is integrated inside the black hole without need (those from the other universe end at once).
#include "grtrace/integrate/step_controller.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/flight_path.hpp"
#include "grtrace/observer/timelike_start.hpp"
#include "grtrace/observer/worldline.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace horizon_crossing_test {

namespace {

using namespace grtrace;

constexpr double kM = 1.0;

/// Proper time of the fall from rest at r0 to r (Schwarzschild): r = r0 (1 + cos eta) / 2,
/// tau = sqrt(r0^3 / 8M) (eta + sin eta); the same on both sides of the horizon (the chart only relabels t).
double cycloid_tau(double r0, double r) {
  const double eta = std::acos(2.0 * r / r0 - 1.0);
  return std::sqrt(r0 * r0 * r0 / (8.0 * kM)) * (eta + std::sin(eta));
}
double cycloid_r(double r0, double tau) {
  const double scale = std::sqrt(r0 * r0 * r0 / (8.0 * kM));
  double eta = 0.0;  // Newton on tau(eta), monotonic on [0, pi)
  for (int it = 0; it < 80; ++it) eta -= (scale * (eta + std::sin(eta)) - tau) / (scale * (1.0 + std::cos(eta)));
  return 0.5 * r0 * (1.0 + std::cos(eta));
}

TEST(HorizonCrossing, KerrSchildCameraFollowsTheCycloidThroughTheHorizon) {
  const KerrSchildMetric metric = kerr_schild_for_flights(kM, 0.0);
  const double r0 = 6.0, r_end = 1.6;  // the ingoing chart's capture radius for the camera is r_c = 1.5 M
  const TimelikeStart start = radial_infall_start(metric, r0);
  EXPECT_NEAR(metric.radius(start.x), r0, 1e-12);
  const int n = 201;
  const Worldline w = sample_worldline(metric, start, cycloid_tau(r0, r_end) / (n - 1), n);
  ASSERT_TRUE(w.complete()) << "stopped at r = " << metric.radius(w.samples.back().x);
  int inside = 0;
  for (const WorldlineSample& s : w.samples) {
    const double r = metric.radius(s.x);
    inside += r < 2.0 * kM;
    EXPECT_NEAR(r, cycloid_r(r0, s.tau), 1e-9 * r0) << "tau " << s.tau;
    EXPECT_NEAR(inner_product(metric, s.x, s.u, s.u), 1.0, 1e-10) << "tau " << s.tau;
    EXPECT_GT(s.u[0], 0.0);
    // Released from rest on the equator at phi = 0: it stays on the positive x axis.
    EXPECT_NEAR(s.x[2], 0.0, 1e-12);
    EXPECT_NEAR(s.x[3], 0.0, 1e-12);
  }
  EXPECT_GE(inside, 4);  // tau from 2M to 1.6M is 3 % of the fall from 6M
  EXPECT_NEAR(metric.radius(w.samples.back().x), r_end, 1e-9);
}

TEST(HorizonCrossing, AutomaticInfallEndsInsideTheHorizonInKerrSchild) {
  FlightPathSpec spec;
  spec.kind = "infall";
  spec.r = 8.0;
  spec.frames = 30;
  const KerrSchildMetric ks = kerr_schild_for_flights(kM, 0.0);
  const Worldline path = flight_path(ks, spec);
  ASSERT_EQ(path.samples.size(), 30u);
  // The fall to 1.1 r_c, r_c = r_+ - (r_+ - r_-) / 4 = 1.5 M: inside the horizon.
  EXPECT_NEAR(ks.radius(path.samples.back().x), 1.1 * 1.5 * kM, 1e-8);
  // In Schwarzschild's own chart the same request ends outside, at 1.1 r_h = 2.2 M.
  const Worldline outside = flight_path(SchwarzschildMetric{kM}, spec);
  EXPECT_NEAR(outside.samples.back().x[1], 2.2 * kM, 1e-8);
  // A circular orbit is stated in the spherical chart: refused in Kerr-Schild, saying so.
  spec.kind = "circular";
  EXPECT_THROW((void)flight_path(ks, spec), std::invalid_argument);
}

TEST(HorizonCrossing, KerrPathKeepsItsConstantsThroughTheHorizon) {
  const double a = 0.9;
  const KerrSchildMetric metric = kerr_schild_for_flights(kM, a);
  const TimelikeStart start = radial_infall_start(metric, 8.0, 1.2, 0.3);  // off the equator: frame dragging too
  const GeodesicState y0 = start.state();
  const double e0 = metric.energy(y0), l0 = metric.angular_momentum(y0);
  const Worldline w = sample_worldline(metric, start, 0.5, 60);
  ASSERT_FALSE(w.samples.empty());
  EXPECT_LT(metric.radius(w.samples.back().x), metric.outer_horizon()) << "the body should end inside r_+";
  for (const WorldlineSample& s : w.samples) {
    const GeodesicState y = make_state(s.x, s.u);
    EXPECT_NEAR(metric.energy(y), e0, 1e-10) << "tau " << s.tau;
    EXPECT_NEAR(metric.angular_momentum(y), l0, 1e-10) << "tau " << s.tau;
    EXPECT_NEAR(inner_product(metric, s.x, s.u, s.u), 1.0, 1e-10) << "tau " << s.tau;
  }
}

TEST(HorizonCrossing, KerrSchildFlightCamerasAreTheSchwarzschildOnesOutside) {
  FlightPathSpec spec;
  spec.kind = "infall";
  spec.r = 10.0;
  spec.frames = 6;
  spec.dtau = 5.0;  // the sixth frame at tau = 25, r ~ 5.1 M
  const SchwarzschildMetric bl{kM};
  const KerrSchildMetric ks = kerr_schild_for_flights(kM, 0.0);
  const Worldline pb = flight_path(bl, spec), pk = flight_path(ks, spec);
  ASSERT_EQ(pb.samples.size(), pk.samples.size());
  const CameraView view{{-1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, 9, 7, 100.0};
  for (std::size_t i = 0; i < pb.samples.size(); ++i) {
    const WorldlineSample &b = pb.samples[i], &k = pk.samples[i];
    EXPECT_NEAR((bl_to_ks_position(ks, b.x) - k.x).norm(), 0.0, 1e-8 * (1.0 + b.x.norm())) << "frame " << i;
    const Mat4 j = bl_to_ks_jacobian(ks, b.x);
    EXPECT_NEAR((j * b.u - k.u).norm(), 0.0, 1e-8 * k.u.norm()) << "frame " << i;
    const Camera cb = make_moving_camera(bl, b.x, b.u, view), ck = make_moving_camera(ks, k.x, k.u, view);
    for (int row = 0; row < 7; row += 3)
      for (int col = 0; col < 9; col += 4) {
        const Vec4 kb = j * cb.pixel_momentum(col, row), kk = ck.pixel_momentum(col, row);
        EXPECT_NEAR((kb - kk).norm(), 0.0, 1e-8 * kk.norm()) << "frame " << i << " pixel " << col << "," << row;
      }
  }
}

// Carter's Q from the Kerr-Schild state (through the Boyer-Lindquist one), inside the horizon as outside: the
// radial potential R(r) built from E, L_z and Q must be (Sigma dr/dlambda)^2 of the ray itself.
TEST(HorizonCrossing, RadialPotentialIsTheRaysRadialSpeedInsideAndOutside) {
  const double a = 0.7;
  const KerrSchildMetric metric = kerr_schild_for_flights(kM, a);
  const TimelikeStart start = radial_infall_start(metric, 5.0, 1.1, 0.4);
  const Worldline path = sample_worldline(metric, start, 0.05, 4000);
  int inside = 0;
  for (std::size_t i = 0; i < path.samples.size(); ++i) {
    const WorldlineSample& at = path.samples[i];
    if (i % 20 != 0 && metric.radius(at.x) > metric.outer_horizon()) continue;  // every sample inside, a few outside
    const Camera camera =
        make_moving_camera(metric, at.x, at.u, CameraView{{1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, 5, 5, 170.0});
    const double r = metric.radius(at.x);
    inside += r < metric.outer_horizon();
    for (int pixel = 0; pixel < 25; ++pixel) {
      const GeodesicState y = camera.pixel_state(pixel % 5, pixel / 5);
      const KerrSchildTerms q = metric.terms(y.head<4>());
      const double cos_theta = y[3] / r, sigma = r * r + a * a * cos_theta * cos_theta;
      const double sigma_rdot = sigma * q.dr.dot(y.tail<3>());
      const double potential = metric.boyer_lindquist().radial_potential(metric.energy(y), metric.angular_momentum(y),
                                                                         metric.carter_constant(y), r);
      EXPECT_NEAR(potential, sigma_rdot * sigma_rdot, 1e-9 * (1.0 + sigma_rdot * sigma_rdot)) << "r " << r;
    }
  }
  EXPECT_GT(inside, 3);
}

/// What Schwarzschild geometry says of the ray traced back from a pixel (see the top of this file), or nothing
/// for a pixel within round-off of the critical impact parameter or of E = 0.
std::optional<RayStatus> expected_fate(const KerrSchildMetric& m, const GeodesicState& y) {
  const Vec3 x = y.segment<3>(1), k = y.tail<3>();
  const double e_photon = -m.energy(y);  // the photon's momentum is -k (k is traced into the past)
  const double b = x.cross(k).norm() / std::abs(e_photon), b_crit = 3.0 * std::sqrt(3.0) * kM;
  const double r = x.norm();
  if (std::abs(e_photon) < 1e-9 * std::abs(y[4]) || std::abs(b / b_crit - 1.0) < 1e-6) return std::nullopt;
  if (r < 2.0 * kM && e_photon < 0.0) return RayStatus::captured;  // from the other universe
  const bool outwards = r < 2.0 * kM || x.dot(k) > 0.0;            // inside, every past-directed ray moves out
  return outwards && b < b_crit ? RayStatus::escaped : RayStatus::captured;
}

TEST(HorizonCrossing, EveryPixelOfAFallingCameraEndsWhereGeometrySays) {
  const KerrSchildMetric metric = kerr_schild_for_flights(kM, 0.0);
  const double r0 = 6.0;
  TraceSettings settings;
  settings.integrator.tolerance = {1e-10, 1e-12};
  settings.escape_radius = 500.0;
  const GeodesicTracer<KerrSchildMetric, DormandPrince54, PIController> tracer(metric, settings);
  const TimelikeStart start = radial_infall_start(metric, r0);
  for (const double r_cam : {2.6, 1.95, 1.6}) {
    const Worldline w = sample_worldline(metric, start, cycloid_tau(r0, r_cam), 2);
    ASSERT_TRUE(w.complete());
    const WorldlineSample& at = w.samples.back();
    int ended_at_once = 0;
    for (const double look : {-1.0, 1.0}) {  // at the hole, and away from it
      const Camera camera =
          make_moving_camera(metric, at.x, at.u, CameraView{{look, 0.0, 0.0}, {0.0, -1.0, 0.0}, 21, 21, 150.0});
      int judged = 0, escaped = 0;
      for (int row = 0; row < 21; ++row)
        for (int col = 0; col < 21; ++col) {
          const GeodesicState y = camera.pixel_state(col, row);
          ASSERT_LT(y[4], 0.0);  // traced into the past
          const TraceResult res = tracer.trace(y);
          EXPECT_TRUE(res.status == RayStatus::escaped || res.status == RayStatus::captured)
              << "r " << r_cam << " pixel " << col << "," << row << ": " << static_cast<int>(res.status);
          ended_at_once += res.accepted == 0;
          const auto fate = expected_fate(metric, y);
          if (!fate) continue;
          ++judged;
          escaped += *fate == RayStatus::escaped;
          EXPECT_EQ(res.status, *fate) << "r " << r_cam << " look " << look << " pixel " << col << "," << row
                                       << " E " << -metric.energy(y);
        }
      EXPECT_GT(judged, 21 * 21 - 5) << "r " << r_cam;
      if (look > 0.0) {
        EXPECT_GT(escaped, 0) << "r " << r_cam << ": the sky behind the falling camera";
      }
    }
    // Inside the horizon the photons with E < 0 (from the other universe) end without a step; outside, none.
    if (r_cam < 2.0) {
      EXPECT_GT(ended_at_once, 0) << "r " << r_cam;
    } else {
      EXPECT_EQ(ended_at_once, 0) << "r " << r_cam;
    }
  }
}

TEST(HorizonCrossing, KerrCameraInsideTheHorizonTracesEveryPixel) {
  for (const double a : {0.5, 0.9}) {
    const KerrSchildMetric metric = kerr_schild_for_flights(kM, a);
    // The fall from rest at r = 6 M on the equator, as deep as the chart's capture radius lets the camera go.
    const Worldline path = sample_worldline(metric, radial_infall_start(metric, 6.0), 0.02, 5000);
    const WorldlineSample& at = path.samples.back();
    ASSERT_LT(metric.radius(at.x), 1.01 * metric.horizon_radius()) << "a " << a;
    TraceSettings settings;
    settings.integrator.tolerance = {1e-10, 1e-12};
    settings.escape_radius = 500.0;
    const GeodesicTracer<KerrSchildMetric, DormandPrince54, PIController> tracer(metric, settings);
    const double omega_h = metric.horizon_angular_velocity();
    EXPECT_NEAR(omega_h, a / (metric.outer_horizon() * metric.outer_horizon() + a * a), 1e-15);
    int escaped = 0, from_other_universe = 0, turning_back = 0;
    for (const double look : {-1.0, 1.0}) {  // at the hole, then away from it
      const Camera camera =
          make_moving_camera(metric, at.x, at.u, CameraView{{look, 0.0, 0.0}, {0.0, -1.0, 0.0}, 17, 17, 160.0});
      for (int row = 0; row < 17; ++row)
        for (int col = 0; col < 17; ++col) {
          const GeodesicState y = camera.pixel_state(col, row);
          const TraceResult res = tracer.trace(y);
          ASSERT_TRUE(res.status == RayStatus::escaped || res.status == RayStatus::captured)
              << "a " << a << " pixel " << col << "," << row << ": " << static_cast<int>(res.status);
          escaped += res.status == RayStatus::escaped;
          // A photon with E - Omega_H L_z < 0 cannot have crossed our future horizon, and one with a radial turning
          // point above r_+ came out of the past horizon: both captured without a step. Every other one escapes.
          const double e = metric.energy(y), lz = metric.angular_momentum(y);
          const double chi_p = -(e - omega_h * lz);
          const bool turns = metric.boyer_lindquist().radial_turning_point_outside(e, lz, metric.carter_constant(y));
          from_other_universe += chi_p < 0.0;
          turning_back += chi_p >= 0.0 && turns;
          if (chi_p < 0.0 || turns) {
            EXPECT_EQ(res.status, RayStatus::captured);
            EXPECT_EQ(res.accepted, 0);
          } else {
            EXPECT_EQ(res.status, RayStatus::escaped) << "a " << a << " pixel " << col << "," << row;
            // On its way out E, L_z and g(k, k) = 0 are kept.
            const GeodesicState& z = res.final_state;
            EXPECT_NEAR(metric.energy(z), e, 1e-7 * std::abs(y[4]));
            EXPECT_NEAR(metric.angular_momentum(z), lz, 1e-6 * std::abs(y[4]));
          }
        }
    }
    EXPECT_GT(escaped, 0) << "a " << a;
    EXPECT_GT(from_other_universe, 0) << "a " << a;
    EXPECT_GT(turning_back, 0) << "a " << a;
  }
}

}  // namespace

}  // namespace horizon_crossing_test
