// grtrace/trace/straight_line.hpp
// Flat spacetime is never integrated: a light ray is a straight line, and where it meets the sky sphere is a
// quadratic equation. Works in the spherical chart (t, r, theta, phi) the cameras use (MinkowskiSpherical).
#pragma once

#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <cmath>

namespace grtrace {

class StraightLineTracer {
 public:
  static constexpr const char* name = "straight-line";

  StraightLineTracer(double sky_radius, AngleCorrection correction)
      : sky_radius_(sky_radius), correction_(correction) {}

  /// Takes a state in flat spherical coordinates; the ray leaves the sky sphere (radius > camera radius).
  RayOutcome trace(const GeodesicState& y) const {
    const SphericalBasis e = spherical_basis(y[2], y[3]);
    const Vec3 p = y[1] * e.r;
    const Vec3 v = embedded_velocity(y, e);
    // |p + s v| = R for the positive root s.
    const double a = v.squaredNorm(), b = p.dot(v), c = p.squaredNorm() - sky_radius_ * sky_radius_;
    const double s = (-b + std::sqrt(b * b - a * c)) / a;
    const Vec3 hit = p + s * v;
    RayOutcome out;
    out.status = RayStatus::escaped;
    out.object = SceneObjectId::sky;
    out.where = exact::sky_direction_of(correction_ == AngleCorrection::none ? hit : v);
    out.radius = sky_radius_;
    out.redshift = -1.0 / y[4];  // static source in flat space: g(u, k) = k^t, and g(e_0, k_cam) = -1
    return out;
  }

 private:
  double sky_radius_;
  AngleCorrection correction_;
};

}  // namespace grtrace
