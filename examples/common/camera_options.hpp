// examples/common/camera_options.hpp
// The camera options grtrace-render and grtrace-view share, declared once (each tool gives its own defaults) and
// read into typed fields with the refusals worded once:
//
//   --camera-r, --camera-theta, --camera-phi   the event: r in the metric's own radius (Boyer-Lindquist r for Kerr
//                                              in both charts), angles in degrees, theta strictly inside (0, 180)
//   --observer static|zamo                     (kerr_options.hpp: zamo is Kerr's default)
//   --velocity, --look, --up                   three comma-separated numbers each, in the observer's frame
//   --fov                                      horizontal field of view in degrees, in (0, 180)
//
// Reading takes an option source: the CommandLine itself, or grtrace-view's frame-aware one (a value not given is
// then the --frame header's). Both have text(name) and number(name); numbers are read by the rules every tool
// shares (grtrace/core/number_text.hpp, CommandLine::parse_number).
#pragma once

#include "command_line.hpp"
#include "json_writer.hpp"
#include "kerr_options.hpp"

#include "grtrace/core/types.hpp"
#include "grtrace/observer/camera_spec.hpp"

#include <numbers>
#include <string>
#include <vector>

namespace grtrace::tools {

/// One tool's defaults and the wording of its radius option's help.
struct CameraOptionDefaults {
  const char* r;
  const char* theta;
  const char* fov;
  const char* r_help;
};

/// Declares --camera-r, --camera-theta, --camera-phi, --observer, --velocity, --look, --up and --fov.
inline void declare_camera_options(CommandLine& cli, const CameraOptionDefaults& d) {
  cli.option("camera-r", d.r, d.r_help)
      .option("camera-theta", d.theta, "camera polar angle theta in degrees, strictly between 0 and 180 (90: the "
                                       "equatorial plane)")
      .option("camera-phi", "0", "camera azimuth phi in degrees");
  declare_observer_option(cli);
  cli.option("velocity", "0,0,0", "camera 3-velocity beta_r,beta_theta,beta_phi (fraction of c, observer's frame)")
      .option("look", "-1,0,0", "look direction r,theta,phi in the observer's frame (-1,0,0: at the hole)")
      .option("up", "0,-1,0", "up direction r,theta,phi in the observer's frame (0,-1,0: the north pole)")
      .option("fov", d.fov, "horizontal field of view in degrees, in (0, 180)");
}

/// The three comma-separated numbers of --name from `source` (UsageError naming the option otherwise).
template <class Source>
Vec3 read_option_triple(const Source& source, const std::string& name) {
  const std::vector<double> v = CommandLine::parse_numbers(name, source.text(name), 3);
  return {v[0], v[1], v[2]};
}

/// The camera options, typed and checked (everything but the radius, which needs the metric: check_camera_radius).
struct CameraOptions {
  double r = 0.0;              ///< the metric's own radius (Boyer-Lindquist r for Kerr)
  double theta_degrees = 0.0;  ///< in (0, 180)
  double phi_degrees = 0.0;
  double fov_degrees = 0.0;  ///< in (0, 180)
  ObserverKind observer = ObserverKind::static_observer;
  Vec3 velocity = Vec3::Zero(), look{-1.0, 0.0, 0.0}, up{0.0, -1.0, 0.0};

  /// The library's camera description of a width x height frame at this event, placed in Boyer-Lindquist
  /// (t, r, theta, phi) with (r, theta, phi) axes for every chart (spherical_position).
  CameraSpec spec(int width, int height) const {
    CameraSpec s;
    s.position = Vec4(0.0, r, theta_degrees * std::numbers::pi / 180.0, phi_degrees * std::numbers::pi / 180.0);
    s.spherical_position = true;
    s.observer = observer;
    s.velocity = velocity;
    s.look = look;
    s.up = up;
    s.width = width;
    s.height = height;
    s.fov_degrees = fov_degrees;
    return s;
  }
};

/// Reads the camera options from `source` (numbers) and `cli` (--observer, whose default depends on the metric:
/// read_observer). UsageError for a polar angle or field of view out of range, a malformed triple or observer.
template <class Source>
CameraOptions read_camera_options(const Source& source, const CommandLine& cli, const std::string& metric_name) {
  CameraOptions c;
  c.r = source.number("camera-r");
  c.theta_degrees = source.number("camera-theta");
  c.phi_degrees = source.number("camera-phi");
  if (!(c.theta_degrees > 0.0 && c.theta_degrees < 180.0))
    throw UsageError("--camera-theta must lie strictly between 0 and 180 degrees (the chart is singular on the axis)");
  c.fov_degrees = source.number("fov");
  if (!(c.fov_degrees > 0.0 && c.fov_degrees < 180.0))
    throw UsageError("--fov must lie in (0, 180) degrees, got " + source.text("fov"));
  c.observer = read_observer(cli, metric_name);
  c.velocity = read_option_triple(source, "velocity");
  c.look = read_option_triple(source, "look");
  c.up = read_option_triple(source, "up");
  return c;
}

/// The radius checks both tools make, in the metric's own radius: outside the horizon guard (`guard`, 0 for no
/// horizon) and inside the sky sphere. `r_text` is --camera-r as the user wrote it.
inline void check_camera_radius(const std::string& r_text, double camera_radius, double guard, double sky_radius) {
  if (!(camera_radius > guard))
    throw UsageError("--camera-r " + r_text + " is at or inside the horizon (guard r = " + JsonObject::number(guard) +
                     "); move the camera out");
  if (!(camera_radius < sky_radius)) throw UsageError("--camera-r must be inside --sky-radius");
}

}  // namespace grtrace::tools
