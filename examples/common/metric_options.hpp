// examples/common/metric_options.hpp
// The metric options grtrace-render and grtrace-view share: declared once for the metrics a tool offers, read into
// the library's MetricSpec (grtrace/metric/named_metrics.hpp), whose check_metric_spec words the refusals:
//
//   --metric NAME        one of the tool's metrics (grtrace-render: all named metrics; grtrace-view: schwarzschild,
//                        kerr)
//   --mass M             all but minkowski and wormhole
//   --spin, --charge, --lambda, --throat   the one parameter of kerr, rn, sds, wormhole; declared only where the
//                        tool offers that metric, and refused (refuse_inapplicable_options) with any other metric
//
// --chart is not part of the group: its values differ by tool (grtrace-view also takes the older --chart
// orbit|norm|step); the caller passes the chart it read.
#pragma once

#include "command_line.hpp"
#include "kerr_options.hpp"

#include "grtrace/metric/named_metrics.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace grtrace::tools {

/// The parameter option of each named metric that has one: {metric, option, help, default, the field it sets}.
struct MetricParameterOption {
  const char* metric;
  const char* option;
  const char* help;
  const char* default_value;
  double MetricSpec::*field;
};
inline constexpr MetricParameterOption kMetricParameterOptions[] = {
    {"kerr", "spin", "kerr: spin a, |a| < M (negative: rotation towards -phi)", "0", &MetricSpec::spin},
    {"rn", "charge", "rn: charge Q, |Q| < M", "0.5", &MetricSpec::charge},
    {"sds", "lambda", "sds: cosmological constant, 0 < Lambda < 1/(9 M^2); the sky sphere must lie inside the "
                      "cosmological horizon", "1e-5", &MetricSpec::lambda},
    {"wormhole", "throat", "wormhole: throat radius b0 (--camera-r is then the proper distance l; l < 0 is the other "
                           "side, whose sky is drawn differently: green-violet checker, orange stars)", "1",
     &MetricSpec::throat},
};

/// Every named metric (grtrace-render offers them all).
inline std::vector<std::string> all_metric_names() { return {std::begin(kMetricNames), std::end(kMetricNames)}; }

/// Declares --metric (help: `metric_help`, which lists the tool's metrics), --mass, and the parameter option of
/// each offered metric that has one.
inline void declare_metric_options(CommandLine& cli, const std::vector<std::string>& offered,
                                   const std::string& metric_help) {
  cli.option("metric", "schwarzschild", metric_help).option("mass", "1", "black-hole mass M (G = c = 1)");
  for (const MetricParameterOption& p : kMetricParameterOptions)
    if (std::find(offered.begin(), offered.end(), p.metric) != offered.end())
      cli.option(p.option, p.default_value, p.help);
}

/// The metric of the options: --metric one of `offered` (UsageError naming them otherwise), --mass, the parameter
/// of that metric, `chart`; a parameter option of another metric given (command line or --config) is refused;
/// then check_metric_spec's refusals as UsageError. `source` gives the texts (the CommandLine, or grtrace-view's
/// frame-aware source), `cli` says what was given.
template <class Source>
MetricSpec read_metric_options(const Source& source, const CommandLine& cli, const std::vector<std::string>& offered,
                               const std::string& chart) {
  MetricSpec ms;
  ms.name = source.text("metric");
  if (std::find(offered.begin(), offered.end(), ms.name) == offered.end()) {
    std::string list;
    for (std::size_t i = 0; i < offered.size(); ++i)
      list += (i == 0 ? "" : i + 1 == offered.size() ? " or " : ", ") + offered[i];
    throw UsageError("--metric must be " + list + ", got '" + ms.name + "'");
  }
  ms.mass = source.number("mass");
  ms.chart = chart;
  for (const MetricParameterOption& p : kMetricParameterOptions) {
    if (std::find(offered.begin(), offered.end(), p.metric) == offered.end()) continue;
    const std::string needs = std::string("--metric ") + p.metric;
    refuse_inapplicable_options(cli, {{p.option, ms.name == p.metric, needs.c_str()}});
    if (ms.name == p.metric) ms.*p.field = source.number(p.option);
  }
  try {
    check_metric_spec(ms);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return ms;
}

}  // namespace grtrace::tools
