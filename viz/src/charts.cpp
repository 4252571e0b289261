// Line charts with vtkChartXY (see grtrace/viz/charts.hpp).
#include "grtrace/viz/charts.hpp"

#include "grtrace/viz/viewer_window.hpp"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace grtrace::viz {

namespace {

void style_axis(vtkAxis* axis, const std::string& title) {
  axis->SetTitle(title);
  axis->GetTitleProperties()->SetFontSize(17);
  axis->GetTitleProperties()->BoldOff();
  axis->GetLabelProperties()->SetFontSize(14);
  axis->GetGridPen()->SetColor(215, 215, 215, 255);
}

}  // namespace

namespace {

/// Builds the chart into `view` (sized width x height).
void build_chart(vtkContextView* view, vtkChartXY* chart, vtkTextActor* title, vtkTextActor* note,
                 const ChartSpec& spec, int width, int height) {
  if (width < 100 || height < 100) throw std::invalid_argument("chart size must be at least 100 x 100");
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  view->GetRenderWindow()->SetSize(width, height);

  view->GetScene()->AddItem(chart);
  // Title and note as text actors, so the note sits under the title whatever the layout.
  auto place_text = [&](vtkTextActor* actor, const std::string& text, int size, double gray, bool bold, double y) {
    actor->SetInput(text.c_str());
    actor->GetTextProperty()->SetFontSize(size);
    actor->GetTextProperty()->SetColor(gray, gray, gray);
    actor->GetTextProperty()->SetBold(bold);
    actor->GetTextProperty()->SetJustificationToCentered();
    actor->GetTextProperty()->SetVerticalJustificationToTop();
    actor->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    actor->GetPositionCoordinate()->SetValue(0.5 * width, y);
    view->GetRenderer()->AddActor2D(actor);
  };
  place_text(title, spec.title, 21, 0.0, true, height - 14.0);
  if (!spec.note.empty()) place_text(note, spec.note, 14, 0.3, false, height - 44.0);
  chart->SetShowLegend(spec.legend);
  if (spec.legend) {
    chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
    chart->GetLegend()->SetVerticalAlignment(spec.legend_at_bottom ? vtkChartLegend::BOTTOM : vtkChartLegend::TOP);
    chart->GetLegend()->SetLabelSize(14);
  }

  for (const auto& s : spec.series) {
    if (s.x.size() != s.y.size()) throw std::invalid_argument("chart series '" + s.name + "': x and y differ in length");
    vtkNew<vtkTable> table;
    vtkNew<vtkDoubleArray> xs, ys;
    xs->SetName("x");
    ys->SetName(s.name.empty() ? "y" : s.name.c_str());
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      if (spec.log_y && !(s.y[i] > 0.0)) continue;
      xs->InsertNextValue(s.x[i]);
      ys->InsertNextValue(s.y[i]);
    }
    table->AddColumn(xs);
    table->AddColumn(ys);
    vtkPlot* plot = chart->AddPlot(s.points ? vtkChart::POINTS : vtkChart::LINE);
    plot->SetInputData(table, 0, 1);
    plot->SetColor(s.color[0], s.color[1], s.color[2], 255);
    plot->SetWidth(s.width);
    plot->SetLabel(s.name);
    if (auto* pts = vtkPlotPoints::SafeDownCast(plot)) {
      if (s.points) {
        pts->SetMarkerStyle(vtkPlotPoints::CIRCLE);
        pts->SetMarkerSize(s.width);
      } else {
        pts->SetMarkerStyle(vtkPlotPoints::NONE);
      }
    }
  }

  vtkAxis* left = chart->GetAxis(vtkAxis::LEFT);
  vtkAxis* bottom = chart->GetAxis(vtkAxis::BOTTOM);
  style_axis(left, spec.y_title);
  style_axis(bottom, spec.x_title);
  if (spec.log_y) {
    // vtkAxis' automatic range misses data on log axes: fix it to the data, with a margin.
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const auto& s : spec.series)
      for (double v : s.y)
        if (v > 0.0 && std::isfinite(v)) {
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
    left->SetLogScale(true);
    if (hi > 0.0 && !spec.y_range) {
      left->SetBehavior(vtkAxis::FIXED);
      left->SetUnscaledRange(lo / 1.6, hi * 1.6);
    }
  }
  if (spec.x_range) {
    bottom->SetBehavior(vtkAxis::FIXED);
    bottom->SetRange((*spec.x_range)[0], (*spec.x_range)[1]);
  }
  if (spec.y_range) {
    left->SetBehavior(vtkAxis::FIXED);
    left->SetUnscaledRange((*spec.y_range)[0], (*spec.y_range)[1]);
  }
  const int top_margin = spec.note.empty() ? 62 : 86;
  if (spec.equal_aspect) {
    // Square plot area on the left, the legend outside it on the right (it would hide part of the curve).
    const int side = std::min(width - 150, height - top_margin - 75);
    chart->SetLayoutStrategy(vtkChart::AXES_TO_RECT);
    chart->SetSize(vtkRectf(static_cast<float>((width - side) / 2 + 25), 70.0f, static_cast<float>(side),
                            static_cast<float>(side)));
  } else {
    chart->SetLayoutStrategy(vtkChart::AXES_TO_RECT);
    chart->SetSize(vtkRectf(100.0f, 70.0f, static_cast<float>(width - 140), static_cast<float>(height - top_margin - 70)));
  }

}

}  // namespace

Rgb8Image render_chart(const ChartSpec& spec, int width, int height) {
  vtkNew<vtkContextView> view;
  vtkNew<vtkChartXY> chart;
  vtkNew<vtkTextActor> title, note;
  vtkRenderWindow* window = view->GetRenderWindow();
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  prepare_window(window);
  build_chart(view, chart, title, note, spec, width, height);
  window->Render();
  Rgb8Image out = capture_window(window);
  window->Finalize();
  return out;
}

void save_chart_png(const ChartSpec& spec, int width, int height, const std::string& path) {
  write_png(render_chart(spec, width, height), path);
}

void show_chart(const ChartSpec& spec, int width, int height) {
  vtkNew<vtkContextView> view;
  vtkNew<vtkChartXY> chart;
  vtkNew<vtkTextActor> title, note;
  prepare_window(view->GetRenderWindow());
  build_chart(view, chart, title, note, spec, width, height);
  view->GetRenderWindow()->SetWindowName(spec.title.c_str());
  view->GetRenderWindow()->Render();
  view->GetInteractor()->Initialize();
  view->GetInteractor()->Start();
}

ChartSpec orbit_chart(const TracedPath& path, double mass, const std::string& note) {
  ChartSpec spec;
  spec.title = "Timelike orbit in the equatorial plane";
  spec.note = note;
  spec.x_title = "x / M";
  spec.y_title = "y / M";
  spec.equal_aspect = true;
  spec.legend = true;
  spec.legend_at_bottom = true;  // a precessing orbit from phi = 0 leaves that corner free longest
  ChartSeries orbit{"orbit", {}, {}, {31, 119, 180}, 1.5f, false};
  double extent = 6.0 * mass;
  for (const auto& s : path.samples) {
    orbit.x.push_back(s.position[0]);
    orbit.y.push_back(s.position[1]);
    extent = std::max({extent, std::abs(s.position[0]), std::abs(s.position[1])});
  }
  spec.series.push_back(orbit);
  auto circle = [&](const std::string& name, double r, Rgb8 c) {
    ChartSeries s{name, {}, {}, c, 2.0f, false};
    for (int i = 0; i <= 180; ++i) {
      const double a = 2.0 * std::numbers::pi * i / 180.0;
      s.x.push_back(r * std::cos(a));
      s.y.push_back(r * std::sin(a));
    }
    return s;
  };
  spec.series.push_back(circle("horizon r = 2M", 2.0 * mass, {0, 0, 0}));
  spec.series.push_back(circle("ISCO r = 6M", 6.0 * mass, {255, 127, 14}));
  if (!path.samples.empty()) {
    const Vec3& p0 = path.samples.front().position;
    spec.series.push_back({"start", {p0[0]}, {p0[1]}, {214, 39, 40}, 8.0f, true});
  }
  const double r = 1.08 * extent;
  spec.x_range = std::array<double, 2>{-r, r};
  spec.y_range = std::array<double, 2>{-r, r};
  return spec;
}

ChartSpec norm_chart(const TracedPath& path, const std::string& note) {
  ChartSpec spec;
  spec.title = "4-velocity norm drift";
  spec.note = note;
  spec.x_title = "step";
  spec.y_title = "g(u, u) - 1";
  ChartSeries s{"g(u,u) - 1", {}, {}, {31, 119, 180}, 2.0f, false};
  for (std::size_t i = 0; i < path.steps.size(); ++i) {
    if (path.steps[i].located) continue;  // an interpolated end point, not an integration step
    s.x.push_back(static_cast<double>(i));
    s.y.push_back(path.steps[i].norm - 1.0);
  }
  spec.series.push_back(s);
  return spec;
}

ChartSpec step_chart(const TracedPath& path, const std::string& note) {
  ChartSpec spec;
  spec.title = "Step size";
  spec.note = note;
  spec.x_title = "step";
  spec.y_title = "accepted step size h (proper time)";
  spec.log_y = true;
  ChartSeries s{"h", {}, {}, {44, 160, 44}, 2.0f, false};
  for (std::size_t i = 1; i < path.steps.size(); ++i) {
    if (path.steps[i].located) continue;
    s.x.push_back(static_cast<double>(i));
    s.y.push_back(path.steps[i].h);
  }
  spec.series.push_back(s);
  return spec;
}

}  // namespace grtrace::viz
