// grtrace-stability: linear stability of every shipped Butcher tableau (contract in shared/DESIGN.md).
//
//   grtrace-stability --json      ONE line of JSON on stdout: {"euler":[-2,0],"rk4":[-2.78529356341,0],...},
//                                 each tableau's real stability interval [x_min, 0]; needs no display.
//   grtrace-stability             the same line, and one PNG per tableau of its stability region boundary
//                                 |R(z)| = 1 in the complex plane (axes Re z, Im z) plus overview.png with all
//                                 boundaries, in --out-dir. Draws with VTK charts offscreen, which on Debian's
//                                 VTK needs an X display: run under  xvfb-run -a -s "-screen 0 1280x1024x24".
// R(z) = 1 + z b^T (I - zA)^-1 1 and the contour come from grtrace/tableau/stability.hpp (Hairer & Wanner II, IV.2).
#include "command_line.hpp"
#include "grtrace/viz/viewer_window.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/tableau/stability.hpp"
#include "json_writer.hpp"

#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

using namespace grtrace;
using tools::CommandLine;
using tools::JsonObject;
using tools::UsageError;

struct MethodStability {
  std::string name;
  int order = 0;
  std::size_t stages = 0;
  RealInterval interval{};
  ComplexBox box{};
  std::vector<ComplexPolyline> curves;
  std::vector<std::complex<double>> r_samples;  ///< R at a few fixed points, to spot methods with equal R

  bool same_r(const std::vector<std::complex<double>>& other) const {
    if (other.size() != r_samples.size()) return false;
    for (std::size_t i = 0; i < other.size(); ++i)
      if (std::abs(other[i] - r_samples[i]) > 1e-12 * (1.0 + std::abs(other[i]))) return false;
    return true;
  }
};

/// Plot box: the bounding box of the contour found in a generous search box, padded by 8 %.
template <class T>
ComplexBox fitted_box() {
  const ComplexBox search{-8.0, 3.0, -8.0, 8.0};
  double re_lo = 0.0, re_hi = 0.0, im_hi = 0.0;
  for (const auto& curve : stability_boundary<T>(search, {.nx = 221, .ny = 321, .refine_iterations = 30}))
    for (const auto& z : curve) {
      re_lo = std::min(re_lo, z.real());
      re_hi = std::max(re_hi, z.real());
      im_hi = std::max(im_hi, std::abs(z.imag()));
    }
  const double pad = 0.08 * std::max(re_hi - re_lo, 2.0 * im_hi);
  return {re_lo - pad, std::max(re_hi, 0.0) + pad, -im_hi - pad, im_hi + pad};
}

template <class T>
MethodStability analyse(int grid) {
  MethodStability m;
  m.name = std::string(T::name);
  m.order = T::order;
  m.stages = T::stages;
  m.interval = real_stability_interval<T>();
  m.box = fitted_box<T>();
  m.curves = stability_boundary<T>(m.box, {.nx = grid, .ny = grid, .refine_iterations = 48});
  for (const std::complex<double> z : {std::complex<double>(-1.3, 0.7), {0.4, 2.1}, {-2.9, -1.6}, {1.7, 0.3}})
    m.r_samples.push_back(stability_function<T>(z));
  return m;
}

/// Interval ends to 12 significant digits (the bisection is good to ~1e-12): -2 prints as -2.
std::string interval_number(double v) {
  if (!std::isfinite(v)) return "null";
  if (v == 0.0) return "0";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

std::string intervals_json(const std::vector<MethodStability>& methods) {
  std::string json = "{";
  for (const auto& m : methods) {
    if (json.size() > 1) json += ",";
    json += JsonObject::quote(m.name) + ":[" + interval_number(m.interval.lower) + "," +
            interval_number(m.interval.upper) + "]";
  }
  return json + "}";
}

// ---- drawing ----------------------------------------------------------------------------------------------

using Rgb = std::array<unsigned char, 3>;

/// 12 distinguishable colours (Tableau-20 dark shades, then a few more).
constexpr std::array<Rgb, 12> kPalette = {{{31, 119, 180},
                                           {255, 127, 14},
                                           {44, 160, 44},
                                           {214, 39, 40},
                                           {148, 103, 189},
                                           {140, 86, 75},
                                           {227, 119, 194},
                                           {127, 127, 127},
                                           {188, 189, 34},
                                           {23, 190, 207},
                                           {0, 0, 0},
                                           {128, 0, 64}}};

struct Series {
  std::string label;
  std::vector<double> x, y;
  Rgb color{0, 0, 0};
  float width = 2.0f;
  bool in_legend = true;
  int line_type = vtkPen::SOLID_LINE;
};

void add_series(vtkChartXY* chart, const Series& s) {
  if (s.x.size() < 2) return;
  vtkNew<vtkTable> table;
  vtkNew<vtkDoubleArray> xs, ys;
  xs->SetName("Re z");
  ys->SetName(s.label.c_str());
  table->AddColumn(xs);
  table->AddColumn(ys);
  table->SetNumberOfRows(static_cast<vtkIdType>(s.x.size()));
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    table->SetValue(static_cast<vtkIdType>(i), 0, s.x[i]);
    table->SetValue(static_cast<vtkIdType>(i), 1, s.y[i]);
  }
  vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
  plot->SetInputData(table, 0, 1);
  plot->SetColor(s.color[0], s.color[1], s.color[2], 255);
  plot->SetWidth(s.width);
  plot->GetPen()->SetLineType(s.line_type);
  plot->SetLegendVisibility(s.in_legend);
}

/// Draws the series in a vtkChartXY offscreen and writes an RGB PNG atomically (temporary name, then rename).
void write_chart_png(OutputSet& set, const std::filesystem::path& file, const std::string& title, const std::vector<Series>& series,
                     const ComplexBox& box, int width) {
  // Roughly equal scales on both axes: plot area ~ width - 130 px wide, margins ~ 120 px vertically.
  const double plot_w = width - 130.0;
  const int height =
      static_cast<int>(std::lround(plot_w * (box.im_max - box.im_min) / (box.re_max - box.re_min) + 120.0));

  vtkNew<vtkContextView> view;
  view->GetRenderWindow()->SetOffScreenRendering(1);
  view->GetRenderWindow()->SetSize(width, height);
  viz::prepare_window(view->GetRenderWindow());  // the shared X connection; no interactor offscreen
  view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  vtkNew<vtkChartXY> chart;
  view->GetScene()->AddItem(chart);
  chart->SetTitle(title);
  chart->GetTitleProperties()->SetFontSize(16);
  vtkAxis* bottom = chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* left = chart->GetAxis(vtkAxis::LEFT);
  bottom->SetTitle("Re z");
  left->SetTitle("Im z");
  bottom->SetRange(box.re_min, box.re_max);
  left->SetRange(box.im_min, box.im_max);
  bottom->SetBehavior(vtkAxis::FIXED);
  left->SetBehavior(vtkAxis::FIXED);
  for (vtkAxis* axis : {bottom, left}) {
    axis->GetTitleProperties()->SetFontSize(15);
    axis->GetLabelProperties()->SetFontSize(13);
  }

  // Coordinate axes Re z = 0 and Im z = 0, thin grey, not in the legend.
  add_series(chart, {"Im axis", {0.0, 0.0}, {box.im_min, box.im_max}, {160, 160, 160}, 1.0f, false, vtkPen::DASH_LINE});
  add_series(chart, {"Re axis", {box.re_min, box.re_max}, {0.0, 0.0}, {160, 160, 160}, 1.0f, false, vtkPen::DASH_LINE});
  for (const auto& s : series) add_series(chart, s);
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::LEFT);
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  chart->GetLegend()->GetLabelProperties()->SetFontSize(13);

  view->GetRenderWindow()->Render();
  viz::save_window_png(set, view->GetRenderWindow(), file.string());
}

std::vector<Series> boundary_series(const MethodStability& m, Rgb color) {
  std::vector<Series> out;
  bool first = true;
  for (const auto& curve : m.curves) {
    Series s;
    s.label = m.name;
    s.color = color;
    s.in_legend = first;
    first = false;
    for (const auto& z : curve) {
      s.x.push_back(z.real());
      s.y.push_back(z.imag());
    }
    out.push_back(std::move(s));
  }
  return out;
}

std::string interval_label(const RealInterval& r) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "x_min = %.4f", r.lower);
  return buf;
}

/// The name of an earlier method with the same stability function (e.g. rk38 and rk4), or "".
std::string same_function_as(const std::vector<MethodStability>& methods, std::size_t i) {
  for (std::size_t j = 0; j < i; ++j)
    if (methods[j].same_r(methods[i].r_samples)) return methods[j].name;
  return {};
}

/// Every PNG is written to its temporary first and all are renamed together at the end: all new or all old.
void write_pngs(const std::vector<MethodStability>& methods, const std::filesystem::path& dir, int width) {
  OutputSet set;
  std::vector<std::string> written;
  ComplexBox all{0.0, 0.0, 0.0, 0.0};
  std::vector<Series> overview;
  for (std::size_t i = 0; i < methods.size(); ++i) {
    const MethodStability& m = methods[i];
    const Rgb color = kPalette[i % kPalette.size()];
    std::vector<Series> series = boundary_series(m, kPalette[0]);
    for (auto& s : series) s.label = m.name + " |R(z)| = 1";
    // The real stability interval, drawn on the real axis.
    series.push_back({"real stability interval, " + interval_label(m.interval),
                      {m.interval.lower, 0.0},
                      {0.0, 0.0},
                      {214, 39, 40},
                      4.0f,
                      true,
                      vtkPen::SOLID_LINE});
    const std::string twin = same_function_as(methods, i);
    const std::string title = m.name + " (order " + std::to_string(m.order) + ", " + std::to_string(m.stages) +
                              " stages): stability region |R(z)| <= 1, " + interval_label(m.interval) +
                              (twin.empty() ? "" : " (same R as " + twin + ")");
    const auto file = dir / (m.name + ".png");
    write_chart_png(set, file, title, series, m.box, 900);
    written.push_back(file.string());

    all.re_min = std::min(all.re_min, m.box.re_min);
    all.re_max = std::max(all.re_max, m.box.re_max);
    all.im_min = std::min(all.im_min, m.box.im_min);
    all.im_max = std::max(all.im_max, m.box.im_max);
    for (auto& s : boundary_series(m, color)) {
      if (!twin.empty()) s.label += " (= " + twin + ")";
      overview.push_back(std::move(s));
    }
  }
  const auto file = dir / "overview.png";
  write_chart_png(set, file, "Stability region boundaries |R(z)| = 1 of all tableaux", overview, all, width);
  written.push_back(file.string());
  set.commit();
  for (const auto& w : written) std::cerr << "wrote " << w << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  CommandLine cli("grtrace-stability",
                  "Linear stability of every Runge-Kutta tableau: prints ONE line of JSON with each real stability\n"
                  "interval [x_min, 0]; without --json also draws each stability region boundary |R(z)| = 1 as a\n"
                  "PNG (needs an X display for VTK: run under xvfb-run -a -s \"-screen 0 1280x1024x24\").");
  cli.flag("json", "print the intervals only (no PNGs, no display needed)")
      .option("out-dir", "stability", "directory for <tableau>.png and overview.png (created if missing)")
      .option("grid", "321", "marching-squares grid points per axis for each boundary (21 .. 2001)")
      .option("size", "1000", "width in pixels of overview.png (400 .. 4000); per-tableau PNGs are 900 wide");
  return tools::run_tool(cli, argc, argv, [&] {
    const bool json_only = cli.flag_set("json");
    const long grid = cli.integer("grid");
    if (grid < 21 || grid > 2001) throw UsageError("--grid must be in 21 .. 2001, got " + cli.text("grid"));
    const long size = cli.integer("size");
    if (size < 400 || size > 4000) throw UsageError("--size must be in 400 .. 4000, got " + cli.text("size"));
    const std::filesystem::path dir = cli.text("out-dir");
    if (dir.empty()) throw UsageError("--out-dir must not be empty");
    if (cli.write_config_if_asked()) return 0;
    if (!json_only) {
      std::error_code ec;
      if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
        throw UsageError("--out-dir '" + dir.string() + "' exists and is not a directory");
      if (!std::filesystem::exists(dir, ec)) {
        std::filesystem::path existing = std::filesystem::absolute(dir, ec);
        while (!existing.empty() && existing != existing.root_path() && !std::filesystem::exists(existing, ec))
          existing = existing.parent_path();
        if (!std::filesystem::is_directory(existing, ec))
          throw UsageError("--out-dir '" + dir.string() + "': '" + existing.string() + "' is not a directory");
        if (::access(existing.c_str(), W_OK | X_OK) != 0)
          throw UsageError("--out-dir '" + dir.string() + "': cannot create it, '" + existing.string() +
                           "' is not writable");
      }
      try {
        viz::require_display("grtrace-stability", "use --json for the intervals only");
      } catch (const viz::NoDisplayError& e) {
        throw UsageError(std::string("drawing the PNGs: ") + e.what());
      }
      if (!std::filesystem::exists(dir, ec)) {
        std::filesystem::create_directories(dir, ec);
        if (ec) throw UsageError("--out-dir: cannot create '" + dir.string() + "': " + ec.message());
      }
      for_each_tableau([&](auto tag) {
        tools::check_command_output(cli, "out-dir", dir / (std::string(decltype(tag)::type::name) + ".png"), {});
      });
      tools::check_command_output(cli, "out-dir", dir / "overview.png", {});
    }

    std::vector<MethodStability> methods;
    for_each_tableau([&](auto tag) {
      using T = typename decltype(tag)::type;
      if (json_only) {
        MethodStability m;
        m.name = std::string(T::name);
        m.interval = real_stability_interval<T>();
        methods.push_back(std::move(m));
      } else {
        methods.push_back(analyse<T>(static_cast<int>(grid)));
      }
    });
    if (!json_only) write_pngs(methods, dir, static_cast<int>(size));
    std::cout << intervals_json(methods) << std::endl;
    return 0;
  });
}
