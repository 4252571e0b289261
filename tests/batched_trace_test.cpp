// tests/batched_trace_test.cpp
// trace/batched_trace.hpp: rays traced side by side in lanes, handed to the scalar loop where something happens,
// must end exactly, bit for bit, as each ray traced alone: status, end state, step counts, right-hand sides and
// the rest of TraceResult; and through GeneralSceneTracer::trace_many and render_frame, every pixel's outcome.
// The cases make every hand-over happen (a surface crossed and refused, hit, capture, escape, the polar axis,
// max_steps, a step below h_min) and the tests check that they did.
#include "grtrace/grtrace.hpp"
#include "grtrace/render/frame.hpp"

#include "common/trace_settings.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <type_traits>
#include <vector>

namespace {

using namespace grtrace;

bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

/// Bit for bit, or both NaN (a pixel without a redshift or direction).
bool same_or_nan(double a, double b) { return same(a, b) || (std::isnan(a) && std::isnan(b)); }

using test_settings::settings_at;

/// The disk scene's general tracer (tsit5, I), as grtrace-render builds it.
auto disk_tracer(const SchwarzschildMetric& metric) {
  StandardSceneSpec spec;
  spec.name = "disk";
  return make_general_tracer<Tsitouras54, IController>(metric, settings_at(2e-9, 400.0), AngleCorrection::exact,
                                                       disk_scene(spec));
}

bool same(const GeodesicState& a, const GeodesicState& b) {
  for (int i = 0; i < 8; ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

void expect_same(const TraceResult& batched, const TraceResult& alone, std::size_t ray) {
  EXPECT_EQ(batched.status, alone.status) << "ray " << ray;
  EXPECT_TRUE(same(batched.final_state, alone.final_state)) << "ray " << ray;
  EXPECT_TRUE(same(batched.step_end_state, alone.step_end_state)) << "ray " << ray;
  EXPECT_TRUE(same(batched.lambda, alone.lambda)) << "ray " << ray;
  EXPECT_EQ(batched.accepted, alone.accepted) << "ray " << ray;
  EXPECT_EQ(batched.rejected, alone.rejected) << "ray " << ray;
  EXPECT_EQ(batched.rhs_evals, alone.rhs_evals) << "ray " << ray;
  EXPECT_EQ(batched.refinement_evals, alone.refinement_evals) << "ray " << ray;
  EXPECT_TRUE(same(batched.constraint_drift, alone.constraint_drift)) << "ray " << ray;
  EXPECT_EQ(batched.hit_event, alone.hit_event) << "ray " << ray;
  EXPECT_EQ(batched.chart_wraps, alone.chart_wraps) << "ray " << ray;
}

/// A camera's pixel states (n x n), spherical position (r, theta in degrees), looking at the hole.
template <MetricPolicy M>
std::vector<GeodesicState> pixel_states(const M& metric, double r, double theta_degrees, int n, double fov) {
  CameraSpec spec;
  spec.position = Vec4(0.0, r, theta_degrees * std::numbers::pi / 180.0, 0.0);
  spec.spherical_position = true;
  spec.observer = ObserverKind::zamo;
  spec.width = spec.height = n;
  spec.fov_degrees = fov;
  const Camera cam = make_camera(metric, spec);
  std::vector<GeodesicState> states;
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) states.push_back(cam.pixel_state(col, row));
  return states;
}

/// The equatorial plane between two radii: two-sided, and crossings outside the band are refused (the ray goes on).
struct EquatorBand {
  static constexpr bool two_sided = true;
  double operator()(const GeodesicState& y) const { return std::cos(y[2]); }
  bool accepts(const GeodesicState& y) const { return y[1] > 6.0 && y[1] < 14.0; }
};

struct Census {
  int statuses[kRayStatusCount] = {};
  int wrapped = 0, refused_crossings = 0;
};

/// Traces the rays both ways and compares; returns what happened to them.
template <class Tracer>
Census compare(const Tracer& tracer, const std::vector<GeodesicState>& y0) {
  std::vector<TraceResult> batched(y0.size());
  trace_batched(tracer, std::span<const GeodesicState>(y0), std::span(batched), EquatorBand{});
  Census census;
  for (std::size_t i = 0; i < y0.size(); ++i) {
    const TraceResult alone = tracer.trace(y0[i], EquatorBand{});
    expect_same(batched[i], alone, i);
    ++census.statuses[static_cast<std::size_t>(alone.status)];
    census.wrapped += alone.chart_wraps > 0 ? 1 : 0;
  }
  return census;
}

int count(const Census& c, RayStatus s) { return c.statuses[static_cast<std::size_t>(s)]; }

TEST(BatchedTrace, SchwarzschildTsit5RaysEndAsAlone) {
  const SchwarzschildMetric metric{1.0};
  const TraceSettings settings = settings_at(2e-9, 400.0);
  const GeodesicTracer<SchwarzschildMetric, Tsitouras54, IController> tracer(metric, settings);
  const Census c = compare(tracer, pixel_states(metric, 50.0, 80.0, 24, 40.0));
  EXPECT_GT(count(c, RayStatus::captured), 0);
  EXPECT_GT(count(c, RayStatus::escaped), 0);
  EXPECT_GT(count(c, RayStatus::hit), 0);
}

TEST(BatchedTrace, ThroughThePolarAxisWithRkf78AndPi) {
  // A camera near the north pole: rays cross the axis (the chart wraps them) on their way round the hole.
  const SchwarzschildMetric metric{1.0};
  const TraceSettings settings = settings_at(1e-9, 300.0);
  const GeodesicTracer<SchwarzschildMetric, Fehlberg78, PIController> tracer(metric, settings);
  const Census c = compare(tracer, pixel_states(metric, 30.0, 10.0, 21, 60.0));
  EXPECT_GT(c.wrapped, 0);
  EXPECT_GT(count(c, RayStatus::escaped), 0);
}

TEST(BatchedTrace, MaxStepsAndStepUnderflowAreTheLoopsAsAlone) {
  const SchwarzschildMetric metric{1.0};
  TraceSettings settings = settings_at(1e-10, 400.0);
  settings.integrator.h_min = 0.05;  // rays that skim the horizon need shorter steps: they underflow
  settings.initial_step = 0.5;
  settings.max_steps = 200;
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, IController> tracer(metric, settings);
  const Census c = compare(tracer, pixel_states(metric, 20.0, 90.0, 24, 70.0));
  EXPECT_GT(count(c, RayStatus::max_steps), 0);
  EXPECT_GT(count(c, RayStatus::step_underflow), 0);
}

TEST(BatchedTrace, KerrWithoutALaneAccelerationEndsAsAlone) {
  const KerrMetric metric{1.0, 0.9};
  const TraceSettings settings = settings_at(2e-9, 400.0);
  const GeodesicTracer<KerrMetric, Tsitouras54, IController> tracer(metric, settings);
  const Census c = compare(tracer, pixel_states(metric, 40.0, 75.0, 16, 40.0));
  EXPECT_GT(count(c, RayStatus::hit), 0);
  EXPECT_GT(count(c, RayStatus::captured), 0);
}

TEST(BatchedTrace, FewerRaysThanLanesAndNone) {
  const SchwarzschildMetric metric{1.0};
  const GeodesicTracer<SchwarzschildMetric, Tsitouras54, IController> tracer(metric, TraceSettings{});
  const auto all = pixel_states(metric, 50.0, 80.0, 4, 40.0);
  compare(tracer, std::vector<GeodesicState>(all.begin(), all.begin() + 3));
  std::vector<TraceResult> none;
  trace_batched(tracer, std::span<const GeodesicState>(), std::span(none), EquatorBand{});
  // A ray that starts outside the sky sphere ends at once, in a lane or not.
  GeodesicState far = all.front();
  far[1] = 2000.0;
  compare(tracer, {far, all[1]});
}

TEST(BatchedTrace, DiskFrameOutcomesAreThePixelsTracedOneByOne) {
  const SchwarzschildMetric metric{1.0};
  const auto tracer = disk_tracer(metric);
  static_assert(TracesMany<decltype(tracer)>);
  const auto y0 = pixel_states(metric, 50.0, 80.0, 20, 50.0);
  std::vector<RayOutcome> many(y0.size());
  tracer.trace_many(y0, many);
  int on_disk = 0;
  for (std::size_t i = 0; i < y0.size(); ++i) {
    const RayOutcome one = tracer.trace(y0[i]);
    EXPECT_EQ(many[i].status, one.status) << i;
    EXPECT_EQ(many[i].object, one.object) << i;
    EXPECT_EQ(many[i].steps, one.steps) << i;
    EXPECT_EQ(many[i].order, one.order) << i;
    EXPECT_TRUE(same(many[i].state, one.state)) << i;
    EXPECT_TRUE(same_or_nan(many[i].radius, one.radius)) << i;
    EXPECT_TRUE(same_or_nan(many[i].redshift, one.redshift)) << i;
    EXPECT_TRUE(same_or_nan(many[i].where.theta, one.where.theta)) << i;
    EXPECT_TRUE(same_or_nan(many[i].where.phi, one.where.phi)) << i;
    on_disk += one.object >= kFirstSceneObject ? 1 : 0;
  }
  EXPECT_GT(on_disk, 0);
}

/// A scene tracer without trace_many: render_frame traces its pixels one by one.
template <class Inner>
struct OneByOne {
  const Inner* inner;
  static constexpr const char* name = "general";
  RayOutcome trace(const GeodesicState& y) const { return inner->trace(y); }
  const auto& scene() const { return inner->scene(); }
};

TEST(BatchedTrace, RenderFrameTracesTilesTogetherWithTheSamePixels) {
  // render_frame hands a TracesMany tracer each tile at once; a wrapper that hides trace_many renders pixel by
  // pixel. The two images must be the same bytes.
  const SchwarzschildMetric metric{1.0};
  const auto tracer = disk_tracer(metric);
  using Alone = OneByOne<std::remove_cvref_t<decltype(tracer)>>;
  static_assert(!TracesMany<Alone>);
  CameraSpec cs;
  cs.position = Vec4(0.0, 40.0, 1.3, 0.0);
  cs.spherical_position = true;
  cs.width = 37;  // tiles of 16 that do not divide the frame
  cs.height = 21;
  cs.fov_degrees = 50.0;
  const Camera cam = make_camera(metric, cs);
  RenderOptions options;
  options.progress = ProgressMode::never;
  const Frame a = render_frame(cam, tracer, options);
  const Frame b = render_frame(cam, Alone{&tracer}, options);
  ASSERT_EQ(a.image.pixel_count(), b.image.pixel_count());
  EXPECT_EQ(a.stats.total_steps, b.stats.total_steps);
  for (const auto& name : a.image.channel_names()) {
    const auto& ca = a.image.channel(name);
    const auto& cb = b.image.channel(name);
    ASSERT_EQ(ca.size(), cb.size());
    for (std::size_t i = 0; i < ca.size(); ++i)
      ASSERT_TRUE(ca[i] == cb[i] || (ca[i] != ca[i] && cb[i] != cb[i])) << name << " " << i;
  }
}

}  // namespace
