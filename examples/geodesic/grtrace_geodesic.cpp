// grtrace-geodesic: trace one geodesic (null or timelike) in Schwarzschild or flat spacetime and print
// ONE line of JSON (contract in shared/DESIGN.md):
//   {"status","deflection","steps","rejected","rhs_evals","constraint_drift","final":{...}, ...}
// --impact B traces a photon from far away with impact parameter B; "deflection" is the total bending from
// infinity to infinity (the legs outside the integrated region are added exactly), with the exact value
// and the error beside it. --path FILE.csv writes every accepted step (lambda, x^mu, k^mu, h).
// --vtp FILE.vtp writes the same points as a VTK XML polyline for ParaView (grtrace/viz/vtk_export.hpp: point data
// affine_parameter, step_size, redshift, status, pixel, ...; the redshift is relative to the static observer at the
// start event); it needs the build with VTK (grtrace::viz). The files of one run are renamed into place together.
// --metric kerr --spin A [--chart bl|ks]: Kerr in Boyer-Lindquist or Kerr-Schild coordinates. Positions and
// velocities are given in Boyer-Lindquist (t, r, theta, phi) for both charts; the JSON adds the conserved energy
// E, axial angular momentum L_z and Carter constant Q at the start and their drifts; --impact B traces an
// equatorial photon with E = 1, L_z = B (B > 0: towards +phi, prograde for A > 0) and compares its deflection with
// the exact equatorial result (Iyer & Hansen 2009, exact/kerr_exact.hpp).
#include "geodesic_run.hpp"

#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

using namespace grtrace;
using namespace grtrace::geodesic_tool;

int main(int argc, char** argv) {
  CommandLine cli = make_command_line();
  return tools::run_tool(cli, argc, argv, [&] {
    const Request q = read_request(cli);
    const std::string tableau = cli.text("tableau"), control = cli.text("control");
    const auto error = dispatch_method(tableau, control, []<class T, class C>() {});  // names checked, nothing run
    if (error != DispatchError::none) throw UsageError(describe(error, tableau, control));
    if (cli.write_config_if_asked()) return 0;  // checked as for a run (output paths: at the run)
    const Outputs files{cli.text("path"), cli.text("vtp")};
    if (cli.given("path")) tools::check_command_output(cli, "path", files.path, {});  // --path "" is refused
    if (cli.given("vtp")) {
#if !GRTRACE_GEODESIC_VTP
      throw UsageError("--vtp: this grtrace-geodesic was built without VTK (grtrace::viz)");
#endif
      tools::check_command_output(cli, "vtp", files.vtp, {});
      if (!files.path.empty() && same_file(files.vtp, files.path))
        throw UsageError("--vtp and --path name the same file '" + files.vtp + "'");
    }
    std::optional<JsonObject> json = run_low_order(q, files, tableau, control);
    if (!json) json = run_fifth_order(q, files, tableau, control);
    if (!json) json = run_high_order(q, files, tableau, control);
    if (!json) throw std::logic_error("grtrace-geodesic: tableau '" + tableau + "' is in no group");
    std::cout << json->str() << std::endl;
    return 0;
  });
}
