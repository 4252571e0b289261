// grtrace/viz/orbits.hpp
// Timelike orbits for the 3D view (as tubes) and the charts, and the seed report's test orbit as a built-in.
// Header-only and VTK-free.
//
// The seed orbit (report sec. 3.2.1, Figs. 1-3): a particle at r = 100 M in the equatorial plane of a
// Schwarzschild hole of mass M = 1, starting with dphi/dtau = 0.00075 and no radial velocity. Its speed is below
// the circular one (v^2/r ~ 0.56 M/r^2), so it falls in to periapsis ~ 39 M and back: a precessing ellipse.
// It is traced for `revolutions` turns in phi (an event phi = 2 pi revolutions ends it) with lambda = proper time.
//
// A camera flight's path (observer/flight_path.hpp, a Worldline) is drawn as an orbit too: worldline_path.
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

/// Takes a metric and a sampled worldline (a camera flight: one sample per frame); returns it as a TracedPath with
/// one sample per worldline sample, in order: position = the metric's Cartesian embedding of x, state = (x, u),
/// lambda = tau, h = the proper time to the next sample (the last one repeats its predecessor's), step = the
/// sample's (frame's) index; one step record per sample with g(u, u). Status: why the worldline stopped, or
/// max_steps when it took every sample asked for (its count ran out, nothing ended it).
template <MetricPolicy M>
TracedPath worldline_path(const M& metric, const Worldline& worldline) {
  TracedPath path;
  const auto& w = worldline.samples;
  for (std::size_t i = 0; i < w.size(); ++i) {
    PathSample s;
    s.state = make_state(w[i].x, w[i].u);
    s.position = metric.to_cartesian(w[i].x);
    s.lambda = w[i].tau;
    s.h = i + 1 < w.size() ? w[i + 1].tau - w[i].tau : i > 0 ? w[i].tau - w[i - 1].tau : 0.0;
    s.step = static_cast<int>(i);
    path.samples.push_back(s);
    path.steps.push_back({s.lambda, s.h, s.state, s.position, inner_product(metric, w[i].x, w[i].u, w[i].u)});
  }
  path.status = worldline.stopped.value_or(RayStatus::max_steps);
  return path;
}

}  // namespace grtrace::viz
