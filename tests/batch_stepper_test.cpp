// tests/batch_stepper_test.cpp
// integrate/batch_stepper.hpp: W problems stepped at once must give, lane by lane, exactly the numbers of the scalar
// stepper on each problem alone (the planar table's nodes rely on it: trace_node and the batched build must agree
// bit for bit); ControlledIntegrator::judge_trial, fed a lane's trial, must take the steps advance() takes; and so
// must every lane of a BatchedIntegrator (integrate/batch_integrator.hpp), also across unload / resume_at / load.
#include "grtrace/integrate/batch_integrator.hpp"
#include "grtrace/integrate/batch_stepper.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"
#include "grtrace/tableau/all_tableaux.hpp"

#include "common/tableau_types.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

namespace {

using namespace grtrace;

// A small nonlinear system with a state of 3 (a rigid body's Euler equations, plus a nonlinear coupling), so each
// stage's numbers depend on all components.
Vector<3> euler_rhs(const Vector<3>& y) {
  return {y[1] * y[2] - 0.3 * y[0] * y[0], -2.0 * y[0] * y[2], 0.7 * y[0] * y[1] + std::sin(y[2])};
}

template <int W>
void batch_rhs(const Batch<3, W>& y, Batch<3, W>& dy) {
  for (int l = 0; l < W; ++l) set_lane(dy, l, euler_rhs(lane_of(y, l)));
}

// Every shipped tableau on its own (BatchStepperOfEveryTableau/<name>).
template <class T>
class BatchStepperOfEveryTableau : public ::testing::Test {};
TYPED_TEST_SUITE(BatchStepperOfEveryTableau, tableau_tests::AllTableauTypes, tableau_tests::TableauName);

TYPED_TEST(BatchStepperOfEveryTableau, EveryLaneIsTheScalarStepBitForBit) {
  constexpr int W = 3;
  using T = TypeParam;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  RungeKuttaBatchStepper<T, 3, W> batch;
  Batch<3, W> y{}, f{}, y_new{}, err{};
  std::array<double, W> h{};
  std::array<Vector<3>, W> ys;
  for (int l = 0; l < W; ++l) {
    ys[static_cast<std::size_t>(l)] = Vector<3>(u(rng), u(rng), u(rng));
    set_lane(y, l, ys[static_cast<std::size_t>(l)]);
    set_lane(f, l, euler_rhs(ys[static_cast<std::size_t>(l)]));
    h[static_cast<std::size_t>(l)] = 0.05 * (l + 1) + 0.01 * u(rng);  // a different step in every lane
  }
  batch.step(batch_rhs<W>, y, f, h, y_new, err);
  for (int l = 0; l < W; ++l) {
    RungeKuttaStepper<T, 3> scalar;
    Vector<3> s_new, s_err = Vector<3>::Zero();
    const Vector<3>& y0 = ys[static_cast<std::size_t>(l)];
    scalar.step(euler_rhs, y0, euler_rhs(y0), h[static_cast<std::size_t>(l)], s_new, s_err);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(lane_of(y_new, l)[i], s_new[i]) << T::name << " lane " << l << " component " << i;
      if constexpr (has_embedded_pair<T>) {
        EXPECT_EQ(lane_of(err, l)[i], s_err[i]) << T::name << " lane " << l;
      }
    }
    for (std::size_t s = 0; s < T::stages; ++s) EXPECT_EQ(lane_of(batch.stage(s), l), scalar.stage(s)) << T::name;
  }
}

// A lane driven by batched trials and judge_trial takes advance()'s accepted and rejected steps exactly, for an
// FSAL pair (Tsitouras 5(4), PI) and a pair whose last stage is not f(y_new) (Fehlberg 7(8), I).
template <class T, class C>
void expect_judged_lanes_follow_advance() {
  constexpr int W = 2;
  const IntegratorSettings settings{Tolerance{1e-10, 1e-12}};
  const std::array<Vector<3>, W> starts = {Vector<3>(1.0, 0.2, -0.4), Vector<3>(-0.3, 1.1, 0.9)};
  std::array<ControlledIntegrator<T, C, 3>, W> lanes{ControlledIntegrator<T, C, 3>(settings),
                                                     ControlledIntegrator<T, C, 3>(settings)};
  // A first step far too long: the first trials are rejected, so the comparison covers rejections too.
  constexpr double first_step = 2.0;
  for (int l = 0; l < W; ++l)
    lanes[static_cast<std::size_t>(l)].start(euler_rhs, starts[static_cast<std::size_t>(l)], first_step);
  RungeKuttaBatchStepper<T, 3, W> batch;
  Batch<3, W> y{}, f{}, y_new{}, err{};
  std::array<double, W> h{};
  std::array<int, W> accepted{};
  while (accepted[0] < 200 || accepted[1] < 200) {
    for (int l = 0; l < W; ++l) {
      auto& lane = lanes[static_cast<std::size_t>(l)];
      h[static_cast<std::size_t>(l)] = *lane.trial_step();
      set_lane(y, l, lane.state());
      set_lane(f, l, lane.derivative());
    }
    batch.step(batch_rhs<W>, y, f, h, y_new, err);
    for (int l = 0; l < W; ++l)
      if (lanes[static_cast<std::size_t>(l)].judge_trial(euler_rhs, h[static_cast<std::size_t>(l)], lane_of(y_new, l),
                                                         lane_of(err, l), lane_of(batch.stage(T::stages - 1), l)))
        ++accepted[static_cast<std::size_t>(l)];
  }
  for (int l = 0; l < W; ++l) {
    ControlledIntegrator<T, C, 3> alone(settings);
    alone.start(euler_rhs, starts[static_cast<std::size_t>(l)], first_step);
    const auto& lane = lanes[static_cast<std::size_t>(l)];
    while (alone.accepted() < lane.accepted()) ASSERT_EQ(alone.advance(euler_rhs), StepOutcome::ok);
    EXPECT_EQ(alone.state(), lane.state()) << T::name << " lane " << l;
    EXPECT_EQ(alone.lambda(), lane.lambda()) << T::name << " lane " << l;
    EXPECT_EQ(alone.rejected(), lane.rejected()) << T::name << " lane " << l;
    EXPECT_EQ(alone.rhs_evals(), lane.rhs_evals()) << T::name << " lane " << l;
    EXPECT_EQ(alone.next_step(), lane.next_step()) << T::name << " lane " << l;
    EXPECT_GT(lane.rejected(), 0) << "the comparison should include rejected trials";
  }
}

TEST(BatchStepper, JudgedLanesTakeTheStepsAdvanceTakes) {
  expect_judged_lanes_follow_advance<Tsitouras54, PIController>();
  expect_judged_lanes_follow_advance<Fehlberg78, IController>();
}

// Every lane of a BatchedIntegrator takes advance()'s steps bit for bit (accepted and rejected, the counts, the next
// step), for W = 4 (the lane norm in vector registers) and W = 3 (lane by lane), an FSAL pair with PI and a pair
// without with I; halfway, each ray leaves its lane for a ControlledIntegrator (unload, resume_at), takes one step
// there and comes back (load), as the batched tracer hands rays over.
template <class T, class C, int W>
void expect_batched_lanes_follow_advance() {
  const IntegratorSettings settings{Tolerance{1e-10, 1e-12}};
  constexpr double first_step = 2.0;  // far too long: the first trials are rejected
  const auto start_of = [](int l) { return Vector<3>(1.0 - 0.3 * l, 0.2 + 0.4 * l, -0.4 + 0.5 * l); };
  BatchedIntegrator<T, C, 3, W> batch(settings);
  for (int l = 0; l < W; ++l) {
    ControlledIntegrator<T, C, 3> starter(settings);
    starter.start(euler_rhs, start_of(l), first_step);
    batch.load(l, starter);
  }
  std::array<bool, static_cast<std::size_t>(W)> visited{};
  bool all_done = false;
  while (!all_done) {
    const auto verdict = batch.trial(batch_rhs<W>);
    all_done = true;
    for (int l = 0; l < W; ++l) {
      const auto s = static_cast<std::size_t>(l);
      ASSERT_NE(verdict[s], TrialVerdict::not_taken);
      if (verdict[s] == TrialVerdict::accepted) batch.commit(l);
      if (batch.counters(l).accepted == 100 && !visited[s]) {  // a step outside the lane, then back
        visited[s] = true;
        ControlledIntegrator<T, C, 3> outside(settings);
        batch.unload(l, outside);
        ASSERT_EQ(outside.advance(euler_rhs), StepOutcome::ok);
        batch.load(l, outside);
      }
      all_done = all_done && batch.counters(l).accepted >= 200;
    }
  }
  for (int l = 0; l < W; ++l) {
    ControlledIntegrator<T, C, 3> alone(settings);
    alone.start(euler_rhs, start_of(l), first_step);
    const auto& lane = batch.counters(l);
    while (alone.accepted() < lane.accepted) ASSERT_EQ(alone.advance(euler_rhs), StepOutcome::ok);
    ControlledIntegrator<T, C, 3> lane_state(settings);
    batch.unload(l, lane_state);
    EXPECT_EQ(alone.state(), lane_state.state()) << T::name << " lane " << l;
    EXPECT_EQ(alone.derivative(), lane_state.derivative()) << T::name << " lane " << l;
    EXPECT_EQ(alone.lambda(), lane.lambda) << T::name << " lane " << l;
    EXPECT_EQ(alone.rejected(), lane.rejected) << T::name << " lane " << l;
    EXPECT_EQ(alone.rhs_evals(), lane.rhs_evals) << T::name << " lane " << l;
    EXPECT_EQ(alone.next_step(), lane.h_next) << T::name << " lane " << l;
    EXPECT_GT(lane.rejected, 0) << "the comparison should include rejected trials";
  }
}

TEST(BatchedIntegrator, LanesTakeTheStepsAdvanceTakes) {
  expect_batched_lanes_follow_advance<Tsitouras54, PIController, 4>();
  expect_batched_lanes_follow_advance<Tsitouras54, PIController, 3>();
  expect_batched_lanes_follow_advance<Fehlberg78, IController, 4>();
  expect_batched_lanes_follow_advance<DormandPrince54, IController, 3>();
}

}  // namespace
