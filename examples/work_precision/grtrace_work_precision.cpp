// grtrace-work-precision: speed against accuracy for every tableau x controller x tolerance.
//
// Traces a fixed set of Schwarzschild rays whose answers are known exactly (impact parameters from near-critical
// to weak field, judged with measure_deflection against exact::deflection_angle, and the pixels of a static
// camera, judged with exact::asymptotic_direction) once per configuration and records max/median angular error,
// right-hand-side evaluations, accepted/rejected steps and wall time (work_precision.hpp). Adaptive controllers
// sweep the relative tolerance; `fixed` sweeps the step size instead (same chart axes: error against cost).
// Writes a CSV (--out-csv), log-log PNG charts drawn with VTK (--out-png), a table or ONE line of JSON (--json).
// --metric kerr --spin A traces equatorial Kerr photons instead (prograde and retrograde impact rays judged against
// Iyer & Hansen's exact deflection; no camera rays, which have no exact answer in Kerr).
// --exit node continues escaped rays exactly from the last accepted step instead of the interpolated sky-sphere
// crossing (which limits tableaux without their own dense output; see docs/benchmarks.md).
#include "chart.hpp"
#include "command_line.hpp"
#include "json_writer.hpp"
#include "methods.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace grtrace;
using namespace grtrace::work_precision;
using tools::CommandLine;
using tools::JsonObject;
using tools::UsageError;

CommandLine make_command_line() {
  CommandLine cli("grtrace-work-precision",
                  "Sweep tableaux x controllers x tolerances over Schwarzschild (or equatorial Kerr) rays with exact\n"
                  "answers; "
                  "record max/median angular error, RHS evaluations, steps and wall time; write CSV and charts.\n"
                  "Charts need an X display: without one, run under xvfb-run -a -s \"-screen 0 1280x1024x24\".");
  cli.option("metric", "schwarzschild",
             "schwarzschild | kerr (Boyer-Lindquist; equatorial impact rays only: --grid defaults to 0 and must stay 0)")
      .option("spin", "0.9", "Kerr spin a/M, |a| < 1 (with --metric kerr only)")
      .option("tableaux", "all", "comma-separated tableaux to sweep: all | " + tools::join(tableau_names(), ","))
      .option("controllers", "all",
              "comma-separated controllers: all | fixed,doubling,i,pi (I/PI only with an "
              "embedded pair; invalid pairs are skipped)")
      .option("tolerances", "", "explicit comma-separated relative tolerances (overrides --tol-min/--tol-max)")
      .option("tol-min", "1e-12", "tightest relative tolerance of the sweep")
      .option("tol-max", "1e-3", "loosest relative tolerance of the sweep")
      .option("tol-per-decade", "1", "tolerances per decade between --tol-max and --tol-min (1..10)")
      .option("atol-ratio", "1e-2", "absolute tolerance = this x relative tolerance")
      .option("steps", "4,2,1,0.5,0.25,0.125", "affine step sizes swept by the fixed-step controller")
      .option("impacts", "5.25,5.3,5.5,6,7,10,20,50,100,1000",
              "impact parameters (M) of the deflection rays; 'none' for no impact rays. Kerr: signed (b > 0 moves "
              "towards +phi, prograde for a > 0), default the critical b_c of each sense times "
              "1.02,1.1,1.3,2,4,10,100")
      .option("camera-r", "50", "radius of the static camera (M); it looks at the hole, up = +z")
      .option("sky-r", "400", "radius of the sky (escape) sphere of the camera rays (M)")
      .option("fov", "90", "horizontal field of view of the camera (degrees, 0 < fov < 180)")
      .option("grid", "32", "camera pixels per side (0 = no camera rays; --metric kerr: 0)")
      .option("exit", "surface",
              "where the exact continuation to infinity starts: surface (the sky-sphere crossing "
              "the tracer reports, read from the interpolant) | node (the last accepted step)")
      .option("max-steps", "100000", "accepted steps per ray before it ends as max_steps")
      .flag("keep-going",
            "keep sweeping a method after a configuration ran out of steps (default: skip the "
            "rest of its sweep, which would only cost more)")
      .option("threads", "1", "OpenMP threads over the rays (1 = clean single-core timings)")
      .option("repeat", "1", "time each configuration this many times and keep the fastest")
      .option("target-error", "1e-6",
              "report the cheapest configuration (by the --chart-time clock, and by RHS "
              "evaluations) whose max error is below this (radians), with no failed ray")
      .option("out-csv", "", "write one row per configuration to this CSV file")
      .option("out-png", "", "chart prefix: writes PREFIX-time.png and PREFIX-evals.png (log-log, VTK)")
      .option("chart-error", "max", "error drawn in the charts: max | median")
      .option("chart-time", "wall", "time drawn in the charts: wall | cpu (processor time; steadier on a busy machine)")
      .flag("json", "print ONE line of JSON (summary) on stdout instead of the table")
      .flag("quiet", "no per-configuration progress lines on stderr");
  return cli;
}

std::vector<std::string> split_names(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

struct Plan {
  std::vector<Method> methods;
  std::vector<double> tolerances;  ///< loose -> tight
  std::vector<double> steps;       ///< large -> small
  double atol_ratio = 1e-2;
  RaySet rays;
  std::string metric = "schwarzschild";
  double spin = 0.0;
  RunOptions run;
  bool keep_going = false;
  double target_error = 1e-6;
  std::string out_csv, out_png;
  bool chart_median = false;
  bool chart_cpu = false;
};

Plan read_plan(const CommandLine& cli) {
  Plan p;
  // Methods.
  const auto all = all_methods();
  const std::string tab_text = cli.text("tableaux"), ctl_text = cli.text("controllers");
  std::vector<std::string> tabs = tab_text == "all" ? std::vector<std::string>{} : split_names(tab_text);
  std::vector<std::string> ctls = ctl_text == "all" ? std::vector<std::string>{} : split_names(ctl_text);
  if (tab_text != "all" && tabs.empty()) throw UsageError("--tableaux is empty; give names or 'all'");
  if (ctl_text != "all" && ctls.empty()) throw UsageError("--controllers is empty; give names or 'all'");
  const auto names = tableau_names();
  for (const auto& t : tabs)
    if (std::find(names.begin(), names.end(), t) == names.end())
      throw UsageError("unknown tableau '" + t + "'; choose from: " + tools::join(names, ", "));
  for (const auto& c : ctls)
    if (std::find(kControllerNames.begin(), kControllerNames.end(), c) == kControllerNames.end())
      throw UsageError("unknown controller '" + c + "'; choose from: fixed, doubling, i, pi");
  for (const Method& m : all) {
    const bool t_ok = tabs.empty() || std::find(tabs.begin(), tabs.end(), m.tableau) != tabs.end();
    const bool c_ok = ctls.empty() || std::find(ctls.begin(), ctls.end(), m.controller) != ctls.end();
    if (t_ok && c_ok) p.methods.push_back(m);
  }
  if (p.methods.empty())
    throw UsageError("no valid (tableau, controller) pair in --tableaux " + tab_text + " --controllers " + ctl_text +
                     ": the i and pi controllers need a tableau with an embedded pair (heun, bs3, rkf45, cashkarp, "
                     "dopri5, tsit5, vern6, rkf78)");

  // Sweep points.
  if (cli.given("tolerances")) {
    p.tolerances = cli.numbers("tolerances", 0);
    if (p.tolerances.empty()) throw UsageError("--tolerances is empty");
  } else {
    const double lo = cli.number("tol-min"), hi = cli.number("tol-max");
    const long per = cli.integer("tol-per-decade");
    if (!(lo > 0.0 && hi >= lo && hi < 1.0))
      throw UsageError("need 0 < --tol-min <= --tol-max < 1, got " + cli.text("tol-min") + " and " +
                       cli.text("tol-max"));
    if (per < 1 || per > 10) throw UsageError("--tol-per-decade must be 1..10, got " + cli.text("tol-per-decade"));
    const double span = std::log10(hi / lo) * static_cast<double>(per);
    const int n = static_cast<int>(std::floor(span + 1e-9));
    for (int i = 0; i <= n; ++i)
      p.tolerances.push_back(hi * std::pow(10.0, -static_cast<double>(i) / static_cast<double>(per)));
  }
  for (const double t : p.tolerances)
    if (!(t > 0.0 && t < 1.0)) {
      std::ostringstream msg;
      msg << "every tolerance must lie in (0, 1); got " << t;
      throw UsageError(msg.str());
    }
  std::sort(p.tolerances.begin(), p.tolerances.end(), std::greater<>());
  p.steps = cli.numbers("steps", 0);
  if (p.steps.empty()) throw UsageError("--steps is empty");
  for (const double h : p.steps)
    if (!(h > 0.0)) throw UsageError("every --steps value must be > 0");
  std::sort(p.steps.begin(), p.steps.end(), std::greater<>());
  p.atol_ratio = cli.number("atol-ratio");
  if (!(p.atol_ratio >= 0.0 && p.atol_ratio <= 1.0))
    throw UsageError("--atol-ratio must lie in [0, 1] (atol = ratio x rtol < 1), got " + cli.text("atol-ratio"));

  // Rays.
  p.metric = cli.text("metric");
  if (p.metric != "schwarzschild" && p.metric != "kerr")
    throw UsageError("--metric must be schwarzschild or kerr, got '" + p.metric + "'");
  const bool kerr = p.metric == "kerr";
  if (cli.given("spin") && !kerr) throw UsageError("--spin needs --metric kerr");
  if (kerr) {
    p.spin = cli.number("spin");
    if (!(std::abs(p.spin) < 1.0)) throw UsageError("--spin must satisfy |a| < 1 (M = 1), got " + cli.text("spin"));
  }
  std::vector<double> impacts;
  if (kerr && !cli.given("impacts")) {
    impacts = default_kerr_impacts(p.spin);
  } else if (cli.text("impacts") != "none") {
    impacts = cli.numbers("impacts", 0);
    for (const double b : impacts) {
      if (!kerr && !(b > 0.0 && b <= 1e6)) throw UsageError("--impacts: every impact parameter must be in (0, 1e6] M");
      if (kerr && !(b != 0.0 && std::abs(b) <= 1e6))
        throw UsageError("--impacts: every Kerr impact parameter must be nonzero with |b| <= 1e6 M");
      // Kerr: a captured ray has no exact deflection (exact::equatorial_deflection refuses it).
      if (kerr && !(std::abs(b) > std::abs(exact::equatorial_critical_impact(p.spin, b > 0.0 ? 1.0 : -1.0)))) {
        std::ostringstream msg;
        msg << "--impacts: the Kerr ray b = " << b << " is captured (critical b = "
            << exact::equatorial_critical_impact(p.spin, b > 0.0 ? 1.0 : -1.0) << " M for a = " << p.spin
            << "); give |b| beyond it";
        throw UsageError(msg.str());
      }
    }
  }
  StaticCamera cam;
  cam.radius = cli.number("camera-r");
  cam.fov_degrees = cli.number("fov");
  const long grid = kerr && !cli.given("grid") ? 0 : cli.integer("grid");
  if (kerr && grid != 0)
    throw UsageError("--metric kerr has no camera rays (no exact answer for a Kerr pixel): leave out --grid or give "
                     "--grid 0");
  const double sky = cli.number("sky-r");
  if (grid < 0 || grid > 4096) throw UsageError("--grid must be 0..4096, got " + cli.text("grid"));
  cam.width = cam.height = static_cast<int>(grid);
  if (grid > 0) {
    const double guard = 2.0 * (1.0 + TraceSettings{}.horizon_epsilon);
    if (!(cam.radius > guard))
      throw UsageError("--camera-r must be outside the horizon guard r = " + std::to_string(guard) + " M");
    if (!(sky > cam.radius)) throw UsageError("--sky-r must be larger than --camera-r");
    if (!(sky <= 1e100)) throw UsageError("--sky-r must be at most 1e100 (r^2 must not overflow), got " + cli.text("sky-r"));
    if (!(cam.fov_degrees > 0.0 && cam.fov_degrees < 180.0)) throw UsageError("--fov must lie in (0, 180) degrees");
  }
  if (impacts.empty() && grid == 0) throw UsageError("no rays: give --impacts or --grid > 0");
  p.rays = kerr ? make_kerr_ray_set(impacts, p.spin, 1.0) : make_ray_set(impacts, cam, sky, 1.0);

  // Run options and outputs.
  const long max_steps = cli.integer("max-steps"), threads = cli.integer("threads"), repeat = cli.integer("repeat");
  if (max_steps < 1 || max_steps > 100'000'000) throw UsageError("--max-steps must be 1..1e8");
  if (threads < 1 || threads > 1024) throw UsageError("--threads must be 1..1024");
  if (repeat < 1 || repeat > 100) throw UsageError("--repeat must be 1..100");
  p.run.max_steps = static_cast<int>(max_steps);
  p.run.threads = static_cast<int>(threads);
  p.run.repeat = static_cast<int>(repeat);
  p.keep_going = cli.flag_set("keep-going");
  const std::string exit = cli.text("exit");
  if (exit != "surface" && exit != "node") throw UsageError("--exit must be surface or node, got '" + exit + "'");
  p.run.exit = exit == "node" ? ExitPoint::node : ExitPoint::surface;
  p.target_error = cli.number("target-error");
  if (!(p.target_error > 0.0)) throw UsageError("--target-error must be > 0");
  const std::string chart_error = cli.text("chart-error");
  if (chart_error != "max" && chart_error != "median") throw UsageError("--chart-error must be max or median");
  p.chart_median = chart_error == "median";
  const std::string chart_time = cli.text("chart-time");
  if (chart_time != "wall" && chart_time != "cpu") throw UsageError("--chart-time must be wall or cpu");
  p.chart_cpu = chart_time == "cpu";
  p.out_csv = cli.text("out-csv");
  p.out_png = cli.text("out-png");
  if (cli.given("out-csv")) tools::check_command_output(cli, "out-csv", p.out_csv, {});
  if (cli.given("out-png")) {
    if (p.out_png.empty()) throw UsageError("--out-png needs a file name prefix, got ''");
    if (!charts_available()) throw UsageError("--out-png: this build has no VTK, so it cannot draw charts");
    try {
      require_chart_display();
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("--out-png: ") + e.what());
    }
    tools::check_command_output(cli, "out-png", p.out_png + "-time.png", {});
    tools::check_command_output(cli, "out-png", p.out_png + "-evals.png", {});
    if (!p.out_csv.empty())
      for (const char* suffix : {"-time.png", "-evals.png"})
        if (same_file(p.out_csv, p.out_png + suffix))
          throw UsageError("--out-csv and --out-png name the same file '" + p.out_csv + "'");
  }
  return p;
}

std::string method_label(const Method& m) { return std::string(m.tableau) + "/" + std::string(m.controller); }

// ---- charts ----------------------------------------------------------------------------------------------

std::array<unsigned char, 3> tableau_colour(std::string_view tableau) {
  static constexpr std::array<std::array<unsigned char, 3>, 12> palette = {{{140, 140, 140},
                                                                            {188, 189, 34},
                                                                            {23, 190, 207},
                                                                            {127, 127, 127},
                                                                            {148, 103, 189},
                                                                            {255, 127, 14},
                                                                            {140, 86, 75},
                                                                            {227, 119, 194},
                                                                            {31, 119, 180},
                                                                            {44, 160, 44},
                                                                            {214, 39, 40},
                                                                            {0, 0, 0}}};
  const auto names = tableau_names();
  const auto it = std::find(names.begin(), names.end(), tableau);
  const auto i = static_cast<std::size_t>(it - names.begin());
  return palette[i % palette.size()];
}

LineStyle controller_style(std::string_view c) {
  if (c == "pi") return LineStyle::solid;
  if (c == "i") return LineStyle::dash;
  if (c == "doubling") return LineStyle::dot;
  return LineStyle::dash_dot;
}

void write_charts(OutputSet& set, const Plan& plan, const std::vector<Record>& records) {
  std::vector<ChartSeries> by_time, by_evals;
  for (const Method& m : plan.methods) {
    ChartSeries t, e;
    t.label = e.label = method_label(m);
    t.rgb = e.rgb = tableau_colour(m.tableau);
    t.style = e.style = controller_style(m.controller);
    for (const Record& r : records) {
      if (r.tableau != m.tableau || r.controller != m.controller) continue;
      const double rays = static_cast<double>(r.rays);
      const double err = plan.chart_median ? r.all.median : r.all.max;
      t.x.push_back((plan.chart_cpu ? r.stats.cpu_seconds : r.stats.seconds) / rays * 1e6);
      t.y.push_back(err);
      e.x.push_back(static_cast<double>(r.stats.rhs_evals) / rays);
      e.y.push_back(err);
    }
    if (!t.x.empty()) {
      by_time.push_back(std::move(t));
      by_evals.push_back(std::move(e));
    }
  }
  const std::string which = plan.chart_median ? "median" : "max";
  std::ostringstream rays;
  if (plan.rays.kerr) {
    const auto pro = std::count_if(plan.rays.impacts.begin(), plan.rays.impacts.end(),
                                   [&](const ImpactRay& r) { return (plan.spin < 0.0 ? -r.b : r.b) > 0.0; });  // a = 0: b > 0
    rays << "Kerr a = " << plan.spin << ": " << plan.rays.impacts.size() << " equatorial impact rays (" << pro
         << " prograde, " << plan.rays.impacts.size() - static_cast<std::size_t>(pro) << " retrograde)";
  } else {
    rays << "Schwarzschild: " << plan.rays.impacts.size() << " impact rays + " << plan.rays.pixels.size()
         << " camera pixels (r_c = " << plan.rays.camera.radius << " M)";
  }
  ChartSpec spec;
  spec.y_label = which + " angular error (rad)";
  spec.title = "Work-precision, " + rays.str();
  spec.x_label = std::string(plan.chart_cpu ? "processor" : "wall") + " time per ray (microseconds, " +
                 std::to_string(plan.run.threads) + (plan.run.threads > 1 ? " threads)" : " thread)");
  write_loglog_chart(set, plan.out_png + "-time.png", spec, by_time);
  spec.x_label = "right-hand-side evaluations per ray";
  write_loglog_chart(set, plan.out_png + "-evals.png", spec, by_evals);
}

// ---- reporting -------------------------------------------------------------------------------------------

bool acceptable(const Record& r, double target) {
  return r.stats.failures == 0 && r.stats.verdict_mismatches == 0 && r.all.max <= target;
}

JsonObject record_json(const Record& r) {
  JsonObject j;
  j.add("tableau", r.tableau).add("controller", r.controller);
  if (r.point.fixed_step) j.add("step", r.point.step);
  else j.add("rtol", r.point.rtol).add("atol", r.point.atol);
  j.add("max_error", r.all.max).add("median_error", r.all.median);
  j.add("seconds", r.stats.seconds).add("cpu_seconds", r.stats.cpu_seconds).add("rhs_evals", r.stats.rhs_evals);
  j.add("accepted", r.stats.accepted).add("rejected", r.stats.rejected);
  return j;
}

void print_table(const std::vector<Record>& records) {
  std::printf("%-16s %-6s %9s %10s %10s %11s %10s %9s %5s\n", "method", "sweep", "value", "max_err", "median_err",
              "evals/ray", "us/ray", "rej/ray", "fail");
  for (const Record& r : records) {
    const double rays = static_cast<double>(r.rays);
    const std::string label = r.tableau + "/" + r.controller;
    std::printf("%-16s %-6s %9.3g %10.3e %10.3e %11.1f %10.2f %9.2f %5d\n", label.c_str(),
                r.point.fixed_step ? "step" : "rtol", r.point.fixed_step ? r.point.step : r.point.rtol, r.all.max,
                r.all.median, static_cast<double>(r.stats.rhs_evals) / rays, r.stats.seconds / rays * 1e6,
                static_cast<double>(r.stats.rejected) / rays, r.stats.failures + r.stats.verdict_mismatches);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli = make_command_line();
  return tools::run_tool(cli, argc, argv, [&] {
    const Plan plan = read_plan(cli);
    if (cli.write_config_if_asked()) return 0;
    const bool quiet = cli.flag_set("quiet");
    const auto t_start = std::chrono::steady_clock::now();

    std::vector<Record> records;
    int skipped = 0;
    for (const Method& m : plan.methods) {
      std::vector<SweepPoint> points;
      if (m.fixed_step) {
        for (const double h : plan.steps) points.push_back({true, 1e-8, 1e-10, h});
      } else {
        for (const double t : plan.tolerances) points.push_back({false, t, t * plan.atol_ratio, 0.0});
      }
      for (std::size_t i = 0; i < points.size(); ++i) {
        Record r = make_record(m.tableau, m.controller, m.order, points[i], plan.run.exit,
                               m.run(plan.rays, points[i], plan.run));
        r.metric = plan.metric;
        r.spin = plan.spin;
        if (!quiet) {
          std::fprintf(stderr, "%-16s %s %-8.3g max %.3e  median %.3e  evals/ray %9.1f  %8.3f s%s\n",
                       method_label(m).c_str(), points[i].fixed_step ? "h   " : "rtol",
                       points[i].fixed_step ? points[i].step : points[i].rtol, r.all.max, r.all.median,
                       static_cast<double>(r.stats.rhs_evals) / static_cast<double>(r.rays), r.stats.seconds,
                       r.stats.failures ? "  (failed rays)" : "");
        }
        const bool out_of_steps = r.stats.max_steps_hits > 0;
        records.push_back(std::move(r));
        if (out_of_steps && !plan.keep_going && i + 1 < points.size()) {
          const auto rest = static_cast<int>(points.size() - i - 1);
          skipped += rest;
          if (!quiet)
            std::fprintf(stderr, "%-16s ran out of steps (--max-steps %d): skipping its %d tighter point(s)\n",
                         method_label(m).c_str(), plan.run.max_steps, rest);
          break;
        }
      }
    }
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();

    OutputSet outputs;  // the CSV and both charts: all new or all as they were
    if (!plan.out_csv.empty())
      write_file_atomically(outputs, plan.out_csv, [&](std::ostream& out) { write_csv(out, records); });
    if (!plan.out_png.empty()) write_charts(outputs, plan, records);
    outputs.commit();

    const Record* by_time = nullptr;
    const Record* by_evals = nullptr;
    for (const Record& r : records) {
      if (!acceptable(r, plan.target_error)) continue;
      auto cost = [&](const Record& x) { return plan.chart_cpu ? x.stats.cpu_seconds : x.stats.seconds; };
      if (!by_time || cost(r) < cost(*by_time)) by_time = &r;
      if (!by_evals || r.stats.rhs_evals < by_evals->stats.rhs_evals) by_evals = &r;
    }

    if (cli.flag_set("json")) {
      JsonObject j;
      j.add("configurations", static_cast<long>(records.size())).add("skipped", skipped);
      j.add("methods", static_cast<long>(plan.methods.size()));
      j.add("rays", static_cast<long>(plan.rays.size()));
      j.add("impact_rays", static_cast<long>(plan.rays.impacts.size()));
      j.add("camera_rays", static_cast<long>(plan.rays.pixels.size()));
      j.add("metric", plan.metric).add("spin", plan.spin);
      j.add("exit", plan.run.exit == ExitPoint::node ? "node" : "surface");
      j.add("camera_r", plan.rays.camera.radius).add("sky_r", plan.rays.sky_radius);
      j.add("threads", plan.run.threads).add("seconds", total).add("target_error", plan.target_error);
      if (by_time) j.add("cheapest_by_time", record_json(*by_time));
      else j.add_null("cheapest_by_time");
      if (by_evals) j.add("cheapest_by_evals", record_json(*by_evals));
      else j.add_null("cheapest_by_evals");
      if (plan.out_csv.empty()) j.add_null("out_csv");
      else j.add("out_csv", plan.out_csv);
      if (plan.out_png.empty()) j.add_null("out_png");
      else j.add("out_png", plan.out_png + "-time.png," + plan.out_png + "-evals.png");
      std::cout << j.str() << std::endl;
    } else {
      print_table(records);
      std::printf("%zu configurations (%d skipped) over %zu rays in %.2f s\n", records.size(), skipped,
                  plan.rays.size(), total);
#if GRTRACE_METHOD_MATRIX_UNOPTIMISED
      std::printf("timings of an unoptimised test build (the methods at -O0, GRTRACE_METHOD_MATRIX_UNOPTIMISED): not "
                  "for comparison; build with the release or bench preset\n");
#endif
      if (by_time)
        std::printf("cheapest with max error <= %g: %s/%s at %s %g (%.3g s, max error %.3e)\n", plan.target_error,
                    by_time->tableau.c_str(), by_time->controller.c_str(), by_time->point.fixed_step ? "step" : "rtol",
                    by_time->point.fixed_step ? by_time->point.step : by_time->point.rtol, by_time->stats.seconds,
                    by_time->all.max);
      else std::printf("no configuration reached max error <= %g\n", plan.target_error);
    }
    return 0;
  });
}
