// The measuring core of grtrace-work-precision (examples/work_precision/work_precision.hpp) on a tiny sweep:
// a method's error against the exact reference falls as its tolerance (or step) falls, the CSV carries its
// columns, and a ray that fails is scored as a wrong answer, never as an accurate one. Kerr: equatorial
// prograde and retrograde rays converge on Iyer & Hansen's exact deflection, and the tool refuses a Kerr run it
// cannot judge (--spin 1, camera rays) with exit code 2.
#include "../examples/work_precision/work_precision.hpp"

#include "grtrace/tableau/classic_rk4.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"

#include "common/tool_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace grtrace;
using namespace grtrace::work_precision;

// Near-critical to weak field, and a 9 x 9 camera at r = 50 M whose centre pixels fall into the hole.
const RaySet& tiny_set() {
  static const RaySet set = make_ray_set({5.3, 7.0, 20.0, 100.0}, StaticCamera{50.0, 90.0, 9, 9}, 400.0);
  return set;
}

// a = 0.9 (b_c = +2.85 M prograde, -6.83 M retrograde): near-critical to weak field in both senses.
const RaySet& kerr_set() {
  static const RaySet set = make_kerr_ray_set({3.2, 5.0, 20.0, 100.0, -7.5, -10.0, -20.0, -100.0}, 0.9);
  return set;
}

/// Takes the sweep points, the exit point and the ray set (default the Schwarzschild tiny_set()); returns one
/// record per point for tableau T with controller C.
template <class T, class C>
std::vector<Record> sweep(const std::vector<SweepPoint>& points, ExitPoint exit = ExitPoint::surface,
                          const RaySet& set = tiny_set()) {
  std::vector<Record> out;
  RunOptions options;
  options.exit = exit;
  for (const SweepPoint& p : points)
    out.push_back(make_record(T::name, C::name, T::order, p, exit, run_configuration<T, C>(set, p, options)));
  return out;
}

std::vector<SweepPoint> tolerances(std::initializer_list<double> rtols) {
  std::vector<SweepPoint> p;
  for (const double t : rtols) p.push_back({false, t, 1e-2 * t, 0.0});
  return p;
}

TEST(WorkPrecision, RaySetHasExactAnswersAndCapturedPixels) {
  const RaySet& set = tiny_set();
  ASSERT_EQ(set.impacts.size(), 4u);
  ASSERT_EQ(set.pixels.size(), 81u);
  for (const auto& ray : set.impacts) EXPECT_TRUE(std::isfinite(ray.exact_deflection)) << ray.b;
  const auto captured =
      std::count_if(set.pixels.begin(), set.pixels.end(), [](const CameraRay& r) { return !r.exact; });
  EXPECT_GE(captured, 1);  // the centre pixel looks straight at the hole
  EXPECT_LT(captured, 81);
}

TEST(WorkPrecision, ErrorFallsAsToleranceFalls) {
  for (const ExitPoint exit : {ExitPoint::surface, ExitPoint::node}) {
    const auto records = sweep<DormandPrince54, PIController>(tolerances({1e-4, 1e-6, 1e-8, 1e-10}), exit);
    for (std::size_t i = 0; i < records.size(); ++i) {
      const Record& r = records[i];
      EXPECT_EQ(r.stats.failures, 0);
      EXPECT_EQ(r.stats.verdict_mismatches, 0) << "captured verdicts must agree with the exact ones";
      EXPECT_EQ(r.rays, tiny_set().size());
      if (i == 0) continue;
      const Record& prev = records[i - 1];
      EXPECT_LT(r.all.max, prev.all.max) << "rtol " << r.point.rtol;
      EXPECT_LT(r.all.median, prev.all.median) << "rtol " << r.point.rtol;
      EXPECT_GT(r.stats.rhs_evals, prev.stats.rhs_evals) << "a tighter tolerance must cost more";
    }
    EXPECT_LT(records.back().all.max, 1e-7);
    EXPECT_GT(records.front().all.max, 1e3 * records.back().all.max) << "six decades of tolerance, few of error?";
  }
}

TEST(WorkPrecision, KerrRaySetHasBothSensesAndNoPixels) {
  const RaySet& set = kerr_set();
  ASSERT_TRUE(set.kerr.has_value());
  EXPECT_TRUE(set.pixels.empty());
  for (const auto& ray : set.impacts) {
    EXPECT_TRUE(std::isfinite(ray.exact_deflection)) << ray.b;
    EXPECT_DOUBLE_EQ(ray.exact_deflection, exact::equatorial_deflection(ray.b, 0.9)) << ray.b;
  }
  // The defaults escape in both senses, whatever the spin.
  for (const double a : {0.9, -0.5, 0.0, 0.999}) {
    const auto b = default_kerr_impacts(a);
    EXPECT_EQ(std::count_if(b.begin(), b.end(), [](double x) { return x > 0.0; }), 7) << a;
    EXPECT_NO_THROW(make_kerr_ray_set(b, a)) << a;
  }
}

TEST(WorkPrecision, KerrErrorFallsAsToleranceFallsInBothSenses) {
  for (const ExitPoint exit : {ExitPoint::surface, ExitPoint::node}) {
    RunOptions options;
    options.exit = exit;
    std::vector<double> previous;
    for (const double rtol : {1e-5, 1e-8, 1e-12}) {
      const RunStats s = run_configuration<DormandPrince54, PIController>(kerr_set(), {false, rtol, 1e-2 * rtol, 0.0},
                                                                         options);
      EXPECT_EQ(s.failures, 0);
      EXPECT_EQ(s.verdict_mismatches, 0);
      ASSERT_EQ(s.impact_errors.size(), kerr_set().impacts.size());
      if (!previous.empty()) {
        EXPECT_LT(summarize(s.impact_errors).max, summarize(previous).max) << "rtol " << rtol;
        EXPECT_LT(summarize(s.impact_errors).median, summarize(previous).median) << "rtol " << rtol;
      }
      if (rtol == 1e-5) {
        EXPECT_GT(summarize(s.impact_errors).max, 1e-6) << "a loose tolerance must show its error";
      }
      if (rtol == 1e-12) {
        for (std::size_t i = 0; i < s.impact_errors.size(); ++i)
          EXPECT_LT(s.impact_errors[i], 1e-9) << "b = " << kerr_set().impacts[i].b;  // prograde and retrograde
      }
      previous = s.impact_errors;
    }
  }
}

TEST(WorkPrecision, FixedStepErrorFallsAsStepFalls) {
  std::vector<SweepPoint> steps;
  for (const double h : {1.0, 0.5, 0.25}) steps.push_back({true, 1e-8, 1e-10, h});
  const auto records = sweep<ClassicRK4, FixedStep>(steps);
  for (std::size_t i = 1; i < records.size(); ++i) {
    EXPECT_EQ(records[i].stats.rejected, 0);
    // Fourth order: halving h divides the error by about 16; ask for a factor of 4.
    EXPECT_LT(records[i].impact.max, 0.25 * records[i - 1].impact.max) << "h " << records[i].point.step;
    EXPECT_GT(records[i].stats.rhs_evals, records[i - 1].stats.rhs_evals);
  }
}

TEST(WorkPrecision, FailedRaysScoreAsWrongAnswers) {
  const RaySet& set = tiny_set();
  RunOptions options;
  options.max_steps = 3;  // nothing gets far in three steps
  const RunStats s = run_configuration<DormandPrince54, PIController>(set, {false, 1e-8, 1e-10, 0.0}, options);
  EXPECT_GT(s.failures, 0);
  EXPECT_EQ(s.failures, s.max_steps_hits);
  EXPECT_EQ(summarize(s.camera_errors).max, kWrongAnswer);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

TEST(WorkPrecision, CsvHasTheColumns) {
  auto records = sweep<DormandPrince54, PIController>(tolerances({1e-5}));
  const auto fixed = sweep<ClassicRK4, FixedStep>({{true, 1e-8, 1e-10, 0.5}});
  records.insert(records.end(), fixed.begin(), fixed.end());
  std::ostringstream out;
  write_csv(out, records);
  std::istringstream in(out.str());
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const auto header = split(line);
  for (const char* column : {"tableau",
                             "controller",
                             "order",
                             "sweep",
                             "rtol",
                             "atol",
                             "step",
                             "exit",
                             "rays",
                             "max_error",
                             "median_error",
                             "max_error_impact",
                             "median_error_impact",
                             "max_error_camera",
                             "median_error_camera",
                             "rhs_evals",
                             "accepted",
                             "rejected",
                             "failures",
                             "verdict_mismatches",
                             "seconds",
                             "cpu_seconds",
                             "ns_per_step",
                             "metric",
                             "spin"})
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << "missing column " << column;
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line)) rows.push_back(split(line));
  ASSERT_EQ(rows.size(), 2u);
  for (const auto& row : rows) EXPECT_EQ(row.size(), header.size());
  auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  EXPECT_EQ(rows[0][col("tableau")], "dopri5");
  EXPECT_EQ(rows[0][col("sweep")], "rtol");
  EXPECT_DOUBLE_EQ(std::stod(rows[0][col("rtol")]), 1e-5);
  EXPECT_EQ(rows[1][col("controller")], "fixed");
  EXPECT_EQ(rows[1][col("sweep")], "step");
  EXPECT_TRUE(rows[1][col("rtol")].empty()) << "a fixed-step row has no tolerance";
  EXPECT_DOUBLE_EQ(std::stod(rows[1][col("step")]), 0.5);
  EXPECT_GT(std::stod(rows[0][col("rhs_evals")]), 0.0);
  EXPECT_GT(std::stod(rows[0][col("max_error")]), 0.0);
  EXPECT_EQ(rows[0][col("metric")], "schwarzschild");
  EXPECT_DOUBLE_EQ(std::stod(rows[0][col("spin")]), 0.0);
}

#ifdef GRTRACE_WORK_PRECISION_TOOLS
/// Takes the tool's arguments (shell words); returns its exit status and merged output.
tool_tests::ToolRun run_tool(const std::string& args) {
  const auto tools = tool_tests::named_paths(GRTRACE_WORK_PRECISION_TOOLS);
  return tool_tests::run_command("'" + tools.at("grtrace-work-precision") + "' " + args);
}

TEST(WorkPrecisionTool, KerrRunRecordsMetricAndSpin) {
  const tool_tests::ToolRun r = run_tool("--metric kerr --spin -0.5 --tableaux dopri5 --controllers pi "
                                         "--tolerances 1e-6,1e-10 --json --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"metric\":\"kerr\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"spin\":-0.5"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"camera_rays\":0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"impact_rays\":14"), std::string::npos) << r.output;
}

TEST(WorkPrecisionTool, RefusesKerrRunsItCannotJudge) {
  for (const char* args : {"--metric kerr --spin 1", "--metric kerr --spin -1.5", "--metric kerr --grid 4",
                           "--metric kerr --impacts 3,-6", "--spin 0.5", "--metric reissner"}) {
    const tool_tests::ToolRun r = run_tool(args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << args << ": " << r.output;
  }
}
#endif

}  // namespace
