// grtrace/trace/planar_scene_tracer.hpp
// The planar-path scene tracer: every pixel of a frame in a static spherically symmetric spacetime
// (metric/static_spherical.hpp) read from one table of rays (trace/planar_path_table.hpp), objects included.
//
// Takes:   the metric, trace settings (tolerance, sky radius, horizon guard), the camera (the table covers the
//          angles its pixels need; static or moving: aberration is in each pixel's momentum), the angle
//          correction for escaped rays, and a scene whose objects lie in the equatorial plane (the optional trait
//          `static constexpr bool equatorial = true;`, scene/scene_object.hpp: e.g. ThinDisk).
// Returns: per pixel a RayOutcome like GeneralSceneTracer's: status, object, direction, radius, redshift, and for
//          hits the end state (x, k) (t is not tracked: 0; stationary scenes only). Sky and horizon outcomes carry
//          no state (NaN), like the symmetric-sky tracer's.
// Per pixel: the ray's plane (a rotation), the table look-up of its fate, and for objects the swept angles where
// its plane meets the equatorial plane, psi_k = psi_0 + k pi (every order of image: direct, secondary, ...), each
// read off the tabulated path u(psi) while the ray is alive (psi_k < its sweep to the sky sphere or the guard).
// Redshifts are exact given the radius: E = g_tt k^t and the angular momentum are conserved, so the momentum at a
// hit follows from u and u' there, and the emitter's 4-velocity from the object (ThinDisk: its circular orbit).
// Assumes: pixels whose stencil of table rays lacks a value (a failed table ray nearby; a path asked beyond what a
// neighbour holds) or whose plane is the equatorial plane itself (the ray runs inside the disk's plane: no
// crossing to look up) are traced by the general tracer instead: exact, just slower; fallback_rays() counts them.
#pragma once

#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/trace/planar_geometry.hpp"
#include "grtrace/trace/planar_path_table.hpp"
#include "grtrace/trace/ray_outcome.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <optional>
#include <tuple>
#include <utility>

namespace grtrace {

/// True when the planar tracer can draw every object of the scene: each lies in the equatorial plane (optional
/// object trait `equatorial`, scene/scene_object.hpp); a scene without objects always.
template <class SceneT>
inline constexpr bool planar_supports_scene =
    every_object_of<SceneT>([]<class O>() { return object_is_equatorial<O>(); });

/// The range [min, max] of the angle delta (trace/planar_geometry.hpp) over the camera's pixel centres, without
/// visiting every pixel: delta is the angle between the pixel's direction in the static frame and the outward
/// radial, a function on the sphere whose only critical points are that direction and its opposite; the pixel map
/// (pinhole, then aberration) is a diffeomorphism, so the extremes lie on the frame's border or at the pixels that
/// see straight out (delta = 0) or straight in (delta = pi), included when they fall inside the frame.
template <StaticSphericalMetric Metric>
std::pair<double, double> planar_angle_range(const Metric& metric, const Camera& camera) {
  double lo = std::numbers::pi, hi = 0.0;
  auto visit = [&](int col, int row) {
    const double d = planar_geometry(metric, camera.pixel_state(col, row)).delta;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  };
  const int w = camera.width(), h = camera.height();
  for (int col = 0; col < w; ++col) visit(col, 0), visit(col, h - 1);
  for (int row = 0; row < h; ++row) visit(0, row), visit(w - 1, row);
  // The static-frame radial directions seen by the camera: k = +-e_r - e_0 (past-directed, unit energy in the
  // static frame); its camera-frame direction has components -g(k, e_i) (i = forward, up, right; spacelike e_i
  // have g(e_i, e_i) = -1), up to a positive factor, and lands on the pixel the camera maps that direction to.
  const Vec4 x = camera.position();
  const Mat4 g = metric.metric(x);
  const Tetrad& t = camera.tetrad();
  const double r = x[1];
  Vec4 e0 = Vec4::Zero(), er = Vec4::Zero();
  e0[0] = 1.0 / std::sqrt(metric.lapse_squared(r));
  er[1] = 1.0 / std::sqrt(radial_scale_squared(metric, r));
  for (const double sign : {+1.0, -1.0}) {
    const Vec4 k = sign * er - e0;
    const double forward = -k.dot(g * t.e[1]), up = -k.dot(g * t.e[2]), right = -k.dot(g * t.e[3]);
    if (!(forward > 0.0)) continue;  // behind the camera
    const double tan_half = camera.tan_half_fov();
    const double col = (right / forward / tan_half + 1.0) * (w - 1) / 2.0;
    const double y = h > 1 ? (up / forward / tan_half * w / h + 1.0) * (h - 1) / 2.0 : 0.0;
    if (!(col >= -0.5 && col <= w - 0.5 && y >= -0.5 && y <= h - 0.5)) continue;  // outside the frame
    if (sign > 0.0) lo = 0.0;
    else hi = std::numbers::pi;
  }
  return {lo, hi};
}

template <StaticSphericalMetric Metric, ExplicitTableau T, StepController C, class SceneT>
class PlanarSceneTracer {
  static_assert(planar_supports_scene<SceneT>,
                "the planar tracer intersects objects that lie in the equatorial plane (declare "
                "`static constexpr bool equatorial = true;` if yours does); other objects need GeneralSceneTracer");
  static_assert(C::estimate != ErrorEstimate::none,
                "the planar tracer integrates its table in swept angle, not in the affine parameter: a fixed step "
                "would mean something else there; use an adaptive controller (i, pi, doubling)");

 public:
  static constexpr const char* name = "planar";
  using MetricType = Metric;
  using SceneType = SceneT;

  /// Builds the table for the camera's pixels. Assumes (checked by the table) horizon guard < camera radius < sky.
  PlanarSceneTracer(Metric metric, const TraceSettings& settings, const Camera& camera, AngleCorrection correction,
                    SceneT scene, int nodes_per_side = default_table_rays, C controller = {})
      : metric_(metric), correction_(correction),
        fallback_(metric, settings, controller, correction, std::move(scene)) {
    const auto [lo, hi] = planar_angle_range(metric, camera);
    // A scene without objects reads only each ray's end: the table keeps no paths (planar_path_table.hpp).
    table_.emplace(metric, camera.position()[1], settings, lo, hi, nodes_per_side, controller,
                   /*keep_paths=*/SceneT::object_count > 0);
    camera_r_ = camera.position()[1];
    camera_theta_ = camera.position()[2];
    camera_phi_ = camera.position()[3];
    camera_basis_ = spherical_basis(camera_theta_, camera_phi_);
    camera_frame_ = static_radial_frame(metric, camera_r_);
    sky_lapse_ = std::sqrt(metric.lapse_squared(table_->sky_radius()));
    guard_lapse_ = std::sqrt(metric.lapse_squared(table_->guard_radius()));
  }

  RayOutcome trace(const GeodesicState& y0) const {
    // Every pixel of the frame starts where the camera is: its spherical basis and static frame are computed once
    // (two sincos, a division and a square root per pixel saved).
    const bool at_camera = y0[1] == camera_r_ && y0[2] == camera_theta_ && y0[3] == camera_phi_;
    const StaticRadialFrame frame = at_camera ? camera_frame_ : static_radial_frame(metric_, y0[1]);
    const PlanarGeometry g = planar_geometry(y0, at_camera ? camera_basis_ : spherical_basis(y0[2], y0[3]), frame);
    const auto look = table_->at(g.delta);
    if (look.status != RayStatus::escaped && look.status != RayStatus::captured) return fall_back(y0);
    const double energy = frame.lapse_squared * y0[4];  // conserved E = g_tt k^t (< 0: past-directed)

    if constexpr (SceneT::object_count > 0) {
      const double psi_0 = first_equator_crossing(g);
      if (std::isnan(psi_0)) return fall_back(y0);  // the ray runs in the equatorial plane
      constexpr double pi = std::numbers::pi;
      // cos and sin of the crossings: psi advances by pi, so both only change sign.
      const SinCos first = sin_cos(psi_0);
      double cos_psi = first.cos, sin_psi = first.sin;
      int order = 0;
      for (double psi = psi_0; psi < look.sweep_end; psi += pi, ++order, cos_psi = -cos_psi, sin_psi = -sin_psi) {
        const auto p = table_->path_at(look, psi);
        if (!p) return fall_back(y0);
        const GeodesicState y = state_at(g, energy, cos_psi, sin_psi, *p);
        std::optional<RayOutcome> hit;
        visit_hit(y, [&](int position, const auto& object) {
          RayOutcome out;
          out.status = RayStatus::hit;
          out.object = position;
          out.steps = look.steps;
          out.state = y;
          out.radius = y[1];
          out.where = position_direction(metric_, y.template head<4>());
          out.redshift = redshift_at(metric_, object.emitter_velocity(metric_, y.template head<4>()), y);
          out.order = order;
          hit = out;
        });
        if (hit) return *hit;
      }
    }

    RayOutcome out;
    out.status = look.status;
    out.steps = look.steps;
    const double r_end = look.status == RayStatus::escaped ? table_->sky_radius() : table_->guard_radius();
    out.radius = r_end;
    // A static emitter there: u = d_t / sqrt(g_tt), so f_obs / f_src = -sqrt(g_tt(r_end)) / E.
    out.redshift = -(look.status == RayStatus::escaped ? sky_lapse_ : guard_lapse_) / energy;
    // Where the ray is seen, and its crossings of the plane up to there (planar_geometry.hpp).
    const auto seen_at = [&](double sweep) {
      const Vec3 d = g.direction_at(sweep);
      out.where = sky_direction_of(d);
      out.order = equator_crossings_to(g, sweep, d);
    };
    if (look.status == RayStatus::captured) {
      out.object = kHorizonObject;
      seen_at(look.sweep_end);
      return out;
    }
    out.object = kSkyObject;
    double sweep = look.sweep_end;  // AngleCorrection::none: the point on the sky sphere
    if (correction_ == AngleCorrection::exact && HasExactContinuation<Metric>) {
      sweep = look.sweep_infinity;  // u = 0 on the tabulated path: the direction at infinity
    } else if (correction_ != AngleCorrection::none) {
      // Flat beyond the sphere: the direction of dx/dlambda there, at angle beta from the radial with
      // tan beta = r dpsi/dlambda / (dr/dlambda) = (b / R) / sqrt((1 / A - b^2 / R^2) / B) (E = 1).
      const double rs = r_end, b = g.impact;
      fallback_.note_flat_impact(b);  // for flat_continuation_estimate
      const double rdot2 = (1.0 / metric_.lapse_squared(rs) - b * b / (rs * rs)) / radial_scale_squared(metric_, rs);
      sweep += std::atan2(b / rs, std::sqrt(std::max(0.0, rdot2)));
    }
    seen_at(sweep);
    return out;
  }

  const SceneT& scene() const { return fallback_.scene(); }  // the fallback tracer holds the one copy
  /// Which continuation escaped rays get: the tabulated path to u = 0 where the metric has an exact one, else flat.
  SkyContinuation sky_continuation() const { return sky_continuation_of<Metric>(correction_); }
  /// The flat continuation's error estimate over the rays of this frame, table and fallback together.
  std::optional<FlatContinuationEstimate> flat_continuation_estimate() const {
    return fallback_.flat_continuation_estimate();
  }
  const Metric& metric() const { return metric_; }
  const PlanarPathTable<Metric, T, C>& table() const { return *table_; }
  /// Pixels traced by the general tracer instead (see the top of this file), since construction.
  long fallback_rays() const { return fallbacks_.load(std::memory_order_relaxed); }

 private:
  RayOutcome fall_back(const GeodesicState& y0) const {
    fallbacks_.fetch_add(1, std::memory_order_relaxed);
    return fallback_.trace(y0);
  }

  // The ray's state where it crosses the equatorial plane at swept angle psi (c = cos psi, s = sin psi), from
  // u = 1 / r and w = du/dpsi: theta = pi / 2 exactly, phi from the plane's direction there; momentum from the
  // conserved E (k^t = E / A) and L = r^2 dpsi/dlambda (dr/dlambda = -L w). On the equator e_theta = -z and
  // e_phi = z x e_r, so no trigonometry beyond one atan2 is needed.
  GeodesicState state_at(const PlanarGeometry& g, double energy, double c, double s, const PathPoint& p) const {
    const double r = 1.0 / p.u, L = g.angular_momentum, psidot = L * p.u * p.u;
    const Vec3 n = c * g.radial + s * g.tangential, m = -s * g.radial + c * g.tangential;
    // n is a unit vector in the equatorial plane (|n_z| ~ 1e-16): no overflow for hypot to guard against.
    const double nxy = std::sqrt(n.x() * n.x() + n.y() * n.y()), cp = n.x() / nxy, sp = n.y() / nxy;
    GeodesicState y;
    y << 0.0, r, 0.5 * std::numbers::pi, std::atan2(n.y(), n.x()), energy / metric_.lapse_squared(r), -L * p.w,
        -psidot * m.z(), psidot * (cp * m.y() - sp * m.x());
    return y;
  }

  // Calls f(position, object) for the first object (in scene order) that accepts the crossing state y.
  template <class F>
  void visit_hit(const GeodesicState& y, F&& f) const {
    bool done = false;
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      ((!done && event_accepts(std::get<I>(scene().objects), y)
            ? (f(kFirstSceneObject + static_cast<int>(I), std::get<I>(scene().objects)), void(done = true))
            : void()),
       ...);
    }(std::make_index_sequence<SceneT::object_count>{});
  }

  Metric metric_;
  double camera_r_ = 0.0, camera_theta_ = 0.0, camera_phi_ = 0.0;
  SphericalBasis camera_basis_{};
  StaticRadialFrame camera_frame_{};
  double sky_lapse_ = 0.0, guard_lapse_ = 0.0;  ///< sqrt(g_tt) at the sky sphere and at the horizon guard
  AngleCorrection correction_;
  GeneralSceneTracer<Metric, T, C, SceneT> fallback_;
  std::optional<PlanarPathTable<Metric, T, C>> table_;
  mutable std::atomic<long> fallbacks_{0};
};

}  // namespace grtrace
