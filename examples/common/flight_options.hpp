// examples/common/flight_options.hpp
// The camera-flight options of the tools that fly a camera (grtrace-render renders the flight, grtrace-view draws
// it and looks through one frame's camera): their names, defaults and help, their reading into a FlightPathSpec
// (observer/flight_path.hpp) and the path built from it, checked, with the refusals worded once for every tool.
//
//   --flight seed|circular|orbit|infall|csv   the path (none: no flight)
//   --frames N (300)   --frame-dtau DTAU (0: automatic)   --orbit-dr (0)   --orbit-dphi (0.00075)   --flight-csv FILE
// The start of circular, orbit and infall is --camera-r/--camera-theta/--camera-phi (degrees), which the tool
// declares with its single-frame camera.
#pragma once

#include "command_line.hpp"

#include "grtrace/core/types.hpp"
#include "grtrace/observer/flight_path.hpp"
#include "grtrace/observer/worldline.hpp"

#include <initializer_list>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

namespace grtrace::tools {

/// Takes the tool's command line, what the tool does with the path (a sentence for --flight's help) and what
/// else --orbit-dr/--orbit-dphi set in this tool ("" if nothing); declares the six flight options above with
/// grtrace-render's names and defaults.
inline void declare_flight_options(CommandLine& cli, const std::string& what_the_tool_does,
                                   const std::string& orbit_options_also) {
  cli.option("flight", "", "a camera path: seed (the seed report's orbit: r = 100 M, dphi/dtau = 0.00075/M, "
                           "equatorial) | circular (the circular orbit at --camera-r) | orbit (from "
                           "--camera-r/-theta/-phi with --orbit-dr, --orbit-dphi) | infall (from rest at --camera-r) | "
                           "csv (--flight-csv). Frames are spaced evenly in the camera's proper time; its tetrad is "
                           "rebuilt in every frame from its 4-velocity with the fixed --look/--up rule. " +
                               what_the_tool_does)
      .option("frames", "300", "flight: number of frames")
      .option("frame-dtau", "0", "flight: proper time between frames; 0: one revolution in phi over the frames "
                                 "(seed, circular, orbit) or the fall to 1.1 r_h (infall; with --chart ks r_h is "
                                 "the capture radius inside the horizon: the camera falls through it)")
      .option("orbit-dr", "0", "flight orbit: initial dr/dtau" + orbit_options_also)
      .option("orbit-dphi", "0.00075", "flight orbit: initial dphi/dtau" + orbit_options_also)
      .option("flight-csv", "", "flight csv: camera states, a header line then rows "
                                "tau,t,r,theta,phi,ut,ur,utheta,uphi (angles in radians, g(u,u) = 1)");
}

/// Takes the command line (flight options declared by declare_flight_options, camera-r/-theta/-phi in degrees),
/// the hole's mass, the sky sphere's radius and the tool's other options that only make sense with --flight.
/// Returns the path's spec, or nothing without --flight. Throws UsageError naming the option for a flight option
/// without --flight or with a kind that ignores it (a csv flight takes no --frames or --frame-dtau), an unknown
/// kind, --flight csv without --flight-csv (or the reverse), --frames outside 1 .. 100000. What only the path can
/// tell (a start that cannot exist, a path that ends early) is checked_flight_path's.
inline std::optional<FlightPathSpec> read_flight_spec(const CommandLine& cli, double mass, double sky_radius,
                                                      std::initializer_list<const char*> needing_flight) {
  const std::string kind = cli.text("flight");
  if (kind.empty()) {
    for (const char* name : {"frames", "frame-dtau", "flight-csv"})
      if (cli.given(name)) throw UsageError(std::string("--") + name + " needs --flight (a camera path)");
    for (const char* name : needing_flight)
      if (cli.given(name)) throw UsageError(std::string("--") + name + " needs --flight (a camera path)");
    return std::nullopt;
  }
  if (!is_flight_path_kind(kind))
    throw UsageError("unknown --flight '" + kind + "'; choose seed, circular, orbit, infall or csv");
  if ((kind == "csv") != !cli.text("flight-csv").empty())
    throw UsageError("--flight csv goes with --flight-csv FILE (and --flight-csv only with --flight csv)");
  refuse_inapplicable_options(cli, {{"frames", kind != "csv", "a computed path (a csv flight has one frame per row)"},
                                    {"frame-dtau", kind != "csv", "a computed path (a csv flight's rows give tau)"}});
  const long frames = cli.integer("frames");
  if (frames < 1 || frames > 100000) throw UsageError("--frames must be in 1 .. 100000");
  FlightPathSpec spec;
  spec.kind = kind;
  spec.mass = mass;
  spec.r = cli.number("camera-r");
  spec.theta = cli.number("camera-theta") * std::numbers::pi / 180.0;
  spec.phi = cli.number("camera-phi") * std::numbers::pi / 180.0;
  spec.dr_dtau = cli.number("orbit-dr");
  spec.dphi_dtau = cli.number("orbit-dphi");
  spec.frames = static_cast<int>(frames);
  spec.dtau = cli.number("frame-dtau");
  spec.csv = cli.text("flight-csv");
  spec.sky_radius = sky_radius;
  return spec;
}

/// Takes read_flight_spec's spec and what samples its path (the application layer's app::flight_worldline, which
/// the tools call, or flight_path in one metric); returns the path. Throws UsageError saying what to change: the
/// library's refusal (observer/flight_path.hpp) prefixed with "--flight KIND: ".
template <class SamplePath>
Worldline checked_flight_path(const FlightPathSpec& spec, SamplePath&& sample_path) {
  try {
    return sample_path();
  } catch (const std::invalid_argument& e) {
    throw UsageError("--flight " + spec.kind + ": " + e.what());
  }
}

}  // namespace grtrace::tools
