// grtrace/trace/critical_angle_grid.hpp
// Where the table tracers (symmetric_sky_table.hpp, planar_path_table.hpp) put their table rays on one side of the
// critical angle delta_c, and how a pixel's angle is read from them.
//
// Why this spacing: near delta_c (impact parameter b = b_c) a ray winds around the photon sphere and what it does
// diverges like -ln g, g = |delta - delta_c|; far from it, it is a smooth function of delta. So the nodes are
// uniform in s = ln g + g / kappa over the range of gaps [g_min, g_max] a frame needs: logarithmic spacing close
// to delta_c, even spacing in delta far from it (kappa = g_max / ln(g_max / g_min) puts about half of the nodes in
// each regime). A value at g is the four-point Lagrange (cubic) interpolant in s of the nodes around it.
#pragma once

#include "grtrace/core/rounding.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace grtrace {

struct CriticalAngleGrid {
  double s0 = 0.0, ds = 1.0;  ///< node i sits at s = s0 + i ds
  double kappa = 1.0;         ///< s(g) = ln g + g / kappa
  int nodes = 0;
  // 1 / kappa and 1 / ds: a pixel's look-up multiplies instead of dividing (two divisions off its critical path).
  double inverse_kappa = 1.0, inverse_ds = 1.0;

  /// The four (or fewer) nodes around a gap and their Lagrange weights.
  struct Stencil {
    int first = 0, count = 0;  ///< nodes first .. first + count - 1
    int nearest = 0;           ///< the node closest to the gap (for per-node counts such as steps)
    std::array<double, 4> weight{};
  };

  /// `nodes` nodes covering gaps [gap_min, gap_max] (one node when the range is a point).
  CriticalAngleGrid(double gap_min, double gap_max, int requested_nodes) {
    nodes = gap_max > gap_min * (1.0 + 1e-12) ? std::max(requested_nodes, 4) : 1;
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
    st.count = std::min(4, nodes);
    st.first = std::clamp(static_cast<int>(floor_to_long(x)) - 1, 0, nodes - st.count);
    st.nearest = std::clamp(static_cast<int>(round_nonnegative_to_long(x)), 0, nodes - 1);
    if (st.count == 4) {  // the cubic's weights in closed form (denominators -6, 2, -2, 6): one per pixel
      const double t = x - st.first, t1 = t - 1.0, t2 = t - 2.0, t3 = t - 3.0;
      st.weight = {-t1 * t2 * t3 / 6.0, t * t2 * t3 / 2.0, -t * t1 * t3 / 2.0, t * t1 * t2 / 6.0};
      return st;
    }
    for (int j = 0; j < st.count; ++j) {
      double w = 1.0;
      for (int l = 0; l < st.count; ++l)
        if (l != j) w *= (x - (st.first + l)) / static_cast<double>(j - l);
      st.weight[static_cast<std::size_t>(j)] = w;
    }
    return st;
  }
};

}  // namespace grtrace
