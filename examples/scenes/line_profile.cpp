// examples/scenes/line_profile.cpp
// The iron line of a thin disk around a Kerr hole as a distant observer sees it (spectra/line_profile.hpp): the
// flux per energy bin, in total and by image order n = 0, 1, 2, >= 3, integrated over the image plane on an
// adaptive mesh, each ray in closed form. Writes a CSV and a PNG plot of it beside (one set: both new or both old).
//   line_profile [--out line.csv] [--spin 0.9] [--inclination 30] [--r-in 0 (the ISCO)] [--r-out 30]
//                [--index 3] [--index-outer 3] [--r-break 0 (none)] [--line 6.4] [--bins 120]
//                [--finest 0.015625] [--transparent 0|1]
#include "grtrace/spectra/line_profile.hpp"

#include "example_cli.hpp"
#include "grtrace/core/number_text.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/spectra/line_profile_output.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace grtrace;

/// "--name value" pairs over the defaults; std::invalid_argument for an unknown name or a value that is no number.
std::map<std::string, std::string> parse(int argc, char** argv, std::map<std::string, std::string> values) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help") {
      std::cout << "usage: line_profile";
      for (const auto& [name, value] : values) std::cout << " [--" << name << " " << value << "]";
      std::cout << "\n";
      throw NothingMoreToDo{};
    }
    if (arg.rfind("--", 0) != 0 || !values.count(arg.substr(2)) || i + 1 >= argc)
      throw std::invalid_argument("unknown option or missing value: '" + arg + "' (see --help)");
    values[arg.substr(2)] = argv[++i];
  }
  return values;
}

double number(const std::map<std::string, std::string>& v, const std::string& name) {
  std::size_t used = 0;
  double x = std::numeric_limits<double>::quiet_NaN();
  try {
    x = std::stod(v.at(name), &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.at(name).size() || !std::isfinite(x))
    throw std::invalid_argument("--" + name + " needs a number, got '" + v.at(name) + "'");
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  return run_example("line_profile", [&] {
    const auto v = parse(argc, argv,
                         {{"out", "line.csv"},
                          {"spin", "0.9"},
                          {"inclination", "30"},
                          {"r-in", "0"},
                          {"r-out", "30"},
                          {"index", "3"},
                          {"index-outer", "3"},
                          {"r-break", "0"},
                          {"line", "6.4"},
                          {"bins", "120"},
                          {"finest", "0.015625"},
                          {"transparent", "0"}});
    const std::string out = v.at("out");
    if (out.size() < 5 || out.substr(out.size() - 4) != ".csv")
      throw std::invalid_argument("--out must name a .csv file (the PNG is written beside it), got '" + out + "'");
    const std::string png = out.substr(0, out.size() - 4) + ".png";
    const double spin = number(v, "spin"), inclination = number(v, "inclination");
    if (!(std::abs(spin) < 1.0)) throw std::invalid_argument("--spin must lie in (-1, 1)");
    if (!(inclination > 0.01 && inclination < 179.99))
      throw std::invalid_argument("--inclination must lie in (0.01, 179.99) degrees");
    const double r_in = number(v, "r-in") > 0.0 ? number(v, "r-in") : exact::isco_radius(spin, exact::Orbit::prograde);
    LineProfileSpec spec;
    spec.line_energy = number(v, "line");
    spec.bins = static_cast<int>(number(v, "bins"));
    spec.emissivity.index_inner = number(v, "index");
    spec.emissivity.index_outer = number(v, "index-outer");
    if (number(v, "r-break") > 0.0) spec.emissivity.r_break = number(v, "r-break");
    spec.transparent = number(v, "transparent") != 0.0;
    LineSampling sampling;
    sampling.finest_cell = number(v, "finest");
    check_line_profile(spec, sampling);
    check_output_path(out);
    check_output_path(png);
    KerrMetric metric;
    metric.spin = spin;
    const KerrDiskMap map(metric, 1e7, inclination * std::numbers::pi / 180.0, r_in, number(v, "r-out"));

    const auto start = std::chrono::steady_clock::now();
    const LineProfile p = line_profile(map, spec, sampling);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const std::string text = line_profile_csv(
        p, {"line profile: spin " + shortest_number_text(spin) + ", inclination " + shortest_number_text(inclination) +
                " deg, disk " + shortest_number_text(r_in) + " .. " + shortest_number_text(map.r_out()) + " M (" +
                (spec.transparent ? "transparent" : "opaque") + "), emissivity r^-" +
                shortest_number_text(spec.emissivity.index_inner) + " (r^-" +
                shortest_number_text(spec.emissivity.index_outer) + " beyond " +
                shortest_number_text(spec.emissivity.r_break) + "), line " + shortest_number_text(spec.line_energy),
            "flux: F_E per unit energy, eps(r = M) M^2 units (a distant observer's flux times D^2 / M^2); " +
                std::to_string(p.rays) + " rays"});
    const LineChart chart = line_profile_chart(p, spec.line_energy);
    OutputSet set;
    TemporaryOutput& file = set.add(out);
    file.write(text.data(), text.size());
    file.finish();
    write_png_rgb8(set, png, chart.width, chart.height, chart.rgb);
    set.commit();
    std::printf(
        "{\"seconds\": %.3f, \"rays\": %ld, \"triangles\": %ld, \"total\": %.8g, \"total_n0\": %.8g, "
        "\"total_n1\": %.8g, \"total_n2\": %.8g, \"total_n3_up\": %.8g, \"outside\": %.3g, \"csv\": \"%s\", "
        "\"png\": \"%s\"}\n",
        seconds, p.rays, p.triangles, p.total, p.total_by_order[0], p.total_by_order[1], p.total_by_order[2],
        p.total_by_order[3], p.outside, out.c_str(), png.c_str());
  });
}
