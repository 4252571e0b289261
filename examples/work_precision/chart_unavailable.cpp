// examples/work_precision/chart_unavailable.cpp: stand-in for chart.cpp when VTK was not found.
#include "chart.hpp"

#include <stdexcept>

namespace grtrace::work_precision {

bool charts_available() { return false; }

void require_chart_display() {}

void write_loglog_chart(OutputSet&, const std::string& png, const ChartSpec&, const std::vector<ChartSeries>&) {
  throw std::runtime_error("cannot draw '" + png + "': this build has no VTK (configure with VTK to get charts)");
}

}  // namespace grtrace::work_precision
