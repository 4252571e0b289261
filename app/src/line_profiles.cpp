// A disk's line profile through the front door (grtrace/app/front_door.hpp): the request checked as a frame of the
// disk scene would be (the same disk: its inner edge, the ISCO by default for Kerr, and its sense), then
// spectra/line_profile.hpp on the closed-form Kerr disk map seen from 1e7 M.
#include "frame_tracers.hpp"  // refusal_as_request_error
#include "grtrace/app/front_door.hpp"
#include "grtrace/core/number_text.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/spectra/line_profile.hpp"
#include "grtrace/spectra/line_profile_output.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace grtrace::app {

namespace {

/// The observer's distance: far enough that the profile is the one at infinity to ~1e-7 (tests/line_profile_test).
constexpr double kObserverDistance = 1e7;

}  // namespace

LineProfileResult line_profile(const LineProfileRequest& in) {
  LineProfileResult out;
  out.request = in;
  LineProfileRequest& q = out.request;
  if (q.metric.name != "kerr" && q.metric.name != "schwarzschild")
    throw RequestError(
        "--spectrum line needs --metric kerr or schwarzschild (its rays are Kerr's in closed form), "
        "got --metric " +
        q.metric.name);
  if (q.metric.name == "kerr" && q.metric.chart != "bl")
    throw RequestError("--spectrum line traces Kerr in Boyer-Lindquist coordinates: leave --chart out or use bl");
  if (!(q.inclination_degrees > 0.01 && q.inclination_degrees < 179.99))
    throw RequestError(
        "--spectrum line needs an inclination --camera-theta strictly between 0.01 and 179.99 degrees "
        "(on the axis the closed form is not defined), got " +
        shortest_number_text(q.inclination_degrees));
  // The disk as a frame of the disk scene has it (inner edge, ISCO, sense), with that frame's refusals.
  RenderRequest frame;
  frame.metric = q.metric;
  frame.scene = "disk";
  frame.disk_inner = q.disk_inner;
  frame.disk_outer = q.disk_outer;
  frame.disk_retrograde = q.disk_retrograde;
  frame.camera.theta_degrees = q.inclination_degrees;
  frame.camera.width = frame.camera.height = 1;
  const CheckedRequest checked = check_request(frame);
  const ThinDisk& disk = checked.scene.disk;
  q.disk_inner = disk.r_in;

  LineProfileSpec spec;
  spec.line_energy = q.line_energy;
  spec.bins = q.bins;
  if (q.energy_range) spec.energy_min = (*q.energy_range)[0], spec.energy_max = (*q.energy_range)[1];
  spec.emissivity.index_inner = q.emissivity_index;
  spec.emissivity.index_outer = q.emissivity_index_outer.value_or(q.emissivity_index);
  if (q.emissivity_break) spec.emissivity.r_break = *q.emissivity_break;
  spec.transparent = q.transparent;
  LineSampling sampling;
  sampling.finest_cell = q.finest_cell;
  refusal_as_request_error("", [&] { check_line_profile(spec, sampling); });
  if (q.emissivity_break && !(*q.emissivity_break > 0.0))
    throw RequestError("--emissivity-break must be a positive radius");

  KerrMetric metric;
  metric.mass = q.metric.mass;
  metric.spin = q.metric.name == "kerr" ? q.metric.spin : 0.0;
  const double inclination = q.inclination_degrees * std::numbers::pi / 180.0;
  const KerrDiskMap map = refusal_as_request_error("", [&] {
    return KerrDiskMap(metric, kObserverDistance * metric.mass, inclination, disk.r_in, disk.r_out, disk.sense);
  });

#ifdef _OPENMP
  const int threads_before = omp_get_max_threads();
  if (q.threads > 0) omp_set_num_threads(q.threads);
#endif
  const auto start = std::chrono::steady_clock::now();
  out.profile = line_profile(map, spec, sampling);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
#ifdef _OPENMP
  omp_set_num_threads(threads_before);
#endif

  const LineProfile& p = out.profile;
  const std::string spin = q.metric.name == "kerr" ? shortest_number_text(q.metric.spin) : "0";
  out.csv = line_profile_csv(
      p, {"line profile of a thin disk: --metric " + q.metric.name + " (spin " + spin + ", mass " +
              shortest_number_text(q.metric.mass) + "), inclination " + shortest_number_text(q.inclination_degrees) +
              " deg, disk " + shortest_number_text(disk.r_in) + " .. " + shortest_number_text(disk.r_out) + " M, " +
              (disk.sense > 0 ? "gas towards +phi" : "gas towards -phi") + ", " +
              (q.transparent ? "transparent" : "opaque"),
          "line energy " + shortest_number_text(q.line_energy) + ", emissivity r^-" +
              shortest_number_text(spec.emissivity.index_inner) +
              (q.emissivity_break ? " inside " + shortest_number_text(*q.emissivity_break) + " M, r^-" +
                                        shortest_number_text(spec.emissivity.index_outer) + " beyond"
                                  : ""),
          "flux: F_E per unit energy, in eps(r = M) M^2 (a distant observer's flux times D^2 / M^2); orders n = 0, "
          "1, 2, >= 3 sum to it",
          std::to_string(p.rays) + " rays, " + std::to_string(p.triangles) + " triangles"});
  out.chart = line_profile_chart(p, q.line_energy);

  auto add = [&](const std::string& key, ReportEntry::Counts::value_type::second_type v) {
    out.report.push_back({key, v});
  };
  auto add_number = [&](const std::string& key, double v) { out.report.push_back({key, v}); };
  add_number("seconds", out.seconds);
  add("rays", p.rays);
  add("triangles", p.triangles);
  add("unresolved_triangles", p.unresolved);
  add("uncovered_rays", p.uncovered);
  add_number("total_flux", p.total);
  add_number("total_flux_n0", p.total_by_order[0]);
  add_number("total_flux_n1", p.total_by_order[1]);
  add_number("total_flux_n2", p.total_by_order[2]);
  add_number("total_flux_n3_up", p.total_by_order[3]);
  add_number("flux_outside_bins", p.outside);
  add_number("energy_min", p.edges.front());
  add_number("energy_max", p.edges.back());
  add("energy_bins", static_cast<long>(q.bins));
  add_number("inclination_degrees", q.inclination_degrees);
  add_number("disk_inner", disk.r_in);
  add_number("disk_outer", disk.r_out);
  out.report.push_back({"disk", std::string(q.transparent ? "transparent" : "opaque")});
  out.report.push_back({"tracer", std::string("kerr-closed-form")});
  return out;
}

}  // namespace grtrace::app
