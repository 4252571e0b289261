// grtrace-orbit-drift: how the 4-velocity norm g(u,u) and the Killing energy E drift over many orbits of the seed
// report's timelike orbit (Schwarzschild M = 1, r = 100, equatorial, d phi/d tau = 0.00075, starting at
// apoapsis), for a symplectic implicit Gauss-Legendre method against DP5(4) (adaptive, PI control) and classic
// RK4 (fixed step), at equal work: every method gets about as many right-hand-side evaluations as DP5(4) needs
// at --rtol/--atol for the whole run.
//
// Methods (the formulation matters; see grtrace/integrate/gauss_legendre.hpp):
//   gl6      3-stage Gauss-Legendre (order 6), fixed step, canonical (x, p_mu) form of H = 1/2 g^{mu nu} p p
//   gl4      2-stage Gauss-Legendre (order 4), same form
//   gl6-xk   3-stage Gauss-Legendre in the tracers' (x, k) form (symmetric but not symplectic in these variables)
//   dopri5   Dormand-Prince 5(4), PI controller, (x, k): sets the work budget
//   rk4      classic RK4, fixed step, (x, k)
//   rk4-xp   classic RK4, fixed step, canonical (x, p): same variables as gl*, so the difference is symplecticity
// An "orbit" is one revolution in phi; each orbit's drift is the largest |g(u,u) - 1| and |E/E0 - 1| over the
// accepted steps inside it. In (x, p) form E = p_t is a linear invariant and is conserved exactly by every
// Runge-Kutta method (its drift is 0; not drawn on the log chart).
//
// What it shows with the defaults (measured): the Gauss errors in g(u,u) stay flat (growth 1.0-1.07 from orbits
// 1-10 to 91-100, at ~4e-6) and E is exact; DP5(4) grows ~9.5x in both, RK4 ~6.5x in E, RK4 in (x, p) ~10x in
// g(u,u). At this budget the explicit errors are still the smaller ones after 100 orbits (DP5 3e-8): a fixed-point
// Gauss step costs ~40 evaluations, so its step is ~10x RK4's. The lines cross later: with --orbits 10000, DP5(4)
// reaches 3.3e-6 in g(u,u) (gl6 3.9e-6) and 4.4e-7 in E, RK4 2.4e-5 in E, RK4 (x, p) 3.3e-5 in g(u,u).
//
// Writes a CSV (orbit, then <method>_norm_drift, <method>_energy_drift), a log-scale PNG chart of both drifts
// against orbit number (VTK charts; needs an X display: run under xvfb-run -a -s "-screen 0 1280x1024x24", or
// pass --no-png), and prints ONE line of JSON with the per-method summary.
#include "command_line.hpp"
#include "grtrace/viz/viewer_window.hpp"
#include "grtrace/integrate/controlled_integrator.hpp"
#include "grtrace/integrate/gauss_legendre.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/tableau/classic_rk4.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "json_writer.hpp"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace grtrace;
using tools::CommandLine;
using tools::JsonObject;
using tools::UsageError;

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Setup {
  SchwarzschildMetric metric{1.0};
  GeodesicState y0 = GeodesicState::Zero();  ///< (x, k), unit timelike
  double energy0 = 1.0;
  int orbits = 100;
  Tolerance tolerance{};
  ImplicitSolverSettings solver{};
  long max_steps = 20'000'000;
};

/// One method's run: per-orbit maxima of the two drifts, and what it cost.
struct Drift {
  std::string name, formulation, control;
  std::vector<double> norm, energy;  ///< index n: orbit n + 1; NaN where the run did not get
  long rhs_evals = 0, steps = 0;
  double step = kNaN;  ///< the fixed step (NaN for adaptive)
  double proper_time = 0.0;
  double seconds = 0.0;
  int orbits_completed = 0;
  int max_iterations = -1;  ///< largest fixed-point iteration count in one step (implicit methods)
  int not_converged = 0;
  std::string status = "ok";
};

Drift make_drift(std::string name, std::string formulation, std::string control) {
  Drift d;
  d.name = std::move(name);
  d.formulation = std::move(formulation);
  d.control = std::move(control);
  return d;
}

struct Sample {
  double phi, r, norm_error, energy_error;
};

Sample sample_lagrangian(const Setup& s, const GeodesicState& y) {
  const double norm = inner_product(s.metric, y.head<4>(), y.tail<4>(), y.tail<4>());
  return {y[3], y[1], std::abs(norm - 1.0), std::abs(s.metric.energy(y) / s.energy0 - 1.0)};
}

Sample sample_canonical(const Setup& s, const GeodesicState& y) {
  return {y[3], y[1], std::abs(canonical_norm(s.metric, y) - 1.0), std::abs(y[4] / s.energy0 - 1.0)};
}

/// Steps `advance` (returns "" or a failure status) until phi has made s.orbits revolutions, recording per-orbit
/// maxima of the drifts. Also ends on capture (r at the horizon guard), non-finite states and the step cap.
template <class Advance, class Observe>
void follow(const Setup& s, Drift& d, int orbits, Advance&& advance, Observe&& observe) {
  d.norm.assign(static_cast<std::size_t>(orbits), kNaN);
  d.energy.assign(static_cast<std::size_t>(orbits), kNaN);
  const double r_guard = 2.0 * s.metric.mass * (1.0 + 1e-3);
  const auto t0 = std::chrono::steady_clock::now();
  d.orbits_completed = 0;
  for (long step = 0;; ++step) {
    if (step >= s.max_steps) {
      d.status = "max_steps";
      break;
    }
    if (const std::string status = advance(); !status.empty()) {
      d.status = status;
      break;
    }
    const Sample x = observe();
    if (!std::isfinite(x.phi) || !std::isfinite(x.norm_error) || !std::isfinite(x.energy_error)) {
      d.status = "non_finite";
      break;
    }
    if (!(x.r > r_guard)) {
      d.status = "captured";
      break;
    }
    const double turns = std::floor(x.phi / kTwoPi);
    if (turns >= orbits) {
      d.orbits_completed = orbits;
      break;
    }
    const auto n = static_cast<std::size_t>(std::max(turns, 0.0));
    d.orbits_completed = static_cast<int>(n);
    d.norm[n] = std::isnan(d.norm[n]) ? x.norm_error : std::max(d.norm[n], x.norm_error);
    d.energy[n] = std::isnan(d.energy[n]) ? x.energy_error : std::max(d.energy[n], x.energy_error);
  }
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string outcome_name(StepOutcome o) {
  switch (o) {
    case StepOutcome::ok:
      return "";
    case StepOutcome::step_underflow:
      return "step_underflow";
    case StepOutcome::non_finite:
      return "non_finite";
  }
  return "non_finite";
}

std::string outcome_name(ImplicitStepOutcome o) {
  switch (o) {
    case ImplicitStepOutcome::ok:
      return "";
    case ImplicitStepOutcome::not_converged:
      return "not_converged";
    case ImplicitStepOutcome::non_finite:
      return "non_finite";
  }
  return "non_finite";
}

/// DP5(4) with the PI controller in (x, k): the reference run that sets the work budget.
Drift run_dopri5(const Setup& s) {
  Drift d = make_drift("dopri5", "x,k", "pi");
  const GeodesicEquation<SchwarzschildMetric> rhs{&s.metric};
  IntegratorSettings settings;
  settings.tolerance = s.tolerance;
  ControlledIntegrator<DormandPrince54, PIController, 8> integ(settings);
  integ.start(rhs, s.y0, 0.0);
  follow(
      s, d, s.orbits, [&] { return outcome_name(integ.advance(rhs)); },
      [&] { return sample_lagrangian(s, integ.state()); });
  d.rhs_evals = integ.rhs_evals();
  d.steps = integ.accepted();
  d.proper_time = integ.lambda();
  return d;
}

/// Classic RK4 with a fixed step, in (x, k) or in canonical (x, p) form.
Drift run_rk4(const Setup& s, double h, bool canonical) {
  Drift d = make_drift(canonical ? "rk4-xp" : "rk4", canonical ? "x,p" : "x,k", "fixed");
  d.step = h;
  IntegratorSettings settings;
  settings.h_min = 0.0;
  ControlledIntegrator<ClassicRK4, FixedStep, 8> integ(settings);
  if (canonical) {
    const HamiltonianGeodesicEquation<SchwarzschildMetric> rhs{&s.metric};
    integ.start(rhs, to_canonical(s.metric, s.y0), h);
    follow(
        s, d, s.orbits, [&] { return outcome_name(integ.advance(rhs)); },
        [&] { return sample_canonical(s, integ.state()); });
  } else {
    const GeodesicEquation<SchwarzschildMetric> rhs{&s.metric};
    integ.start(rhs, s.y0, h);
    follow(
        s, d, s.orbits, [&] { return outcome_name(integ.advance(rhs)); },
        [&] { return sample_lagrangian(s, integ.state()); });
  }
  d.rhs_evals = integ.rhs_evals();
  d.steps = integ.accepted();
  d.proper_time = integ.lambda();
  return d;
}

/// Gauss-Legendre with a fixed step h over `orbits` orbits.
template <ImplicitTableau G>
Drift run_gauss(const Setup& s, double h, bool canonical, int orbits) {
  Drift d = make_drift(std::string(G::name) + (canonical ? "" : "-xk"), canonical ? "x,p" : "x,k", "fixed");
  d.step = h;
  GaussLegendreIntegrator<G, 8> integ(h, s.solver);
  if (canonical) {
    const HamiltonianGeodesicEquation<SchwarzschildMetric> rhs{&s.metric};
    integ.start(rhs, to_canonical(s.metric, s.y0));
    follow(
        s, d, orbits, [&] { return outcome_name(integ.advance(rhs)); },
        [&] { return sample_canonical(s, integ.state()); });
  } else {
    const GeodesicEquation<SchwarzschildMetric> rhs{&s.metric};
    integ.start(rhs, s.y0);
    follow(
        s, d, orbits, [&] { return outcome_name(integ.advance(rhs)); },
        [&] { return sample_lagrangian(s, integ.state()); });
  }
  d.rhs_evals = integ.rhs_evals();
  d.steps = integ.accepted();
  d.proper_time = integ.lambda();
  d.max_iterations = integ.max_iterations_seen();
  d.not_converged = integ.not_converged();
  return d;
}

/// The fixed step that spends about `budget` evaluations over the run. Evaluations per step of the fixed-point
/// iteration grow with h, so h is found by bisection (on log h) over the first orbits (at most 20, with the
/// budget scaled to them): a probe that uses fewer evaluations than its share, or does not converge, has too
/// large a step. If the full run then fails to converge, h shrinks by 10 % until it does (or 10 tries pass).
template <ImplicitTableau G>
Drift run_gauss_equal_work(const Setup& s, bool canonical, long budget, double proper_time) {
  const int probe_orbits = std::min(s.orbits, 20);
  const double share = static_cast<double>(budget) * probe_orbits / s.orbits;
  const double h_unit = proper_time / static_cast<double>(budget) * static_cast<double>(G::stages);
  double lo = h_unit, hi = h_unit * s.solver.max_iterations;  // 1 and max_iterations iterations per step
  for (int i = 0; i < 24; ++i) {
    const double h = std::sqrt(lo * hi);
    const Drift probe = run_gauss<G>(s, h, canonical, probe_orbits);
    if (probe.status != "ok" || static_cast<double>(probe.rhs_evals) < share) hi = h;
    else lo = h;
  }
  Drift d = run_gauss<G>(s, lo, canonical, s.orbits);
  for (int retry = 0; retry < 10 && d.status == "not_converged"; ++retry)
    d = run_gauss<G>(s, d.step * 0.9, canonical, s.orbits);
  return d;
}

// ---- summary ---------------------------------------------------------------------------------------------

double max_over(const std::vector<double>& v, std::size_t from, std::size_t to) {
  double m = kNaN;
  for (std::size_t i = from; i < std::min(to, v.size()); ++i)
    if (!std::isnan(v[i])) m = std::isnan(m) ? v[i] : std::max(m, v[i]);
  return m;
}

JsonObject drift_json(const std::vector<double>& v) {
  const std::size_t n = v.size(), k = std::min<std::size_t>(10, n);
  const double first = max_over(v, 0, k), last = max_over(v, n - k, n);
  JsonObject o;
  o.add("first_10_orbits", first).add("last_10_orbits", last).add("growth", first > 0.0 ? last / first : kNaN);
  return o;
}

JsonObject method_json(const Drift& d, long budget) {
  JsonObject o;
  o.add("formulation", d.formulation).add("control", d.control).add("status", d.status);
  o.add("orbits_completed", d.orbits_completed).add("rhs_evals", d.rhs_evals);
  o.add("work_ratio", static_cast<double>(d.rhs_evals) / static_cast<double>(budget)).add("steps", d.steps);
  o.add("step", d.step).add("proper_time", d.proper_time);
  o.add("norm_drift", drift_json(d.norm)).add("energy_drift", drift_json(d.energy));
  if (d.max_iterations >= 0)
    o.add("max_fixed_point_iterations", d.max_iterations).add("not_converged", d.not_converged);
  o.add("seconds", d.seconds);
  return o;
}

void write_csv(OutputSet& set, const std::filesystem::path& file, const std::vector<Drift>& runs, int orbits) {
  write_file_atomically(set, file, [&](std::ostream& out) {
    out << "orbit";
    for (const auto& d : runs) out << ',' << d.name << "_norm_drift," << d.name << "_energy_drift";
    out << '\n';
    char buf[32];
    auto cell = [&](double v) {
      if (std::isnan(v)) return std::string();
      std::snprintf(buf, sizeof buf, "%.6e", v);
      return std::string(buf);
    };
    for (int n = 0; n < orbits; ++n) {
      out << n + 1;
      for (const auto& d : runs) {
        const auto i = static_cast<std::size_t>(n);
        out << ',' << cell(d.norm[i]) << ',' << cell(d.energy[i]);
      }
      out << '\n';
    }
  });
}

// ---- chart -----------------------------------------------------------------------------------------------

using Rgb = std::array<unsigned char, 3>;
constexpr std::array<Rgb, 6> kColors = {
    {{31, 119, 180}, {44, 160, 44}, {148, 103, 189}, {255, 127, 14}, {214, 39, 40}, {140, 86, 75}}};

/// Adds one method's per-orbit drift as a line (orbits without data, or with exact zeros, are left out).
bool add_drift_plot(vtkChartXY* chart, const std::string& label, const std::vector<double>& v, Rgb color,
                    int line_type) {
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> xs, ys;
  xs->SetName("orbit");
  ys->SetName(label.c_str());
  table->AddColumn(xs);
  table->AddColumn(ys);
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (std::isfinite(v[i]) && v[i] > 0.0) points.emplace_back(static_cast<double>(i + 1), v[i]);
  if (points.size() < 2) return false;
  table->SetNumberOfRows(static_cast<vtkIdType>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    table->SetValue(static_cast<vtkIdType>(i), 0, points[i].first);
    table->SetValue(static_cast<vtkIdType>(i), 1, points[i].second);
  }
  vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
  plot->SetInputData(table, 0, 1);
  plot->SetColor(color[0], color[1], color[2], 255);
  plot->SetWidth(2.0f);
  plot->GetPen()->SetLineType(line_type);
  return true;
}

void style_chart(vtkChartXY* chart, const std::string& title, const std::string& y_title) {
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(15);
  vtkAxis* x = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* y = chart->GetAxis(vtkAxis::LEFT);
  x->SetTitle("orbit (revolutions in phi)");
  y->SetTitle(y_title);
  y->SetLogScale(true);
  for (vtkAxis* a : {x, y}) {
    a->GetTitleProperties()->SetFontSize(14);
    a->GetLabelProperties()->SetFontSize(12);
  }
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::BOTTOM);
  chart->GetLegend()->GetLabelProperties()->SetFontSize(12);
}

void write_png(OutputSet& set, const std::filesystem::path& file, const std::vector<Drift>& runs, const Setup& s,
               long budget) {
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(1100, 1100);
  viz::prepare_window(view->GetRenderWindow());  // the shared X connection; no interactor offscreen
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartMatrix> matrix;
  view->GetScene()->AddItem(matrix);
  matrix->SetSize(vtkVector2i(1, 2));
  matrix->SetGutter(vtkVector2f(30.0f, 70.0f));
  matrix->SetBorders(90, 50, 30, 40);  // left, bottom, right, top: room for the log-axis titles
  auto* norm_chart = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 1)));
  auto* energy_chart = vtkChartXY::SafeDownCast(matrix->GetChart(vtkVector2i(0, 0)));
  if (norm_chart == nullptr || energy_chart == nullptr) throw std::runtime_error("VTK chart matrix gave no XY charts");

  std::string exact;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const Drift& d = runs[i];
    const int line = d.formulation == "x,p" ? vtkPen::SOLID_LINE : vtkPen::DASH_LINE;
    const std::string label = d.name + " (" + d.formulation + ")";
    add_drift_plot(norm_chart, label, d.norm, kColors[i % kColors.size()], line);
    if (!add_drift_plot(energy_chart, label, d.energy, kColors[i % kColors.size()], line))
      exact += (exact.empty() ? "" : ", ") + d.name;
  }
  char head[200];
  std::snprintf(head, sizeof head, "M = %g, r0 = %g, dphi/dtau = %g; equal work: ~%ld RHS evaluations each",
                s.metric.mass, s.y0[1], s.y0[7], budget);
  style_chart(norm_chart, std::string("|g(u,u) - 1| per orbit (max over the orbit's steps). ") + head, "|g(u,u) - 1|");
  style_chart(energy_chart,
              "|E/E0 - 1| per orbit" + (exact.empty() ? std::string() : " (exactly 0, not drawn: " + exact + ")"),
              "|E/E0 - 1|");

  view->GetRenderWindow()->Render();
  viz::save_window_png(set, view->GetRenderWindow(), file.string());
}

// ---- command line ----------------------------------------------------------------------------------------

Setup read_setup(const CommandLine& cli) {
  Setup s;
  s.metric.mass = cli.number("mass");
  if (!(s.metric.mass > 0.0)) throw UsageError("--mass must be > 0, got " + cli.text("mass"));
  const double r = cli.number("radius");
  if (!(r > 3.0 * s.metric.mass))
    throw UsageError("--radius must be > 3M (outside the photon sphere; the orbit starts at apoapsis), got " +
                     cli.text("radius"));
  const double omega = cli.number("dphi-dtau");
  if (!(omega > 0.0)) throw UsageError("--dphi-dtau must be > 0, got " + cli.text("dphi-dtau"));
  const long orbits = cli.integer("orbits");
  if (orbits < 1 || orbits > 100000) throw UsageError("--orbits must be in 1 .. 100000, got " + cli.text("orbits"));
  s.orbits = static_cast<int>(orbits);
  s.tolerance.rtol = cli.number("rtol");
  s.tolerance.atol = cli.number("atol");
  if (!(s.tolerance.rtol > 0.0 && s.tolerance.rtol < 1.0))
    throw UsageError("--rtol must lie in (0, 1) (a relative error; e.g. 1e-8), got " + cli.text("rtol"));
  if (!(s.tolerance.atol >= 0.0 && s.tolerance.atol < 1.0))
    throw UsageError("--atol must lie in [0, 1) (e.g. 1e-10), got " + cli.text("atol"));
  const long iterations = cli.integer("max-iterations");
  if (iterations < 2 || iterations > 1000) throw UsageError("--max-iterations must be in 2 .. 1000");
  s.solver.max_iterations = static_cast<int>(iterations);

  const Vec4 x(0.0, r, std::numbers::pi / 2.0, 0.0);
  const auto k = complete_time_component(s.metric, x, Vec4(0.0, 0.0, 0.0, omega), 1.0);
  if (!k) throw UsageError("--dphi-dtau: no timelike 4-velocity has this angular velocity at this radius");
  s.y0 = make_state(x, *k);
  s.energy0 = s.metric.energy(s.y0);
  if (!(s.energy0 < 1.0))
    throw UsageError("--dphi-dtau: the orbit is not bound (E = " + std::to_string(s.energy0) +
                     " >= 1), so it never completes orbits; lower --dphi-dtau or --radius");
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli("grtrace-orbit-drift",
                  "Drift of g(u,u) and of the energy E over many orbits of a timelike Schwarzschild orbit:\n"
                  "Gauss-Legendre (symplectic) against DP5(4) and RK4 at equal work. Writes a CSV and a log-scale\n"
                  "PNG chart (VTK; run under xvfb-run -a -s \"-screen 0 1280x1024x24\", or --no-png) and prints\n"
                  "ONE line of JSON.");
  cli.option("orbits", "100", "revolutions in phi to integrate")
      .option("mass", "1", "black-hole mass M")
      .option("radius", "100", "starting radius (apoapsis; the orbit starts with dr/dtau = 0)")
      .option("dphi-dtau", "0.00075", "starting angular velocity d phi / d tau")
      .option("rtol", "1e-8", "DP5(4) relative tolerance (its RHS count is every method's budget)")
      .option("atol", "1e-10", "DP5(4) absolute tolerance")
      .option("max-iterations", "60", "cap on fixed-point iterations per Gauss-Legendre step")
      .option("csv", "orbit_drift.csv", "per-orbit drifts of every method")
      .option("png", "orbit_drift.png", "log-scale chart of both drifts against orbit number")
      .flag("no-png", "skip the chart (no display needed)");
  return tools::run_tool(cli, argc, argv, [&] {
    const Setup s = read_setup(cli);
    if (cli.write_config_if_asked()) return 0;  // checked as for a run (output paths and display: at the run)
    const std::filesystem::path csv = cli.text("csv"), png = cli.text("png");
    const bool draw = !cli.flag_set("no-png");
    tools::check_command_output(cli, "csv", csv, {});
    if (draw) {
      tools::check_command_output(cli, "png", png, {});
      if (same_file(csv, png)) throw UsageError("--csv and --png name the same file '" + csv.string() + "'");
      try {
        viz::require_display("grtrace-orbit-drift", "pass --no-png");
      } catch (const viz::NoDisplayError& e) {
        throw UsageError(std::string("drawing the PNG: ") + e.what());
      }
    }
    const auto t0 = std::chrono::steady_clock::now();

    const Drift dopri5 = run_dopri5(s);
    if (dopri5.status != "ok")
      throw std::runtime_error("the DP5(4) reference run ended with status " + dopri5.status +
                               " before completing the orbits; choose a bound orbit (e.g. the defaults)");
    const long budget = dopri5.rhs_evals;
    const double tau = dopri5.proper_time;
    const double h_rk4 = 4.0 * tau / static_cast<double>(budget);  // RK4: 4 evaluations per step

    std::vector<Drift> runs;
    runs.push_back(run_gauss_equal_work<GaussLegendre6>(s, true, budget, tau));
    runs.push_back(run_gauss_equal_work<GaussLegendre4>(s, true, budget, tau));
    runs.push_back(run_gauss_equal_work<GaussLegendre6>(s, false, budget, tau));
    runs.push_back(dopri5);
    runs.push_back(run_rk4(s, h_rk4, false));
    runs.push_back(run_rk4(s, h_rk4, true));

    OutputSet outputs;  // the CSV and the PNG: both new or both as they were
    write_csv(outputs, csv, runs, s.orbits);
    if (draw) write_png(outputs, png, runs, s, budget);
    outputs.commit();

    JsonObject methods;
    for (const auto& d : runs) methods.add(d.name, method_json(d, budget));
    JsonObject json;
    json.add("orbits", s.orbits).add("mass", s.metric.mass).add("radius", s.y0[1]).add("dphi_dtau", s.y0[7]);
    json.add("budget_rhs_evals", budget).add("proper_time", tau);
    json.add("methods", methods);
    json.add("csv", csv.string());
    if (draw) json.add("png", png.string());
    else json.add_null("png");
    json.add("seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    std::cout << json.str() << std::endl;
    return 0;
  });
}
