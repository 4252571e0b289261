// Every place a method can fail ends in a reported status, in bounded time, with no NaN in what is reported
// Each test drives one guard.
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/tableau/classic_rk4.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace {

using namespace grtrace;
constexpr double kPi = std::numbers::pi;

GeodesicState null_ray(double r, double theta, double phi, double kr, double ktheta, double kphi) {
  const SchwarzschildMetric m{1.0};
  const Vec4 x(0.0, r, theta, phi);
  return make_state(x, *complete_time_component(m, x, Vec4(0.0, kr, ktheta, kphi), 0.0));
}

TraceSettings settings(double escape = 100.0) {
  TraceSettings s;
  s.escape_radius = escape;
  return s;
}

// An inward ray from r = 2.6: fixed steps cannot follow k^t ~ 1/(1 - 2M/r) as r -> 2M.
TEST(Guards, FixedStepNearTheHorizonFailsWhereTheAdaptiveDefaultSucceeds) {
  const GeodesicState y0 = null_ray(2.6, kPi / 2, 0.0, -0.3, 0.0, 0.15);
  for (double h : {0.05, 0.3, 2.0}) {
    TraceSettings s = settings();
    s.initial_step = h;
    const GeodesicTracer<SchwarzschildMetric, ClassicRK4, FixedStep> fixed(SchwarzschildMetric{1.0}, s);
    const TraceResult r = fixed.trace(y0);
    EXPECT_EQ(r.status, RayStatus::non_finite) << "h = " << h;
    EXPECT_LT(r.accepted, 1000) << "the failure is found early, not after a long walk";
    // A fixed step has no tolerance: a loose rtol in its settings leaves its guard at constraint_tolerance (an
    // adaptive step's guard grows with rtol, TraceSettings::constraint_guard).
    TraceSettings loose = s;
    loose.integrator.tolerance.rtol = 1e-2;
    const GeodesicTracer<SchwarzschildMetric, ClassicRK4, FixedStep> fixed_loose(SchwarzschildMetric{1.0}, loose);
    EXPECT_EQ(fixed_loose.trace(y0).status, RayStatus::non_finite) << "h = " << h;
    // Without the guard the same run reports "captured" with a meaningless state.
    s.constraint_tolerance = 0.0;
    const GeodesicTracer<SchwarzschildMetric, ClassicRK4, FixedStep> unguarded(SchwarzschildMetric{1.0}, s);
    const TraceResult u = unguarded.trace(y0);
    EXPECT_GT(std::abs(u.constraint_drift), 1e-2) << "h = " << h;
  }
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> adaptive(SchwarzschildMetric{1.0},
                                                                                    settings());
  const TraceResult a = adaptive.trace(y0);
  EXPECT_EQ(a.status, RayStatus::captured);
  EXPECT_LT(std::abs(a.constraint_drift), 1e-4);
  EXPECT_TRUE(a.final_state.allFinite());
}

TEST(Guards, StepFloorEndsAsStepUnderflow) {
  TraceSettings s = settings();
  s.integrator.tolerance = {1e-14, 1e-16};
  s.integrator.h_min = 0.5;  // far larger than such a tolerance allows near r = 4
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> t(SchwarzschildMetric{1.0}, s);
  const TraceResult r = t.trace(null_ray(4.0, kPi / 2, 0.0, -0.5, 0.0, 0.2));
  EXPECT_EQ(r.status, RayStatus::step_underflow);
  EXPECT_TRUE(r.final_state.allFinite());
}

// The unstable circular photon orbit r = 3M: a ray that never leaves the photon sphere on its own.
TEST(Guards, PhotonSphereOrbitEndsWithinTheStepBudget) {
  const double kphi = 1.0 / (3.0 * std::sqrt(3.0));  // b = 3 sqrt 3 at r = 3 with unit energy: k^phi = b / r^2
  const GeodesicState y0 = null_ray(3.0, kPi / 2, 0.0, 0.0, 0.0, kphi);
  TraceSettings s = settings();
  s.integrator.tolerance = {1e-12, 1e-14};
  s.max_steps = 60;
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> budget(SchwarzschildMetric{1.0}, s);
  const TraceResult r = budget.trace(y0);
  EXPECT_EQ(r.status, RayStatus::max_steps);
  EXPECT_EQ(r.accepted, 60);
  EXPECT_NEAR(r.final_state[1], 3.0, 1e-3) << "still on the photon sphere when the budget ran out";
  EXPECT_GT(r.final_state[3], 6.0 * kPi) << "it went round the hole three times and more";
  // With a large budget the instability (e-folding once per radian) takes it off the sphere: it ends.
  s.max_steps = 1'000'000;
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> free(SchwarzschildMetric{1.0}, s);
  const TraceResult f = free.trace(y0);
  EXPECT_TRUE(f.status == RayStatus::captured || f.status == RayStatus::escaped) << to_string(f.status);
  EXPECT_LT(f.accepted, 20000);
}

// A metric whose right-hand side is NaN in a shell 9 < r < 10 (a stand-in for a user's broken metric).
struct BrokenShellMetric : SchwarzschildMetric {
  Vec4 acceleration(const Vec4& x, const Vec4& k) const {
    if (x[1] > 9.0 && x[1] < 10.0) return Vec4::Constant(std::numeric_limits<double>::quiet_NaN());
    return SchwarzschildMetric::acceleration(x, k);
  }
};

TEST(Guards, NonFiniteStagesEndCleanly) {
  const GeodesicState y0 = null_ray(20.0, kPi / 2, 0.0, -0.9, 0.0, 0.01);
  TraceSettings s = settings();
  s.initial_step = 0.7;
  const GeodesicTracer<BrokenShellMetric, ClassicRK4, FixedStep> fixed(BrokenShellMetric{}, s);
  const TraceResult f = fixed.trace(y0);
  EXPECT_EQ(f.status, RayStatus::non_finite);
  EXPECT_GT(f.final_state[1], 9.0) << "it stopped at the shell, not beyond";
  // An adaptive method shrinks its step in front of the shell until the floor.
  const GeodesicTracer<BrokenShellMetric, DormandPrince54, PIController> adaptive(BrokenShellMetric{}, settings());
  const TraceResult a = adaptive.trace(y0);
  EXPECT_EQ(a.status, RayStatus::step_underflow);
  EXPECT_TRUE(a.final_state.allFinite());
  EXPECT_NEAR(a.final_state[1], 10.0, 1e-6) << "it got as close to the bad region as the floor allows";
}

TEST(Guards, RayAcrossThePoleWrapsTheChartAndKeepsItsDirection) {
  // A meridional ray heading over the north pole (k^phi = 0), and one that passes close to it.
  for (double kphi : {0.0, 1e-4}) {
    const GeodesicState y0 = null_ray(10.0, 0.3, 0.7, 0.2, -0.08, kphi);
    const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> t(SchwarzschildMetric{1.0},
                                                                               settings(1000.0));
    const TraceResult r = t.trace(y0);
    ASSERT_EQ(r.status, RayStatus::escaped) << "kphi = " << kphi;
    EXPECT_GE(r.final_state[2], 0.0);
    EXPECT_LE(r.final_state[2], kPi);
    if (kphi == 0.0) {
      EXPECT_EQ(r.chart_wraps, 1);
    }
    const auto expected = exact::asymptotic_direction(y0, 1.0);
    const auto reached = exact::asymptotic_direction(r.final_state, 1.0);
    ASSERT_TRUE(expected && reached);
    EXPECT_LT(exact::angular_distance(*expected, *reached), 1e-6) << "kphi = " << kphi;
  }
}

TEST(Guards, WrapPolarAxisIsTheSamePointAndDirection) {
  GeodesicState y = null_ray(10.0, 0.3, 0.7, 0.2, -0.08, 0.01);
  GeodesicState crossed = y;
  crossed[2] = -0.2;  // the same chart point seen from the other side of the axis
  GeodesicState wrapped = crossed;
  ASSERT_TRUE(wrap_polar_axis(wrapped));
  const SchwarzschildMetric m{1.0};
  EXPECT_LT((m.to_cartesian(crossed.head<4>()) - m.to_cartesian(wrapped.head<4>())).norm(), 1e-12);
  EXPECT_NEAR(wrapped[2], 0.2, 1e-15);
  EXPECT_FALSE(wrap_polar_axis(y)) << "a state inside [0, pi] is left alone";
}

}  // namespace
