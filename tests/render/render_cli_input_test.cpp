// grtrace-render as a program: every bad input is refused before any ray is traced (exit code 2, a message on
// stderr, nothing on stdout, no file left behind); a good run ends with the one-line JSON of the contract,
// writes the EXR (+ PNG) with the reproduction metadata, and gives identical pixels on 1 and 2 threads.
//
// The binary: GRTRACE_RENDER_BINARY if CMake defines it for this target (tests/render/CMakeLists.txt), else
// <build>/examples/render/grtrace-render next to this test's <build>/tests/render/.
#include "grtrace/render/exr_io.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
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

class RenderCliInput : public ::testing::Test {
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

  std::vector<std::string> out_listing() const { return grtrace::tool_tests::files_in(base_ / "out"); }

  fs::path out(const std::string& name) const { return base_ / "out" / name; }

  /// Each run (args, a small frame to out/frame.exr) exits 2 before any work, saying `says`, and writes no frame.
  void expect_refusals(const std::vector<std::pair<std::vector<std::string>, std::string>>& cases) const {
    for (const auto& [args, says] : cases) {
      std::vector<std::string> full = args;
      full.insert(full.end(), {"--out", out("frame.exr").string(), "--width", "8", "--height", "8"});
      const ToolRun r = run(full);
      EXPECT_EQ(r.status, 2) << r.err;
      EXPECT_NE(r.err.find(says), std::string::npos) << "expected '" << says << "' in: " << r.err;
      EXPECT_FALSE(fs::exists(out("frame.exr")) || fs::exists(out("frame.png"))) << says;
    }
  }

  grtrace::tool_tests::ScratchDir scratch_{"grtrace_render_cli_input"};
  fs::path binary_, base_ = scratch_.path();
};

/// Small, fast frames for the runs that should succeed.
std::vector<std::string> small(std::vector<std::string> args) {
  for (const char* a : {"--width", "24", "--height", "16", "--rtol", "1e-8", "--atol", "1e-10"}) args.emplace_back(a);
  return args;
}

}  // namespace

TEST_F(RenderCliInput, RefusesEveryBadInputBeforeTracingAndLeavesNoFile) {
  const std::string target = out("frame.exr").string();
  const std::vector<std::vector<std::string>> bad = {
      {"--camera-r", "2"},                    // on the horizon
      {"--camera-r", "1"},                    // inside it
      {"--camera-r", "2.002"},                // on the horizon guard (1 + 1e-3) r_h
      {"--camera-r", "-5"},                   //
      {"--camera-r", "500"},                  // outside the sky sphere (400)
      {"--camera-r", "50", "--sky-radius", "40"},
      {"--mass", "2", "--camera-r", "4"},     // the horizon scales with the mass
      {"--fov", "0"},
      {"--fov", "180"},
      {"--fov", "-30"},
      {"--fov", "200"},
      {"--width", "0"},
      {"--height", "0"},
      {"--width", "-4"},
      {"--width", "abc"},
      {"--mass", "nan"},
      {"--mass", "0"},
      {"--camera-r", "inf"},
      {"--camera-theta", "nan"},
      {"--camera-theta", "180.5"},
      {"--camera-phi", "inf"},
      {"--fov", "nan"},
      {"--rtol", "nan"},
      {"--atol", "-1"},
      {"--rtol", "0"},
      {"--sky-radius", "nan"},
      {"--step", "inf"},
      {"--velocity", "nan,0,0"},
      {"--velocity", "1,0,0"},               // |v| = c
      {"--velocity", "0.6,0,0.8"},           // |v| = c
      {"--velocity", "0,2,0"},               // faster than light
      {"--velocity", "0.5,0.5"},             // two components
      {"--look", "0,-1,0"},                  // parallel to the default up
      {"--look", "0,1,0"},                   // anti-parallel to it
      {"--up", "-2,0,0"},                    // parallel to the default look
      {"--look", "0,0,0"},
      {"--look", "1,inf,0"},
      {"--up", "0,0,nan"},
      {"--scene", "teapot"},
      {"--metric", "kerr", "--spin", "1"},  // |a| >= M (kerr with a = 0 is a valid Schwarzschild hole)
      {"--chart", "ks"},                    // Kerr's chart: Schwarzschild would silently ignore it
      {"--metric", "rn", "--charge", "0.5", "--chart", "ks"},
      {"--tableau", "rk5000"},
      {"--control", "magic"},
      {"--tableau", "rk4", "--control", "pi"},  // no embedded pair
      {"--angle-correction", "sideways"},
      {"--tracer", "symmetric"},  // retired from the tools: the planar tracer draws its frames
      {"--max-steps", "0"},
      {"--max-steps", "99999999999999999999"},  // beyond a long: refused, not saturated
      {"--threads", "-1"},
      {"--no-such-option", "1"},
      {"--exr-compression", "dwaa"},         // lossy: the channels must read back bit for bit
      {"--exr-compression", "pxr24"},
      {"--exr-compression", ""},
      {"--out", (base_ / "missing-dir" / "frame.exr").string()},
      {"--out", (base_ / "out").string()},  // a directory
  };
  for (const auto& args : bad) {
    std::vector<std::string> full = args;
    bool has_out = false;
    for (const auto& a : args) has_out = has_out || a == "--out";
    if (!has_out) full.insert(full.end(), {"--out", target});
    full.insert(full.end(), {"--width", "16", "--height", "16"});
    // (a later --width overrides an earlier one: keep the size check's own values)
    if (args[0] == "--width" || args[0] == "--height") full.resize(full.size() - 4);
    std::string shown;
    for (const auto& a : args) shown += a + " ";
    SCOPED_TRACE(shown);
    const ToolRun r = run(full);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << "stdout: " << r.out;
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_TRUE(out_listing().empty()) << "left a file behind";
  }
}

TEST_F(RenderCliInput, OptionsThatMeanNothingHereAreRefusedNamingWhatTheyNeed) {
  const std::string csv = out("path.csv").string();
  std::ofstream(csv) << "tau,t,r,theta,phi,ut,ur,utheta,uphi\n0,0,100,1.57,0,1.0101525445522108,0,0,0\n";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--spin", "0.5"}, "--spin applies only with --metric kerr"},
      {{"--metric", "kerr", "--spin", "0.5", "--charge", "0.3"}, "--charge applies only with --metric rn"},
      {{"--metric", "rn", "--lambda", "1e-4"}, "--lambda applies only with --metric sds"},
      {{"--throat", "2"}, "--throat applies only with --metric wormhole"},
      {{"--scene", "checker", "--disk-retrograde"}, "--disk-retrograde applies only with --scene disk"},
      {{"--scene", "sky", "--disk-outer", "30"}, "--disk-outer applies only with --scene disk"},
      {{"--orbit-dr", "0.01"}, "--orbit-dr needs --flight"},
      {{"--flight", "seed", "--frames", "3", "--orbit-dphi", "0.001"}, "--orbit-dphi applies only with --flight orbit"},
      {{"--flight", "csv", "--flight-csv", csv, "--frames", "3"}, "--frames applies only with a computed path"},
  };
  expect_refusals(cases);
}

TEST_F(RenderCliInput, UnwritableDirectoryIsRefused) {
  if (::geteuid() == 0) {
    // root writes anyway; the missing-directory and directory cases above still cover the path check.
    GTEST_SKIP() << "running as root: directory permissions do not stop writes";
  }
  fs::permissions(base_ / "out", fs::perms::owner_read | fs::perms::owner_exec);
  const ToolRun r = run(small({"--out", out("frame.exr").string()}));
  fs::permissions(base_ / "out", fs::perms::owner_all);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(out_listing().empty());
}

TEST_F(RenderCliInput, GoodRunPrintsTheContractJsonAndRecordsTheParameters) {
  const fs::path exr = out("frame.exr");
  const ToolRun r = run(small({"--camera-r", "30", "--fov", "60", "--velocity", "0,0,0.3", "--out", exr.string()}));
  ASSERT_EQ(r.status, 0) << r.err;
  // ONE line of JSON on stdout, with every key of the contract and all six status names.
  ASSERT_FALSE(r.out.empty());
  EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << r.out;
  EXPECT_EQ(r.out.front(), '{');
  for (const char* key : {"\"width\":24", "\"height\":16", "\"seconds\":", "\"rays_per_second\":", "\"mean_steps\":",
                          "\"status_counts\":{", "\"tracer\":", "\"tableau\":\"rkf78\"", "\"rtol\":1e-08",
                          "\"atol\":", "\"out\":", "\"escaped\":", "\"captured\":", "\"hit\":", "\"max_steps\":",
                          "\"step_underflow\":", "\"non_finite\":"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key << " missing in " << r.out;
  ASSERT_TRUE(fs::exists(exr));
  EXPECT_TRUE(fs::exists(out("frame.png")));
  EXPECT_EQ(out_listing().size(), 2u) << "only the EXR and its PNG";

  const grtrace::Image image = grtrace::read_exr(exr);
  EXPECT_EQ(image.width(), 24);
  EXPECT_EQ(image.height(), 16);
  for (const char* c : grtrace::Image::kStandardChannels) EXPECT_TRUE(image.has_channel(c)) << c;
  for (const char* key : {"scene", "metric", "mass", "camera_position", "fov_degrees", "tableau", "control", "rtol",
                          "atol", "max_steps", "sky_radius", "angle_correction", "render_seconds"})
    EXPECT_TRUE(image.metadata.count(key)) << "EXR header lacks " << key;
  long counted = 0;
  for (float s : image.channel("status")) counted += s == 0.0f || s == 1.0f ? 1 : 0;
  EXPECT_EQ(counted, 24 * 16) << "every ray escaped or was captured";
  for (const char* c : {"R", "G", "B"})
    for (float v : image.channel(c)) EXPECT_TRUE(std::isfinite(v));
}

TEST_F(RenderCliInput, OneAndTwoThreadsGiveIdenticalPixels) {
  for (const char* tracer : {"general", "planar"}) {
    SCOPED_TRACE(tracer);
    const ToolRun a = run(small({"--tracer", tracer, "--camera-r", "12", "--threads", "1", "--out", out("a.exr").string()}));
    const ToolRun b = run(small({"--tracer", tracer, "--camera-r", "12", "--threads", "2", "--out", out("b.exr").string()}));
    ASSERT_EQ(a.status, 0) << a.err;
    ASSERT_EQ(b.status, 0) << b.err;
    const grtrace::Image ia = grtrace::read_exr(out("a.exr")), ib = grtrace::read_exr(out("b.exr"));
    for (const char* c : grtrace::Image::kStandardChannels) {
      const auto& x = ia.channel(c);
      const auto& y = ib.channel(c);
      ASSERT_EQ(x.size(), y.size());
      EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "channel " << c << " differs";
    }
  }
}

TEST_F(RenderCliInput, FlatSpaceIsNeverIntegrated) {
  const ToolRun r = run(small({"--metric", "minkowski", "--velocity", "0,0,0.5", "--out", out("flat.exr").string()}));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("\"tracer\":\"straight-line\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"escaped\":384"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"mean_steps\":0"), std::string::npos) << r.out;
}

TEST_F(RenderCliInput, TheDeviceIsChosenBeforeAnyWorkAndNamedInTheJsonAndHeader) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--device", "teapot"}, "choose auto, cpu or cuda"},
      {{"--device", "cuda", "--tableau", "tsit5"}, "--tableau rkf78 --control i only"},
      {{"--device", "cuda", "--tracer", "planar"}, "use --tracer general or auto"},
      {{"--device", "cuda", "--metric", "minkowski"}, "use --device cpu"},
  };
  expect_refusals(cases);
  // auto: the GPU where this build and machine have one, else the CPU; the JSON line and the header say which.
  const fs::path exr = out("frame.exr");
  const ToolRun a = run(small({"--tracer", "general", "--out", exr.string()}));
  ASSERT_EQ(a.status, 0) << a.err;
  const std::string key = "\"device\":\"";
  const std::size_t at = a.out.find(key);
  ASSERT_NE(at, std::string::npos) << a.out;
  const std::string device = a.out.substr(at + key.size(), a.out.find('"', at + key.size()) - at - key.size());
  EXPECT_EQ(grtrace::read_exr(exr).metadata.at("device"), device);
  fs::remove(exr);
  fs::remove(out("frame.png"));
  const ToolRun c = run(small({"--tracer", "general", "--device", "cuda", "--out", exr.string()}));
  if (device == "cpu") {  // no GPU here: --device cuda is refused, saying what to use
    EXPECT_EQ(c.status, 2) << c.err;
    EXPECT_NE(c.err.find("use --device cpu"), std::string::npos) << c.err;
    EXPECT_TRUE(out_listing().empty());
  } else {
    EXPECT_EQ(c.status, 0) << c.err;
    EXPECT_NE(c.out.find(key + device + "\""), std::string::npos) << c.out;
  }
}
