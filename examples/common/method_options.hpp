// examples/common/method_options.hpp
// The integration options grtrace-render and grtrace-view share, declared once (names, defaults, help) and read
// once into typed fields, with their refusals worded once for both tools:
//   --tableau, --control   one of the methods the tools offer (grtrace/app/tool_methods.hpp)
//   --step                 the initial step (0 = automatic), or the step of --control fixed
//   --rtol, --atol         the step controller's tolerances
//   --max-steps            accepted steps before a ray ends as max_steps
//   --angle-correction     the sky direction of escaped rays: none | flat | exact
// A prefix declares the group again for a second integration (grtrace-view's --orbit-tableau, ...). Reading takes
// any source of option values with text(), number() and integer() (the CommandLine, or grtrace-view's Params that
// fall back on a frame's header).
#pragma once

#include "command_line.hpp"

#include "grtrace/app/tool_methods.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <stdexcept>
#include <string>

namespace grtrace::tools {

/// One tool's defaults for the group, and the words its help puts before each option's ("orbit: ").
struct MethodDefaults {
  std::string tableau = "rkf78", control = "i", rtol = "1e-9", atol = "1e-11";
  std::string help_prefix;
};

/// Declares --<prefix>tableau, --<prefix>control, --<prefix>step, --<prefix>rtol and --<prefix>atol.
inline void declare_method_options(CommandLine& cli, const std::string& prefix, const MethodDefaults& d) {
  const std::string& h = d.help_prefix;
  cli.option(prefix + "tableau", d.tableau,
             h + "Runge-Kutta tableau: " + app::tool_tableau_names() + ". With --" + prefix +
                 "control, one of the offered methods: " + app::tool_methods_list() +
                 " (every pair: grtrace-work-precision, grtrace-geodesic)")
      .option(prefix + "control", d.control,
              h + "step control: " + app::tool_control_names() + " (see --" + prefix + "tableau for the pairs)")
      .option(prefix + "step", "0", h + "initial step (0 = automatic), or the step of --" + prefix + "control fixed")
      .option(prefix + "rtol", d.rtol, h + "relative tolerance")
      .option(prefix + "atol", d.atol, h + "absolute tolerance");
}

/// Reads the group declared with `prefix` into the pair's names, tolerances and initial step (the caller sets the
/// rest: escape radius, max steps); throws UsageError naming the option and what to change: a pair the tools do not
/// offer, tolerances outside (0, 1) and [0, 1), a negative step, a fixed step without a step.
template <class Source>
app::MethodChoice read_method_options(const Source& p, const std::string& prefix) {
  app::MethodChoice m{p.text(prefix + "tableau"), p.text(prefix + "control"), {}};
  try {
    app::check_tool_method(m.tableau, m.control);
  } catch (const std::invalid_argument& e) {
    throw UsageError("--" + prefix + "tableau / --" + prefix + "control: " + e.what());
  }
  Tolerance& t = m.settings.integrator.tolerance;
  t = {p.number(prefix + "rtol"), p.number(prefix + "atol")};
  if (!(t.rtol > 0.0 && t.rtol < 1.0))
    throw UsageError("--" + prefix + "rtol must lie in (0, 1) (a relative error; e.g. 1e-9), got " +
                     p.text(prefix + "rtol"));
  if (!(t.atol >= 0.0 && t.atol < 1.0))
    throw UsageError("--" + prefix + "atol must lie in [0, 1) (e.g. 1e-11), got " + p.text(prefix + "atol"));
  m.settings.initial_step = p.number(prefix + "step");
  if (m.settings.initial_step < 0.0) throw UsageError("--" + prefix + "step must be >= 0");
  if (m.control == "fixed" && m.settings.initial_step <= 0.0)
    throw UsageError("--" + prefix + "control fixed needs a step: add --" + prefix + "step H > 0");
  return m;
}

/// --max-steps: a whole number in 1 .. 1e8.
template <class Source>
int read_max_steps(const Source& p) {
  const long max_steps = p.integer("max-steps");
  if (max_steps < 1 || max_steps > 100'000'000) throw UsageError("--max-steps must be in 1 .. 1e8");
  return static_cast<int>(max_steps);
}

/// --angle-correction: none, flat or exact.
template <class Source>
AngleCorrection read_angle_correction(const Source& p) {
  const std::string name = p.text("angle-correction");
  if (name == "none") return AngleCorrection::none;
  if (name == "flat") return AngleCorrection::flat;
  if (name == "exact") return AngleCorrection::exact;
  throw UsageError("unknown --angle-correction '" + name + "'; choose none, flat or exact");
}

}  // namespace grtrace::tools
