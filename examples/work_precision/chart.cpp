// examples/work_precision/chart.cpp: VTK log-log line charts (see chart.hpp).
#include "chart.hpp"

#include "grtrace/render/output_file.hpp"
#include "grtrace/viz/viewer_window.hpp"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace grtrace::work_precision {

bool charts_available() { return true; }

void require_chart_display() { viz::require_display("grtrace-work-precision", "leave out --out-png"); }

namespace {

int vtk_line_type(LineStyle s) {
  switch (s) {
    case LineStyle::solid:
      return vtkPen::SOLID_LINE;
    case LineStyle::dash:
      return vtkPen::DASH_LINE;
    case LineStyle::dot:
      return vtkPen::DOT_LINE;
    case LineStyle::dash_dot:
      return vtkPen::DASH_DOT_LINE;
  }
  return vtkPen::SOLID_LINE;
}

int marker_for(LineStyle s) {
  switch (s) {
    case LineStyle::solid:
      return vtkPlotPoints::CIRCLE;
    case LineStyle::dash:
      return vtkPlotPoints::SQUARE;
    case LineStyle::dot:
      return vtkPlotPoints::DIAMOND;
    case LineStyle::dash_dot:
      return vtkPlotPoints::CROSS;
  }
  return vtkPlotPoints::CIRCLE;
}

void style_axis(vtkAxis* axis, const std::string& title, double lo, double hi) {
  axis->SetTitle(title);
  axis->SetLogScale(true);
  axis->SetBehavior(vtkAxis::FIXED);
  axis->SetUnscaledRange(lo, hi);
  axis->SetNotation(vtkAxis::SCIENTIFIC_NOTATION);
  axis->SetPrecision(0);
  axis->GetTitleProperties()->SetFontSize(18);
  axis->GetLabelProperties()->SetFontSize(14);
  axis->SetGridVisible(true);
}

/// Decade-aligned range covering [lo, hi].
std::pair<double, double> decades(double lo, double hi) {
  if (!(lo > 0.0) || !(hi >= lo)) return {1e-1, 1e1};
  double a = std::pow(10.0, std::floor(std::log10(lo)));
  double b = std::pow(10.0, std::ceil(std::log10(hi)));
  if (b <= a) b = a * 10.0;
  return {a, b};
}

}  // namespace

void write_loglog_chart(OutputSet& set, const std::string& png, const ChartSpec& spec, const std::vector<ChartSeries>& series) {
  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(spec.width, spec.height);
  viz::prepare_window(view->GetRenderWindow());  // the shared X connection; no interactor offscreen
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);

  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetTitle(spec.title);
  chart->GetTitleProperties()->SetFontSize(20);
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  chart->GetLegend()->GetLabelProperties()->SetFontSize(series.size() > 24 ? 11 : 14);
  chart->GetLegend()->SetInline(false);

  double x_lo = std::numeric_limits<double>::infinity(), x_hi = 0.0;
  double y_lo = std::numeric_limits<double>::infinity(), y_hi = 0.0;
  std::vector<vtkSmartPointer<vtkTable>> tables;
  for (const ChartSeries& s : series) {
    vtkNew<vtkDoubleArray> xs, ys;
    xs->SetName((s.label + " x").c_str());
    ys->SetName(s.label.c_str());
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      const double x = s.x[i], y = std::max(s.y[i], spec.y_floor);
      if (!(x > 0.0) || !std::isfinite(x) || !std::isfinite(y)) continue;
      xs->InsertNextValue(x);
      ys->InsertNextValue(y);
      x_lo = std::min(x_lo, x);
      x_hi = std::max(x_hi, x);
      y_lo = std::min(y_lo, y);
      y_hi = std::max(y_hi, y);
    }
    if (xs->GetNumberOfTuples() == 0) continue;
    auto table = vtkSmartPointer<vtkTable>::New();
    table->AddColumn(xs);
    table->AddColumn(ys);
    tables.push_back(table);
    vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
    plot->SetInputData(table, 0, 1);
    plot->SetColor(s.rgb[0], s.rgb[1], s.rgb[2], 255);
    plot->SetWidth(2.0f);
    plot->GetPen()->SetLineType(vtk_line_type(s.style));
    plot->SetLabel(s.label);
    if (auto* points = vtkPlotPoints::SafeDownCast(plot)) {
      points->SetMarkerStyle(marker_for(s.style));
      points->SetMarkerSize(7.0f);
    }
  }
  if (tables.empty()) throw std::runtime_error("chart '" + png + "': no positive data to draw");

  const auto [xa, xb] = decades(x_lo, x_hi);
  const auto [ya, yb] = decades(y_lo, y_hi);
  style_axis(chart->GetAxis(vtkAxis::BOTTOM), spec.x_label, xa, xb);
  style_axis(chart->GetAxis(vtkAxis::LEFT), spec.y_label, ya, yb);

  view->GetRenderWindow()->Render();
  viz::save_window_png(set, view->GetRenderWindow(), png);  // RGB grab (an RGBA one is transparent)
}

}  // namespace grtrace::work_precision
