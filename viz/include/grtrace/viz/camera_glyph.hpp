// grtrace/viz/camera_glyph.hpp
// The camera as the 3D view draws it: its event and tetrad pushed into the Cartesian embedding.
// Header-only and VTK-free (the drawing is in surfaces.hpp).
//
// Takes:   a metric, the camera event x and tetrad e_a^mu (e_0 4-velocity, e_1 forward, e_2 up, e_3 right,
//          as in shared/DESIGN.md), the horizontal field of view and the frame size.
// Returns: a CameraGlyph: the embedded position; the embedded directions of e_1, e_2, e_3 and of the spatial
//          part of e_0 (the camera's coordinate velocity, zero for a static camera); and the initial embedded
//          directions of the four corner pixels' rays k = (e_1 + u e_2 + r e_3)/sqrt(1 + u^2 + r^2) - e_0, so a
//          moving camera's frustum shows its aberration. Vectors are pushed forward with the Jacobian of
//          metric.to_cartesian (central differences), then normalised (zero stays zero).
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <concepts>
#include <array>
#include <cmath>
#include <numbers>

namespace grtrace::viz {

struct CameraGlyph {
  Vec3 position = Vec3::Zero();
  Vec3 forward = Vec3::UnitX(), up = Vec3::UnitZ(), right = -Vec3::UnitY();
  Vec3 velocity = Vec3::Zero();  ///< embedded direction of e_0's spatial part, scaled by its speed share (<= 1)
  /// Initial embedded directions of the corner rays: bottom-left, bottom-right, top-right, top-left.
  std::array<Vec3, 4> corners{};
  double fov_degrees = 60.0;
};

/// Anything with the embedding to_cartesian(x): a metric policy, or a named metric's app::MetricGeometry.
template <class M>
concept HasEmbedding = requires(const M& m, const Vec4& x) {
  { m.to_cartesian(x) } -> std::convertible_to<Vec3>;
};

/// d to_cartesian / dx^mu at x, 3 x 4, by central differences.
template <HasEmbedding Metric>
Eigen::Matrix<double, 3, 4> embedding_jacobian(const Metric& metric, const Vec4& x) {
  Eigen::Matrix<double, 3, 4> J;
  for (int mu = 0; mu < 4; ++mu) {
    const double d = 1e-6 * std::max(1.0, std::abs(x[mu]));
    Vec4 a = x, b = x;
    a[mu] += d;
    b[mu] -= d;
    J.col(mu) = (metric.to_cartesian(a) - metric.to_cartesian(b)) / (2.0 * d);
  }
  return J;
}

namespace detail {
inline Vec3 unit_or_zero(const Vec3& v) {
  const double n = v.norm();
  return n > 0.0 && std::isfinite(n) ? Vec3(v / n) : Vec3(Vec3::Zero());
}
}  // namespace detail

/// e[a] = e_a^mu (a = 0..3). width/height fix the vertical extent of the frustum (the pixel formula).
template <HasEmbedding Metric>
CameraGlyph make_camera_glyph(const Metric& metric, const Vec4& x, const std::array<Vec4, 4>& e, double fov_degrees,
                              int width, int height) {
  const auto J = embedding_jacobian(metric, x);
  CameraGlyph g;
  g.position = metric.to_cartesian(x);
  g.forward = detail::unit_or_zero(J * e[1]);
  g.up = detail::unit_or_zero(J * e[2]);
  g.right = detail::unit_or_zero(J * e[3]);
  // Share of e_0's embedded length relative to e_1's: 0 for a static observer, -> 1 as the speed -> c.
  const Vec3 v = J * e[0];
  const double f = (J * e[1]).norm();
  g.velocity = f > 0.0 ? Vec3(v / f) : Vec3(Vec3::Zero());
  g.fov_degrees = fov_degrees;
  const double t = std::tan(fov_degrees * std::numbers::pi / 360.0);
  const double aspect = static_cast<double>(height) / static_cast<double>(width);
  const std::array<std::array<double, 2>, 4> ru = {{{-t, -t * aspect}, {t, -t * aspect}, {t, t * aspect}, {-t, t * aspect}}};
  for (std::size_t i = 0; i < 4; ++i) {
    const double r = ru[i][0], u = ru[i][1];
    const Vec4 k = (e[1] + u * e[2] + r * e[3]) / std::sqrt(1.0 + u * u + r * r) - e[0];
    g.corners[i] = detail::unit_or_zero(J * k);
  }
  return g;
}

}  // namespace grtrace::viz
