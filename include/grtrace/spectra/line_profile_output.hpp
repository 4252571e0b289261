// grtrace/spectra/line_profile_output.hpp
// A line profile (spectra/line_profile.hpp) as a user reads it: a CSV table and a PNG plot.
//
// line_profile_csv: "# " comment lines, then energy_low, energy_high, flux, flux_n0, flux_n1, flux_n2, flux_n3_up
//   per bin (F_E: energy flux per unit energy, see line_profile.hpp), at 10 significant digits.
// line_profile_chart: a 720 x 540 8-bit RGB picture in two panels on one energy axis: above, the total (white)
//   and the first image n = 0 (orange) on a linear scale from 0 to the peak; below, every order on a logarithmic
//   scale of four decades under the peak (n = 0 orange, 1 cyan, 2 green, >= 3 red). Ticks every 0.1 of the
//   energy unit, labelled at whole units (render/scale_bar.hpp's 3 x 5 digits); a dashed line at the line's rest
//   energy.
#pragma once

#include "grtrace/render/scale_bar.hpp"
#include "grtrace/spectra/line_profile.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace grtrace {

inline std::string line_profile_csv(const LineProfile& p, const std::vector<std::string>& comments) {
  std::ostringstream csv;
  csv.precision(10);
  for (const std::string& c : comments) csv << "# " << c << "\n";
  csv << "energy_low,energy_high,flux,flux_n0,flux_n1,flux_n2,flux_n3_up\n";
  for (std::size_t b = 0; b < p.flux.size(); ++b) {
    csv << p.edges[b] << "," << p.edges[b + 1] << "," << p.flux[b];
    for (const auto& o : p.flux_by_order) csv << "," << o[b];
    csv << "\n";
  }
  return csv.str();
}

namespace line_chart_detail {

/// The plot: W x H RGB, two panels sharing the energy axis.
struct Plot {
  static constexpr int W = 720, H = 540, left = 40, right = 12, top = 12, gap = 28, bottom = 30;
  std::vector<std::uint8_t> rgb = std::vector<std::uint8_t>(3u * W * H, 24);
  double e_lo, e_hi;

  void put(int x, int y, std::array<std::uint8_t, 3> c) {
    if (x < 0 || y < 0 || x >= W || y >= H) return;
    for (std::size_t k = 0; k < 3; ++k)
      rgb[3u * (static_cast<std::size_t>(y) * W + static_cast<std::size_t>(x)) + k] = c[k];
  }
  void line(double x0, double y0, double x1, double y1, std::array<std::uint8_t, 3> c, int dash = 0) {
    const int n = static_cast<int>(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
    for (int i = 0; i <= n; ++i) {
      if (dash > 0 && (i / dash) % 2 == 1) continue;
      const double t = static_cast<double>(i) / n;
      put(static_cast<int>(std::lround(x0 + t * (x1 - x0))), static_cast<int>(std::lround(y0 + t * (y1 - y0))), c);
    }
  }
  void text(int x, int y, const std::string& s, int scale = 2) {
    for (char ch : s) {
      const auto g = scale_bar_detail::glyph(ch);
      for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 3; ++col)
          if (g[static_cast<std::size_t>(row)] & (4 >> col))
            for (int dy = 0; dy < scale; ++dy)
              for (int dx = 0; dx < scale; ++dx) put(x + col * scale + dx, y + row * scale + dy, {230, 230, 230});
      x += 4 * scale;
    }
  }
  double x_of(double e) const { return left + (e - e_lo) / (e_hi - e_lo) * (W - left - right); }

  /// One panel between rows y0 and y1: the series (bin centres, values mapped to [0, 1] by `scale`).
  template <class Scale>
  void panel(int y0, int y1, const std::vector<double>& centres, const std::vector<std::vector<double>>& series,
             const std::vector<std::array<std::uint8_t, 3>>& colours, Scale scale, double line_energy) {
    const std::array<std::uint8_t, 3> axis{160, 160, 160};
    line(left, y1, W - right, y1, axis);
    line(left, y0, left, y1, axis);
    for (double e = std::ceil(e_lo * 10.0) / 10.0; e <= e_hi + 1e-9; e += 0.1) {
      const bool whole = std::abs(e - std::round(e)) < 1e-6;
      line(x_of(e), y1, x_of(e), y1 + (whole ? 6 : 3), axis);
      if (whole && y1 + 8 + 10 < H) text(static_cast<int>(x_of(e)) - 3, y1 + 9, std::to_string(std::lround(e)));
    }
    line(x_of(line_energy), y0, x_of(line_energy), y1, {120, 120, 120}, 4);
    for (std::size_t s = 0; s < series.size(); ++s)
      for (std::size_t i = 0; i + 1 < centres.size(); ++i) {
        const double a = scale(series[s][i]), b = scale(series[s][i + 1]);
        if (!std::isfinite(a) || !std::isfinite(b)) continue;
        line(x_of(centres[i]), y1 - a * (y1 - y0), x_of(centres[i + 1]), y1 - b * (y1 - y0), colours[s]);
      }
  }
};

}  // namespace line_chart_detail

inline LineChart line_profile_chart(const LineProfile& p, double line_energy) {
  using line_chart_detail::Plot;
  Plot plot;
  plot.e_lo = p.edges.front();
  plot.e_hi = p.edges.back();
  std::vector<double> centres;
  for (std::size_t b = 0; b < p.flux.size(); ++b) centres.push_back(0.5 * (p.edges[b] + p.edges[b + 1]));
  const double peak = std::max(*std::max_element(p.flux.begin(), p.flux.end()), std::numeric_limits<double>::min());
  const int mid = Plot::top + (Plot::H - Plot::top - Plot::bottom - Plot::gap) / 2;
  plot.panel(
      Plot::top, mid, centres, {p.flux, p.flux_by_order[0]}, {{240, 240, 240}, {255, 150, 40}},
      [&](double f) { return f / peak; }, line_energy);
  plot.panel(
      mid + Plot::gap, Plot::H - Plot::bottom, centres,
      {p.flux_by_order[0], p.flux_by_order[1], p.flux_by_order[2], p.flux_by_order[3]},
      {{255, 150, 40}, {60, 200, 230}, {90, 220, 90}, {230, 70, 70}},
      [&](double f) {
        return f > 0.0 ? std::max(0.0, 1.0 + std::log10(f / peak) / 4.0) : -std::numeric_limits<double>::infinity();
      },
      line_energy);
  return {Plot::W, Plot::H, std::move(plot.rgb)};
}

}  // namespace grtrace
