// examples/work_precision/chart.hpp
// Log-log line charts for grtrace-work-precision, drawn with VTK's charts (vtkChartXY) into a PNG.
// Implemented in chart.cpp (the only VTK translation unit of the tool); built only when VTK is found.
// VTK on Debian renders through X only: run the tool under `xvfb-run -a -s "-screen 0 1280x1024x24"` when
// there is no display (the tool asks for an X server, require_chart_display(), before any work starts).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace grtrace {
class OutputSet;
}

namespace grtrace::work_precision {

enum class LineStyle { solid, dash, dot, dash_dot };

struct ChartSeries {
  std::string label;
  std::vector<double> x, y;  ///< positive values (log axes); others are dropped
  std::array<unsigned char, 3> rgb{0, 0, 0};
  LineStyle style = LineStyle::solid;
};

struct ChartSpec {
  std::string title, x_label, y_label;
  int width = 1400;
  int height = 1000;
  double y_floor = 1e-17;  ///< errors below this (e.g. exactly 0) are drawn at it
};

/// True when this build can draw charts (VTK was found at configure time).
bool charts_available();

/// Throws (viz::NoDisplayError, a std::runtime_error) when no X server answers: call before any work.
void require_chart_display();

/// Writes the chart to `png` into a set of outputs (renamed into place by set.commit()). Throws
/// std::runtime_error on failure.
void write_loglog_chart(OutputSet& set, const std::string& png, const ChartSpec& spec, const std::vector<ChartSeries>& series);

}  // namespace grtrace::work_precision
