// grtrace-view --metric kerr as a program (issue 12): bad Kerr input is refused (exit 2, a message naming the
// option), and a Kerr scene (frame by the general tracer, rays, outer horizon, ergosphere, ISCO) is drawn offscreen.
// The rendering case skips without DISPLAY (run under xvfb-run).
#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#ifndef GRTRACE_VIEW_EXE
#error "GRTRACE_VIEW_EXE (path of grtrace-view) must be defined by the build"
#endif

namespace {

using grtrace::tool_tests::ToolRun;

/// Runs grtrace-view with `args` (shell words); returns the exit status and the merged output.
ToolRun run(const std::string& args) { return grtrace::tool_tests::run_command(std::string(GRTRACE_VIEW_EXE) + " " + args); }

TEST(ViewKerr, BadKerrInputExitsWithTwo) {
  const std::array<std::pair<const char*, const char*>, 6> cases = {{
      {"--metric kerr --spin 1", "--spin"},
      {"--metric kerr --spin nan", "--spin"},
      {"--metric kerr --spin 0.9 --camera-r 1.3", "horizon"},
      {"--metric kerr --spin 0.9 --bundle beam", "--bundle beam"},
      {"--metric kerr --spin 0.9 --orbit", "--orbit"},
      {"--metric kerr --spin 0.9 --disk-inner 1.4", "disk"},
  }};
  for (const auto& [args, says] : cases) {
    const ToolRun r = run(std::string(args) + " --screenshot /tmp/never-written.png");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
  }
}

TEST(ViewKerr, DrawsAKerrSceneOffscreen) {
  if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  const auto png = std::filesystem::temp_directory_path() / ("grtrace-view-kerr-" + std::to_string(::getpid()) + ".png");
  const ToolRun r = run("--metric kerr --spin 0.9 --camera-r 30 --camera-theta 80 --width 40 --height 30 "
                        "--bundle-size 4x3 --rtol 1e-7 --atol 1e-9 --size 400x200 --screenshot " + png.string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(png)) << r.output;
  std::filesystem::remove(png);
}

}  // namespace
