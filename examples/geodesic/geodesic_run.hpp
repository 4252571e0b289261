// examples/geodesic/geodesic_run.hpp
// grtrace-geodesic's request, its outputs and its run for one (tableau, controller) pair (see grtrace_geodesic.cpp).
// The tool offers every pair (the research matrix: 40 valid pairs, Schwarzschild/flat and Kerr in two charts); they
// are instantiated in three translation units by tableau group (geodesic_methods_*.cpp) so that they compile in
// parallel and no compiler process needs more than about 1 GB.
#pragma once

#include "command_line.hpp"
#include "json_writer.hpp"

#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/trace/deflection.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/method_dispatch.hpp"

#if GRTRACE_GEODESIC_VTP
#include "grtrace/viz/traced_path.hpp"
#include "grtrace/viz/vtk_export.hpp"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>
#include <optional>
#include <string_view>

namespace grtrace::geodesic_tool {

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
  bool kerr = false;           // --metric kerr: the fields below, and `initial` is in Boyer-Lindquist coordinates
  double spin = 0.0;
  std::string chart = "bl";
  TraceSettings settings;
  bool richardson = false;
  bool impact_run = false;
  double impact = 0.0;
  GeodesicState initial = GeodesicState::Zero();
  bool timelike = false;
};

inline CommandLine make_command_line() {
  CommandLine cli("grtrace-geodesic", "Trace one geodesic and print one line of JSON.");
  cli.option("metric", "schwarzschild", "spacetime: schwarzschild | minkowski (flat, spherical chart) | kerr")
      .option("mass", "1", "black-hole mass M (G = c = 1)")
      .option("spin", "0", "kerr: spin a, |a| < M (negative: rotation towards -phi)")
      .option("chart", "bl", "kerr: bl (Boyer-Lindquist) | ks (Kerr-Schild); --position/--velocity are Boyer-Lindquist "
                             "for both")
      .option("tableau", "dopri5", "Runge-Kutta tableau: " + tools::join(tableau_names(), "|"))
      .option("control", "pi", "step control: fixed | doubling | i | pi")
      .flag("richardson", "with --control doubling: propagate the Richardson-extrapolated value")
      .option("rtol", "1e-8", "relative tolerance")
      .option("atol", "1e-10", "absolute tolerance")
      .option("step", "0", "initial step (adaptive; 0 = automatic) or the step of --control fixed")
      .option("min-step", "1e-12", "smallest step before the ray ends as step_underflow")
      .option("max-steps", "100000", "accepted steps before the ray ends as max_steps")
      .option("escape-radius", "1000", "the ray has escaped at this radius (ignored with --impact)")
      .option("horizon-eps", "1e-3", "captured at r <= (1 + eps) r_h (2M; kerr: r_+, or inside it for ks)")
      .option("impact", "", "photon from infinity with this impact parameter (reports the total deflection)")
      .option("kind", "null", "with --position: null | timelike")
      .option("position", "", "initial event t,r,theta,phi (radians)")
      .option("velocity", "", "initial spatial components k^r,k^theta,k^phi; k^t solves g(k,k) = 0 or 1")
      .flag("past-directed", "with --position: k^t < 0 (trace back in time, as cameras do)")
      .option("path", "", "write every accepted step to this CSV file")
      .option("vtp", "", "write the geodesic (every accepted step) as a VTK XML polyline for ParaView (.vtp)");
  return cli;
}

inline Request read_request(const CommandLine& cli) {
  Request q;
  // The named metric (metric/named_metrics.hpp: its checks and their words), of the three this tool traces: the
  // integration of each uses its own conserved quantities and exact references below.
  MetricSpec ms;
  ms.name = cli.text("metric");
  if (ms.name != "schwarzschild" && ms.name != "minkowski" && ms.name != "kerr")
    throw UsageError("unknown metric '" + ms.name + "'; choose schwarzschild, minkowski or kerr");
  if (ms.name != "kerr" && (cli.given("spin") || cli.given("chart")))
    throw UsageError("--spin and --chart go with --metric kerr");
  ms.mass = cli.number("mass");
  ms.spin = cli.number("spin");
  ms.chart = cli.text("chart");
  CommandLine::as_usage_error([&] {
    check_metric_spec(ms);
    return 0;
  });
  const double mass = ms.mass;
  q.metric.mass = named_metric_has_mass(ms.name) ? mass : 0.0;  // flat space: Schwarzschild's chart with M = 0
  q.kerr = ms.name == "kerr";
  q.spin = ms.spin;
  q.chart = ms.chart;

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
  // Options that would be ignored: tolerances with a fixed step, what a ray from --position is
  // given with a ray from infinity (--impact: null, future-directed, followed to its own distance).
  const bool adaptive = cli.text("control") != "fixed", from_position = !cli.given("impact");
  const char* const adaptive_needs = "an adaptive --control (i, pi or doubling)";
  tools::refuse_inapplicable_options(cli, {{"rtol", adaptive, adaptive_needs},
                                           {"atol", adaptive, adaptive_needs},
                                           {"escape-radius", from_position, "--position and --velocity"},
                                           {"kind", from_position, "--position and --velocity"},
                                           {"past-directed", from_position, "--position and --velocity"}});

  // Kerr: the Boyer-Lindquist guard at r_+ (the start must be outside the horizon in both charts).
  const double r_guard = (1.0 + s.horizon_epsilon) * (q.kerr ? KerrMetric{mass, q.spin}.horizon_radius()
                                                              : q.metric.horizon_radius());
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
    throw UsageError("--position " + cli.text("position") + ": r = " + JsonObject::number(x[1]) +
                     " is not outside the horizon guard r = " + JsonObject::number(r_guard) +
                     "; move the start out");
  if (!(x[2] > 0.0 && x[2] < std::numbers::pi))
    throw UsageError("--position: theta must lie strictly between 0 and pi (the chart is singular on the axis)");
  if (!(x[1] < s.escape_radius)) throw UsageError("--position: r must be inside --escape-radius");
  const std::string kind = cli.text("kind");
  if (kind != "null" && kind != "timelike") throw UsageError("--kind must be null or timelike, got '" + kind + "'");
  q.timelike = kind == "timelike";
  if (!q.timelike && v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0)
    throw UsageError("--velocity 0,0,0 gives a null ray zero momentum (k = 0 is no direction); give a nonzero "
                     "spatial direction, e.g. -1,0,0.01");
  const auto k = q.kerr ? complete_time_component(KerrMetric{mass, q.spin}, x, Vec4(0.0, v[0], v[1], v[2]),
                                                  q.timelike ? 1.0 : 0.0)
                         : complete_time_component(q.metric, x, Vec4(0.0, v[0], v[1], v[2]), q.timelike ? 1.0 : 0.0);
  if (!k) throw UsageError("--velocity: no real k^t makes this vector " + kind + " (spatial speed too large?)");
  Vec4 kk = *k;
  if (cli.flag_set("past-directed")) kk[0] = -kk[0];
  q.initial = make_state(x, kk);
  return q;
}

/// The output files of a run (--path, --vtp), written together.
struct Outputs {
  std::string path, vtp;
};

/// Writes the accepted steps as CSV; `cartesian` names the columns of a Cartesian chart (Kerr-Schild).
inline void write_path(OutputSet& set, const std::string& file, const std::vector<PathRow>& rows, bool cartesian = false) {
  write_file_atomically(set, file, [&](std::ostream& out) {
    out << (cartesian ? "lambda,t,x,y,z,kt,kx,ky,kz,h\n" : "lambda,t,r,theta,phi,kt,kr,ktheta,kphi,h\n");
    out.precision(17);
    for (const auto& row : rows) {
      out << row.lambda;
      for (int i = 0; i < 8; ++i) out << ',' << row.y[i];
      out << ',' << row.h << '\n';
    }
  });
}

/// Writes the accepted steps as a .vtp polyline: points metric.to_cartesian(x), the rows' lambda and h, the
/// status, no pixel, and the redshift f_static(start) / f_static(x) (NaN where g_tt <= 0: no static observer).
template <class Metric>
void write_vtp([[maybe_unused]] OutputSet& set, [[maybe_unused]] const std::string& file,
               [[maybe_unused]] const Metric& metric, [[maybe_unused]] const std::vector<PathRow>& rows,
               [[maybe_unused]] RayStatus status) {
#if GRTRACE_GEODESIC_VTP
  viz::TracedPath path;
  path.status = status;
  auto static_energy = [&](const GeodesicState& y) {
    const Mat4 g = metric.metric(Vec4(y.head<4>()));
    return g(0, 0) > 0.0 ? g.row(0).dot(y.tail<4>()) / std::sqrt(g(0, 0)) : viz::kNaN;
  };
  const double e0 = rows.empty() ? viz::kNaN : static_energy(rows.front().y);
  int step = 0;
  for (const PathRow& row : rows) {
    viz::PathSample s;
    s.state = row.y;
    s.position = metric.to_cartesian(Vec4(row.y.head<4>()));
    s.lambda = row.lambda;
    s.h = row.h;
    s.step = step++;
    s.redshift = e0 / static_energy(row.y);
    path.samples.push_back(s);
  }
  viz::write_vtk_xml(set, viz::paths_to_export_polydata(std::span(&path, 1)), file);
#else
  throw std::logic_error("--vtp: built without VTK");  // refused in main before any work
#endif
}

template <class Metric>
void write_outputs(const Outputs& files, const Metric& metric, const std::vector<PathRow>& rows, RayStatus status,
                   bool cartesian = false) {
  if (files.path.empty() && files.vtp.empty()) return;
  OutputSet set;
  if (!files.path.empty()) write_path(set, files.path, rows, cartesian);
  if (!files.vtp.empty()) write_vtp(set, files.vtp, metric, rows, status);
  set.commit();
}

template <ExplicitTableau T, StepController C>
JsonObject run(const Request& q, const Outputs& files) {
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
  write_outputs(files, q.metric, rows, r.status);

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

// ---- Kerr ---------------------------------------------------------------------------------------------------

/// The chart's state for a Boyer-Lindquist one (Kerr-Schild: the slicing the ray's time direction crosses).
template <class Metric>
GeodesicState to_chart(const Metric& m, const GeodesicState& y_bl) {
  if constexpr (std::is_same_v<Metric, KerrSchildMetric>) return bl_to_ks(m, y_bl);
  else return y_bl;
}

/// Boyer-Lindquist phi of a state (KS: from its Cartesian position; valid outside r_+).
template <class Metric>
double bl_phi(const Metric& m, const GeodesicState& y) {
  if constexpr (std::is_same_v<Metric, KerrSchildMetric>) return ks_to_bl_position(m, y.head<4>())[3];
  else return y[3];
}

/// Traces the request in Kerr (Boyer-Lindquist or Kerr-Schild `metric`) and returns the JSON of the contract plus
/// E, L_z, Q at the start and their drifts. Assumes q.kerr, the request checked, q.initial in BL coordinates.
template <ExplicitTableau T, StepController C, class Metric>
JsonObject run_kerr(const Request& q, const Metric& metric, const Outputs& files) {
  C controller{};
  if constexpr (std::is_same_v<C, StepDoubling>) controller.richardson = q.richardson;
  const KerrMetric bl{q.metric.mass, q.spin};
  TraceSettings settings = q.settings;
  GeodesicState start_bl = q.initial;
  double start_radius = 0.0;
  if (q.impact_run) {
    // Start where Schwarzschild's --impact starts (impact_start_radius: max(50 M, 4 |b|), so the photon's state
    // there is a null state for every b; a fixed sphere would be inside a large b's turning point), end on the same
    // sphere on the way out; the legs beyond are added exactly.
    start_radius = impact_start_radius(std::abs(q.impact));
    settings.escape_radius = start_radius * (1.0 + 1e-9);
    start_bl = kerr_equatorial_photon(bl, q.impact, start_radius);  // grtrace/trace/deflection.hpp
  }
  const GeodesicState start = to_chart(metric, start_bl);
  const GeodesicTracer<Metric, T, C> tracer(metric, settings, controller);
  std::vector<PathRow> rows;
  const PathRecorder recorder{&rows};
  const auto t0 = std::chrono::steady_clock::now();
  const TraceResult r = tracer.trace_observed(start, recorder);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_outputs(files, metric, rows, r.status, std::is_same_v<Metric, KerrSchildMetric>);

  JsonObject json;
  json.add("status", to_string(r.status));
  if (q.impact_run && r.status == RayStatus::escaped) {
    // Angle swept in phi (unwrapped step by step: the KS chart gives phi modulo 2 pi), plus the exact legs from
    // infinity to the start radius and from the escape sphere to infinity.
    double swept = 0.0, last = bl_phi(metric, rows.front().y);
    for (const PathRow& row : rows) {
      const double now = bl_phi(metric, row.y);
      swept += std::remainder(now - last, 2.0 * std::numbers::pi);
      last = now;
    }
    const double legs = exact::equatorial_phi_from_infinity(q.impact, 1.0 / start_radius, q.spin, q.metric.mass) +
                        exact::equatorial_phi_from_infinity(q.impact, 1.0 / metric.radius(r.final_state.head<4>()),
                                                            q.spin, q.metric.mass);
    const double deflection = std::abs(swept + legs) - std::numbers::pi;
    const double exact_value = exact::equatorial_deflection(q.impact, q.spin, q.metric.mass, 256);
    json.add("deflection", deflection).add("deflection_exact", exact_value);
    json.add("deflection_error", deflection - exact_value);
  } else {
    json.add_null("deflection");
  }
  json.add("steps", r.accepted).add("rejected", r.rejected).add("rhs_evals", r.rhs_evals);
  json.add("constraint_drift", r.constraint_drift);
  const double e0 = metric.energy(start), l0 = metric.angular_momentum(start);
  const double q0 = metric.carter_constant(start);
  const GeodesicState& y = r.final_state;
  json.add("energy_drift", metric.energy(y) / e0 - 1.0);
  json.add("angular_momentum_drift", l0 != 0.0 ? metric.angular_momentum(y) / l0 - 1.0 : metric.angular_momentum(y));
  json.add("energy", e0).add("angular_momentum", l0).add("carter_q", q0);
  // Q changes sign and vanishes for equatorial rays: its drift is relative to max(|Q|, (E M)^2).
  const double q_scale = std::max(std::abs(q0), e0 * e0 * q.metric.mass * q.metric.mass);
  if (std::is_same_v<Metric, KerrSchildMetric> && !(metric.radius(y.head<4>()) > bl.outer_horizon())) {
    json.add_null("carter_drift");  // Q is computed through Boyer-Lindquist coordinates: not inside r_+
  } else {
    json.add("carter_drift", (metric.carter_constant(y) - q0) / q_scale);
  }
  JsonObject fin;
  fin.add("lambda", r.lambda).add("t", y[0]);
  if constexpr (std::is_same_v<Metric, KerrSchildMetric>) {
    fin.add("x", y[1]).add("y", y[2]).add("z", y[3]).add("r", metric.radius(y.head<4>()));
    fin.add("kt", y[4]).add("kx", y[5]).add("ky", y[6]).add("kz", y[7]);
  } else {
    fin.add("r", y[1]).add("theta", y[2]).add("phi", y[3]);
    fin.add("kt", y[4]).add("kr", y[5]).add("ktheta", y[6]).add("kphi", y[7]);
  }
  json.add("final", fin);
  json.add("metric", "kerr").add("spin", q.spin).add("chart", q.chart);
  json.add("tableau", T::name).add("control", C::name);
  json.add("rtol", q.settings.integrator.tolerance.rtol).add("atol", q.settings.integrator.tolerance.atol);
  json.add("seconds", seconds);
  return json;
}

/// run_kerr in the requested chart (KS: the slicing whose horizon the ray's time direction crosses).
template <ExplicitTableau T, StepController C>
JsonObject run_kerr_chart(const Request& q, const Outputs& files) {
  if (q.chart == "ks") {
    KerrSchildMetric ks = KerrSchildMetric::checked(q.metric.mass, q.spin);
    ks.slicing = slicing_crossed_by(q.impact_run ? 1.0 : q.initial[4]);
    return run_kerr<T, C>(q, ks, files);
  }
  return run_kerr<T, C>(q, KerrMetric::checked(q.metric.mass, q.spin), files);
}

/// Runs the request with the named pair when its tableau is one of Tableaux (a group's share of the matrix);
/// nothing when the tableau is another group's. Assumes the pair was checked (dispatch_method).
template <class... Tableaux>
std::optional<JsonObject> run_among(const Request& q, const Outputs& files, std::string_view tableau,
                                    std::string_view control) {
  std::optional<JsonObject> json;
  const auto one = [&]<class T>() {
    if (T::name != tableau) return;
    dispatch_controller(control, [&]<class C>(std::type_identity<C>) {
      if constexpr (is_valid_method<T, C>) json = q.kerr ? run_kerr_chart<T, C>(q, files) : run<T, C>(q, files);
    });
  };
  (one.template operator()<Tableaux>(), ...);
  return json;
}

// The three groups (geodesic_methods_low.cpp, _fifth.cpp, _high.cpp).
std::optional<JsonObject> run_low_order(const Request& q, const Outputs& files, std::string_view tableau,
                                        std::string_view control);
std::optional<JsonObject> run_fifth_order(const Request& q, const Outputs& files, std::string_view tableau,
                                          std::string_view control);
std::optional<JsonObject> run_high_order(const Request& q, const Outputs& files, std::string_view tableau,
                                         std::string_view control);

}  // namespace grtrace::geodesic_tool
