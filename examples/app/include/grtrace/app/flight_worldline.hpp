// grtrace/app/flight_worldline.hpp
// A camera flight's path in a named metric, compiled once: grtrace-render renders the flight and grtrace-view draws
// it and looks through one of its frames; both ask here, so the path's integration (sample_worldline and the
// proper-time searches of observer/flight_path.hpp, with their integrator steps) is instantiated for each named
// metric in one unit of the application layer instead of once per tool.
//
// Takes:   a metric spec (metric/named_metrics.hpp; Kerr-Schild flights use the ingoing slicing) and a flight spec
//          (observer/flight_path.hpp).
// Returns: flight_path(metric, spec) in the spec's metric, the same samples bit for bit.
// Throws:  std::invalid_argument with flight_path's words (a path the metric or its chart cannot fly, a csv file
//          that cannot be read); the tools prefix it with the option (tools::checked_flight_path).
#pragma once

#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/flight_path.hpp"
#include "grtrace/observer/worldline.hpp"

namespace grtrace::app {

Worldline flight_worldline(const MetricSpec& metric, const FlightPathSpec& spec);

}  // namespace grtrace::app
