// Hardening of the drawing tools: without an X server they refuse up front (exit 2, a message that
// says to use xvfb-run, no file) instead of dying with SIGSEGV/abort; output paths are checked before any work;
// grtrace-view --frame refuses headers that are not a grtrace-render camera, naming what is wrong.
// None of these cases needs a display: every refusal comes before VTK renders anything.
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/static_frame.hpp"
#include "grtrace/observer/tetrad.hpp"
#include "grtrace/render/exr_io.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using grtrace::tool_tests::ToolRun;

/// Runs exe with args after the environment prefix env; stdout and stderr merged in output, and a status that
/// tells a crash (minus the signal's number) from a refusal.
ToolRun run(const std::string& env, const std::string& exe, const std::vector<std::string>& args) {
  return grtrace::tool_tests::run_command(grtrace::tool_tests::command_line(exe, args, env));
}

class VizHardening : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_ / "out"); }
  bool out_empty() const { return fs::is_empty(dir_ / "out"); }
  void expect_refused(const ToolRun& r, const std::string& message) const {
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << "expected '" << message << "' in: " << r.output;
    EXPECT_TRUE(out_empty()) << "a file was left in out/";
  }
  grtrace::tool_tests::ScratchDir scratch_{"grtrace_viz_hardening"};
  fs::path dir_ = scratch_.path();
};

constexpr const char* kNoServer = "DISPLAY=:987";  // names a display no X server answers

/// A frame EXR with the header keys grtrace-render writes; `edit` changes them before writing.
template <class Edit>
fs::path write_frame(const fs::path& file, Edit&& edit) {
  using namespace grtrace;
  Image image(8, 6);
  const SchwarzschildMetric metric{1.0};
  const Vec4 x(0.0, 25.0, 1.4, 0.5);
  const StaticFrame frame(metric.metric(x));
  const Tetrad t = make_tetrad(metric.metric(x), frame.velocity(Vec3::Zero()), frame.spatial(Vec3(-1, 0, 0)),
                               frame.spatial(Vec3(0, -1, 0)));
  auto four = [](const Vec4& v) {
    return std::to_string(v[0]) + "," + std::to_string(v[1]) + "," + std::to_string(v[2]) + "," + std::to_string(v[3]);
  };
  image.metadata["scene"] = "checker";
  image.metadata["metric"] = "schwarzschild";
  image.metadata["mass"] = "1";
  image.metadata["camera_position"] = four(x);
  for (int a = 0; a < 4; ++a) image.metadata["tetrad_e" + std::to_string(a)] = four(t.e[static_cast<std::size_t>(a)]);
  image.metadata["fov_degrees"] = "70";
  image.metadata["sky_radius"] = "100";
  edit(image.metadata);
  write_exr(file, image);
  return file;
}

}  // namespace

TEST_F(VizHardening, ChartToolsAndTheViewerRefuseWithoutAnXServer) {
  const std::string out = (dir_ / "out").string();
  struct Case {
    const char* exe;
    std::vector<std::string> args;
  };
  const std::vector<Case> cases = {
      {GRTRACE_STABILITY_EXE, {"--out-dir", out + "/stability"}},
      {GRTRACE_ORBIT_DRIFT_EXE, {"--orbits", "2", "--csv", out + "/d.csv", "--png", out + "/d.png"}},
      {GRTRACE_WORK_PRECISION_EXE, {"--out-csv", out + "/wp.csv", "--out-png", out + "/wp"}},
      {GRTRACE_VIEW_EXE, {"--screenshot", out + "/v.png", "--size", "200x100"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.exe);
    const ToolRun r = run(kNoServer, c.exe, c.args);
    expect_refused(r, "xvfb-run");
    EXPECT_NE(r.output.find("DISPLAY=':987'"), std::string::npos) << r.output;
  }
  // Unset DISPLAY: the same refusal.
  expect_refused(run("env -u DISPLAY", GRTRACE_VIEW_EXE, {"--screenshot", out + "/v.png"}), "xvfb-run");
  // Tools that do not draw still work without a display.
  const ToolRun json = run(kNoServer, GRTRACE_STABILITY_EXE, {"--json"});
  EXPECT_EQ(json.status, 0) << json.output;
}

TEST_F(VizHardening, OutputPathsAreCheckedBeforeAnyWork) {
  const fs::path out = dir_ / "out";
  fs::create_directory(out / "a-dir.csv");
  std::ofstream(dir_ / "plain-file") << "x";
  fs::create_directories(dir_ / "export" / "rays.vtp");  // a directory where the export writes a file
  const std::string missing = (dir_ / "missing" / "x").string();
  struct Case {
    const char* exe;
    std::vector<std::string> args;
    const char* message;
  };
  const std::vector<Case> cases = {
      {GRTRACE_ORBIT_DRIFT_EXE, {"--no-png", "--csv", (out / "a-dir.csv").string()}, "it is a directory"},
      {GRTRACE_ORBIT_DRIFT_EXE, {"--no-png", "--csv", missing + ".csv"}, "does not exist"},
      {GRTRACE_ORBIT_DRIFT_EXE, {"--no-png", "--csv", ""}, "--csv needs a file name"},
      {GRTRACE_WORK_PRECISION_EXE, {"--out-csv", (out / "a-dir.csv").string()}, "it is a directory"},
      {GRTRACE_WORK_PRECISION_EXE, {"--out-csv", missing + ".csv"}, "does not exist"},
      {GRTRACE_WORK_PRECISION_EXE, {"--out-csv="}, "--out-csv needs a file name"},
      {GRTRACE_STABILITY_EXE, {"--out-dir", (dir_ / "plain-file").string()}, "is not a directory"},
      {GRTRACE_STABILITY_EXE, {"--out-dir", (dir_ / "plain-file" / "sub").string()}, "is not a directory"},
      {GRTRACE_VIEW_EXE, {"--screenshot", ""}, "--screenshot needs a file name"},
      {GRTRACE_VIEW_EXE, {"--screenshot", (out / "a-dir.csv").string()}, "it is a directory"},
      {GRTRACE_VIEW_EXE, {"--screenshot", missing + ".png"}, "does not exist"},
      {GRTRACE_VIEW_EXE, {"--json=maybe"}, "unknown option"},
      {GRTRACE_VIEW_EXE, {"--export", (dir_ / "export").string()}, "rays.vtp': it is a directory"},
  };
  for (const Case& c : cases) {
    std::string shown = c.exe;
    for (const auto& a : c.args) shown += " [" + a + "]";
    SCOPED_TRACE(shown);
    // Under a display-less environment too: the path is refused (exit 2) whatever the display.
    const ToolRun r = run(kNoServer, c.exe, c.args);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1) << "only a-dir.csv";
  }
  // The frame is not overwritten by the screenshot.
  const fs::path frame = write_frame(out / "f.exr", [](auto&) {});
  const ToolRun same = run(kNoServer, GRTRACE_VIEW_EXE, {"--frame", frame.string(), "--screenshot", frame.string()});
  EXPECT_EQ(same.status, 2) << same.output;
  EXPECT_NE(same.output.find("is the input given as --frame"), std::string::npos) << same.output;
}

TEST_F(VizHardening, BooleanFlagValuesOnTheChartTools) {
  const ToolRun yes = run(kNoServer, GRTRACE_STABILITY_EXE, {"--json=yes"});
  EXPECT_EQ(yes.status, 0) << yes.output;
  const ToolRun no = run(kNoServer, GRTRACE_STABILITY_EXE, {"--json=false", "--out-dir", (dir_ / "out" / "s").string()});
  EXPECT_EQ(no.status, 2) << "--json=false draws the PNGs, which needs a display: " << no.output;
  EXPECT_NE(no.output.find("xvfb-run"), std::string::npos) << no.output;
  const ToolRun bad = run(kNoServer, GRTRACE_STABILITY_EXE, {"--json=maybe"});
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--json=maybe: a flag takes true/false"), std::string::npos) << bad.output;
}

TEST_F(VizHardening, ViewRefusesForgedFrameHeaders) {
  const fs::path out = dir_ / "out";
  const std::string shot = (dir_ / "shot.png").string();
  struct Case {
    const char* what;
    void (*edit)(std::map<std::string, std::string>&);
    const char* message;
  };
  const std::vector<Case> cases = {
      {"camera inside the horizon", [](auto& m) { m["camera_position"] = "0,1.5,1.4,0.5"; },
       "must be outside the horizon"},
      {"camera on the axis", [](auto& m) { m["camera_position"] = "0,25,0,0.5"; }, "off the polar axis"},
      {"zero tetrad vector", [](auto& m) { m["tetrad_e2"] = "0,0,0,0"; }, "'tetrad_e2' is the zero vector"},
      {"non-numeric tetrad", [](auto& m) { m["tetrad_e1"] = "a,b,c,d"; }, "'tetrad_e1' is not 4 finite numbers"},
      {"trailing garbage", [](auto& m) { m["tetrad_e1"] = "1,0,0,0x"; }, "'tetrad_e1' is not 4 finite numbers"},
      {"five numbers", [](auto& m) { m["camera_position"] = "0,25,1.4,0.5,9"; }, "'camera_position' is not 4"},
      {"fov abc", [](auto& m) { m["fov_degrees"] = "abc"; }, "'fov_degrees' must be a number in (0, 180)"},
      {"fov 500", [](auto& m) { m["fov_degrees"] = "500"; }, "'fov_degrees' must be a number in (0, 180)"},
      {"mass abc", [](auto& m) { m["mass"] = "abc"; }, "--mass expects a number, got 'abc' (from the frame's header)"},
      {"not a grtrace frame", [](auto& m) { m.erase("camera_position"); m.erase("tetrad_e0"); },
       "is not a grtrace-render frame: its header has no camera_position, tetrad_e0"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    const fs::path frame = write_frame(dir_ / "frame.exr", c.edit);
    const ToolRun r = run(kNoServer, GRTRACE_VIEW_EXE, {"--frame", frame.string(), "--screenshot", shot});
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("stod"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(shot));
  }
  // A texture EXR (R, G, B only, no header): refused with what is missing.
  grtrace::write_exr(dir_ / "texture.exr", grtrace::Image::with_channels(4, 2, {"R", "G", "B"}, 0.5f));
  const ToolRun tex = run(kNoServer, GRTRACE_VIEW_EXE, {"--frame", (dir_ / "texture.exr").string(), "--screenshot", shot});
  EXPECT_EQ(tex.status, 2) << tex.output;
  EXPECT_NE(tex.output.find("not a grtrace-render frame"), std::string::npos) << tex.output;
  EXPECT_TRUE(fs::is_empty(out));
}
