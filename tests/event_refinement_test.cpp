// tests/event_refinement_test.cpp
// Tests that a ray's event crossing (a scene surface, the sky sphere, the horizon guard) is located to the
// integration's accuracy for every adaptive tableau, not to its interpolant's: the tracer
// brackets a crossing on the dense output and then refines it on the integrator's own step map
// (ControlledIntegrator::step_from_previous, refine_crossing in integrate/event_locator.hpp).
//
// The judge is exact. A Schwarzschild photon moves in a plane through the hole; that plane meets the equatorial
// plane along a line, so the photon crosses the equator after sweeping, in its own plane, an angle psi fixed by
// the geometry of the initial state. Where it is then follows from the orbit: Phi(u) = Phi(u0) + psi, with
// Phi(u) the angle swept from infinity (exact/schwarzschild_exact.hpp, elliptic integrals), inverted by
// bisection; independently, u'' = -u + 3 M u^2 integrated by classical RK4 with a tiny step.
// Every check also runs with TraceSettings::refine_events = false (the crossing read from the interpolant, the
// old behaviour) and prints both, so the tables show before and after. M = 1 throughout.
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include "common/tableau_types.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace grtrace {
namespace {

constexpr double kPi = std::numbers::pi;

std::string name_of(std::string_view v) { return std::string(v); }

// -----------------------------------------------------------------------------------------------------------
// Events

/// The equatorial plane as a two-sided event, g = cos(theta) (as scene/thin_disk.hpp's disk, without its radii).
struct EquatorialPlane {
  static constexpr bool two_sided = true;
  double operator()(const GeodesicState& y) const { return std::cos(y[2]); }
};

/// A thin annulus r_in <= r <= r_out in the equatorial plane: the plane, filtered by accepts().
struct Annulus {
  static constexpr bool two_sided = true;
  double r_in = 6.0, r_out = 20.0;
  double operator()(const GeodesicState& y) const { return std::cos(y[2]); }
  bool accepts(const GeodesicState& y) const { return y[1] >= r_in && y[1] <= r_out; }
};

// -----------------------------------------------------------------------------------------------------------
// The inclined photon and its exact equator crossing

/// A photon of energy 1 (k_t = -1) and impact parameter b at (r0, theta0, phi = 0), moving inward, whose
/// angular motion points at the angle alpha from e_phi towards north (-e_theta): its orbital plane is
/// inclined to the equator.
struct InclinedPhoton {
  double b = 7.0, r0 = 30.0, theta0 = 1.2, alpha = 0.0;

  /// The initial state in Schwarzschild coordinates (null: -f k_t^2 + k_r^2 / f + b^2 / r^2 = 0).
  GeodesicState state() const {
    const double f = 1.0 - 2.0 / r0, w = b / (r0 * r0);
    const Vec4 x(0.0, r0, theta0, 0.0);
    const Vec4 k(1.0 / f, -std::sqrt(1.0 - f * b * b / (r0 * r0)), -w * std::sin(alpha),
                 w * std::cos(alpha) / std::sin(theta0));
    return make_state(x, k);
  }

  /// Angle the photon sweeps in its orbital plane from the start to its first crossing of the equator.
  /// Along the orbit the position's direction is n cos psi + t sin psi, with n = (sin theta0, 0, cos theta0)
  /// and t = cos(alpha) e_phi - sin(alpha) e_theta; its z component cos(theta0) cos psi +
  /// sin(alpha) sin(theta0) sin psi = R cos(psi - beta) vanishes at psi = beta + pi/2 (mod pi).
  double sweep_to_equator() const {
    const double beta = std::atan2(std::sin(alpha) * std::sin(theta0), std::cos(theta0));
    double psi = beta + kPi / 2.0;
    while (psi <= 0.0) psi += kPi;
    while (psi > kPi) psi -= kPi;
    return psi;
  }
};

/// u = 1/r at which the photon has swept `sweep` from its start, from the exact Phi(u) inverted by bisection
/// (Phi increases with u on either branch's own interval). Nothing if it escapes or reaches r <= r_stop first.
std::optional<double> exact_radius_after(const InclinedPhoton& p, double sweep, double r_stop) {
  const double u0 = 1.0 / p.r0, u_stop = 1.0 / r_stop;
  const double target = exact::phi_from_infinity(p.b, u0) + sweep;
  auto solve = [](auto&& phi, double lo, double hi, double value) {
    for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (phi(mid) < value ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  auto phi = [&](double u) { return exact::phi_from_infinity(p.b, u); };
  if (p.b > exact::critical_impact_parameter()) {
    const double u_p = 1.0 / exact::periapsis_from_impact(p.b);
    const double phi_p = phi(u_p);
    if (target <= phi_p) return 1.0 / solve(phi, u0, u_p, target);           // before the periapsis
    const double back = 2.0 * phi_p - target;                                 // after it, moving out
    if (back <= 0.0) return std::nullopt;
    return 1.0 / solve(phi, 0.0, u_p, back);
  }
  if (target > phi(u_stop)) return std::nullopt;
  return 1.0 / solve(phi, u0, u_stop, target);
}

/// The same radius from the orbit equation u'' = -u + 3 u^2 (M = 1), u(0) = 1/r0, u'(0) = -k^r / b, by
/// classical RK4 in the swept angle with `steps` equal steps: an independent check on the bisection.
double rk4_radius_after(const InclinedPhoton& p, double sweep, int steps) {
  const double f = 1.0 - 2.0 / p.r0;
  std::array<double, 2> y = {1.0 / p.r0, std::sqrt(1.0 - f * p.b * p.b / (p.r0 * p.r0)) / p.b};
  auto d = [](const std::array<double, 2>& v) { return std::array<double, 2>{v[1], -v[0] + 3.0 * v[0] * v[0]}; };
  auto add = [](const std::array<double, 2>& v, double h, const std::array<double, 2>& k) {
    return std::array<double, 2>{v[0] + h * k[0], v[1] + h * k[1]};
  };
  const double h = sweep / steps;
  for (int i = 0; i < steps; ++i) {
    const auto k1 = d(y), k2 = d(add(y, 0.5 * h, k1)), k3 = d(add(y, 0.5 * h, k2)), k4 = d(add(y, h, k3));
    for (std::size_t j = 0; j < 2; ++j) y[j] += h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
  }
  return 1.0 / y[0];
}

/// The test photons: one crossing the equator before its periapsis, one behind the hole after it, one
/// (b < b_c) on its way in, on a steep plunge.
const std::array<InclinedPhoton, 3> kPhotons = {{
    {8.0, 30.0, kPi / 2.0 - 0.4, -0.5},
    {6.0, 30.0, kPi / 2.0 - 0.3, 0.6},
    {4.0, 30.0, kPi / 2.0 - 0.2, -1.2},
}};

/// The exact equator-crossing radius of each test photon.
std::vector<double> exact_crossing_radii() {
  std::vector<double> r;
  for (const InclinedPhoton& p : kPhotons) r.push_back(exact_radius_after(p, p.sweep_to_equator(), 2.002).value());
  return r;
}

TEST(ExactReference, BisectionAndOrbitEquationAgree) {
  for (const InclinedPhoton& p : kPhotons) {
    const double psi = p.sweep_to_equator();
    const auto r = exact_radius_after(p, psi, 2.002);
    ASSERT_TRUE(r.has_value()) << "b = " << p.b;
    const double r_rk4 = rk4_radius_after(p, psi, 40000);
    std::printf("b = %.1f: sweep to the equator %.6f rad, crossing at r = %.15f (RK4 on u'': %.15f)\n", p.b, psi,
                *r, r_rk4);
    EXPECT_NEAR(r_rk4 / *r, 1.0, 1e-12);
    EXPECT_GT(psi, 0.0);
    EXPECT_LT(psi, kPi);
  }
}

TEST(ExactReference, TheInitialStateIsNullAndOnItsPlane) {
  const SchwarzschildMetric m;
  for (const InclinedPhoton& p : kPhotons) {
    const GeodesicState y = p.state();
    EXPECT_NEAR(inner_product(m, y.head<4>(), y.tail<4>(), y.tail<4>()), 0.0, 1e-14);
    // |L| = r^2 sqrt(k_theta^2 + sin^2(theta) k_phi^2) (SchwarzschildMetric::total_angular_momentum has
    // sin^4 where sin^2 belongs, so it is exact only on the equator: not used here).
    const double st = std::sin(y[2]);
    EXPECT_NEAR(y[1] * y[1] * std::sqrt(y[6] * y[6] + st * st * y[7] * y[7]), p.b, 1e-12);
  }
}

// -----------------------------------------------------------------------------------------------------------
// The pieces: the step map and the secant refinement

/// Kepler problem, y = (x, y, vx, vy): a smooth nonlinear right-hand side for the integrator-level checks.
struct Kepler {
  Vector<4> operator()(const Vector<4>& y) const {
    const double r2 = y[0] * y[0] + y[1] * y[1], r3 = r2 * std::sqrt(r2);
    Vector<4> d;
    d << y[2], y[3], -y[0] / r3, -y[1] / r3;
    return d;
  }
};

template <class T, class C>
void check_step_map(C controller) {
  SCOPED_TRACE(name_of(T::name) + " + " + name_of(C::name));
  IntegratorSettings s;
  s.tolerance = {1e-6, 1e-9};
  ControlledIntegrator<T, C, 4> integ(s, controller);
  const Kepler f{};
  Vector<4> y0;
  y0 << 0.5, 0.0, 0.0, std::sqrt(3.0);  // eccentricity 0.5 at periapsis
  integ.start(f, y0, 0.05);
  for (int i = 0; i < 5; ++i) ASSERT_EQ(integ.advance(f), StepOutcome::ok);
  const Vector<4> dense_before = integ.dense(0.37);
  const long evals_before = integ.rhs_evals();
  // theta = 1 is the accepted step itself, bit for bit.
  EXPECT_EQ(integ.step_from_previous(f, 1.0), integ.state());
  // Any other theta is the same method's step theta h from the step's start: as a fresh fixed-step integrator
  // would take it (for step doubling: its two half steps, extrapolated or not).
  const double theta = 0.37;
  const Vector<4> y = integ.step_from_previous(f, theta);
  using FreshController = std::conditional_t<C::estimate == ErrorEstimate::step_doubling, C, FixedStep>;
  FreshController fresh_controller{};
  if constexpr (std::is_same_v<FreshController, C>) fresh_controller = controller;
  ControlledIntegrator<T, FreshController, 4> fresh(
      IntegratorSettings{s.tolerance, 0.0, std::numeric_limits<double>::infinity()}, fresh_controller);
  fresh.start(f, integ.previous_state(), theta * integ.last_step());
  ASSERT_EQ(fresh.advance(f), StepOutcome::ok);
  EXPECT_LT((y - fresh.state()).cwiseAbs().maxCoeff(), 1e-15);
  // The probes are counted, and the dense output still describes the accepted step.
  EXPECT_GT(integ.rhs_evals(), evals_before);
  EXPECT_EQ(integ.dense(0.37), dense_before);
}

TEST(StepMap, ReTakesTheLastStepShortenedWithTheSameMethod) {
  check_step_map<Fehlberg78, IController>({});
  check_step_map<Tsitouras54, PIController>({});
  check_step_map<ClassicRK4, FixedStep>({});
  check_step_map<ClassicRK4, StepDoubling>({});
  StepDoubling richardson;
  richardson.richardson = true;
  check_step_map<Rule38, StepDoubling>(richardson);
}

TEST(RefineCrossing, SecantFromAnInterpolantsEstimateConvergesInAFewProbes) {
  // The "step map" g(theta) = cos(3 theta) - 0.4 crosses at acos(0.4) / 3; the "interpolant" is off by 1e-4.
  const double root = std::acos(0.4) / 3.0;
  int calls = 0;
  auto probe = [&](double t) {
    ++calls;
    return Probed<double>{std::cos(3.0 * t) - 0.4, t};
  };
  const double theta0 = root + 1e-4, slope0 = -3.0 * std::sin(3.0 * (root - 2e-4));
  const auto c = refine_crossing(probe, theta0, slope0);
  ASSERT_TRUE(c.has_value());
  EXPECT_TRUE(c->converged);
  EXPECT_EQ(c->probes, calls);
  EXPECT_LE(c->probes, 3);
  EXPECT_EQ(c->payload, c->theta);
  EXPECT_LE(std::abs(c->pending), 1e-7);
  EXPECT_NEAR(c->theta + c->pending, root, 1e-15);
  // A non-finite probe at the start gives nothing; a crossing beyond the step is clamped to its end.
  auto nan_probe = [](double t) { return Probed<double>{std::nan(""), t}; };
  EXPECT_FALSE(refine_crossing(nan_probe, 0.5, -1.0).has_value());
  auto late = [](double t) { return Probed<double>{1.5 - t, t}; };
  const auto e = refine_crossing(late, 0.99, -1.0);
  ASSERT_TRUE(e.has_value());
  EXPECT_LE(e->theta + e->pending, 1.0);
}

// -----------------------------------------------------------------------------------------------------------
// Convergence of the equator crossing with the tolerance, for every adaptive tableau

struct CrossingErrors {
  double refined = 0.0, dense = 0.0;  ///< worst |r - r_exact| / r_exact over the photons
  long evals_refined = 0, evals_dense = 0;
  long refinement_evals = 0;
};

/// Traces every test photon to the equator with tableau T and controller C at rtol (atol 1e-3 rtol), once
/// with refinement and once located on the dense output only. Returns the worst relative radius errors.
template <class T, class C>
CrossingErrors equator_crossing_errors(double rtol) {
  CrossingErrors out;
  const std::vector<double> exact = exact_crossing_radii();
  for (const bool refine : {true, false}) {
    TraceSettings s;
    s.integrator.tolerance = {rtol, 1e-3 * rtol};
    s.max_steps = 10'000'000;
    s.refine_events = refine;
    const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{}, s);
    for (std::size_t i = 0; i < kPhotons.size(); ++i) {
      const TraceResult r = tracer.trace(kPhotons[i].state(), EquatorialPlane{});
      EXPECT_EQ(r.status, RayStatus::hit) << "photon " << i;
      const double err = std::abs(r.final_state[1] - exact[i]) / exact[i];
      (refine ? out.refined : out.dense) = std::max(refine ? out.refined : out.dense, err);
      (refine ? out.evals_refined : out.evals_dense) += r.rhs_evals;
      if (refine) out.refinement_evals += r.refinement_evals;
      else EXPECT_EQ(r.refinement_evals, 0);
    }
  }
  return out;
}

/// The tolerance ladder of a tableau: 1e-6, 1e-9, 1e-12, shifted up for the low orders whose steps at
/// 1e-12 would number in the tens of millions.
template <class T>
std::array<double, 3> rtol_ladder() {
  if constexpr (T::order <= 2) return {1e-4, 1e-6, 1e-8};
  else return {1e-6, 1e-9, 1e-12};
}

template <class T, class C>
void check_convergence(double bound_at_finest) {
  SCOPED_TRACE(name_of(T::name) + " + " + name_of(C::name));
  const auto ladder = rtol_ladder<T>();
  std::array<CrossingErrors, 3> e;
  for (std::size_t j = 0; j < 3; ++j) e[j] = equator_crossing_errors<T, C>(ladder[j]);
  std::printf("%-9s %-8s", name_of(T::name).c_str(), name_of(C::name).c_str());
  for (std::size_t j = 0; j < 3; ++j)
    std::printf(" | %.0e: %.1e (dense %.1e)", ladder[j], e[j].refined, e[j].dense);
  std::printf(" | evals at finest %+.2f %% (%ld for the 3 refinements)\n",
              100.0 * (static_cast<double>(e[2].evals_refined) / static_cast<double>(e[2].evals_dense) - 1.0),
              e[2].refinement_evals);
  EXPECT_LT(e[1].refined, e[0].refined);
  EXPECT_LT(e[2].refined, e[1].refined);
  EXPECT_LT(e[2].refined, bound_at_finest);
}

/// The table's header, before its first row (the rows come from one test per tableau).
void print_convergence_header() {
  if (!tableau_tests::first_row("equator crossing convergence")) return;
  std::printf("worst relative error of the equator-crossing radius over %zu photons, refined on the step map\n"
              "(and located on the dense output only, as before):\n",
              kPhotons.size());
}

// Every adaptive tableau on its own (EventRefinementOfEveryAdaptiveTableau/<name>).
template <class T>
class EventRefinementOfEveryAdaptiveTableau : public ::testing::Test {};
TYPED_TEST_SUITE(EventRefinementOfEveryAdaptiveTableau, tableau_tests::EmbeddedPairTableauTypes,
                 tableau_tests::TableauName);

TYPED_TEST(EventRefinementOfEveryAdaptiveTableau, EquatorCrossingConvergesWithTheTolerance) {
  using T = TypeParam;
  print_convergence_header();
  // The bound at the finest tolerance: 1e-9 relative for the 1e-12 ladder (measured: 4e-13 ... 1.5e-10, the
  // integration's own global error; located on the dense output only, rkf78 was 4e-7 ... 9e-7 off and
  // vern6 4e-9 ... 6e-9), 1e-7 for the 1e-8 ladder of the second-order pair (measured 2e-8).
  const double bound = T::order <= 2 ? 1e-7 : 1e-9;
  check_convergence<T, PIController>(bound);
  check_convergence<T, IController>(bound);
}

TEST(EventRefinement, EquatorCrossingConvergesWithTheToleranceUnderStepDoubling) {
  print_convergence_header();
  check_convergence<ClassicRK4, StepDoubling>(1e-9);  // a tableau without an embedded pair
}

// -----------------------------------------------------------------------------------------------------------
// A small ball the ray can enter and leave within one step: interior samples, then refinement

/// A ball of radius rho around the Cartesian point c (of the chart's embedding), with interior samples so that
/// a step that passes through it is caught.
struct SmallBall {
  static constexpr int interior_samples = 8;
  Vec3 c;
  double rho;
  double operator()(const GeodesicState& y) const { return (spherical_to_cartesian(y.head<4>()) - c).norm() - rho; }
};

/// The exact point (Cartesian) of the first test photon after sweeping psi, and the ball it enters: centred on
/// its exact equator crossing, radius 0.4. Returns the ball and the exact entry radius (bisection on the swept
/// angle: the distance to the centre falls monotonically over the last 0.3 rad before it).
struct BallReference {
  SmallBall ball;
  double entry_radius;
};
BallReference ball_on_first_photon() {
  const InclinedPhoton& p = kPhotons[0];
  const Vec3 n(std::sin(p.theta0), 0.0, std::cos(p.theta0));
  const Vec3 t(-std::sin(p.alpha) * std::cos(p.theta0), std::cos(p.alpha), std::sin(p.alpha) * std::sin(p.theta0));
  auto point = [&](double psi) {
    return exact_radius_after(p, psi, 2.002).value() * (n * std::cos(psi) + t * std::sin(psi));
  };
  const double psi_c = p.sweep_to_equator(), rho = 0.4;
  const Vec3 c = point(psi_c);
  double lo = psi_c - 0.3, hi = psi_c;  // outside at lo, inside at hi
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    ((point(mid) - c).norm() > rho ? lo : hi) = mid;
  }
  return {SmallBall{c, rho}, exact_radius_after(p, 0.5 * (lo + hi), 2.002).value()};
}

template <class T, class C>
void check_ball(double rtol, double bound) {
  SCOPED_TRACE(name_of(T::name) + " + " + name_of(C::name));
  const BallReference ref = ball_on_first_photon();
  std::array<double, 2> err{};
  std::array<double, 2> largest_step{};
  for (const bool refine : {true, false}) {
    TraceSettings s;
    s.integrator.tolerance = {rtol, 1e-3 * rtol};
    s.refine_events = refine;
    const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{}, s);
    double h = 0.0;
    const TraceResult r = tracer.trace_observed(
        kPhotons[0].state(), [&](const auto& integ, double) { h = std::max(h, integ.last_step()); }, ref.ball);
    ASSERT_EQ(r.status, RayStatus::hit);
    err[refine ? 0 : 1] = std::abs(r.final_state[1] / ref.entry_radius - 1.0);
    largest_step[refine ? 0 : 1] = h;
  }
  std::printf("%-9s %-8s rtol %.0e: ball entry radius error %.1e (dense only: %.1e), largest step %.1f M "
              "(the ball is %.1f M across)\n",
              name_of(T::name).c_str(), name_of(C::name).c_str(), rtol, err[0], err[1], largest_step[0],
              2.0 * ref.ball.rho);
  EXPECT_LT(err[0], bound);
}

TEST(EventRefinement, ABallEnteredAndLeftWithinOneStepIsHitWhereItIs) {
  // Loose tolerances: steps longer than the ball, so interior samples find it; then refined all the same.
  check_ball<Fehlberg78, PIController>(1e-6, 1e-6);
  check_ball<Verner65, PIController>(1e-6, 1e-5);
  check_ball<Tsitouras54, IController>(1e-6, 1e-5);
  check_ball<Fehlberg78, PIController>(1e-12, 1e-9);
}

// -----------------------------------------------------------------------------------------------------------
// The termination surfaces: sky sphere and horizon guard

/// The swept angle phi of the equatorial photon incoming_photon(b, r_start) at radius r, exactly: on the way in,
/// or (outgoing) after the periapsis.
double exact_phi(double b, double r_start, double r, bool outgoing) {
  const double phi_r = exact::phi_from_infinity(b, 1.0 / r), phi_start = exact::phi_from_infinity(b, 1.0 / r_start);
  if (!outgoing) return phi_r - phi_start;
  return 2.0 * exact::phi_from_infinity(b, 1.0 / exact::periapsis_from_impact(b)) - phi_r - phi_start;
}

struct SurfaceErrors {
  double radius_miss = 0.0;  ///< |r - R| / R of the final state
  double phi_error = 0.0;    ///< |phi - phi_exact(r)|: is the state on the true orbit there?
};

template <class T, class C>
SurfaceErrors surface_errors(double b, bool refine, double rtol) {
  constexpr double r_start = 30.0, R = 60.0, eps = 1e-3;
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-3 * rtol};
  s.escape_radius = R;
  s.horizon_epsilon = eps;
  s.refine_events = refine;
  const GeodesicTracer<SchwarzschildMetric, T, C> tracer(SchwarzschildMetric{}, s);
  const TraceResult r = tracer.trace(incoming_photon(b, r_start));
  const bool escapes = b > exact::critical_impact_parameter();
  EXPECT_EQ(r.status, escapes ? RayStatus::escaped : RayStatus::captured);
  const double surface = escapes ? R : 2.0 * (1.0 + eps);
  const double rf = r.final_state[1];
  return {std::abs(rf - surface) / surface, std::abs(r.final_state[3] - exact_phi(b, r_start, rf, escapes))};
}

template <class T, class C>
void check_surfaces() {
  SCOPED_TRACE(name_of(T::name) + " + " + name_of(C::name));
  constexpr double rtol = 1e-12;
  for (const double b : {7.0, 4.0}) {
    const SurfaceErrors refined = surface_errors<T, C>(b, true, rtol), dense = surface_errors<T, C>(b, false, rtol);
    std::printf("%-9s %-8s b = %.0f (%s): |r - R|/R = %.1e, phi error %.1e (dense only: %.1e, %.1e)\n",
                name_of(T::name).c_str(), name_of(C::name).c_str(), b, b > 5.2 ? "sky sphere" : "horizon guard",
                refined.radius_miss, refined.phi_error, dense.radius_miss, dense.phi_error);
    EXPECT_LT(refined.radius_miss, 1e-12);
    // The integration's own phi error at this tolerance is ~1e-11; the interpolant's may be ~1e-6.
    EXPECT_LT(refined.phi_error, 1e-9);
  }
}

TEST(EventRefinement, SkySphereAndHorizonGuardAreHitToIntegrationAccuracy) {
  check_surfaces<Fehlberg78, IController>();
  check_surfaces<Verner65, PIController>();
  check_surfaces<CashKarp54, PIController>();
  check_surfaces<Tsitouras54, PIController>();
  check_surfaces<ClassicRK4, StepDoubling>();
}

// -----------------------------------------------------------------------------------------------------------
// No new misses: a frame-like set of rays ends the same way with and without refinement

/// Rays from a camera at r = 30, 9 degrees above the equator: impact parameters 0.25 ... 15 against 32
/// directions of the orbital plane (as a frame samples impact parameter and position angle), through an annulus
/// 6 <= r <= 20 (the renderer's default disk).
std::vector<InclinedPhoton> frame_like_rays() {
  std::vector<InclinedPhoton> rays;
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 32; ++j)  // half-integer j: no ray straight over the pole (a coordinate singularity)
      rays.push_back({0.25 + 0.62 * i, 30.0, kPi / 2.0 - 0.15, 2.0 * kPi * (j + 0.5) / 32.0});
  return rays;
}

/// The exact radius at which the photon hits the annulus: its k-th equator crossing (swept angle
/// psi_0 + k pi) is the first with r_in <= r <= r_out, or nothing if it escapes or falls in first.
std::optional<double> exact_annulus_hit(const InclinedPhoton& p, const Annulus& disk) {
  for (int k = 0; k < 8; ++k) {
    const auto r = exact_radius_after(p, p.sweep_to_equator() + k * kPi, 2.002);
    if (!r) return std::nullopt;
    if (*r >= disk.r_in && *r <= disk.r_out) return r;
  }
  return std::nullopt;
}

/// Traces the frame-like rays into the annulus with and without refinement at rtol: the same rays must end the
/// same way, hit exactly where the exact orbits do, and (refined) within `bound` M of the exact hit radius.
template <class T, class C>
void check_same_outcomes(double rtol, double bound) {
  SCOPED_TRACE(name_of(T::name) + " + " + name_of(C::name));
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-3 * rtol};
  TraceSettings dense_only = s;
  dense_only.refine_events = false;
  const GeodesicTracer<SchwarzschildMetric, T, C> refined(SchwarzschildMetric{}, s);
  const GeodesicTracer<SchwarzschildMetric, T, C> dense(SchwarzschildMetric{}, dense_only);
  const Annulus disk{};
  int hits = 0, hits_dense = 0, hits_exact = 0, differing = 0, compared = 0;
  long evals = 0, evals_dense = 0;
  double largest_shift = 0.0, worst = 0.0, worst_dense = 0.0;
  const std::vector<InclinedPhoton> rays = frame_like_rays();
  for (const InclinedPhoton& p : rays) {
    const TraceResult a = refined.trace(p.state(), disk), b = dense.trace(p.state(), disk);
    const auto exact = exact_annulus_hit(p, disk);
    hits += a.status == RayStatus::hit;
    hits_dense += b.status == RayStatus::hit;
    hits_exact += exact.has_value();
    if (exact.has_value() != (a.status == RayStatus::hit))  // say which, if any
      std::printf("  b = %.2f alpha = %.3f: %s, r = %.6f, exact %.6f, steps %d\n", p.b, p.alpha,
                  std::string(to_string(a.status)).c_str(), a.final_state[1], exact.value_or(-1.0), a.accepted);
    differing += a.status != b.status;
    evals += a.rhs_evals;
    evals_dense += b.rhs_evals;
    if (a.status == RayStatus::hit && b.status == RayStatus::hit)
      largest_shift = std::max(largest_shift, std::abs(a.final_state[1] - b.final_state[1]));
    if (exact && a.status == RayStatus::hit && b.status == RayStatus::hit) {
      ++compared;
      worst = std::max(worst, std::abs(a.final_state[1] - *exact));
      worst_dense = std::max(worst_dense, std::abs(b.final_state[1] - *exact));
    }
  }
  std::printf("%-9s %-8s rtol %.0e: %d of %zu rays hit the disk (dense only: %d, exact: %d), %d end differently; "
              "largest hit-radius shift %.1e M; worst |r - r_exact| over %d hits %.1e M (dense only %.1e M); rhs "
              "evaluations %+.2f %%\n",
              name_of(T::name).c_str(), name_of(C::name).c_str(), rtol, hits, rays.size(), hits_dense, hits_exact,
              differing, largest_shift, compared, worst, worst_dense,
              100.0 * (static_cast<double>(evals) / static_cast<double>(evals_dense) - 1.0));
  EXPECT_EQ(hits, hits_dense);
  EXPECT_EQ(differing, 0);
  EXPECT_EQ(hits, hits_exact);
  EXPECT_GT(hits, 100);
  EXPECT_LT(worst, bound);
}

TEST(EventRefinement, AFrameOfRaysEndsTheSameWayWithAndWithoutRefinement) {
  // Bounds: the measured worst refined errors (M) times ~3; located on the dense output only, the rkf78 rows
  // were 5.5e-4 and 1.0e-5 M off and vern6 3.5e-3 M.
  check_same_outcomes<Tsitouras54, IController>(2e-9, 1e-7);  // the renderer's default (refined 2.9e-8)
  check_same_outcomes<Fehlberg78, PIController>(1e-9, 2e-7);   // refined 4.7e-8
  check_same_outcomes<Fehlberg78, IController>(1e-13, 2e-11);  // far below the interpolant's error; refined 5.9e-12
  check_same_outcomes<Verner65, PIController>(1e-6, 1.5e-3);   // refined 4.4e-4
  check_same_outcomes<BogackiShampine32, PIController>(1e-6, 5e-4);  // 1.5e-4 (integration error, both)
  check_same_outcomes<ClassicRK4, StepDoubling>(1e-8, 5e-5);   // 1.2e-5 (integration error, both)
}

}  // namespace
}  // namespace grtrace
