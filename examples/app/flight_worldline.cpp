// The flights' paths for every named metric (see grtrace/app/flight_worldline.hpp).
#include "grtrace/app/flight_worldline.hpp"

namespace grtrace::app {

Worldline flight_worldline(const MetricSpec& metric, const FlightPathSpec& spec) {
  return with_named_metric(metric, [&](const auto& m) { return flight_path(m, spec); });
}

}  // namespace grtrace::app
