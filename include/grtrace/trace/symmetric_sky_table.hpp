// grtrace/trace/symmetric_sky_table.hpp
// The reduced tracer for spherically symmetric scenes: Schwarzschild, a static sky sphere and the horizon.
//
// Why: every ray from a camera at radius r_c stays in the plane through the centre spanned by the radial
// direction n and its initial direction, and what happens to it depends only on delta, the angle between
// its direction of travel and n in the static frame at the camera. So a frame needs a one-dimensional
// function, not one integration per pixel: the angle `sweep(delta)` the ray turns through (around the
// centre, in its plane) before it reaches the sky sphere or the horizon guard. We integrate the rays of a
// table of delta values with the general tracer and interpolate; a pixel then costs a few flops.
//
// Accuracy: near the critical angle delta_c (impact parameter b = b_c = 3 sqrt(3) M) sweep diverges like
// -ln g, g = |delta - delta_c|, so each side of delta_c is tabulated uniformly in s = ln g + g / kappa over
// the range of angles the frame needs: logarithmic spacing close to delta_c, where sweep is a smooth
// function of ln g (it tends to a linear one), and even spacing in delta far from it (kappa puts about half
// the nodes in each regime). Values are read with six-point Lagrange (quintic) interpolation (trace/critical_angle_grid.hpp). Escaped rays also get the exact bending beyond the sky
// sphere (exact/schwarzschild_exact.hpp) folded into a second tabulated value, so the asymptotic direction
// costs no elliptic integral per pixel. tests/symmetric_sky_test.cpp proves it equal to the general tracer.
//
// delta_c is where b = b_c: sin(pi - delta_c) = (3 sqrt 3 M / r_c) sqrt(1 - 2M/r_c) for r_c >= 3M (the
// capture cone around the inward direction), and delta_c = that arcsine for r_c < 3M (escape cone around
// the outward direction); rays with delta > delta_c are captured.
#pragma once

#include "grtrace/metric/schwarzschild_lapse.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/trace/critical_angle_grid.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/planar_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace grtrace {

/// The planar geometry of a ray in Schwarzschild spacetime of mass `mass` (trace/planar_geometry.hpp).
inline PlanarGeometry planar_geometry(const GeodesicState& y, double mass) {
  return planar_geometry(SchwarzschildMetric{mass}, y);
}

template <ExplicitTableau T, StepController C = PIController>
class SymmetricSkyTable {
 public:
  struct Entry {
    RayStatus status;
    double sweep;           ///< angle turned until the sky sphere (escaped) or the horizon guard (captured)
    double sweep_infinity;  ///< escaped: sweep plus the exact bending beyond the sky sphere
    double steps;           ///< accepted steps of the table ray(s) it was read from
  };

  /// Takes the metric, camera radius and sky radius, the tracer settings for the table rays, the range of
  /// delta the frame needs [delta_min, delta_max] and the number of table rays on each side of delta_c.
  /// Assumes 2M (1 + eps) < camera_r < sky_r.
  SymmetricSkyTable(SchwarzschildMetric metric, double camera_r, double sky_r, TraceSettings settings,
                    double delta_min, double delta_max, int nodes_per_side = default_table_rays)
      : metric_(metric), camera_r_(camera_r), sky_r_(sky_r) {
    const double guard = (1.0 + settings.horizon_epsilon) * metric.horizon_radius();
    if (!(camera_r > guard && camera_r < sky_r))
      throw std::invalid_argument("SymmetricSkyTable: need horizon guard < camera radius < sky radius");
    settings.escape_radius = sky_r;
    tracer_.emplace(metric, settings);
    const double M = metric.mass, f = schwarzschild_f(camera_r, M);
    const double a = std::asin(std::min(1.0, exact::critical_impact_parameter(M) / camera_r * std::sqrt(f)));
    delta_c_ = camera_r >= 3.0 * M ? std::numbers::pi - a : a;
    delta_min = std::clamp(delta_min, 0.0, std::numbers::pi);
    delta_max = std::clamp(delta_max, 0.0, std::numbers::pi);
    // Each side covers the frame's angles on that side; the gap to delta_c is bounded below so that the
    // logarithm stays finite (rays closer than 1e-14 rad to delta_c are read from the last node).
    constexpr double min_gap = 1e-14;
    if (delta_min < delta_c_) escaped_side_ = build(+1, std::max(delta_c_ - std::min(delta_max, delta_c_), min_gap),
                                                    delta_c_ - delta_min, nodes_per_side);
    if (delta_max > delta_c_) captured_side_ = build(-1, std::max(std::max(delta_min, delta_c_) - delta_c_, min_gap),
                                                     delta_max - delta_c_, nodes_per_side);
  }

  double critical_angle() const { return delta_c_; }
  long table_steps() const { return total_steps_; }
  int table_rays() const { return static_cast<int>(escaped_side_.values.size() + captured_side_.values.size()); }

  /// Interpolated outcome of the ray leaving the camera at angle delta.
  Entry at(double delta) const {
    const bool escaped = delta < delta_c_;
    const Side& side = escaped ? escaped_side_ : captured_side_;
    if (side.values.empty()) throw std::out_of_range("SymmetricSkyTable: delta outside the tabulated range");
    return side.interpolate(std::abs(delta - delta_c_), escaped ? RayStatus::escaped : RayStatus::captured);
  }

  const SchwarzschildMetric& metric() const { return metric_; }
  double camera_radius() const { return camera_r_; }
  double sky_radius() const { return sky_r_; }

 private:
  struct Side {
    CriticalAngleGrid grid;
    std::vector<Entry> values;

    Entry interpolate(double gap, RayStatus status) const {
      const CriticalAngleGrid::Stencil st = grid.stencil(gap);
      Entry e{status, 0.0, 0.0, 0.0};
      for (int j = 0; j < st.count; ++j) {
        const Entry& v = values[static_cast<std::size_t>(st.first + j)];
        const double w = st.weight[static_cast<std::size_t>(j)];
        if (v.status != status) e.status = v.status;  // a failed table ray poisons its neighbourhood
        e.sweep += w * v.sweep;
        e.sweep_infinity += w * v.sweep_infinity;
      }
      e.steps = values[static_cast<std::size_t>(st.nearest)].steps;
      return e;
    }
  };

  // sign +1: escaped side, delta = delta_c - gap; sign -1: captured side, delta = delta_c + gap.
  Side build(int sign, double gap_min, double gap_max, int nodes) {
    Side side{CriticalAngleGrid(gap_min, gap_max, nodes), {}};
    const int n = side.grid.nodes;
    side.values.resize(static_cast<std::size_t>(n));
    long steps = 0;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : steps)
#endif
    for (int i = 0; i < n; ++i) {
      const double delta = delta_c_ - sign * side.grid.gap_of_node(i);
      const Entry e = trace_one(delta);
      side.values[static_cast<std::size_t>(i)] = e;
      steps += static_cast<long>(e.steps);
    }
    total_steps_ += steps;
    return side;
  }

  // One planar ray in the equatorial plane, starting at phi = 0 with angle delta to the outward radial.
  Entry trace_one(double delta) const {
    const double M = metric_.mass, r = camera_r_, f = schwarzschild_f(r, M);
    const Vec4 x(0.0, r, std::numbers::pi / 2.0, 0.0);
    // Unit-energy null vector in the static frame, moving at angle delta from e_r towards +phi.
    const Vec4 k(1.0 / std::sqrt(f), std::sqrt(f) * std::cos(delta), 0.0, std::sin(delta) / r);
    const TraceResult res = tracer_->trace(make_state(x, k));
    Entry e{res.status, res.final_state[3], std::numeric_limits<double>::quiet_NaN(),
            static_cast<double>(res.accepted)};
    if (res.status == RayStatus::escaped) {
      // Continue exactly from the last accepted step (just beyond the sky sphere): integrator error only.
      const GeodesicState& end = res.step_end_state;
      const double b = r * std::sin(delta) / std::sqrt(f);
      const auto rest = exact::remaining_sweep(b, end[1], end[5] > 0.0, M);
      e.sweep_infinity = rest ? end[3] + *rest : std::numeric_limits<double>::quiet_NaN();
    }
    return e;
  }

  SchwarzschildMetric metric_;
  double camera_r_, sky_r_;
  double delta_c_ = 0.0;
  std::optional<GeodesicTracer<SchwarzschildMetric, T, C>> tracer_;
  Side escaped_side_, captured_side_;
  long total_steps_ = 0;
};

}  // namespace grtrace
