// grtrace/viz/orbits.hpp
// Timelike orbits for the 3D view (as tubes) and the charts, and the seed report's test orbit as a built-in.
// Header-only and VTK-free.
//
// The seed orbit (report sec. 3.2.1, Figs. 1-3): a particle at r = 100 M in the equatorial plane of a
// Schwarzschild hole of mass M = 1, starting with dphi/dtau = 0.00075 and no radial velocity. Its speed is below
// the circular one (v^2/r ~ 0.56 M/r^2), so it falls in to periapsis ~ 39 M and back: a precessing ellipse.
// It is traced for `revolutions` turns in phi (an event phi = 2 pi revolutions ends it) with lambda = proper time.
//
// A camera flight's path (observer/flight_path.hpp, a Worldline) is drawn as an orbit too: worldline_path
// (observer/worldline.hpp).
#pragma once

#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/observer/worldline.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace grtrace::viz {

struct OrbitSpec {
  double mass = 1.0;
  double r0 = 100.0;          ///< start radius (turning point), equatorial plane, phi = 0
  double dphi_dtau = 0.00075;  ///< initial angular velocity dphi/dtau
  double dr_dtau = 0.0;        ///< initial radial velocity
  double revolutions = 12.0;   ///< turns in phi before the trace ends
};

/// The seed report's orbit.
inline OrbitSpec seed_orbit() { return {}; }

/// Initial state (x, u) with g(u, u) = 1; throws std::invalid_argument when no such 4-velocity exists.
inline GeodesicState orbit_initial_state(const OrbitSpec& spec) {
  if (!(spec.mass > 0.0)) throw std::invalid_argument("orbit: mass must be > 0");
  if (!(spec.r0 > 2.0 * spec.mass)) throw std::invalid_argument("orbit: start radius must be outside r = 2M");
  if (!(spec.revolutions > 0.0)) throw std::invalid_argument("orbit: revolutions must be > 0");
  const SchwarzschildMetric metric{spec.mass};
  const Vec4 x(0.0, spec.r0, std::numbers::pi / 2.0, 0.0);
  const auto u = complete_time_component(metric, x, Vec4(0.0, spec.dr_dtau, 0.0, spec.dphi_dtau), 1.0);
  if (!u) throw std::invalid_argument("orbit: no timelike 4-velocity with these components");
  return make_state(x, *u);
}

/// Ends the orbit after the given turns in phi (phi grows for dphi/dtau > 0, shrinks otherwise).
struct RevolutionsEvent {
  double phi_end;
  double sign;
  double operator()(const GeodesicState& y) const { return sign * (phi_end - y[3]); }
};

/// Traces the orbit with a tracer over SchwarzschildMetric (its mass must match spec.mass).
/// Settings need escape_radius beyond the apoapsis and enough max_steps.
template <class Tracer>
TracedPath trace_orbit(const Tracer& tracer, const OrbitSpec& spec, int samples_per_step = 8) {
  const GeodesicState y0 = orbit_initial_state(spec);
  const double sign = spec.dphi_dtau >= 0.0 ? 1.0 : -1.0;
  const RevolutionsEvent end{sign * 2.0 * std::numbers::pi * spec.revolutions, sign};
  return trace_path(tracer, y0, samples_per_step, std::nullopt, end);
}

/// A camera flight's path as the 3D view draws it (observer/worldline.hpp).
using grtrace::worldline_path;

}  // namespace grtrace::viz
