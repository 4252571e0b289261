// grtrace/trace/critical_angle_grid.hpp
// Where the table tracers (symmetric_sky_table.hpp, planar_path_table.hpp) put their table rays on one side of the
// critical angle delta_c, and how a pixel's angle is read from them.
//
// Why this spacing: near delta_c (impact parameter b = b_c) a ray winds around the photon sphere and what it does
// diverges like -ln g, g = |delta - delta_c|; far from it, it is a smooth function of delta. So the nodes are
// uniform in s = ln g + g / kappa over the range of gaps [g_min, g_max] a frame needs: logarithmic spacing close
// to delta_c, even spacing in delta far from it (kappa = g_max / ln(g_max / g_min) puts about half of the nodes in
// each regime). A value at g is the six-point Lagrange (quintic) interpolant in s of the nodes around it.
//
// Why six points: the interpolation across delta, not the integration of the table rays, set the accuracy of a
// table-read frame. With four points (cubic, error ~ ds^4) the seed's main frame needed 2048 rays per side for
// 1.8e-9 rad at its worst pixel (1024: 3.1e-8, 512: 5.0e-7); with six (error ~ ds^6) 512 rays give 2.7e-9 and 1024
// give 4.5e-10, the error of the rays themselves (2048 give the same), for two more products per weight
// (docs/benchmarks.md, "Six-point interpolation across the table"). Hence default_table_rays = 1024.
#pragma once

#include "grtrace/core/rounding.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace grtrace {

/// Table rays on each side of the critical angle where the caller names no number (the planar and symmetric
/// tracers, grtrace-render's --table-rays, grtrace-view): see the top of this file for why 1024.
inline constexpr int default_table_rays = 1024;

struct CriticalAngleGrid {
  /// Nodes a value is interpolated from (fewer only for a one-node grid).
  static constexpr int stencil_size = 6;

  double s0 = 0.0, ds = 1.0;  ///< node i sits at s = s0 + i ds
  double kappa = 1.0;         ///< s(g) = ln g + g / kappa
  int nodes = 0;
  // 1 / kappa and 1 / ds: a pixel's look-up multiplies instead of dividing (two divisions off its critical path).
  double inverse_kappa = 1.0, inverse_ds = 1.0;

  /// The six (or, for a one-node grid, one) nodes around a gap and their Lagrange weights.
  struct Stencil {
    int first = 0, count = 0;  ///< nodes first .. first + count - 1
    int nearest = 0;           ///< the node closest to the gap (for per-node counts such as steps)
    std::array<double, stencil_size> weight{};
  };

  /// `nodes` nodes covering gaps [gap_min, gap_max] (one node when the range is a point).
  CriticalAngleGrid(double gap_min, double gap_max, int requested_nodes) {
    nodes = gap_max > gap_min * (1.0 + 1e-12) ? std::max(requested_nodes, stencil_size) : 1;
    kappa = gap_max / std::max(1.0, std::log(gap_max / gap_min));
    inverse_kappa = 1.0 / kappa;
    s0 = coordinate(gap_min);
    ds = nodes > 1 ? (coordinate(gap_max) - s0) / (nodes - 1) : 1.0;
    inverse_ds = 1.0 / ds;
  }
  CriticalAngleGrid() = default;

  double coordinate(double gap) const { return std::log(gap) + gap * inverse_kappa; }

  /// The gap of node i: the inverse of coordinate(), by Newton in x = ln g on x + e^x / kappa = s (increasing
  /// and convex in x, so Newton from below converges monotonically).
  double gap_of_node(int i) const {
    const double s = s0 + i * ds;
    double x = std::min(s, std::log(kappa * std::max(s, 1.0)));
    for (int it = 0; it < 60; ++it) {
      const double e = std::exp(x) * inverse_kappa, dx = (x + e - s) / (1.0 + e);
      x -= dx;
      if (std::abs(dx) < 1e-15 * (1.0 + std::abs(x))) break;
    }
    return std::exp(x);
  }

  /// Nodes and weights for the value at `gap` (clamped to the covered range).
  Stencil stencil(double gap) const {
    Stencil st;
    if (nodes <= 1) {
      st.count = nodes;
      st.weight[0] = 1.0;
      return st;
    }
    const double x =
        std::clamp((coordinate(std::max(gap, 1e-300)) - s0) * inverse_ds, 0.0, static_cast<double>(nodes - 1));
    st.count = stencil_size;  // nodes >= stencil_size (constructor)
    st.first = std::clamp(static_cast<int>(floor_to_long(x)) - (stencil_size / 2 - 1), 0, nodes - stencil_size);
    st.nearest = std::clamp(static_cast<int>(round_nonnegative_to_long(x)), 0, nodes - 1);
    // Lagrange weights on the equispaced nodes 0..5 at t: w_j = prod_{l != j} (t - l) / prod_{l != j} (j - l), the
    // numerator as (product of the factors before j) (product of those after j), the denominators
    // (-1)^(5 - j) j! (5 - j)! = -120, 24, -12, 12, -24, 120 applied as their reciprocals (multiplications off the
    // pixel's critical path; one rounding more, far below the interpolation's error).
    const double t = x - st.first;
    std::array<double, stencil_size> d{}, before{}, after{};
    for (int l = 0; l < stencil_size; ++l) d[static_cast<std::size_t>(l)] = t - l;
    before[0] = 1.0;
    after[stencil_size - 1] = 1.0;
    for (std::size_t l = 1; l < stencil_size; ++l) before[l] = before[l - 1] * d[l - 1];
    for (std::size_t l = stencil_size - 1; l > 0; --l) after[l - 1] = after[l] * d[l];
    constexpr std::array<double, stencil_size> inverse_denominator{-1.0 / 120.0, 1.0 / 24.0, -1.0 / 12.0,
                                                                   1.0 / 12.0,   -1.0 / 24.0, 1.0 / 120.0};
    for (std::size_t j = 0; j < stencil_size; ++j) st.weight[j] = before[j] * after[j] * inverse_denominator[j];
    return st;
  }
};

}  // namespace grtrace
