// examples/common/kerr_options.hpp
// The options of a Kerr hole's picture that grtrace-render and grtrace-view share (issue 12): their names,
// defaults and help, and their reading, with the refusals worded once for both tools.
//
//   --chart bl|ks           kerr: Boyer-Lindquist or Kerr-Schild coordinates (the camera is placed in BL for both)
//   --observer static|zamo  the observer carrying the camera; default zamo for kerr, static otherwise
//   --disk-retrograde       the disk turns against the hole; for kerr the disk's inner edge defaults to the ISCO of
//                           its sense and --disk-inner inside that ISCO is refused
// The static observer's refusal inside the ergosphere is the library's (observer/observers.hpp), so both tools
// give the same message by building the camera with make_camera.
#pragma once

#include "command_line.hpp"

#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/observers.hpp"
#include "grtrace/scene/thin_disk.hpp"

#include <optional>
#include <sstream>
#include <string>

namespace grtrace::tools {

/// --chart's help for the coordinate charts (a tool that gives --chart more values appends to it).
inline const std::string kKerrChartHelp =
    "kerr: bl (Boyer-Lindquist) | ks (Kerr-Schild, horizon-penetrating); the camera is placed in Boyer-Lindquist "
    "coordinates for both";

/// Takes the tool's command line; declares --observer (default static: read it with observer_name).
inline void declare_observer_option(CommandLine& cli) {
  cli.option("observer", "static", "static | zamo: the observer whose frame carries the camera (same for a "
                                   "non-rotating hole); --metric kerr defaults to zamo (valid in the ergosphere)");
}

/// Takes the tool's command line and what else the flag does in this tool ("" if nothing); declares
/// --disk-retrograde.
inline void declare_disk_retrograde_flag(CommandLine& cli, const std::string& also) {
  cli.flag("disk-retrograde", "disk scene: the gas turns against the hole's rotation (default: with it; towards "
                              "+phi for a non-rotating hole)" + also);
}

/// --disk-inner's help: its default and, for kerr, the ISCO bound.
inline std::string disk_inner_help() {
  return "disk inner radius (disk scene); kerr: default and lower bound the ISCO of the disk's sense (BPT 1972), "
         "e.g. 2.32 for a = 0.9 prograde";
}

/// The observer carrying the camera: --observer as given, else the ZAMO for Kerr (it exists everywhere outside the
/// horizon, the static observer not inside the ergosphere) and the static observer for the other metrics.
inline std::string observer_name(const CommandLine& cli, const std::string& metric_name) {
  if (cli.given("observer")) return cli.text("observer");
  return metric_name == "kerr" ? "zamo" : "static";
}

/// observer_name as an ObserverKind; throws UsageError for a name that is neither static nor zamo.
inline ObserverKind read_observer(const CommandLine& cli, const std::string& metric_name) {
  const auto observer = observer_kind_from_string(observer_name(cli, metric_name));
  if (!observer) throw UsageError("unknown --observer '" + cli.text("observer") + "'; choose static or zamo");
  return *observer;
}

/// The disk's sense of rotation and, for Kerr, its inner edge: the ISCO of that sense when no inner edge was asked
/// for, and a refusal (UsageError naming the ISCO) when one was asked for inside the ISCO, where no stable circular
/// orbit exists. Takes the checked metric spec, the sense (retrograde: against the hole), the inner edge's text as
/// asked for (--disk-inner, or a frame's header; nothing: not asked for) and the disk, whose r_in holds the edge
/// asked for; sets disk.sense (+1: towards +phi; prograde follows the sign of the spin, +phi for a = 0) and
/// disk.r_in.
inline void set_disk_sense_and_isco(const MetricSpec& ms, bool retrograde, const std::optional<std::string>& inner,
                                    ThinDisk& disk) {
  const int hole = ms.name == "kerr" && ms.spin < 0.0 ? -1 : +1;
  disk.sense = retrograde ? -hole : hole;
  if (ms.name != "kerr") return;  // Schwarzschild and the others keep --disk-inner as given (default 6)
  const exact::Orbit orbit = retrograde ? exact::Orbit::retrograde : exact::Orbit::prograde;
  const double isco = exact::isco_radius(ms.spin, orbit, ms.mass);
  if (!inner) {
    disk.r_in = isco;
  } else if (!(disk.r_in >= isco * (1.0 - 1e-12))) {  // the printed ISCO itself is accepted
    std::ostringstream msg;
    msg.precision(10);
    msg << "--disk-inner " << *inner << " is inside the ISCO r_isco = " << isco << " M of this "
        << (retrograde ? "retrograde" : "prograde") << " disk (a = " << ms.spin
        << "): no stable circular orbit exists there; raise --disk-inner to at least the ISCO or leave it out";
    throw UsageError(msg.str());
  }
}

/// set_disk_sense_and_isco with the sense and the inner edge of the command line (--disk-retrograde, --disk-inner).
inline void set_disk_sense_and_isco(const CommandLine& cli, const MetricSpec& ms, ThinDisk& disk) {
  const std::optional<std::string> inner =
      cli.given("disk-inner") ? std::optional<std::string>(cli.text("disk-inner")) : std::nullopt;
  set_disk_sense_and_isco(ms, cli.flag_set("disk-retrograde"), inner, disk);
}

}  // namespace grtrace::tools
