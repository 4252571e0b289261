// grtrace/metric/minkowski.hpp
// Flat spacetime in Cartesian coordinates x = (t, x, y, z): all Christoffel symbols vanish and geodesics
// are straight lines, so tracers never need to integrate it (trace/straight_line.hpp). The integrating
// tracer accepts it too, which is how tests check that every tableau follows a straight line to round-off.
// Flat space in spherical coordinates is MinkowskiSpherical in schwarzschild.hpp.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/metric/metric_concept.hpp"

namespace grtrace {

struct MinkowskiMetric {
  static constexpr std::string_view name = "minkowski";
  static constexpr Chart chart = Chart::cartesian;
  static constexpr bool flat = true;  ///< optional trait: straight lines, never integrated (metric_traits.hpp)

  GRTRACE_HD Mat4 metric(const Vec4& /*x*/) const { return minkowski_eta(); }
  GRTRACE_HD Christoffel christoffel(const Vec4& /*x*/) const {
    Christoffel G;
    for (auto& g : G) g.setZero();
    return G;
  }
  GRTRACE_HD Vec4 acceleration(const Vec4& /*x*/, const Vec4& /*k*/) const { return Vec4::Zero(); }
  GRTRACE_HD double radius(const Vec4& x) const { return x.tail<3>().norm(); }
  GRTRACE_HD double horizon_radius() const { return 0.0; }
  GRTRACE_HD Vec3 to_cartesian(const Vec4& x) const { return x.tail<3>(); }
};

static_assert(MetricPolicy<MinkowskiMetric>);

}  // namespace grtrace
