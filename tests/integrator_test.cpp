// tests/integrator_test.cpp
// Tests of the integration core (grtrace/integrate/*) for every tableau: straight lines in flat space to
// round-off, the measured fixed-step convergence order, the I / PI / step-doubling controllers, exact counts of
// right-hand-side evaluations, the failure statuses (step underflow, non-finite right-hand side), the dense
// output's order, and event location on the dense output.
//
// The smooth nonlinear test problem is the Kepler orbit (mu = 1, a = 1, eccentricity e, periapsis at t = 0),
// whose exact state at any time follows from Kepler's equation E - e sin E = t, solved here by Newton's method.
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"
#include "grtrace/integrate/event_locator.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include "common/tableau_types.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace grtrace {
namespace {

using State4 = Vector<4>;

// -----------------------------------------------------------------------------------------------------------
// The Kepler problem and its exact solution

/// y = (x, y, vx, vy), y' = (vx, vy, -x/r^3, -y/r^3). Counts its evaluations.
struct KeplerRhs {
  long* calls = nullptr;
  State4 operator()(const State4& y) const {
    if (calls) ++*calls;
    const double r2 = y[0] * y[0] + y[1] * y[1], r3 = r2 * std::sqrt(r2);
    State4 d;
    d << y[2], y[3], -y[0] / r3, -y[1] / r3;
    return d;
  }
};

/// Exact state at time t of the orbit with a = 1 (period 2 pi), eccentricity e, periapsis on +x at t = 0.
State4 kepler_exact(double e, double t) {
  double E = t;
  for (int i = 0; i < 100; ++i) {
    const double dE = (E - e * std::sin(E) - t) / (1.0 - e * std::cos(E));
    E -= dE;
    if (std::abs(dE) < 1e-16) break;
  }
  const double den = 1.0 - e * std::cos(E), s = std::sqrt(1.0 - e * e);
  State4 y;
  y << std::cos(E) - e, s * std::sin(E), -std::sin(E) / den, s * std::cos(E) / den;
  return y;
}

double max_abs(const State4& v) { return v.cwiseAbs().maxCoeff(); }

std::string name_of(std::string_view v) { return std::string(v); }

/// Least-squares slope of log(err) against log(h).
double loglog_slope(const std::vector<double>& h, const std::vector<double>& err) {
  const std::size_t n = h.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = std::log(h[i]), y = std::log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double dn = static_cast<double>(n);
  return (dn * sxy - sx * sy) / (dn * sxx - sx * sx);
}

/// Runs an adaptive integrator from the Kepler periapsis to t_end; the last piece, shorter than the step the
/// controller proposes, is one fixed step of the same tableau, so the result is the method's own, not an
/// interpolant's.
struct AdaptiveRun {
  double error = 0.0;
  int accepted = 0, rejected = 0;
  long rhs_evals = 0;
  bool ok = true;
};

template <class T, class C>
AdaptiveRun run_kepler_adaptive(double e, double t_end, double rtol, C controller = {}) {
  IntegratorSettings s;
  s.tolerance = {rtol, 1e-3 * rtol};
  ControlledIntegrator<T, C, 4> integ(s, controller);
  const KeplerRhs f{};
  integ.start(f, kepler_exact(e, 0.0), 0.0);
  AdaptiveRun out;
  while (integ.lambda() + integ.next_step() < t_end) {
    if (integ.advance(f) != StepOutcome::ok || integ.accepted() > 10'000'000) {
      out.ok = false;
      return out;
    }
  }
  ControlledIntegrator<T, FixedStep, 4> last;
  last.start(f, integ.state(), t_end - integ.lambda());
  out.ok = last.advance(f) == StepOutcome::ok;
  out.error = max_abs(last.state() - kepler_exact(e, t_end));
  out.accepted = integ.accepted();
  out.rejected = integ.rejected();
  out.rhs_evals = integ.rhs_evals();
  return out;
}

// -----------------------------------------------------------------------------------------------------------
// Straight lines in flat space

// Every shipped tableau on its own (FlatSpace/<name>).
template <class T>
class FlatSpace : public ::testing::Test {};
TYPED_TEST_SUITE(FlatSpace, tableau_tests::AllTableauTypes, tableau_tests::TableauName);

TYPED_TEST(FlatSpace, FollowsAStraightLineToRoundOff) {
  using T = TypeParam;
  const MinkowskiMetric flat;
  const Vec4 x0(0.5, 1.0, 2.0, 3.0), k(1.0, 0.6, -0.48, 0.64);  // null: 0.36 + 0.2304 + 0.4096 = 1
  TraceSettings s;
  s.initial_step = 0.37;
  s.max_steps = 300;
  s.escape_radius = 1e6;
  const GeodesicTracer<MinkowskiMetric, T, FixedStep> tracer(flat, s);
  const TraceResult r = tracer.trace(make_state(x0, k));
  EXPECT_EQ(r.status, RayStatus::max_steps);
  EXPECT_EQ(r.accepted, 300);
  EXPECT_NEAR(r.lambda, 300 * 0.37, 1e-12 * 300 * 0.37);
  const Vec4 expected = x0 + r.lambda * k;
  const double rel = (r.final_state.head<4>() - expected).norm() / expected.norm();
  EXPECT_LT(rel, 1e-12) << "relative position error " << rel;
  EXPECT_EQ((r.final_state.tail<4>() - k).cwiseAbs().maxCoeff(), 0.0);  // k never changes
  EXPECT_EQ(r.constraint_drift, 0.0);
}

/// With a controller the ray ends on the escape sphere, located on the dense output (which is exact on a line).
TYPED_TEST(FlatSpace, AdaptiveRunsEndOnTheEscapeSphereOnTheLine) {
  using T = TypeParam;
  using C = std::conditional_t<has_embedded_pair<T>, PIController, StepDoubling>;
  const MinkowskiMetric flat;
  const Vec4 x0(0.0, 1.0, 2.0, 3.0), k(1.0, 0.6, -0.48, 0.64);
  TraceSettings s;
  s.escape_radius = 1000.0;
  s.integrator.h_max = 50.0;
  const GeodesicTracer<MinkowskiMetric, T, C> tracer(flat, s);
  const TraceResult r = tracer.trace(make_state(x0, k));
  EXPECT_EQ(r.status, RayStatus::escaped);
  EXPECT_NEAR(flat.radius(r.final_state.head<4>()), 1000.0, 1e-9);
  const Vec4 expected = x0 + r.lambda * k;
  EXPECT_LT((r.final_state.head<4>() - expected).norm() / expected.norm(), 1e-12);
  EXPECT_EQ(r.rejected, 0);  // the error estimate of a straight line is zero
}

// -----------------------------------------------------------------------------------------------------------
// Fixed-step convergence order

/// Four step sizes, each half the previous, chosen per order so the errors lie between ~1e-3 and ~1e-12
/// (asymptotic regime, above round-off).
int first_step_count(int order) {
  switch (order) {
    case 1:
      return 4096;
    case 2:
      return 512;
    case 3:
      return 128;
    case 4:
      return 64;
    case 5:
      return 64;
    case 6:
      return 48;
    default:
      return 8;
  }
}

// Every shipped tableau on its own (Convergence/<name>); the rows of one table.
template <class T>
class Convergence : public ::testing::Test {};
TYPED_TEST_SUITE(Convergence, tableau_tests::AllTableauTypes, tableau_tests::TableauName);

TYPED_TEST(Convergence, FixedStepOrderMatchesTheStatedOrder) {
  using T = TypeParam;
  constexpr double e = 0.3, t_end = 3.0;
  const State4 y0 = kepler_exact(e, 0.0), y_end = kepler_exact(e, t_end);
  if (tableau_tests::first_row("convergence"))
    std::printf("%-9s %5s %8s   errors at n, 2n, 4n, 8n steps over t = %.1f (Kepler e = %.1f)\n", "tableau",
                "order", "slope", t_end, e);
  std::vector<double> hs, errs;
  const int n0 = first_step_count(T::order);
  for (int n = n0; n <= 8 * n0; n *= 2) {
    const double h = t_end / n;
    ControlledIntegrator<T, FixedStep, 4> integ;
    const KeplerRhs f{};
    integ.start(f, y0, h);
    for (int i = 0; i < n; ++i) ASSERT_EQ(integ.advance(f), StepOutcome::ok);
    hs.push_back(h);
    errs.push_back(max_abs(integ.state() - y_end));
  }
  const double slope = loglog_slope(hs, errs);
  std::printf("%-9s %5d %8.3f   %.2e %.2e %.2e %.2e\n", name_of(T::name).c_str(), T::order, slope, errs[0], errs[1],
              errs[2], errs[3]);
  EXPECT_NEAR(slope, T::order, 0.2);
  EXPECT_GT(errs.back(), 1e-14);  // still above round-off, so the slope is the method's
}

// -----------------------------------------------------------------------------------------------------------
// Step controllers

// Every tableau with an embedded pair on its own (EmbeddedPairControllers/<name>); the rows of one table.
template <class T>
class EmbeddedPairControllers : public ::testing::Test {};
TYPED_TEST_SUITE(EmbeddedPairControllers, tableau_tests::EmbeddedPairTableauTypes, tableau_tests::TableauName);

TYPED_TEST(EmbeddedPairControllers, MeetTighterTolerancesAndPIRejectsLess) {
  using T = TypeParam;
  constexpr double e = 0.5, t_end = 2.0 * std::numbers::pi;
  if (tableau_tests::first_row("embedded pair controllers"))
    std::printf("%-9s %6s | %-28s | %-28s\n", "tableau", "rtol", "I: error  acc  rej", "PI: error  acc  rej");
  const std::vector<double> rtols =
      T::order <= 2 ? std::vector<double>{1e-5, 1e-7, 1e-9} : std::vector<double>{1e-5, 1e-7, 1e-9, 1e-11};
  int rejected_i = 0, rejected_pi = 0;
  double prev_i = std::numeric_limits<double>::infinity(), prev_pi = prev_i;
  for (double rtol : rtols) {
    const AdaptiveRun i = run_kepler_adaptive<T, IController>(e, t_end, rtol);
    const AdaptiveRun pi = run_kepler_adaptive<T, PIController>(e, t_end, rtol);
    ASSERT_TRUE(i.ok && pi.ok);
    std::printf("%-9s %6.0e | %.2e %7d %4d | %.2e %7d %4d\n", name_of(T::name).c_str(), rtol, i.error, i.accepted,
                i.rejected, pi.error, pi.accepted, pi.rejected);
    // A 100x tighter tolerance buys at least 10x in the global error, and the global error over one orbit
    // stays within a fixed multiple of the tolerance (tolerance proportionality).
    EXPECT_LT(i.error, prev_i / 10.0) << "rtol " << rtol;
    EXPECT_LT(pi.error, prev_pi / 10.0) << "rtol " << rtol;
    EXPECT_LT(i.error, 3e3 * rtol);
    EXPECT_LT(pi.error, 3e3 * rtol);
    prev_i = i.error;
    prev_pi = pi.error;
    rejected_i += i.rejected;
    rejected_pi += pi.rejected;
  }
  EXPECT_LE(rejected_pi, rejected_i) << "PI rejected " << rejected_pi << " steps, I " << rejected_i;
}

// Every tableau without an embedded pair on its own (StepDoublingController/<name>); the rows of one table.
template <class T>
class StepDoublingController : public ::testing::Test {};
TYPED_TEST_SUITE(StepDoublingController, tableau_tests::NoEmbeddedPairTableauTypes, tableau_tests::TableauName);

TYPED_TEST(StepDoublingController, WorksWithATableauWithoutAnEmbeddedPair) {
  using T = TypeParam;
  constexpr double e = 0.5, t_end = 2.0 * std::numbers::pi;
  if (tableau_tests::first_row("step doubling controller"))
    std::printf("%-9s %6s | %-28s | %-28s\n", "tableau", "rtol", "doubling: error acc rej",
                "+richardson: error acc rej");
  const std::vector<double> rtols =
      T::order == 1 ? std::vector<double>{1e-5, 1e-7, 1e-9} : std::vector<double>{1e-5, 1e-7, 1e-9, 1e-11};
  double prev = std::numeric_limits<double>::infinity(), prev_r = prev;
  for (double rtol : rtols) {
    StepDoubling plain, extrapolated;
    extrapolated.richardson = true;
    const AdaptiveRun d = run_kepler_adaptive<T, StepDoubling>(e, t_end, rtol, plain);
    const AdaptiveRun r = run_kepler_adaptive<T, StepDoubling>(e, t_end, rtol, extrapolated);
    ASSERT_TRUE(d.ok && r.ok);
    std::printf("%-9s %6.0e | %.2e %7d %4d | %.2e %7d %4d\n", name_of(T::name).c_str(), rtol, d.error, d.accepted,
                d.rejected, r.error, r.accepted, r.rejected);
    EXPECT_LT(d.error, prev / 5.0) << "rtol " << rtol;
    EXPECT_LT(r.error, prev_r / 5.0) << "rtol " << rtol;
    // The extrapolated value has order p + 1: for the same tolerance it is the more accurate one.
    EXPECT_LT(r.error, d.error) << "rtol " << rtol;
    prev = d.error;
    prev_r = r.error;
  }
}

// -----------------------------------------------------------------------------------------------------------
// Right-hand-side evaluations are counted exactly, and no more are made than the method needs

/// What one run should cost: 1 (f(y0)) + 1 if the initial step is chosen automatically (one trial Euler step)
/// + per trial (accepted or rejected) S - 1 new stages (stage 1 reuses the stored f(y)),
///   or 3(S - 1) + 1 for step doubling (full step, two half steps, f at the midpoint)
/// + per accepted step f(y_new), unless the tableau is FSAL and its last stage already is f(y_new)
///   (step doubling always evaluates it: its last stage belongs to the full step, not to y_new).
template <class T, class C>
long expected_rhs_evals(int accepted, int rejected, bool automatic_h0) {
  constexpr long S = static_cast<long>(T::stages);
  const long per_trial = C::estimate == ErrorEstimate::step_doubling ? 3 * (S - 1) + 1 : S - 1;
  const long per_accept = (T::fsal && C::estimate != ErrorEstimate::step_doubling) ? 0 : 1;
  return 1 + (automatic_h0 ? 1 : 0) + per_trial * (accepted + rejected) + per_accept * accepted;
}

template <class T, class C>
void check_rhs_count(double h0, bool expect_rejections = false) {
  SCOPED_TRACE(name_of(T::name) + " + " + name_of(C::name));
  long calls = 0;
  const KeplerRhs f{&calls};
  IntegratorSettings s;
  s.tolerance = {1e-7, 1e-10};
  ControlledIntegrator<T, C, 4> integ(s);
  integ.start(f, kepler_exact(0.5, 0.0), h0);
  for (int i = 0; i < 60; ++i) ASSERT_EQ(integ.advance(f), StepOutcome::ok);
  EXPECT_EQ(integ.rhs_evals(), calls);
  EXPECT_EQ(calls, (expected_rhs_evals<T, C>(integ.accepted(), integ.rejected(), h0 <= 0.0)))
      << "accepted " << integ.accepted() << " rejected " << integ.rejected();
  if (expect_rejections) {
    EXPECT_GT(integ.rejected(), 0);  // rejected trials are counted too
  }
}

// Every shipped tableau on its own (RhsEvaluationsOfEveryTableau/<name>).
template <class T>
class RhsEvaluationsOfEveryTableau : public ::testing::Test {};
TYPED_TEST_SUITE(RhsEvaluationsOfEveryTableau, tableau_tests::AllTableauTypes, tableau_tests::TableauName);

TYPED_TEST(RhsEvaluationsOfEveryTableau, AreCountedExactlyForEveryController) {
  using T = TypeParam;
  check_rhs_count<T, FixedStep>(0.01);
  check_rhs_count<T, StepDoubling>(0.0);
  check_rhs_count<T, StepDoubling>(1.0, true);  // a too-large first step forces rejections
  if constexpr (has_embedded_pair<T>) {
    check_rhs_count<T, IController>(0.0);
    check_rhs_count<T, PIController>(1.0, true);
  }
}

TEST(RhsEvaluations, Dp5CostsSixPerTrial) {
  // The brief's example, spelled out: DP5 is FSAL with 7 stages, so every trial costs 6 evaluations.
  long calls = 0;
  const KeplerRhs f{&calls};
  ControlledIntegrator<DormandPrince54, PIController, 4> integ;
  integ.start(f, kepler_exact(0.5, 0.0), 0.0);
  for (int i = 0; i < 40; ++i) integ.advance(f);
  EXPECT_EQ(calls, 1 + 1 + 6 * (integ.accepted() + integ.rejected()));
}

/// The tracer reports the integrator's count.
TEST(RhsEvaluations, TracerReportsTheIntegratorCount) {
  struct CountingSchwarzschild : SchwarzschildMetric {
    long* calls;
    Vec4 acceleration(const Vec4& x, const Vec4& k) const {
      ++*calls;
      return SchwarzschildMetric::acceleration(x, k);
    }
  };
  long calls = 0;
  CountingSchwarzschild m;
  m.calls = &calls;
  TraceSettings s;
  s.escape_radius = 200.0;
  const GeodesicTracer<CountingSchwarzschild, Tsitouras54, PIController> tracer(m, s);
  const TraceResult r = tracer.trace(incoming_photon(7.0, 150.0));
  EXPECT_EQ(r.status, RayStatus::escaped);
  EXPECT_EQ(r.rhs_evals, calls);
  // 1 at the start, 1 for the initial step guess, 6 per step (FSAL), and those spent putting the escape on the
  // integration's step map rather than on its interpolant.
  EXPECT_GT(r.refinement_evals, 0);
  EXPECT_EQ(r.rhs_evals, 1 + 1 + 6 * (r.accepted + r.rejected) + r.refinement_evals);
}

// -----------------------------------------------------------------------------------------------------------
// Failure statuses

TEST(Failures, HugeMinimumStepEndsInStepUnderflow) {
  const KeplerRhs f{};
  IntegratorSettings s;
  s.tolerance = {1e-10, 1e-12};
  s.h_min = 0.5;
  {  // adaptive: the first trial step of 1 is rejected, the retry would be below h_min
    ControlledIntegrator<DormandPrince54, PIController, 4> integ(s);
    integ.start(f, kepler_exact(0.5, 0.0), 1.0);
    EXPECT_EQ(integ.advance(f), StepOutcome::step_underflow);
    EXPECT_EQ(integ.accepted(), 0);
    EXPECT_GE(integ.rejected(), 1);
    EXPECT_LT(integ.next_step(), s.h_min);
  }
  {  // automatic initial step far below h_min: fails before any trial
    ControlledIntegrator<Verner65, IController, 4> integ(s);
    integ.start(f, kepler_exact(0.5, 0.0), 0.0);
    EXPECT_EQ(integ.advance(f), StepOutcome::step_underflow);
    EXPECT_EQ(integ.rhs_evals(), 2);
  }
  {  // fixed step below h_min
    ControlledIntegrator<ClassicRK4, FixedStep, 4> integ(s);
    integ.start(f, kepler_exact(0.5, 0.0), 0.1);
    EXPECT_EQ(integ.advance(f), StepOutcome::step_underflow);
  }
  {  // through the tracer, as a ray status
    TraceSettings ts;
    ts.integrator = s;
    ts.integrator.h_min = 1e3;
    const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> tracer(SchwarzschildMetric{}, ts);
    const TraceResult r = tracer.trace(incoming_photon(7.0, 50.0));
    EXPECT_EQ(r.status, RayStatus::step_underflow);
    EXPECT_EQ(r.accepted, 0);
    EXPECT_TRUE(r.final_state.allFinite());
  }
}

/// Schwarzschild whose acceleration is NaN inside r < r_poison: a right-hand side that breaks mid-ray.
struct PoisonedSchwarzschild : SchwarzschildMetric {
  double r_poison = 8.0;
  Vec4 acceleration(const Vec4& x, const Vec4& k) const {
    if (x[1] < r_poison) return Vec4::Constant(std::numeric_limits<double>::quiet_NaN());
    return SchwarzschildMetric::acceleration(x, k);
  }
};

// Every shipped tableau on its own (FailuresOfEveryTableau/<name>).
template <class T>
class FailuresOfEveryTableau : public ::testing::Test {};
TYPED_TEST_SUITE(FailuresOfEveryTableau, tableau_tests::AllTableauTypes, tableau_tests::TableauName);

TYPED_TEST(FailuresOfEveryTableau, NonFiniteRightHandSideEndsAFixedStepRunAsNonFinite) {
  using T = TypeParam;
  // Integrator level: the Kepler right-hand side turns NaN once y > 0.5.
  auto poisoned = [](const State4& y) {
    State4 d = KeplerRhs{}(y);
    if (y[1] > 0.5) d.setConstant(std::numeric_limits<double>::quiet_NaN());
    return d;
  };
  ControlledIntegrator<T, FixedStep, 4> integ;
  integ.start(poisoned, kepler_exact(0.5, 0.0), 0.05);
  StepOutcome outcome = StepOutcome::ok;
  int steps = 0;
  while (outcome == StepOutcome::ok && steps < 1000) {
    outcome = integ.advance(poisoned);
    ++steps;
  }
  EXPECT_EQ(outcome, StepOutcome::non_finite);
  EXPECT_LT(steps, 100);                   // y passes 0.5 after t ~ 0.4 (8 steps)
  EXPECT_TRUE(integ.state().allFinite());  // the failed step was not accepted
  EXPECT_LE(integ.state()[1], 0.5);
}

TEST(Failures, NonFiniteRightHandSideEndsAFixedStepTraceAsNonFinite) {
  // Tracer level, fixed step: status non_finite, the last good state returned.
  PoisonedSchwarzschild m;
  TraceSettings s;
  s.initial_step = 1.0;
  const GeodesicTracer<PoisonedSchwarzschild, ClassicRK4, FixedStep> fixed(m, s);
  const TraceResult r = fixed.trace(incoming_photon(3.0, 30.0));
  EXPECT_EQ(r.status, RayStatus::non_finite);
  EXPECT_TRUE(r.final_state.allFinite());
  EXPECT_GE(r.final_state[1], m.r_poison);
  EXPECT_LT(r.accepted, 40);
}

TEST(Failures, NonFiniteRightHandSideNeverHangsAnAdaptiveRun) {
  PoisonedSchwarzschild m;
  TraceSettings s;
  s.max_steps = 1'000'000;
  const GeodesicTracer<PoisonedSchwarzschild, DormandPrince54, PIController> tracer(m, s);
  const TraceResult r = tracer.trace(incoming_photon(3.0, 30.0));
  // Adaptive methods shrink the step towards the bad region until the step underflows.
  EXPECT_TRUE(r.status == RayStatus::step_underflow || r.status == RayStatus::non_finite) << to_string(r.status);
  EXPECT_LT(r.accepted + r.rejected, 5000);
  EXPECT_TRUE(r.final_state.allFinite());
  EXPECT_NEAR(r.final_state[1], m.r_poison, 1e-6);  // it got as close as the step floor allows
  std::printf("poisoned adaptive run: %s after %d accepted, %d rejected, r = %.12f\n",
              std::string(to_string(r.status)).c_str(), r.accepted, r.rejected, r.final_state[1]);
}

// -----------------------------------------------------------------------------------------------------------
// Dense output

/// Error of dense(theta) on one step of size h from the Kepler state at t0, against the exact solution.
template <class T, class C>
double dense_error(double h, double theta) {
  constexpr double e = 0.5, t0 = 1.0;
  const KeplerRhs f{};
  IntegratorSettings s;
  s.tolerance = {1.0, 1.0};  // controlled variants: accept the first step whatever its size
  ControlledIntegrator<T, C, 4> integ(s);
  integ.start(f, kepler_exact(e, t0), h);
  EXPECT_EQ(integ.advance(f), StepOutcome::ok);
  EXPECT_EQ(integ.last_step(), h);
  EXPECT_EQ(max_abs(integ.dense(0.0) - kepler_exact(e, t0)), 0.0);
  EXPECT_LT(max_abs(integ.dense(1.0) - integ.state()), 1e-15);
  return max_abs(integ.dense(theta) - kepler_exact(e, t0 + theta * h));
}

/// Local error of an interpolant of order q is O(h^(q+1)): halving h divides it by ~2^(q+1).
template <class T, class C>
void check_dense_order(int interpolant_order, double theta) {
  SCOPED_TRACE(name_of(T::name) + " + " + name_of(C::name) + " theta " + std::to_string(theta));
  std::vector<double> hs, errs;
  for (double h = 0.1; h > 0.01; h /= 2.0) {
    hs.push_back(h);
    errs.push_back(dense_error<T, C>(h, theta));
  }
  std::printf("%-9s %-8s dense(%.1f) errors:", name_of(T::name).c_str(), name_of(C::name).c_str(), theta);
  for (double v : errs) std::printf(" %.3e", v);
  std::printf("   log2 ratios:");
  for (std::size_t i = 1; i < errs.size(); ++i) {
    const double ratio = std::log2(errs[i - 1] / errs[i]);
    std::printf(" %.2f", ratio);
    EXPECT_NEAR(ratio, interpolant_order + 1, 0.35) << "h = " << hs[i];
  }
  std::printf("\n");
}

TEST(DenseOutput, FreeInterpolantsOfDP5AndTsit5HaveOrderFour) {
  for (double theta : {0.3, 0.5}) {
    check_dense_order<DormandPrince54, FixedStep>(4, theta);
    check_dense_order<Tsitouras54, FixedStep>(4, theta);
    check_dense_order<DormandPrince54, PIController>(4, theta);  // the controller does not change the interpolant
  }
}

TEST(DenseOutput, OtherTableauxFallBackToCubicHermite) {
  for (double theta : {0.3, 0.5}) {
    check_dense_order<ClassicRK4, FixedStep>(3, theta);
    check_dense_order<Verner65, FixedStep>(3, theta);
    check_dense_order<Fehlberg78, FixedStep>(3, theta);
    check_dense_order<DormandPrince54, StepDoubling>(3, theta);  // a doubling step's stages are not its own
  }
}

// -----------------------------------------------------------------------------------------------------------
// Event location

TEST(EventLocator, FindsTheFirstRootAndSurfacesInsideOneStep) {
  // A plain root.
  auto g = [](double t) { return 0.3 - t * t; };
  const auto c = locate_first_crossing(g, g(0.0), g(1.0));
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->theta, std::sqrt(0.3), 1e-12);
  EXPECT_LE(c->value, 0.0);
  // A surface entered and left within the step: invisible at the end points, found with interior samples.
  auto dip = [](double t) { return (t - 0.5) * (t - 0.5) - 0.01; };
  EXPECT_FALSE(locate_first_crossing(dip, dip(0.0), dip(1.0)).has_value());
  const auto d = locate_first_crossing(dip, dip(0.0), dip(1.0), 8);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(d->theta, 0.4, 1e-12);
  // Already inside at the start.
  const auto s = locate_first_crossing(g, -1.0, -1.0);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->theta, 0.0);
  // Non-finite end value: bisected away, root still found.
  auto nan_end = [](double t) { return t < 0.9 ? 0.5 - t : std::numeric_limits<double>::quiet_NaN(); };
  const auto n = locate_first_crossing(nan_end, 0.5, nan_end(1.0));
  ASSERT_TRUE(n.has_value());
  EXPECT_NEAR(n->theta, 0.5, 1e-12);
}

/// A user event r = R on a photon: the ray ends on the sphere (not at the end of the step that crossed it),
/// at the angle the exact orbit has there.
struct SphereEvent {
  double R;
  double operator()(const GeodesicState& y) const { return y[1] - R; }
};

struct LastStepRecorder {
  GeodesicState* step_start;
  GeodesicState* step_end;
  double* theta;
  double* lambda_start;
  double* lambda_end;
  template <class Integrator>
  void operator()(const Integrator& integ, double theta_end) const {
    *step_start = integ.previous_state();
    *step_end = integ.state();
    *theta = theta_end;
    *lambda_start = integ.previous_lambda();
    *lambda_end = integ.lambda();
  }
};

/// phi of the incoming photon (impact parameter b, phi = 0 at r_start) at radius r, exactly.
double exact_incoming_phi(double b, double r_start, double r) {
  return exact::phi_from_infinity(b, 1.0 / r) - exact::phi_from_infinity(b, 1.0 / r_start);
}

/// `own_interpolant`: the tableau's dense output has order 4 (else cubic Hermite, order 3, whose error on a
/// long step can exceed the integration tolerance: the located point is then less accurate than the steps).
template <class T, class C>
void check_sphere_hit(double rtol, double h_max, double phi_tolerance) {
  SCOPED_TRACE(name_of(T::name) + " + " + name_of(C::name));
  constexpr double b = 10.0, r_start = 60.0, R = 20.0;
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-3 * rtol};
  s.integrator.h_max = h_max;
  s.initial_step = C::estimate == ErrorEstimate::none ? h_max : 0.0;
  const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{}, s);
  GeodesicState y0 = GeodesicState::Zero(), y1 = GeodesicState::Zero();
  double theta = 0, l0 = 0, l1 = 0;
  const TraceResult r =
      tracer.trace_observed(incoming_photon(b, r_start), LastStepRecorder{&y0, &y1, &theta, &l0, &l1}, SphereEvent{R});
  ASSERT_EQ(r.status, RayStatus::hit);
  EXPECT_EQ(r.hit_event, 0);
  const double miss = std::abs(r.final_state[1] - R);
  EXPECT_LT(miss, 1e-9);
  // The crossing step straddles R; stopping at its end (the seed's behaviour) would miss R by far more.
  EXPECT_GT(y0[1], R);
  EXPECT_LT(y1[1], R);
  EXPECT_GT(R - y1[1], 1e-2);
  EXPECT_GT(theta, 0.0);
  EXPECT_LT(theta, 1.0);
  EXPECT_NEAR(r.lambda, l0 + theta * (l1 - l0), 1e-12 * l1);
  EXPECT_EQ((r.step_end_state - y1).cwiseAbs().maxCoeff(), 0.0);  // the step's own end is reported too
  // Both the step's end and the located event lie on the true orbit: phi(r) from the exact elliptic integral.
  const double step_end_error = y1[3] - exact_incoming_phi(b, r_start, y1[1]);
  const double located_error = r.final_state[3] - exact_incoming_phi(b, r_start, R);
  std::printf(
      "%-9s %-8s: |r - R| = %.1e; step ended at r = %.3f (%.3f past R); phi error at step end %.1e, at the "
      "located event %.1e\n",
      name_of(T::name).c_str(), name_of(C::name).c_str(), miss, y1[1], R - y1[1], step_end_error, located_error);
  EXPECT_LT(std::abs(step_end_error), 1e3 * rtol);
  EXPECT_LT(std::abs(located_error), phi_tolerance);
}

TEST(EventLocator, RayHitsASphereWhereItIsNotOneStepLate) {
  // Own order-4 interpolants: the event is as accurate as the steps.
  check_sphere_hit<DormandPrince54, PIController>(1e-8, 15.0, 1e-5);
  check_sphere_hit<Tsitouras54, PIController>(1e-8, 15.0, 1e-5);
  check_sphere_hit<DormandPrince54, FixedStep>(1e-3, 3.0, 1e-5);
  // Cubic Hermite: fine for a low-order method, loose for a high-order one taking long steps.
  check_sphere_hit<ClassicRK4, StepDoubling>(1e-8, 15.0, 1e-5);
  check_sphere_hit<Fehlberg78, IController>(1e-8, 15.0, 1e-3);
}

}  // namespace
}  // namespace grtrace
