// grtrace/metric/examples/minkowski_components.hpp
// Flat spacetime in Cartesian coordinates x = (t, x, y, z), written the automatic way.
// Takes:   nothing. Returns: MinkowskiComponents (constant g = diag(1, -1, -1, -1)) and AutoMinkowski; every
//          derivative is exactly zero, so AutoMinkowski's Christoffel symbols are exactly MinkowskiMetric's.
// Assumes: nothing (no horizon, no chart singularity).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/auto_metric.hpp"

namespace grtrace {

struct MinkowskiComponents {
  static constexpr std::string_view name = "minkowski-auto";
  static constexpr Chart chart = Chart::cartesian;

  template <class S>
  GRTRACE_HD Mat4Of<S> metric_components(const Vec4Of<S>& /*x*/) const {
    return diagonal_metric<S>(1.0, -1.0, -1.0, -1.0);
  }
  GRTRACE_HD double radius(const Vec4& x) const { return x.tail<3>().norm(); }
  GRTRACE_HD double horizon_radius() const { return 0.0; }
};

using AutoMinkowski = AutoMetric<MinkowskiComponents>;
static_assert(MetricComponents<MinkowskiComponents>);
static_assert(MetricPolicy<AutoMinkowski>);

}  // namespace grtrace
