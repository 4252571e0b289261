// Library functions validate their input as documented: exact::asymptotic_direction gives
// nullopt, never a NaN direction, for input that is not a ray; a ray started exactly on the polar axis of the
// spherical chart (theta = 0) ends as non_finite (its right-hand side has cot(theta) = inf), not as a step-size
// problem.
#include "grtrace/core/number_text.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace {

using namespace grtrace;
constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

GeodesicState null_ray(double r, double theta, double phi, double kr, double ktheta, double kphi) {
  const SchwarzschildMetric m{1.0};
  const Vec4 x(0.0, r, theta, phi);
  return make_state(x, *complete_time_component(m, x, Vec4(0.0, kr, ktheta, kphi), 0.0));
}

}  // namespace

TEST(HardeningCore, AsymptoticDirectionRefusesWhatIsNotARay) {
  const GeodesicState good = null_ray(50.0, kPi / 2, 0.0, -1.0, 0.0, 0.005);
  ASSERT_TRUE(exact::asymptotic_direction(good, 1.0).has_value());

  GeodesicState nan = good;
  nan[5] = kNaN;
  EXPECT_FALSE(exact::asymptotic_direction(nan, 1.0).has_value());
  nan = good;
  nan[1] = kNaN;
  EXPECT_FALSE(exact::asymptotic_direction(nan, 1.0).has_value());
  EXPECT_FALSE(exact::asymptotic_direction(good, kNaN).has_value());
  EXPECT_FALSE(exact::asymptotic_direction(good, -1.0).has_value());

  GeodesicState zero = good;
  zero.tail<4>().setZero();
  EXPECT_FALSE(exact::asymptotic_direction(zero, 1.0).has_value()) << "zero momentum";
  GeodesicState no_energy = good;
  no_energy[4] = 0.0;
  EXPECT_FALSE(exact::asymptotic_direction(no_energy, 1.0).has_value()) << "k^t = 0";
  GeodesicState inside = good;
  inside[1] = 1.5;
  EXPECT_FALSE(exact::asymptotic_direction(inside, 1.0).has_value()) << "r < 2M";

  // Whatever comes back is never NaN, over a spread of valid rays (also on the polar axis).
  for (double theta : {0.0, 0.3, kPi / 2, kPi})
    for (double kr : {-1.0, 0.0, 1.0}) {
      const auto d = exact::asymptotic_direction(null_ray(30.0, theta, 0.4, kr, 0.01, 0.0), 1.0);
      if (d) {
        EXPECT_TRUE(std::isfinite(d->theta) && std::isfinite(d->phi)) << theta << " " << kr;
      }
    }
}

TEST(HardeningCore, RayStartedOnThePolarAxisEndsAsNonFinite) {
  TraceSettings s;
  s.escape_radius = 100.0;
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> tracer(SchwarzschildMetric{1.0}, s);
  const TraceResult r = tracer.trace(null_ray(20.0, 0.0, 0.0, -1.0, 0.02, 0.01));
  EXPECT_EQ(r.status, RayStatus::non_finite) << to_string(r.status);
  // theta = pi in double is 1.2e-16 off the axis: cot(theta) ~ 8e15 is finite, so the right-hand side is finite
  // but enormous and the step controller gives up: an honest step_underflow (the tools refuse both angles).
  const TraceResult south = tracer.trace(null_ray(20.0, kPi, 0.0, -1.0, 0.02, 0.01));
  EXPECT_TRUE(south.status == RayStatus::step_underflow || south.status == RayStatus::non_finite)
      << to_string(south.status);
  // Just off the axis the same ray is traced normally.
  const TraceResult near = tracer.trace(null_ray(20.0, 1e-3, 0.0, -1.0, 0.02, 0.01));
  EXPECT_TRUE(near.status == RayStatus::escaped || near.status == RayStatus::captured) << to_string(near.status);
}

// One reading of user-written numbers for options, scene files and camera-path CSVs (core/number_text.hpp).
TEST(HardeningCore, NumbersFromTextFollowOneSetOfRules) {
  using grtrace::NumberText;
  const auto number = [](const char* t) { return grtrace::parse_finite_number(t); };
  EXPECT_EQ(number(" 1.5e-3\t").value, 1.5e-3);
  EXPECT_EQ(number("0x1p3").value, 8.0);
  EXPECT_EQ(number("-2").result, NumberText::ok);
  EXPECT_EQ(number("1e-320").result, NumberText::ok);  // subnormal: read as strtod gives it
  EXPECT_EQ(number("1e-400").value, 0.0);
  for (const char* not_finite : {"1e400", "-1e400", "inf", "nan", "Infinity"})
    EXPECT_EQ(number(not_finite).result, NumberText::not_finite) << not_finite;
  for (const char* bad : {"", " ", "1,5", "1.5x", "x", "1 2", "\n1", "--1", "1e"})
    EXPECT_EQ(number(bad).result, NumberText::not_a_number) << "'" << bad << "'";
  const auto whole = [](const char* t) { return grtrace::parse_whole_number(t); };
  EXPECT_EQ(whole(" 12 ").value, 12);
  EXPECT_EQ(whole("-7").value, -7);
  EXPECT_EQ(whole("9223372036854775807").result, NumberText::ok);
  EXPECT_EQ(whole("9223372036854775808").result, NumberText::out_of_range);
  EXPECT_EQ(whole("-99999999999999999999").result, NumberText::out_of_range);
  for (const char* bad : {"", "1.5", "1e3", "0x10", "12a", "\n3"})
    EXPECT_EQ(whole(bad).result, NumberText::not_a_number) << "'" << bad << "'";
  EXPECT_NE(grtrace::number_text_problem(NumberText::out_of_range).find("9223372036854775807"), std::string::npos);
}
