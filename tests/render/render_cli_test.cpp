// grtrace-render as a user runs it: the JSON contract, the EXR channels, identical pixels for any thread count,
// and every kind of bad input refused before any work, with exit code 2 and no file left behind.
#include "grtrace/render/exr_io.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;

using grtrace::tool_tests::ToolRun;

/// Runs grtrace-render with `args` (shell words); stdout and stderr merged.
ToolRun run(const std::string& args) {
  return grtrace::tool_tests::run_command(grtrace::tool_tests::quoted(GRTRACE_RENDER_BINARY) + " " + args);
}

class RenderCli : public ::testing::Test {
 protected:
  /// Takes a file name; returns its path in this test's scratch directory.
  fs::path scratch(const std::string& name) const { return scratch_ / name; }
  grtrace::tool_tests::ScratchDir scratch_{"grtrace_render_cli"};
};

TEST_F(RenderCli, WritesTheContractedJsonExrAndPng) {
  const fs::path out = scratch("frame.exr");
  const ToolRun r = run("--width 48 --height 32 --camera-r 15 --tracer general --rtol 1e-8 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* key : {"\"width\":48", "\"height\":32", "\"seconds\"", "\"rays_per_second\"", "\"mean_steps\"",
                          "\"status_counts\"", "\"escaped\"", "\"captured\"", "\"hit\"", "\"max_steps\"",
                          "\"step_underflow\"", "\"non_finite\"", "\"tracer\":\"general\"", "\"tableau\"", "\"rtol\"",
                          "\"atol\"", "\"out\""})
    EXPECT_NE(r.output.find(key), std::string::npos) << key << " missing in " << r.output;
  ASSERT_TRUE(fs::exists(out));
  EXPECT_TRUE(fs::exists(out.parent_path() / "frame.png"));
  const grtrace::Image img = grtrace::read_exr(out);
  for (const char* ch : {"R", "G", "B", "object", "status", "redshift", "sky_theta", "sky_phi", "steps", "order"})
    EXPECT_TRUE(img.has_channel(ch)) << ch;
  for (float v : img.channel("R")) ASSERT_TRUE(std::isfinite(v));
  EXPECT_EQ(img.metadata.at("tableau"), "rkf78");
  EXPECT_EQ(img.metadata.at("angle_correction"), "exact");
}

// The accuracy target on the seed's main frame with the default settings: every escaped pixel's direction within
// 1e-6 rad of the exact elliptic-integral answer (judged by --error-map, after the clock has stopped).
TEST_F(RenderCli, DefaultsKeepTheMainFrameWithinOneMicroradian) {
  const fs::path out = scratch("main.exr");
  const ToolRun r = run("--error-map --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto value = [&](const std::string& key) {
    const auto at = r.output.find("\"" + key + "\":");
    EXPECT_NE(at, std::string::npos) << key << " missing in " << r.output;
    return at == std::string::npos ? std::nan("") : std::stod(r.output.substr(at + key.size() + 3));
  };
  const double max_error = value("max_error"), median_error = value("median_error");
  EXPECT_LT(max_error, 1e-6);
  EXPECT_LT(median_error, 1e-8);
  EXPECT_GT(max_error, 0.0) << "an error map of exact zeros would mean it compared a thing with itself";
  EXPECT_TRUE(fs::exists(out.parent_path() / "main-error.png"));
  const grtrace::Image img = grtrace::read_exr(out);
  ASSERT_TRUE(img.has_channel("error"));
  EXPECT_EQ(img.width(), 1024);
}

// A frame from the equator looking at the hole is mirror symmetric top-bottom and left-right: a quarter of its
// pixels is traced and the rest reflected (render/mirror_symmetry.hpp); --no-mirrors traces them all, to the same
// picture. The JSON and the EXR header say how many were traced and which mirrors were used.
TEST_F(RenderCli, MirrorSymmetricFramesTraceAQuarterAndSayWhich) {
  const std::string common = "--width 40 --height 30 --camera-r 15 --tracer general --rtol 1e-9 ";
  const fs::path mirrored = scratch("mirrored.exr"), full = scratch("full.exr"), tilted = scratch("tilted.exr");
  const ToolRun a = run(common + "--out " + mirrored.string());
  ASSERT_EQ(a.status, 0) << a.output;
  EXPECT_NE(a.output.find("\"traced_rays\":300,"), std::string::npos) << a.output;
  EXPECT_NE(a.output.find("\"mirrors\":\"equator,meridian\""), std::string::npos) << a.output;
  const ToolRun b = run(common + "--no-mirrors --out " + full.string());
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_NE(b.output.find("\"traced_rays\":1200,"), std::string::npos) << b.output;
  EXPECT_NE(b.output.find("\"mirrors\":\"none\""), std::string::npos) << b.output;
  const ToolRun c = run(common + "--camera-theta 80 --out " + tilted.string());  // off the equator: left-right only
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_NE(c.output.find("\"traced_rays\":600,"), std::string::npos) << c.output;
  EXPECT_NE(c.output.find("\"mirrors\":\"meridian\""), std::string::npos) << c.output;

  const grtrace::Image x = grtrace::read_exr(mirrored), y = grtrace::read_exr(full);
  EXPECT_EQ(x.metadata.at("mirrors"), "equator,meridian");
  EXPECT_EQ(x.metadata.at("traced_rays"), "300");
  EXPECT_EQ(y.metadata.at("mirrors"), "none");
  EXPECT_EQ(x.channel("status"), y.channel("status"));
  EXPECT_EQ(x.channel("object"), y.channel("object"));
  const auto& st = y.channel("status");
  int escaped = 0;
  for (std::size_t i = 0; i < st.size(); ++i) {
    if (st[i] != 0.0f) continue;  // escaped only: the sky channels are NaN elsewhere
    ++escaped;
    EXPECT_NEAR(x.channel("sky_theta")[i], y.channel("sky_theta")[i], 1e-6f) << "pixel " << i;
    // phi in (-pi, pi]: the sky behind the hole sits on the seam, so compare modulo 2 pi
    const double dphi = std::remainder(double(x.channel("sky_phi")[i]) - double(y.channel("sky_phi")[i]), 2.0 * M_PI);
    EXPECT_NEAR(dphi, 0.0, 1e-6) << "pixel " << i;
  }
  EXPECT_GT(escaped, 600);
}

TEST_F(RenderCli, OneAndTwoThreadsGiveIdenticalPixels) {
  const fs::path a = scratch("t1.exr"), b = scratch("t2.exr");
  const std::string common = "--scene disk --camera-r 25 --camera-theta 80 --fov 60 --width 40 --height 30 --rtol 1e-7 ";
  ASSERT_EQ(run(common + "--threads 1 --out " + a.string()).status, 0);
  ASSERT_EQ(run(common + "--threads 2 --out " + b.string()).status, 0);
  const grtrace::Image x = grtrace::read_exr(a), y = grtrace::read_exr(b);
  for (const auto& name : x.channel_names()) {
    const auto &p = x.channel(name), &q = y.channel(name);
    ASSERT_EQ(p.size(), q.size());
    for (std::size_t i = 0; i < p.size(); ++i)
      ASSERT_TRUE(p[i] == q[i] || (std::isnan(p[i]) && std::isnan(q[i]))) << name << " pixel " << i;
  }
}

// --exr-compression changes how the EXR is stored, never what it holds: every choice reads back the same bits as
// the default, and the file says which compression it uses (zips by default: the fastest to write on
// all cores among those that keep files small).
TEST_F(RenderCli, EveryExrCompressionHoldsTheSamePixels) {
  const std::string common = "--width 40 --height 36 --camera-r 15 --scene disk --fov 60 --camera-theta 80 ";
  const fs::path reference = scratch("default-compression.exr");
  ASSERT_EQ(run(common + "--out " + reference.string()).status, 0);
  EXPECT_EQ(Imf::InputFile(reference.c_str()).header().compression(), Imf::ZIPS_COMPRESSION);
  const grtrace::Image x = grtrace::read_exr(reference);
  for (const auto& [name, compression] : grtrace::kExrLosslessCompressions) {
    SCOPED_TRACE(std::string(name));
    const fs::path out = scratch("compression-" + std::string(name) + ".exr");
    const ToolRun r = run(common + "--exr-compression " + std::string(name) + " --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(Imf::InputFile(out.c_str()).header().compression(), compression);
    const grtrace::Image y = grtrace::read_exr(out);
    ASSERT_EQ(x.channel_names(), y.channel_names());
    for (const auto& channel : x.channel_names()) {
      const auto &p = x.channel(channel), &q = y.channel(channel);
      ASSERT_EQ(p.size(), q.size());
      for (std::size_t i = 0; i < p.size(); ++i)
        ASSERT_EQ(std::bit_cast<std::uint32_t>(p[i]), std::bit_cast<std::uint32_t>(q[i])) << channel << " " << i;
    }
    EXPECT_EQ(y.metadata.at("option_exr-compression"), name);
  }
}

TEST_F(RenderCli, RefusesBadInputBeforeAnyWork) {
  const fs::path out = scratch("bad.exr");
  const std::string o = "--width 8 --height 8 --out " + out.string() + " ";  // the bad option comes last and wins
  const char* bad[] = {"--camera-r 2", "--camera-r 1.5", "--camera-r 500", "--fov 0", "--fov 180", "--fov nan",
                       "--width 0", "--height -3", "--mass inf", "--velocity 0.8,0.8,0", "--look 0,-1,0",
                       "--scene nope", "--metric kerr --spin 1", "--tableau nope", "--control pi --tableau rk4",
                       "--angle-correction sometimes", "--camera-theta -1", "--threads -1", "--rtol 0"};
  for (const char* args : bad) {
    const ToolRun r = run(o + args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << args;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  const ToolRun r = run("--width 8 --height 8 --out /nonexistent-dir/x.exr");
  EXPECT_EQ(r.status, 2) << r.output;
  // No name before .exr (the preview would be a hidden ".png"), or a directory named x.exr/: refused by name.
  for (const fs::path& name : {scratch(".exr"), scratch("x.exr") / ""}) {
    const ToolRun unnamed = run("--width 8 --height 8 --out " + name.string());
    EXPECT_EQ(unnamed.status, 2) << unnamed.output;
    EXPECT_NE(unnamed.output.find("must name an .exr file (a name, then .exr)"), std::string::npos) << unnamed.output;
    EXPECT_FALSE(fs::exists(scratch(".png")));
  }
}

// The rendering tools offer a declared list of methods (grtrace/app/tool_methods.hpp): --help lists it, every pair
// on it renders and says so in the JSON and the header, and a valid pair outside it is refused before any work with
// the list and the tools that have every pair.
TEST_F(RenderCli, OffersTheDeclaredMethodsAndRefusesOthersWithTheList) {
  const ToolRun help = run("--help");
  ASSERT_EQ(help.status, 0) << help.output;
  const std::string list = "rkf78 + i, tsit5 + i, dopri5 + pi, vern6 + i, rk4 + fixed, rk4 + doubling";
  EXPECT_NE(help.output.find(list), std::string::npos) << help.output;
  for (const char* method : {"rkf78 --control i", "tsit5 --control i", "dopri5 --control pi", "vern6 --control i",
                             "rk4 --control fixed --step 2", "rk4 --control doubling"}) {
    SCOPED_TRACE(method);
    const fs::path out = scratch("m.exr");
    // Tolerances for the adaptive ones (a fixed step refuses them: they would mean nothing).
    const std::string tolerances = std::string(method).find("fixed") == std::string::npos ? "--rtol 1e-7 --atol 1e-9 " : "";
    const ToolRun r = run("--width 12 --height 8 --camera-r 30 " + tolerances + "--tableau " + std::string(method) +
                          " --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string tableau = std::string(method).substr(0, std::string(method).find(' '));
    EXPECT_NE(r.output.find("\"tableau\":\"" + tableau + "\""), std::string::npos) << r.output;
    EXPECT_EQ(grtrace::read_exr(out).metadata.at("tableau"), tableau);
  }
  for (const char* pair : {"--tableau dopri5 --control i", "--tableau rkf45 --control pi",
                           "--tableau rkf78 --control fixed --step 1", "--tableau rkf78 --control pi"}) {
    SCOPED_TRACE(pair);
    const fs::path out = scratch("refused.exr");
    const ToolRun r = run("--width 8 --height 8 " + std::string(pair) + " --out " + out.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(list), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("grtrace-work-precision"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("grtrace-geodesic"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
