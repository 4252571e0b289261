// grtrace/viz/charts.hpp
// Line charts with VTK's chart classes (vtkChartXY in a vtkContextView), rendered offscreen to PNG, and the
// seed report's three charts of a timelike orbit (Figs. 1-3):
//   orbit_chart  the orbit in the x-y plane (equal axis scales, the hole and the ISCO marked)
//   norm_chart   g(u, u) - 1 of the 4-velocity against the step number (the drift of the constraint)
//   step_chart   the accepted step size against the step number (log scale)
// Rendering needs an X display (run under xvfb-run when headless).
#pragma once

#include "grtrace/viz/frame_image.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace grtrace::viz {

struct ChartSeries {
  std::string name;
  std::vector<double> x, y;
  Rgb8 color{31, 119, 180};
  float width = 2.0f;
  bool points = false;  ///< markers instead of a line
};

struct ChartSpec {
  std::string title, x_title, y_title;
  std::vector<ChartSeries> series;
  bool log_y = false;
  bool equal_aspect = false;  ///< same scale on both axes (the plot area is made square, ranges symmetric)
  std::optional<std::array<double, 2>> x_range, y_range;
  bool legend = false;
  bool legend_at_bottom = false;  ///< legend in the bottom-right corner instead of the top-right
  std::string note;           ///< a line of text under the title (method, tolerance ...)
};

/// Renders the chart offscreen at width x height and returns the pixels.
Rgb8Image render_chart(const ChartSpec& spec, int width, int height);
/// Renders and writes a PNG (whole or not at all).
void save_chart_png(const ChartSpec& spec, int width, int height, const std::string& path);
/// Opens an interactive chart window (pan, zoom) and returns when it is closed.
void show_chart(const ChartSpec& spec, int width, int height);

/// Charts of a traced timelike path (uses its steps; the orbit chart uses the dense samples for a smooth curve).
/// `mass` places the horizon and ISCO marks; `note` is shown under the title.
ChartSpec orbit_chart(const TracedPath& path, double mass, const std::string& note = "");
ChartSpec norm_chart(const TracedPath& path, const std::string& note = "");
ChartSpec step_chart(const TracedPath& path, const std::string& note = "");

}  // namespace grtrace::viz
