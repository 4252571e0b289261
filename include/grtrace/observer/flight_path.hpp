// grtrace/observer/flight_path.hpp
// A camera flight's path from what a person asks for: a named start (or a CSV of camera states), a number of frames
// and the proper time between them, sampled into a Worldline (observer/worldline.hpp). One definition for every
// program that flies a camera (grtrace-render --flight renders it, grtrace-view --flight draws it).
//
//   kind      start                                                              default frame step (dtau = 0)
//   seed      the seed report's orbit: r = 100 M, dphi/dtau = 0.00075 / M         one revolution in phi / frames
//   circular  the circular orbit at r (metric/circular_orbits.hpp)               one revolution / frames
//   orbit     (r, theta, phi) with dr/dtau and dphi/dtau                          one revolution / frames
//   infall    released from rest at (r, theta, phi)                              the fall to 1.1 r_h / (frames - 1)
//   csv       the rows of a CSV file (observer/worldline_csv.hpp), as given      -
// r_h is the metric's capture radius for the camera (metric/metric_traits.hpp capture_radius_of): the horizon in
// Schwarzschild-type charts, which cannot carry a camera across it; inside it in a chart that can (Kerr-Schild's
// ingoing slicing: kerr_schild_for_flights), so that there an infall continues through the horizon, its last frames
// inside the black hole.
// Takes:   a metric and the spec. Starts are stated in spherical (Boyer-Lindquist) coordinates in every chart
//          (observer/timelike_start.hpp maps them); circular and csv need a spherical chart, and so does the
//          automatic step of seed and orbit (a revolution counted in phi).
// Returns: the samples, every one of them (complete).
// Throws:  std::invalid_argument saying what to change, before any rendering: an unknown kind, frames outside
//          1 .. 100000, dtau < 0, a start that cannot exist (observer/timelike_start.hpp), an automatic step that
//          has no revolution or fall to measure, a path that ends (horizon) before its last frame or leaves the
//          sky sphere, a bad CSV.
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/metric/spherical_chart.hpp"
#include "grtrace/observer/timelike_start.hpp"
#include "grtrace/observer/worldline.hpp"
#include "grtrace/observer/worldline_csv.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grtrace {

inline constexpr std::array<std::string_view, 5> kFlightPathKinds = {"seed", "circular", "orbit", "infall", "csv"};

struct FlightPathSpec {
  std::string kind = "seed";  ///< one of kFlightPathKinds
  double mass = 1.0;          ///< seed: the hole's mass M (r = 100 M, dphi/dtau = 0.00075 / M)
  double r = 100.0, theta = std::numbers::pi / 2.0, phi = 0.0;  ///< circular (r), orbit and infall: the start
  double dr_dtau = 0.0, dphi_dtau = 0.00075;                    ///< orbit: the start's velocity
  int frames = 300;
  double dtau = 0.0;  ///< proper time between frames; 0: automatic (see the table above)
  std::filesystem::path csv;  ///< csv: the camera states
  double sky_radius = std::numeric_limits<double>::infinity();  ///< every frame must lie inside it
};

inline bool is_flight_path_kind(std::string_view kind) {
  return std::find(kFlightPathKinds.begin(), kFlightPathKinds.end(), kind) != kFlightPathKinds.end();
}

template <MetricPolicy M>
Worldline flight_path(const M& metric, const FlightPathSpec& spec) {
  auto number = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return std::string(buf);
  };
  if (!is_flight_path_kind(spec.kind))
    throw std::invalid_argument("unknown flight '" + spec.kind + "'; choose seed, circular, orbit, infall or csv");
  Worldline path;
  constexpr bool spherical = M::chart == Chart::spherical;
  if (!spherical && (spec.kind == "csv" || spec.kind == "circular"))
    throw std::invalid_argument("a " + spec.kind + " flight is stated in the spherical chart (t, r, theta, phi); use "
                                "it with Boyer-Lindquist coordinates (the Kerr-Schild chart flies seed, orbit and "
                                "infall)");
  if (spec.kind == "csv") {
    if constexpr (spherical) {
      WorldlineSource source;
      path = read_worldline_csv(spec.csv, &source);
      // A row on the polar axis (theta = 0 or pi) is placed kAxisOffset off it, as a camera is (make_camera): there
      // its frame is the limit of those off the axis at the row's phi, and u keeps its components (g_phi_phi u^phi^2
      // is 1e-18 r^2 u^phi^2 there, below the unit check's 1e-6).
      for (WorldlineSample& sample : path.samples)
        if (sample.x[2] >= 0.0 && sample.x[2] <= std::numbers::pi) sample.x[2] = off_axis(sample.x[2]);
      check_worldline(metric, path, &source);
    }
  } else {
    if (spec.frames < 1 || spec.frames > 100000) throw std::invalid_argument("--frames must be in 1 .. 100000");
    if (!(spec.dtau >= 0.0) || !std::isfinite(spec.dtau))
      throw std::invalid_argument("--frame-dtau must be >= 0 (0: automatic)");
    auto circular = [&] {
      if constexpr (spherical) return circular_orbit_start(metric, spec.r);
      else return TimelikeStart{};  // refused above
    };
    const TimelikeStart start = spec.kind == "seed"       ? seed_orbit_start(metric, spec.mass)
                                : spec.kind == "circular" ? circular()
                                : spec.kind == "infall"   ? radial_infall_start(metric, spec.r, spec.theta, spec.phi)
                                                          : orbit_start(metric, spec.r, spec.theta, spec.phi,
                                                                        spec.dr_dtau, spec.dphi_dtau);
    const double r0 = metric.radius(start.x);
    double dtau = spec.dtau;
    if (dtau == 0.0 && spec.kind == "infall") {
      const double rh = capture_radius_of(metric, start.state());
      const auto fall =
          rh > 0.0 && r0 > 1.1 * rh ? proper_time_until(metric, start, radius_event(metric, 1.1 * rh)) : std::nullopt;
      if (!fall)
        throw std::invalid_argument("no fall to 1.1 r_h from r = " + number(r0) +
                                    " (no horizon, already inside 1.1 r_h, or a chart that cannot carry the camera "
                                    "there); give --frame-dtau, or fall through the horizon in --metric kerr "
                                    "--chart ks");
      dtau = *fall / static_cast<double>(std::max(spec.frames - 1, 1));
    } else if (dtau == 0.0 && !spherical) {
      throw std::invalid_argument("the automatic step of a " + spec.kind + " flight counts a revolution in phi of the "
                                  "spherical chart; give --frame-dtau, or use Boyer-Lindquist coordinates");
    } else if (dtau == 0.0) {
      const auto turn = proper_time_until(metric, start, revolution_event(start));
      if (!turn)
        throw std::invalid_argument("the camera does not complete a revolution in phi (it falls in or escapes "
                                    "first); give --frame-dtau");
      dtau = *turn / static_cast<double>(spec.frames);
    }
    path = sample_worldline(metric, start, dtau, spec.frames);
    if (!path.complete())
      throw std::invalid_argument("the camera's path ends (" +
                                  std::string(kRayStatusNames[static_cast<std::size_t>(*path.stopped)]) +
                                  " at tau = " + number(path.samples.back().tau) + ") before frame " +
                                  std::to_string(path.samples.size()) +
                                  "; use fewer --frames or a smaller --frame-dtau");
  }
  for (std::size_t i = 0; i < path.samples.size(); ++i)
    if (!(metric.radius(path.samples[i].x) < spec.sky_radius))
      throw std::invalid_argument("frame " + std::to_string(i) + " is at r = " +
                                  number(metric.radius(path.samples[i].x)) +
                                  ", outside the sky sphere; raise --sky-radius");
  return path;
}

/// The proper time between the path's first two frames (0 for a single frame).
inline double frame_step(const Worldline& path) {
  return path.samples.size() > 1 ? path.samples[1].tau - path.samples[0].tau : 0.0;
}

}  // namespace grtrace
