// grtrace-geodesic: trace one geodesic (null or timelike) in Schwarzschild or flat spacetime and print
// ONE line of JSON (contract in shared/DESIGN.md):
//   {"status","deflection","steps","rejected","rhs_evals","constraint_drift","final":{...}, ...}
// --impact B traces a photon from far away with impact parameter B; "deflection" is the total bending from
// infinity to infinity (the legs outside the integrated region are added exactly), with the exact value
// and the error beside it. --path FILE.csv writes every accepted step (lambda, x^mu, k^mu, h).
#include "command_line.hpp"
#include "json_writer.hpp"

#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/trace/deflection.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/method_dispatch.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <vector>

namespace {

using namespace grtrace;
using tools::CommandLine;
using tools::JsonObject;
using tools::UsageError;

struct PathRow {
  double lambda;
  GeodesicState y;
  double h;
};

/// Records every accepted step; the last one ends where the ray ended (on the located surface).
struct PathRecorder {
  std::vector<PathRow>* rows;
  template <class Integrator>
  void operator()(const Integrator& integ, double theta_end) const {
    if (rows->empty()) rows->push_back({integ.previous_lambda(), integ.previous_state(), 0.0});
    const double h = theta_end * integ.last_step();
    rows->push_back({integ.previous_lambda() + h, theta_end == 1.0 ? integ.state() : integ.dense(theta_end), h});
  }
};

struct Request {
  SchwarzschildMetric metric;  // mass 0 = flat space (spherical chart)
  TraceSettings settings;
  bool richardson = false;
  bool impact_run = false;
  double impact = 0.0;
  GeodesicState initial = GeodesicState::Zero();
  bool timelike = false;
};

CommandLine make_command_line() {
  CommandLine cli("grtrace-geodesic", "Trace one geodesic and print one line of JSON.");
  cli.option("metric", "schwarzschild", "spacetime: schwarzschild | minkowski (flat, spherical chart)")
      .option("mass", "1", "black-hole mass M (G = c = 1)")
      .option("tableau", "dopri5", "Runge-Kutta tableau: " + tools::join(tableau_names(), "|"))
      .option("control", "pi", "step control: fixed | doubling | i | pi")
      .flag("richardson", "with --control doubling: propagate the Richardson-extrapolated value")
      .option("rtol", "1e-8", "relative tolerance")
      .option("atol", "1e-10", "absolute tolerance")
      .option("step", "0", "initial step (adaptive; 0 = automatic) or the step of --control fixed")
      .option("min-step", "1e-12", "smallest step before the ray ends as step_underflow")
      .option("max-steps", "100000", "accepted steps before the ray ends as max_steps")
      .option("escape-radius", "1000", "the ray has escaped at this radius (ignored with --impact)")
      .option("horizon-eps", "1e-3", "captured at r <= (1 + eps) 2M")
      .option("impact", "", "photon from infinity with this impact parameter (reports the total deflection)")
      .option("kind", "null", "with --position: null | timelike")
      .option("position", "", "initial event t,r,theta,phi (radians)")
      .option("velocity", "", "initial spatial components k^r,k^theta,k^phi; k^t solves g(k,k) = 0 or 1")
      .flag("past-directed", "with --position: k^t < 0 (trace back in time, as cameras do)")
      .option("path", "", "write every accepted step to this CSV file");
  return cli;
}

Request read_request(const CommandLine& cli) {
  Request q;
  const std::string metric = cli.text("metric");
  if (metric != "schwarzschild" && metric != "minkowski")
    throw UsageError("unknown metric '" + metric + "'; choose schwarzschild or minkowski");
  const double mass = cli.number("mass");
  if (mass <= 0.0 && metric == "schwarzschild") throw UsageError("--mass must be > 0, got " + cli.text("mass"));
  q.metric.mass = metric == "minkowski" ? 0.0 : mass;

  TraceSettings& s = q.settings;
  s.integrator.tolerance.rtol = cli.number("rtol");
  s.integrator.tolerance.atol = cli.number("atol");
  if (!(s.integrator.tolerance.rtol > 0.0 && s.integrator.tolerance.rtol < 1.0))
    throw UsageError("--rtol must lie in (0, 1) (a relative error; e.g. 1e-8), got " + cli.text("rtol"));
  if (!(s.integrator.tolerance.atol >= 0.0 && s.integrator.tolerance.atol < 1.0))
    throw UsageError("--atol must lie in [0, 1) (e.g. 1e-10), got " + cli.text("atol"));
  s.initial_step = cli.number("step");
  if (s.initial_step < 0.0) throw UsageError("--step must be >= 0");
  if (cli.text("control") == "fixed" && s.initial_step <= 0.0)
    throw UsageError("--control fixed needs a step: add --step H (e.g. --step 0.5)");
  s.integrator.h_min = cli.number("min-step");
  if (!(s.integrator.h_min > 0.0)) throw UsageError("--min-step must be > 0");
  const long max_steps = cli.integer("max-steps");
  if (max_steps <= 0 || max_steps > 1'000'000'000) throw UsageError("--max-steps must be in 1 .. 1e9");
  s.max_steps = static_cast<int>(max_steps);
  s.horizon_epsilon = cli.number("horizon-eps");
  if (!(s.horizon_epsilon > 0.0 && s.horizon_epsilon < 0.5))
    throw UsageError("--horizon-eps must lie in (0, 0.5) (the capture sphere (1 + eps) 2M must stay inside the "
                     "photon sphere 3M; e.g. 1e-3), got " + cli.text("horizon-eps"));
  s.escape_radius = cli.number("escape-radius");
  if (!(s.escape_radius > 0.0 && s.escape_radius <= 1e100))
    throw UsageError("--escape-radius must lie in (0, 1e100] (r^2 must not overflow), got " +
                     cli.text("escape-radius"));
  if (s.initial_step > 2.0 * s.escape_radius && !cli.given("impact"))
    throw UsageError("--step " + cli.text("step") + " is longer than the escape sphere's diameter (2 x " +
                     "--escape-radius); use a step in (0, " + JsonObject::number(2.0 * s.escape_radius) + "]");
  q.richardson = cli.flag_set("richardson");
  if (q.richardson && cli.text("control") != "doubling") throw UsageError("--richardson goes with --control doubling");

  const double r_guard = (1.0 + s.horizon_epsilon) * q.metric.horizon_radius();
  if (cli.given("impact")) {
    if (cli.given("position") || cli.given("velocity"))
      throw UsageError("give either --impact or --position/--velocity, not both");
    q.impact_run = true;
    q.impact = cli.number("impact");
    const double b_max = 1e10 * std::max(q.metric.mass, 1.0);
    if (!(q.impact > 0.0 && q.impact <= b_max))
      throw UsageError("--impact must lie in (0, " + JsonObject::number(b_max) + "] (1e10 M: beyond, the deflection " +
                       "4M/b is below what the tolerances resolve and the start sphere 4b overflows r^2), got " +
                       cli.text("impact"));
    return q;
  }
  if (!cli.given("position") || !cli.given("velocity"))
    throw UsageError("give --impact B, or both --position t,r,theta,phi and --velocity kr,ktheta,kphi");
  const auto p = cli.numbers("position", 4), v = cli.numbers("velocity", 3);
  const Vec4 x(p[0], p[1], p[2], p[3]);
  if (!(x[1] > r_guard))
    throw UsageError("--position: r = " + cli.text("position") + " is not outside the horizon guard r = " +
                     std::to_string(r_guard));
  if (!(x[2] > 0.0 && x[2] < std::numbers::pi))
    throw UsageError("--position: theta must lie strictly between 0 and pi (the chart is singular on the axis)");
  if (!(x[1] < s.escape_radius)) throw UsageError("--position: r must be inside --escape-radius");
  const std::string kind = cli.text("kind");
  if (kind != "null" && kind != "timelike") throw UsageError("--kind must be null or timelike, got '" + kind + "'");
  q.timelike = kind == "timelike";
  if (!q.timelike && v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0)
    throw UsageError("--velocity 0,0,0 gives a null ray zero momentum (k = 0 is no direction); give a nonzero "
                     "spatial direction, e.g. -1,0,0.01");
  const auto k = complete_time_component(q.metric, x, Vec4(0.0, v[0], v[1], v[2]), q.timelike ? 1.0 : 0.0);
  if (!k) throw UsageError("--velocity: no real k^t makes this vector " + kind + " (spatial speed too large?)");
  Vec4 kk = *k;
  if (cli.flag_set("past-directed")) kk[0] = -kk[0];
  q.initial = make_state(x, kk);
  return q;
}

void write_path(const std::string& file, const std::vector<PathRow>& rows) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "lambda,t,r,theta,phi,kt,kr,ktheta,kphi,h\n";
    out.precision(17);
    for (const auto& row : rows) {
      out << row.lambda;
      for (int i = 0; i < 8; ++i) out << ',' << row.y[i];
      out << ',' << row.h << '\n';
    }
  });
}

template <ExplicitTableau T, StepController C>
JsonObject run(const Request& q, const std::string& path_file) {
  C controller{};
  if constexpr (std::is_same_v<C, StepDoubling>) controller.richardson = q.richardson;
  const GeodesicTracer<SchwarzschildMetric, T, C> tracer(q.metric, q.settings, controller);
  std::vector<PathRow> rows;
  const PathRecorder recorder{&rows};

  const auto t0 = std::chrono::steady_clock::now();
  TraceResult r;
  GeodesicState start = q.initial;
  double deflection = std::numeric_limits<double>::quiet_NaN();
  if (q.impact_run) {
    const DeflectionResult d = measure_deflection(tracer, q.impact, recorder);
    r = d.trace;
    deflection = d.deflection;
    start = incoming_photon(q.impact, d.start_radius, q.metric.mass);
  } else {
    r = tracer.trace_observed(q.initial, recorder);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!path_file.empty()) write_path(path_file, rows);

  JsonObject json;
  json.add("status", to_string(r.status));
  if (q.impact_run) {
    const double exact = exact::deflection_angle(q.impact, q.metric.mass);
    json.add("deflection", deflection).add("deflection_exact", exact).add("deflection_error", deflection - exact);
  } else {
    json.add_null("deflection");
  }
  json.add("steps", r.accepted).add("rejected", r.rejected).add("rhs_evals", r.rhs_evals);
  json.add("constraint_drift", r.constraint_drift);
  const SchwarzschildMetric& m = q.metric;
  json.add("energy_drift", m.energy(r.final_state) / m.energy(start) - 1.0);
  json.add("angular_momentum_drift",
           m.total_angular_momentum(r.final_state) / m.total_angular_momentum(start) - 1.0);
  const GeodesicState& y = r.final_state;
  JsonObject fin;
  fin.add("lambda", r.lambda).add("t", y[0]).add("r", y[1]).add("theta", y[2]).add("phi", y[3]);
  fin.add("kt", y[4]).add("kr", y[5]).add("ktheta", y[6]).add("kphi", y[7]);
  json.add("final", fin);
  json.add("tableau", T::name).add("control", C::name);
  json.add("rtol", q.settings.integrator.tolerance.rtol).add("atol", q.settings.integrator.tolerance.atol);
  json.add("seconds", seconds);
  return json;
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli = make_command_line();
  return tools::run_tool(cli, argc, argv, [&] {
    const Request q = read_request(cli);
    const std::string path_file = cli.text("path");
    if (cli.given("path")) tools::check_output_option("path", path_file);  // --path "" is refused
    JsonObject json;
    const auto error = dispatch_method(cli.text("tableau"), cli.text("control"),
                                       [&]<class T, class C>() { json = run<T, C>(q, path_file); });
    if (error != DispatchError::none) throw UsageError(describe(error, cli.text("tableau"), cli.text("control")));
    std::cout << json.str() << std::endl;
    return 0;
  });
}
