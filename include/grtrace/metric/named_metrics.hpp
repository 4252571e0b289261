// grtrace/metric/named_metrics.hpp
// The metrics a program can choose by name at run time (grtrace-render --metric NAME and its parameters), and one
// dispatch from the name to the concrete metric type: with_named_metric(spec, f) calls f(metric) with a
// SchwarzschildMetric, a KerrMetric, an AutoMetric<EllisWormhole>, ..., so one generic lambda renders any of them
// (each type is its own instantiation: no virtual call in the hot loop).
//
//   name              metric (chart)                                          parameters
//   schwarzschild     SchwarzschildMetric (t, r, theta, phi)                  mass
//   minkowski         MinkowskiSpherical (flat: straight lines)               -
//   kerr              KerrMetric, Boyer-Lindquist (chart "bl")                mass, spin |a| < M
//                     KerrSchildMetric, Cartesian Kerr-Schild (chart "ks"),   (cameras are placed in BL coordinates;
//                     outgoing slicing: camera rays cross the horizon)        the outgoing chart takes past-directed rays;
//                     (ingoing with MetricSpec::slicing: flights fall in)     a flight's camera crosses in the ingoing one)
//   rn                Reissner-Nordstrom, automatic Christoffels             mass, charge |Q| < M
//   sds               Schwarzschild-de Sitter, automatic Christoffels        mass, lambda in (0, 1/(9 M^2))
//   wormhole          Ellis wormhole (t, l, theta, phi), no horizon          throat b0 > 0
//   schwarzschild-ef  Schwarzschild, outgoing Eddington-Finkelstein           mass (horizon-penetrating for camera rays)
// Each is refused (std::invalid_argument, naming the option and the range) before any work when its parameters
// make no black hole or no spacetime: |a| >= M, |Q| >= M, Lambda outside the range with two horizons, b0 <= 0.
#pragma once

#include "grtrace/metric/examples/eddington_finkelstein.hpp"
#include "grtrace/metric/examples/ellis_wormhole.hpp"
#include "grtrace/metric/examples/reissner_nordstrom.hpp"
#include "grtrace/metric/examples/schwarzschild_de_sitter.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/schwarzschild.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grtrace {

inline constexpr std::array<std::string_view, 7> kMetricNames = {
    "schwarzschild", "minkowski", "kerr", "rn", "sds", "wormhole", "schwarzschild-ef"};

struct MetricSpec {
  std::string name = "schwarzschild";  ///< one of kMetricNames
  double mass = 1.0;                   ///< M (all but minkowski and wormhole)
  double spin = 0.0;                   ///< kerr: a, |a| < M (negative: rotation towards -phi)
  std::string chart = "bl";            ///< kerr: "bl" (Boyer-Lindquist) or "ks" (Kerr-Schild); others: "bl" only
  /// kerr, chart ks: outgoing (single frames: camera rays, traced into the past, cross the past horizon and are
  /// captured inside it) or ingoing (flights: the falling camera crosses the future horizon, kerr_schild_for_flights).
  KerrSchildSlicing slicing = KerrSchildSlicing::outgoing;
  double charge = 0.5;                 ///< rn: Q, |Q| < M
  double lambda = 1e-5;                ///< sds: cosmological constant, 0 < Lambda < 1 / (9 M^2) (r_c ~ 547 M)
  double throat = 1.0;                 ///< wormhole: throat radius b0
};

inline bool is_named_metric(std::string_view name) {
  for (std::string_view n : kMetricNames)
    if (n == name) return true;
  return false;
}

/// Refuses a spec that names no metric or whose parameters make none (std::invalid_argument saying what to change).
inline void check_metric_spec(const MetricSpec& s) {
  auto finite = [](double v) { return std::isfinite(v); };
  if (!is_named_metric(s.name))
    throw std::invalid_argument("unknown metric '" + s.name +
                                "'; choose schwarzschild, minkowski, kerr, rn, sds, wormhole or schwarzschild-ef");
  if (s.name != "minkowski" && s.name != "wormhole" && !(s.mass > 0.0 && finite(s.mass)))
    throw std::invalid_argument("--mass must be a positive number");
  if (s.name == "kerr") {
    if (!finite(s.spin) || !(std::abs(s.spin) < s.mass))
      throw std::invalid_argument("--spin must satisfy |a| < M (|a| >= M has no horizon); got " + std::to_string(s.spin));
    if (s.chart != "bl" && s.chart != "ks") throw std::invalid_argument("--chart must be bl or ks, got '" + s.chart + "'");
  } else if (s.chart != "bl") {  // the other metrics have one chart each: a chart asked for would be ignored
    throw std::invalid_argument("--chart " + s.chart + " goes with --metric kerr; --metric " + s.name +
                                " has one chart (leave --chart out" +
                                (s.name == "schwarzschild"
                                     ? "; across the horizon: --metric schwarzschild-ef, or --metric kerr --spin 0 "
                                       "--chart ks)"
                                     : ")"));
  }
  if (s.name == "rn" && (!finite(s.charge) || !(std::abs(s.charge) < s.mass)))
    throw std::invalid_argument("--charge must satisfy |Q| < M (|Q| >= M has no horizon); got " + std::to_string(s.charge));
  if (s.name == "sds" && (!finite(s.lambda) || !(s.lambda > 0.0 && 9.0 * s.lambda * s.mass * s.mass < 1.0)))
    throw std::invalid_argument("--lambda must lie in (0, 1/(9 M^2)) for a black hole with two horizons; got " +
                                std::to_string(s.lambda));
  if (s.name == "wormhole" && !(s.throat > 0.0 && finite(s.throat)))
    throw std::invalid_argument("--throat must be a positive number");
}

/// Calls f(metric) with the named metric (checked first). All calls of f must return the same type.
template <class F>
decltype(auto) with_named_metric(const MetricSpec& s, F&& f) {
  check_metric_spec(s);
  if (s.name == "minkowski") return f(MinkowskiSpherical{});
  if (s.name == "kerr") {
    if (s.chart == "ks")
      return f(s.slicing == KerrSchildSlicing::ingoing ? kerr_schild_for_flights(s.mass, s.spin)
                                                       : kerr_schild_for_camera_rays(s.mass, s.spin));
    return f(KerrMetric::checked(s.mass, s.spin));
  }
  if (s.name == "rn") {
    AutoReissnerNordstrom m;
    m.mass = s.mass;
    m.charge = s.charge;
    return f(m);
  }
  if (s.name == "sds") {
    AutoSchwarzschildDeSitter m;
    m.mass = s.mass;
    m.lambda = s.lambda;
    return f(m);
  }
  if (s.name == "wormhole") {
    AutoEllisWormhole m;
    m.throat = s.throat;
    return f(m);
  }
  if (s.name == "schwarzschild-ef") {
    AutoEddingtonFinkelstein m;
    m.mass = s.mass;
    m.outgoing = true;  // camera rays are past-directed: the outgoing chart carries them through r = 2M
    return f(m);
  }
  return f(SchwarzschildMetric{s.mass});
}

}  // namespace grtrace
