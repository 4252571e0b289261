// grtrace-render --metric kerr as a program: bad Kerr input is refused before any ray is traced (exit
// code 2, a message on stderr that says what to change, nothing on stdout, no file left behind); the disk defaults
// to the ISCO of its sense and the EXR header records spin, chart, observer, the disk's sense and radii and the
// tracer auto picked (kerr-mino in Boyer-Lindquist with an adaptive controller, general otherwise).
//
// The binary: GRTRACE_RENDER_BINARY if CMake defines it for this target (tests/render/CMakeLists.txt), else
// <build>/examples/render/grtrace-render next to this test's <build>/tests/render/.
#include "../common/tool_run.hpp"
#include "grtrace/core/physical_units.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/spectra/line_profile.hpp"
#include "grtrace/spectra/ring_image.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using grtrace::tool_tests::ToolRun;

fs::path render_binary() {
#ifdef GRTRACE_RENDER_BINARY
  return grtrace::tool_tests::tool_path(GRTRACE_RENDER_BINARY, "render", "grtrace-render");
#else
  return grtrace::tool_tests::tool_path(nullptr, "render", "grtrace-render");
#endif
}

class KerrCli : public ::testing::Test {
 protected:
  void SetUp() override {
    binary_ = render_binary();
    ASSERT_TRUE(fs::exists(binary_)) << "grtrace-render not found at " << binary_
                                     << "; build the grtrace-render target first";
    fs::create_directories(base_ / "out");
  }

  /// Runs the tool with args (stdout captured, stderr apart through a file outside out/).
  ToolRun run(const std::vector<std::string>& args) const {
    return grtrace::tool_tests::run_tool(binary_, args, base_);
  }

  bool out_empty() const { return fs::is_empty(base_ / "out"); }

  struct BadCase {
    std::vector<std::string> args;
    std::string says;  ///< a piece of the message that tells what is wrong
  };

  /// Each case's arguments after `base`, then --out `target`: refused with exit 2 and a message that says `says`,
  /// leaving no file.
  void expect_refused(const std::vector<std::string>& base, const std::vector<BadCase>& bad,
                      const fs::path& target) const {
    for (const auto& c : bad) {
      std::vector<std::string> a = base;
      for (const auto& x : c.args) a.push_back(x);
      for (const std::string& x : std::vector<std::string>{"--out", target.string()}) a.push_back(x);
      const ToolRun refused = run(a);
      std::string shown;
      for (const auto& x : c.args) shown += x + " ";
      EXPECT_EQ(refused.status, 2) << shown << "\n" << refused.err;
      EXPECT_NE(refused.err.find(c.says), std::string::npos) << shown << ": should say '" << c.says << "':\n"
                                                             << refused.err;
      EXPECT_TRUE(out_empty()) << shown;
    }
  }
  fs::path out(const std::string& name) const { return base_ / "out" / name; }

  grtrace::tool_tests::ScratchDir scratch_{"grtrace_kerr_cli"};
  fs::path binary_, base_ = scratch_.path();
};

/// A small, fast Kerr frame: args plus the size, loose tolerances (where the step is adaptive) and the output path.
std::vector<std::string> kerr(std::vector<std::string> args, const std::string& out) {
  const bool fixed = std::find(args.begin(), args.end(), "fixed") != args.end();
  for (const char* a : {"--metric", "kerr", "--width", "20", "--height", "12"}) args.emplace_back(a);
  if (!fixed)
    for (const char* a : {"--rtol", "1e-7", "--atol", "1e-9"}) args.emplace_back(a);
  args.emplace_back("--out");
  args.push_back(out);
  return args;
}

TEST_F(KerrCli, RefusesBadKerrInputBeforeTracingAndLeavesNoFile) {
  const std::string target = out("frame.exr").string();
  const std::vector<BadCase> bad = {
      {{"--spin", "1"}, "|a| < M"},                 // extremal: no horizon to speak of
      {{"--spin", "-1.2"}, "|a| < M"},              // naked singularity
      {{"--spin", "2", "--mass", "2"}, "|a| < M"},  // |a| = M with M = 2
      {{"--spin", "nan"}, "--spin"},                //
      {{"--spin", "0.9", "--camera-r", "1.8", "--camera-theta", "90", "--observer", "static"}, "ergosphere"},
      {{"--spin", "0.9", "--camera-r", "1.8", "--camera-theta", "90", "--observer", "static", "--chart", "ks"},
       "ergosphere"},
      {{"--spin", "0.9", "--camera-r", "1.2"}, "horizon"},  // r_+ = 1.436
      {{"--spin", "0.9", "--camera-r", "1.2", "--chart", "ks"}, "horizon"},
      {{"--spin", "0.9", "--scene", "disk", "--disk-inner", "2"}, "ISCO"},  // prograde ISCO 2.32
      {{"--spin", "0.9", "--scene", "disk", "--disk-inner", "6", "--disk-retrograde"}, "ISCO"},  // retro 8.72
      {{"--spin", "-0.9", "--scene", "disk", "--disk-inner", "2.3"}, "ISCO"},  // prograde follows the spin's sign
      {{"--spin", "0.9", "--scene", "disk", "--chart", "ks", "--disk-inner", "2"}, "ISCO"},  // checked in BL
  };
  for (const auto& c : bad) {
    const ToolRun r = run(kerr(c.args, target));
    std::string shown;
    for (const auto& a : c.args) shown += a + " ";
    EXPECT_EQ(r.status, 2) << shown << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << shown << "\n" << r.out;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << shown << ": message should say '" << c.says << "':\n" << r.err;
    EXPECT_TRUE(out_empty()) << shown;
  }
  // The ISCO refusal names the value to use.
  const ToolRun r = run(kerr({"--spin", "0.9", "--scene", "disk", "--disk-inner", "2"}, target));
  EXPECT_NE(r.err.find("2.3208"), std::string::npos) << r.err;
}

TEST_F(KerrCli, DiskDefaultsToTheIscoOfItsSenseAndTheHeaderSaysSo) {
  struct Case {
    std::vector<std::string> args;
    double spin;
    grtrace::exact::Orbit orbit;
    std::string sense, observer, chart, tracer;  ///< tracer: the one auto picks (or --tracer asks for)
  };
  using grtrace::exact::Orbit;
  const std::vector<Case> cases = {
      {{"--spin", "0.9"}, 0.9, Orbit::prograde, "prograde", "zamo", "bl", "kerr-closed-form"},
      {{"--spin", "0.9", "--disk-retrograde", "--observer", "static"}, 0.9, Orbit::retrograde, "retrograde", "static",
       "bl", "kerr-closed-form"},
      {{"--spin", "-0.5", "--tracer", "general"}, -0.5, Orbit::prograde, "prograde", "zamo", "bl", "general"},
      {{"--spin", "0.9", "--chart", "ks"}, 0.9, Orbit::prograde, "prograde", "zamo", "ks", "general"},  // KS disk too
      {{"--spin", "0.5", "--tableau", "rk4", "--control", "fixed", "--step", "0.5"}, 0.5, Orbit::prograde, "prograde",
       "zamo", "bl", "general"},  // a fixed step means something else in Mino time
  };
  for (const auto& c : cases) {
    const std::string path = out("disk.exr").string();
    std::vector<std::string> args = c.args;
    for (const char* a : {"--scene", "disk", "--camera-r", "40", "--camera-theta", "80", "--fov", "50"})
      args.emplace_back(a);
    const ToolRun r = run(kerr(args, path));
    ASSERT_EQ(r.status, 0) << r.err;
    const grtrace::Image img = grtrace::read_exr(path);
    const auto& md = img.metadata;
    EXPECT_DOUBLE_EQ(std::stod(md.at("spin")), c.spin);
    EXPECT_EQ(md.at("chart"), c.chart);
    EXPECT_EQ(md.at("observer"), c.observer);
    EXPECT_EQ(md.at("tracer"), c.tracer);
    EXPECT_EQ(md.at("disk_sense"), c.sense);
    EXPECT_NEAR(std::stod(md.at("disk_inner")), grtrace::exact::isco_radius(c.spin, c.orbit), 1e-12);
    // The disk is in the picture.
    long hits = 0;
    for (float o : img.channel("object")) hits += o == 2.0f;
    EXPECT_GT(hits, 5);
    fs::remove(path);
    fs::remove(out("disk.png"));
  }
  // Schwarzschild keeps its default inner edge 6 M.
  const std::string path = out("schw.exr").string();
  const ToolRun r = run({"--scene", "disk", "--width", "8", "--height", "8", "--rtol", "1e-7", "--atol", "1e-9",
                         "--camera-r", "40", "--out", path});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(grtrace::read_exr(path).metadata.at("disk_inner"), "6");
}

// Every tracer the report names can be asked for by that name: the same frame as auto's where auto picks it, and a
// refusal that says why (and what to ask for) where it cannot draw the request.
TEST_F(KerrCli, EveryTracerTheReportNamesCanBeAskedForByName) {
  const std::vector<std::string> disk = {"--scene", "disk", "--spin", "0.9", "--camera-r", "40", "--camera-theta",
                                         "80", "--fov", "50"};
  std::vector<std::string> named = disk;
  named.insert(named.end(), {"--tracer", "kerr-closed-form"});
  const ToolRun picked = run(kerr(disk, out("auto.exr").string()));
  const ToolRun asked = run(kerr(named, out("mino.exr").string()));
  ASSERT_EQ(picked.status, 0) << picked.err;
  ASSERT_EQ(asked.status, 0) << asked.err;
  EXPECT_NE(asked.out.find("\"tracer\":\"kerr-closed-form\""), std::string::npos) << asked.out;
  const grtrace::Image a = grtrace::read_exr(out("auto.exr")), b = grtrace::read_exr(out("mino.exr"));
  EXPECT_EQ(a.metadata.at("tracer"), "kerr-closed-form");
  for (const std::string& channel : a.channel_names()) {  // bit for bit (NaN where a pixel has no sky direction)
    const auto &x = a.channel(channel), &y = b.channel(channel);
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << channel;
  }
  // Flat space by its name.
  const ToolRun flat = run({"--metric", "minkowski", "--tracer", "straight-line", "--width", "8", "--height", "8",
                            "--out", out("flat.exr").string()});
  ASSERT_EQ(flat.status, 0) << flat.err;
  EXPECT_NE(flat.out.find("\"tracer\":\"straight-line\""), std::string::npos) << flat.out;
  for (const char* name : {"auto.exr", "auto.png", "mino.exr", "mino.png", "flat.exr", "flat.png"}) fs::remove(out(name));

  const BadCase refused[] = {
      {{"--metric", "schwarzschild", "--tracer", "kerr-mino"}, "--tracer kerr-mino needs --metric kerr --chart bl"},
      {{"--metric", "kerr", "--spin", "0.5", "--chart", "ks", "--tracer", "kerr-mino"},
       "--tracer kerr-mino needs --metric kerr --chart bl"},
      {{"--metric", "kerr", "--tracer", "kerr-mino", "--tableau", "rk4", "--control", "fixed", "--step", "0.5"},
       "--tracer kerr-mino integrates in Mino time, where a fixed --step would mean something else"},
      {{"--metric", "kerr", "--tracer", "planar"}, "--tracer planar needs a static spherically symmetric metric"},
      {{"--metric", "schwarzschild", "--tracer", "straight-line"}, "--tracer straight-line draws flat space only"},
      {{"--tracer", "mino"},
       "unknown --tracer 'mino'; choose auto, general, planar, kerr-mino, kerr-closed-form or straight-line"},
  };
  for (const BadCase& c : refused) {
    std::vector<std::string> args = c.args;
    for (const char* word : {"--width", "8", "--height", "8", "--out"}) args.emplace_back(word);
    args.push_back(out("refused.exr").string());
    const ToolRun r = run(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.says << "\n" << r.err;
    EXPECT_TRUE(out_empty());
  }
}

// A camera where a telescope is (Sgr A* is at 4.3e10 M from Earth, M87* at 5.4e10 M): a row of pixels across the
// hole, 0.1 M of impact parameter apart, shows the shadow's width to within a pixel: 2 x 3 sqrt(3) M around
// Schwarzschild (the planar table), from one equatorial critical impact parameter to the other around Kerr (the
// reduced tracer; Bardeen's shadow seen edge-on). Kerr-Schild's chart refuses a camera beyond 2e5 M, naming it.
TEST_F(KerrCli, CamerasWhereTelescopesAreDrawTheShadowOfItsSize) {
  const double r = 4e10, half = 8.0;  // the row spans impact parameters -8 M .. 8 M
  char fov[64];
  std::snprintf(fov, sizeof fov, "%.17g", 2.0 * std::atan(half / r) * 180.0 / std::numbers::pi);
  const auto captured_edges = [&](std::vector<std::string> args) {
    for (const char* a : {"--scene", "sky", "--camera-r", "4e10", "--sky-radius", "1e11", "--width", "161", "--height",
                          "1", "--out"})
      args.emplace_back(a);
    args.push_back(out("far.exr").string());
    args.insert(args.end(), {"--fov", fov});
    const ToolRun run_far = run(args);
    EXPECT_EQ(run_far.status, 0) << run_far.err;
    const grtrace::Image img = grtrace::read_exr(out("far.exr"));
    std::array<double, 2> edges{1e9, -1e9};  // impact parameter of the first and last captured pixel
    for (int col = 0; col < 161; ++col)
      if (img.channel("status")[static_cast<std::size_t>(col)] == 1.0f) {
        const double b = half * (2.0 * col / 160.0 - 1.0);
        edges = {std::min(edges[0], b), std::max(edges[1], b)};
      }
    fs::remove(out("far.exr"));
    fs::remove(out("far.png"));
    return edges;
  };
  const double pixel = 0.1, bc = 3.0 * std::sqrt(3.0);
  const auto schwarzschild = captured_edges({"--metric", "schwarzschild"});
  EXPECT_NEAR(schwarzschild[0], -bc, pixel);
  EXPECT_NEAR(schwarzschild[1], bc, pixel);
  const auto kerr_edges = captured_edges({"--metric", "kerr", "--spin", "0.9"});
  const double b1 = grtrace::exact::equatorial_critical_impact(0.9, 1.0),
               b2 = grtrace::exact::equatorial_critical_impact(0.9, -1.0);
  EXPECT_NEAR(kerr_edges[1] - kerr_edges[0], std::abs(b1 - b2), 2.0 * pixel) << b1 << " " << b2;
  EXPECT_NEAR(std::abs(kerr_edges[1] + kerr_edges[0]), std::abs(b1 + b2), 2.0 * pixel) << b1 << " " << b2;
  const ToolRun ks = run(kerr({"--spin", "0.5", "--chart", "ks", "--camera-r", "3e5", "--sky-radius", "1e6"},
                              out("ks.exr").string()));
  EXPECT_EQ(ks.status, 2) << ks.err;
  EXPECT_NE(ks.err.find("the Kerr-Schild chart draws cameras out to r = 2e5 M"), std::string::npos) << ks.err;
  EXPECT_TRUE(out_empty());
  // Its sky sphere: every ray reaches one at 1e50 M; one farther out is refused, naming that radius (every ray ended
  // as max_steps at 1e55 M, and at 1e80 M the sky's emitters were refused as "beyond a horizon").
  const ToolRun far_sky = run(kerr({"--spin", "0.5", "--chart", "ks", "--scene", "sky", "--camera-r", "30",
                                    "--sky-radius", "1e50"},
                                   out("ks.exr").string()));
  ASSERT_EQ(far_sky.status, 0) << far_sky.err;
  for (const char* failure : {"\"max_steps\":0", "\"step_underflow\":0", "\"non_finite\":0"})
    EXPECT_NE(far_sky.out.find(failure), std::string::npos) << far_sky.out;
  fs::remove(out("ks.exr"));
  fs::remove(out("ks.png"));
  for (const char* sky : {"1e55", "1e80"}) {
    const ToolRun refused = run(kerr({"--spin", "0.5", "--chart", "ks", "--sky-radius", sky}, out("ks.exr").string()));
    EXPECT_EQ(refused.status, 2) << refused.err;
    EXPECT_NE(refused.err.find("the Kerr-Schild chart's sky sphere can lie out to r = 1e50 M"), std::string::npos)
        << refused.err;
  }
  EXPECT_TRUE(out_empty());
}

// A face-on view: --camera-theta 0 or 180 (the camera 1e-9 rad off the axis) for Kerr in both charts and for
// Schwarzschild, as a frame and as a fall along the axis; no ray fails in any, and the face-on disk fills the frame
// around the shadow. Angles outside [0, 180] are refused.
TEST_F(KerrCli, ACameraOnTheAxisDrawsTheDiskFaceOn) {
  const std::vector<std::vector<std::string>> cases = {
      {"--metric", "kerr", "--spin", "0.9", "--camera-theta", "0"},
      {"--metric", "kerr", "--spin", "0.9", "--camera-theta", "180"},
      {"--metric", "kerr", "--spin", "0.9", "--camera-theta", "0", "--chart", "ks"},
      {"--metric", "schwarzschild", "--camera-theta", "180"},
      {"--metric", "kerr", "--spin", "0.9", "--camera-theta", "0", "--flight", "infall", "--frames", "3"},
  };
  for (std::vector<std::string> args : cases) {
    std::string shown;
    for (const auto& a : args) shown += a + " ";
    for (const char* a :
         {"--scene", "disk", "--camera-r", "30", "--fov", "60", "--width", "24", "--height", "24", "--out"})
      args.emplace_back(a);
    args.push_back(out("axis.exr").string());
    const ToolRun r = run(args);
    ASSERT_EQ(r.status, 0) << shown << r.err;
    const bool flight = shown.find("--flight") != std::string::npos;
    if (flight) {
      EXPECT_NE(r.out.find("\"frames_with_failed_rays\":[]"), std::string::npos) << shown << r.out;
    } else {
      for (const char* failure : {"\"max_steps\":0", "\"step_underflow\":0", "\"non_finite\":0"})
        EXPECT_NE(r.out.find(failure), std::string::npos) << shown << r.out;
    }
    const grtrace::Image img = grtrace::read_exr(out(flight ? "axis-0000.exr" : "axis.exr"));
    const auto& object = img.channel("object");
    EXPECT_GT(std::count(object.begin(), object.end(), 2.0f), 300) << shown << "the disk, face-on";
    EXPECT_GT(std::count(object.begin(), object.end(), 1.0f), 10) << shown << "the shadow";
    for (const auto& entry : fs::directory_iterator(base_ / "out")) fs::remove(entry.path());
  }
  // A camera path over the north pole (a file of camera states, one frame each), through a row on the axis itself
  // (placed 1e-9 rad off it, as --camera-theta 0 is; such a row used to be refused), moving along the meridian
  // through its frame: every frame's rays pass the axis closely.
  {
    const double r = 30.0, a = 0.9, rate = 0.005;  // dtheta/dtau
    std::string csv = "tau,t,r,theta,phi,ut,ur,utheta,uphi\n";
    const std::array<std::array<double, 2>, 6> rows = {{{0.1, 0.0}, {0.01, 0.0}, {1e-4, 0.0}, {0.0, 3.141592653589793},
                                                         {1e-4, 3.141592653589793}, {0.01, 3.141592653589793}}};
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double theta = rows[i][0], sigma = r * r + a * a * std::cos(theta) * std::cos(theta);
      const double u_theta = rows[i][1] == 0.0 ? -rate : rate;  // towards the pole, then away from it
      const double u_t = std::sqrt((1.0 + sigma * u_theta * u_theta) / (1.0 - 2.0 * r / sigma));  // g(u, u) = 1
      char row[256];
      std::snprintf(row, sizeof row, "%zu,0,%.17g,%.17g,%.17g,%.17g,0,%.17g,0\n", i, r, theta, rows[i][1], u_t, u_theta);
      csv += row;
    }
    const fs::path path = base_ / "over-the-pole.csv";
    std::ofstream(path) << csv;
    const ToolRun r_flight = run({"--metric", "kerr", "--spin", "0.9", "--scene", "disk", "--flight", "csv",
                                  "--flight-csv", path.string(), "--fov", "60", "--width", "24", "--height", "24",
                                  "--out", out("pole.exr").string()});
    ASSERT_EQ(r_flight.status, 0) << r_flight.err;
    EXPECT_NE(r_flight.out.find("\"frames_with_failed_rays\":[]"), std::string::npos) << r_flight.out;
    for (const auto& entry : fs::directory_iterator(base_ / "out")) fs::remove(entry.path());
  }
  for (const char* theta : {"-0.5", "180.5"}) {
    const ToolRun r = run(kerr({"--camera-theta", theta}, out("refused.exr").string()));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("--camera-theta must lie in [0, 180] degrees"), std::string::npos) << r.err;
    EXPECT_TRUE(out_empty());
  }
}

/// The CSV's rows after its comments and header: each a row of numbers.
std::vector<std::vector<double>> csv_rows(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("energy_low", 0) == 0) continue;
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

// --spectrum line: the disk's line profile as a CSV and its plot, the library's numbers to the CSV's 10 digits (the
// tool is a thin client of app::line_profile, itself of spectra/line_profile.hpp), the orders summing to the total;
// a frame's options and bad values refused before any work, leaving no file.
TEST_F(KerrCli, LineProfileIsTheLibrarysAndRefusesFrameOptions) {
  const fs::path csv = out("line.csv");
  const std::vector<std::string> base = {"--spectrum", "line", "--scene", "disk", "--metric", "kerr", "--spin", "0.9",
                                         "--camera-theta", "40", "--energy-bins", "40", "--line-finest", "0.0625",
                                         "--disk-outer", "15"};
  std::vector<std::string> args = base;
  for (const std::string& a : std::vector<std::string>{"--disk-transparent", "--out", csv.string()}) args.push_back(a);
  const ToolRun r = run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"total_flux\":", "\"total_flux_n1\":", "\"rays\":", "\"png\":"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " in " << r.out;
  EXPECT_TRUE(fs::exists(out("line.png")));
  const auto rows = csv_rows(csv);
  ASSERT_EQ(rows.size(), 40u);

  grtrace::KerrMetric metric;
  metric.spin = 0.9;
  const grtrace::KerrDiskMap map(metric, 1e7, 40.0 * std::numbers::pi / 180.0,
                                 grtrace::exact::isco_radius(0.9, grtrace::exact::Orbit::prograde), 15.0);
  grtrace::LineProfileSpec spec;
  spec.bins = 40;
  spec.transparent = true;
  grtrace::LineSampling sampling;
  sampling.finest_cell = 0.0625;
  const grtrace::LineProfile expected = grtrace::line_profile(map, spec, sampling);
  double n1 = 0.0;
  for (std::size_t b = 0; b < rows.size(); ++b) {
    ASSERT_EQ(rows[b].size(), 7u);
    EXPECT_NEAR(rows[b][0], expected.edges[b], 1e-9 * expected.edges[b]);
    EXPECT_NEAR(rows[b][2], expected.flux[b], 1e-9 * expected.flux[b] + 1e-300);
    EXPECT_NEAR(rows[b][3] + rows[b][4] + rows[b][5] + rows[b][6], rows[b][2], 1e-9 * rows[b][2] + 1e-300);
    n1 += rows[b][4];
  }
  EXPECT_GT(n1, 0.0);  // a transparent disk shows its n = 1 image
  for (const auto& entry : fs::directory_iterator(base_ / "out")) fs::remove(entry.path());

  const std::vector<BadCase> bad = {
      {{"--fov", "30"}, "--fov describes a frame"},
      {{"--width", "64"}, "--width describes a frame"},
      {{"--status-map"}, "--status-map is for frames"},
      {{"--camera-theta", "0"}, "inclination"},
      {{"--metric", "rn"}, "--metric must be"},
      {{"--chart", "ks"}, "Boyer-Lindquist"},
      {{"--energy-bins", "0"}, "--energy-bins"},
      {{"--energy-range", "7,6"}, "energy range"},
      {{"--line-energy", "-1"}, "line energy"},
      {{"--disk-inner", "2"}, "ISCO"},
      {{"--scene", "checker"}, "--scene disk"},
      {{"--spectrum", "continuum"}, "--spectrum must be line"},
  };
  expect_refused(base, bad, csv);
  // The CSV's name, and a line option without --spectrum.
  std::vector<std::string> exr = base;
  for (const std::string& x : std::vector<std::string>{"--out", out("line.exr").string()}) exr.push_back(x);
  EXPECT_EQ(run(exr).status, 2);
  const ToolRun stray = run({"--line-energy", "6", "--out", out("frame.exr").string()});
  EXPECT_EQ(stray.status, 2);
  EXPECT_NE(stray.err.find("--line-energy applies only with --spectrum line"), std::string::npos) << stray.err;
  EXPECT_TRUE(out_empty());
}

// --rings: the disk's photon ring by order as an EXR (a channel per order) and two PNGs, the library's image to
// float precision (the tool is a thin client of app::ring_image, itself of spectra/ring_image.hpp), each order's
// pixels summing to its flux in the JSON line; a frame's options and bad values refused before any work.
TEST_F(KerrCli, RingImageIsTheLibrarysAndRefusesFrameOptions) {
  const fs::path exr = out("ring.exr");
  const std::vector<std::string> base = {
      "--rings", "--scene",        "disk", "--metric",     "kerr", "--spin",
      "0.9",     "--camera-theta", "17",   "--width",      "48",   "--height",
      "40",      "--ring-field",   "7",    "--disk-outer", "100",  "--disk-transparent"};
  std::vector<std::string> args = base;
  for (const std::string& a : std::vector<std::string>{"--source", "m87", "--out", exr.string()}) args.push_back(a);
  const ToolRun r = run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(out("ring.png")));
  EXPECT_TRUE(fs::exists(out("ring-orders.png")));
  const grtrace::Image image = grtrace::read_exr(exr);

  grtrace::KerrMetric metric;
  metric.spin = 0.9;
  const grtrace::KerrDiskMap map(metric, 1e7, 17.0 * std::numbers::pi / 180.0,
                                 grtrace::exact::isco_radius(0.9, grtrace::exact::Orbit::prograde), 100.0);
  grtrace::RingImageSpec spec;
  spec.width = 48;
  spec.height = 40;
  spec.half_width = 7.0;
  spec.transparent = true;
  const grtrace::RingImage expected = grtrace::ring_image(map, spec);
  const double pixel_area = expected.pixel * expected.pixel;
  const char* channels[] = {"I_n0", "I_n1", "I_n2", "I_n3_up"};
  const char* keys[] = {"flux_n0", "flux_n1", "flux_n2", "flux_n3_up"};
  for (std::size_t o = 0; o < grtrace::RingImage::kOrderChannels; ++o) {
    const std::vector<float>& plane = image.channel(channels[o]);
    ASSERT_EQ(plane.size(), expected.intensity[o].size());
    double sum = 0.0;
    for (std::size_t i = 0; i < plane.size(); ++i) {
      const double v = plane[i];
      EXPECT_NEAR(v, expected.intensity[o][i], 1e-6 * expected.intensity[o][i] + 1e-30) << channels[o] << i;
      sum += v;
    }
    const double flux = grtrace::tool_tests::json_number(r.out, keys[o]);
    EXPECT_NEAR(flux, expected.flux[o], 1e-9 * expected.flux[o]) << keys[o];
    EXPECT_NEAR(sum * pixel_area, flux, 1e-5 * flux) << keys[o];
    EXPECT_GT(flux, 0.0) << keys[o];
  }
  // The rings' sizes, and in microarcseconds for M87* (3.8 uas per M).
  const double d2 = grtrace::tool_tests::json_number(r.out, "ring_diameter_n2");
  EXPECT_NEAR(d2, expected.rings.diameter[2], 1e-9 * d2);
  EXPECT_NEAR(grtrace::tool_tests::json_number(r.out, "ring_diameter_n2_uas"),
              d2 * grtrace::SourceScale::m87().microarcseconds_per_m(), 1e-6 * d2);
  EXPECT_LT(grtrace::tool_tests::json_number(r.out, "ring_width_n3"),
            0.2 * grtrace::tool_tests::json_number(r.out, "ring_width_n2"));
  for (const auto& entry : fs::directory_iterator(base_ / "out")) fs::remove(entry.path());

  const std::vector<BadCase> bad = {
      {{"--fov", "30"}, "--fov describes a frame"},
      {{"--status-map"}, "--status-map is for frames"},
      {{"--line-energy", "6"}, "--line-energy describes a frame"},
      {{"--camera-theta", "0"}, "inclination"},
      {{"--metric", "rn"}, "--metric must be"},
      {{"--ring-field", "2"}, "--ring-field"},
      {{"--ring-cuts", "1"}, "--ring-cuts"},
      {{"--width", "4"}, "--width"},
      {{"--source", "m31"}, "--source must be"},
      {{"--spectrum", "line"}, "two commands"},
      {{"--disk-inner", "2"}, "ISCO"},
      {{"--scene", "checker"}, "--scene disk"},
  };
  expect_refused(base, bad, exr);
  std::vector<std::string> csv = base;
  for (const std::string& x : std::vector<std::string>{"--out", out("ring.csv").string()}) csv.push_back(x);
  EXPECT_EQ(run(csv).status, 2);
  const ToolRun stray = run({"--ring-field", "9", "--out", out("frame.exr").string()});
  EXPECT_EQ(stray.status, 2);
  EXPECT_NE(stray.err.find("--ring-field applies only with --rings"), std::string::npos) << stray.err;
  EXPECT_TRUE(out_empty());
}

// --scene disk --disk-transparent (or --disk-light): the disk drawn by its light, by image order, every ray in
// closed form: the channels sum to the total, the JSON line's flux by order to its flux, the header says how it
// shines; the options it has no use for, and the light's options without it, refused before any work.
TEST_F(KerrCli, DiskDrawnByItsLightSplitsItsIntensityByOrder) {
  const fs::path exr = out("light.exr");
  const std::vector<std::string> base = {"--scene",    "disk", "--metric",       "kerr", "--spin", "0.9",
                                         "--camera-r", "60",   "--camera-theta", "80",   "--fov",  "35",
                                         "--width",    "40",   "--height",       "30"};
  std::vector<std::string> args = base;
  for (const std::string& a :
       std::vector<std::string>{"--disk-transparent", "--emissivity-index", "2.5", "--out", exr.string()})
    args.push_back(a);
  const ToolRun r = run(args);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(out("light.png")));
  const grtrace::Image image = grtrace::read_exr(exr);
  EXPECT_EQ(image.metadata.at("disk_transparent"), "true");
  EXPECT_EQ(image.metadata.at("tracer"), "kerr-closed-form");
  const char* channels[] = {"intensity_n0", "intensity_n1", "intensity_n2", "intensity_n3_up"};
  const char* keys[] = {"flux_n0", "flux_n1", "flux_n2", "flux_n3_up"};
  const std::vector<float>& total = image.channel("intensity");
  for (std::size_t i = 0; i < total.size(); ++i) {
    float sum = 0.0f;
    for (const char* c : channels) sum += image.channel(c)[i];
    ASSERT_EQ(sum, total[i]) << i;
  }
  double flux_sum = 0.0;
  for (const char* k : keys) flux_sum += grtrace::tool_tests::json_number(r.out, k);
  const double flux = grtrace::tool_tests::json_number(r.out, "flux");
  EXPECT_NEAR(flux_sum, flux, 1e-8 * flux);                            // the JSON line's digits
  EXPECT_GT(grtrace::tool_tests::json_number(r.out, "flux_n1"), 0.0);  // the first ring, seen through the disk
  for (const auto& entry : fs::directory_iterator(base_ / "out")) fs::remove(entry.path());

  const std::vector<BadCase> bad = {
      {{"--disk-light", "--tableau", "rk4"}, "--tableau has no effect on a disk drawn by its light"},
      {{"--disk-light", "--rtol", "1e-6"}, "--rtol has no effect"},
      {{"--disk-light", "--angle-correction", "flat"}, "--angle-correction has no effect"},
      {{"--disk-light", "--tracer", "general"}, "use auto or kerr-closed-form"},
      {{"--disk-light", "--device", "cuda"}, "--device cuda"},
      {{"--disk-light", "--emissivity-break", "-2"}, "a positive break radius"},
      {{"--disk-light", "--redshift-power", "11"}, "--redshift-power must lie in [-10, 10]"},
      {{"--redshift-power", "4"}, "--redshift-power applies only with --rings or --scene disk --disk-light"},
      {{"--emissivity-index", "2"}, "applies only with --spectrum line, --rings or --scene disk --disk-light"},
      {{"--disk-light", "--disk-inner", "1.5"}, "--disk-inner"},
      {{"--disk-light", "--rings"}, "--disk-light applies only with --scene disk frames"},
  };
  expect_refused(base, bad, exr);
  const ToolRun rn = run({"--scene", "disk", "--metric", "rn", "--disk-light", "--out", exr.string()});
  EXPECT_EQ(rn.status, 2);
  EXPECT_NE(rn.err.find("use --metric kerr or schwarzschild"), std::string::npos) << rn.err;
  std::vector<std::string> sky = {"--scene", "sky", "--disk-light", "--out", exr.string()};
  const ToolRun stray = run(sky);
  EXPECT_EQ(stray.status, 2);
  EXPECT_NE(stray.err.find("--disk-light applies only with --scene disk"), std::string::npos) << stray.err;
  EXPECT_TRUE(out_empty());
}

}  // namespace
