// grtrace/trace/ray_outcome.hpp
// What every scene tracer reports for one camera ray, before shading: how it ended, on what (a position in the
// scene: scene/object_ids.hpp), where (the sky direction of an escaped ray after the angle correction, or the
// direction of the hit point), the state at the end, the redshift f_obs / f_src (seed eq. 9), and the order of
// the image (the ray's crossings of the equatorial plane before it ended).
// The tracers (general, symmetric-sky, straight-line) differ in how they get there, not in what they report.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/sky_direction.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/metric_traits.hpp"  // AngleCorrection
#include "grtrace/scene/object_ids.hpp"

#include <limits>
#include <string>
#include <vector>

namespace grtrace {

struct RayOutcome {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  // The members' NaN through a function: device code cannot read the static member (core/host_device.hpp).
  static GRTRACE_HD constexpr double quiet_nan() { return std::numeric_limits<double>::quiet_NaN(); }
  RayStatus status = RayStatus::max_steps;
  int object = kSkyObject;          ///< 0 sky, 1 horizon, 2... the scene's objects in order; meaningful unless failed
  SkyDirection where{quiet_nan(), quiet_nan()};  ///< escaped: sky direction; captured / hit: direction of the hit point
  double radius = quiet_nan();                   ///< metric radius of the end point (sky sphere, horizon guard, hit)
  double redshift = quiet_nan();                 ///< f_obs / f_src; NaN for failed rays
  int steps = 0;                    ///< accepted integration steps (table tracers: the nearest table ray's)
  /// The image's order n: the ray's crossings of the equatorial plane before its end (a hit on a thin disk in
  /// the plane is its (n+1)-th crossing): 0 the direct image, 1 the first photon ring, ... (trace/
  /// geodesic_tracer.hpp TraceResult::crossings). A captured ray's count ends at the tracer's horizon guard, which
  /// a chart through the horizon (Kerr-Schild) puts inside it. -1 for failed rays and tracers that do not count.
  int order = -1;
  GeodesicState state = GeodesicState::Constant(quiet_nan());  ///< (x, k) at the end, in the metric's chart; NaN where
                                                               ///< a tracer does not follow the ray itself (tables)
};

/// The name of the object a ray ended on, from its scene's names by position (Scene::object_names: "sky",
/// "horizon", "disk", ...; "object N" past them); "" for a failed ray, which ended on none.
inline std::string outcome_object_name(const RayOutcome& outcome, const std::vector<std::string>& names) {
  if (is_failure(outcome.status)) return "";
  const auto index = static_cast<std::size_t>(outcome.object);
  return outcome.object >= 0 && index < names.size() ? names[index] : "object " + std::to_string(outcome.object);
}

}  // namespace grtrace
