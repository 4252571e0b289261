// grtrace/trace/symmetric_scene_tracer.hpp
// The reduced scene tracer for a sky and a horizon around a Schwarzschild mass, seen from a camera at radius
// r_c (static or moving: the angle delta is taken in the local static frame, so aberration is included).
// It integrates the rays of a SymmetricSkyTable once for the frame (over the range of delta its pixels need)
// and reads every pixel from it (trace/symmetric_sky_table.hpp). Redshifts are exact: the emitters are static
// and E = g_tt k^t is conserved, so f_obs / f_src = -sqrt(1 - 2M/r_src) / E.
// It draws a scene with a sky and a horizon only: objects break the symmetry (a scene with objects needs the
// general tracer; refused at compile time).
#pragma once

#include "grtrace/observer/camera.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/trace/ray_outcome.hpp"
#include "grtrace/trace/symmetric_sky_table.hpp"

#include <utility>

#include <algorithm>
#include <cmath>
#include <optional>

namespace grtrace {

template <ExplicitTableau T, StepController C, class SceneT>
class SymmetricSceneTracer {
  static_assert(SceneT::object_count == 0,
                "the symmetric-sky tracer draws a sky and a horizon only: objects break the spherical symmetry, "
                "so a scene with objects needs GeneralSceneTracer");

 public:
  static constexpr const char* name = "symmetric-sky";
  using SceneType = SceneT;

  /// Builds the table for the camera's pixels. Assumes horizon guard < camera radius < sky radius.
  SymmetricSceneTracer(SchwarzschildMetric metric, const TraceSettings& settings, const Camera& camera,
                       AngleCorrection correction, SceneT scene, int nodes_per_side = default_table_rays)
      : metric_(metric), correction_(correction), scene_(std::move(scene)), sky_r_(settings.escape_radius),
        guard_r_((1.0 + settings.horizon_epsilon) * metric.horizon_radius()) {
    double lo = 3.2, hi = 0.0;  // delta range over the frame, from the pixel centres
#ifdef _OPENMP
#pragma omp parallel for schedule(static) reduction(min : lo) reduction(max : hi)
#endif
    for (int row = 0; row < camera.height(); ++row)
      for (int col = 0; col < camera.width(); ++col) {
        const double d = planar_geometry(camera.pixel_state(col, row), metric.mass).delta;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    table_.emplace(metric, camera.position()[1], sky_r_, settings, lo, hi, nodes_per_side);
  }

  RayOutcome trace(const GeodesicState& y0) const {
    const PlanarGeometry g = planar_geometry(y0, metric_.mass);
    const auto e = table_->at(g.delta);
    const double energy = metric_.energy(y0);  // conserved E = g_tt k^t (< 0: past-directed)
    RayOutcome out;
    out.status = e.status;
    out.steps = static_cast<int>(e.steps);
    if (e.status == RayStatus::escaped) {
      out.object = kSkyObject;
      const double f_sky = metric_.lapse_squared(sky_r_);
      double sweep = e.sweep;
      if (correction_ == AngleCorrection::exact) sweep = e.sweep_infinity;
      if (correction_ == AngleCorrection::flat) sweep += std::asin(std::min(1.0, g.impact * std::sqrt(f_sky) / sky_r_));
      const Vec3 d = g.direction_at(sweep);
      out.where = sky_direction_of(d);
      out.order = equator_crossings_to(g, sweep, d);  // up to where it is seen
      out.radius = sky_r_;
      out.redshift = -std::sqrt(f_sky) / energy;
    } else if (e.status == RayStatus::captured) {
      out.object = kHorizonObject;
      const Vec3 d = g.direction_at(e.sweep);
      out.where = sky_direction_of(d);
      out.order = equator_crossings_to(g, e.sweep, d);
      out.radius = guard_r_;
      out.redshift = -std::sqrt(metric_.lapse_squared(guard_r_)) / energy;
    }
    return out;
  }

  const SymmetricSkyTable<T, C>& table() const { return *table_; }
  const SceneT& scene() const { return scene_; }

 private:
  SchwarzschildMetric metric_;
  AngleCorrection correction_;
  SceneT scene_;
  double sky_r_, guard_r_;
  std::optional<SymmetricSkyTable<T, C>> table_;
};

}  // namespace grtrace
