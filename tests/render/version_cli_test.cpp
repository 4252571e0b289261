// `--version` on every command-line tool: "<tool> <version>" on stdout, nothing on stderr, exit
// code 0, before any other work (no file written, no display needed, no ray traced), and the version is the CMake
// project version (project(grtrace VERSION ...)), which the generated grtrace/version.hpp carries.
// The tools and their paths come from tests/render/CMakeLists.txt (GRTRACE_VERSION_TOOLS: "name=path|name=path").
#include "grtrace/version.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using grtrace::tool_tests::ToolRun;

std::map<std::string, std::string> tools() { return grtrace::tool_tests::named_paths(GRTRACE_VERSION_TOOLS); }

class Version : public ::testing::Test {
 protected:
  /// Runs `exe args` in the empty directory `cwd` with DISPLAY unset; stdout and stderr kept apart (stderr's
  /// temporary file in root_, outside cwd).
  ToolRun run_in(const fs::path& cwd, const std::string& exe, const std::vector<std::string>& args) const {
    const std::string env = "cd " + grtrace::tool_tests::quoted(cwd.string()) + " && env -u DISPLAY -u WAYLAND_DISPLAY";
    return grtrace::tool_tests::run_tool(exe, args, root_, env);
  }
  grtrace::tool_tests::ScratchDir scratch_{"grtrace_version_cli"};
  const fs::path root_ = scratch_.path();
};

TEST_F(Version, HeaderCarriesTheCMakeProjectVersion) {
  EXPECT_EQ(grtrace::kVersion, GRTRACE_EXPECTED_VERSION);
  EXPECT_EQ(std::string(grtrace::kVersion), std::to_string(GRTRACE_VERSION_MAJOR) + "." +
                                                std::to_string(GRTRACE_VERSION_MINOR) + "." +
                                                std::to_string(GRTRACE_VERSION_PATCH));
}

TEST_F(Version, EveryToolPrintsItsNameAndVersionAndExitsZeroBeforeAnyWork) {
  const auto all = tools();
  ASSERT_GE(all.size(), 8u) << "expected grtrace-render, -geodesic, -stability, -work-precision, -orbit-drift and "
                               "the three example scenes (and grtrace-view when VTK is there): " GRTRACE_VERSION_TOOLS;
  for (const auto& [name, exe] : all) {
    SCOPED_TRACE(name);
    const fs::path cwd = root_ / name;
    fs::create_directories(cwd);
    const ToolRun r = run_in(cwd, exe, {"--version"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, name + " " + std::string(grtrace::kVersion) + "\n");
    EXPECT_EQ(r.err, "");
    EXPECT_TRUE(fs::is_empty(cwd)) << "--version wrote a file";  // e.g. grtrace-render's default render.exr
  }
}

TEST_F(Version, VersionWinsOverTheOptionsAfterIt) {
  // The same rule as --help: options are read left to right and --version ends the run when reached.
  for (const auto& [name, exe] : tools()) {
    SCOPED_TRACE(name);
    const fs::path cwd = root_ / (name + "-late");
    fs::create_directories(cwd);
    const ToolRun r = run_in(cwd, exe, {"--version", "--no-such-option", "1"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out, name + " " + std::string(grtrace::kVersion) + "\n");
    EXPECT_TRUE(fs::is_empty(cwd));
  }
}

TEST_F(Version, HelpListsIt) {
  for (const auto& [name, exe] : tools()) {
    if (name.rfind("grtrace-", 0) != 0) continue;  // the example scenes have no --help, only a usage line
    SCOPED_TRACE(name);
    const ToolRun r = run_in(root_, exe, {"--help"});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("--version"), std::string::npos) << r.out;
  }
}

}  // namespace
