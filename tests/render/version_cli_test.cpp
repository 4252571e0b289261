// `--version` on every command-line tool (issue 15 item 5): "<tool> <version>" on stdout, nothing on stderr, exit
// code 0, before any other work (no file written, no display needed, no ray traced), and the version is the CMake
// project version (project(grtrace VERSION ...)), which the generated grtrace/version.hpp carries.
// The tools and their paths come from tests/render/CMakeLists.txt (GRTRACE_VERSION_TOOLS: "name=path|name=path").
#include "grtrace/version.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::vector<std::pair<std::string, std::string>> tools() {
  std::vector<std::pair<std::string, std::string>> out;
  const std::string all = GRTRACE_VERSION_TOOLS;
  std::size_t start = 0;
  while (start < all.size()) {
    const std::size_t end = std::min(all.find('|', start), all.size());
    const std::string item = all.substr(start, end - start);
    if (const auto eq = item.find('='); eq != std::string::npos) out.emplace_back(item.substr(0, eq), item.substr(eq + 1));
    start = end + 1;
  }
  return out;
}

struct ToolRun {
  int exit_code = -1;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::string s;
  if (FILE* f = std::fopen(p.c_str(), "r")) {
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, n);
    std::fclose(f);
  }
  return s;
}

/// Runs `exe args` in the empty directory `cwd` with DISPLAY unset; stdout and stderr kept apart.
ToolRun run_in(const fs::path& cwd, const std::string& exe, const std::string& args) {
  const fs::path out = cwd.parent_path() / (cwd.filename().string() + ".out");
  const fs::path err = cwd.parent_path() / (cwd.filename().string() + ".err");
  const std::string cmd = "cd '" + cwd.string() + "' && env -u DISPLAY -u WAYLAND_DISPLAY '" + exe + "' " + args +
                          " >'" + out.string() + "' 2>'" + err.string() + "'";
  ToolRun r;
  const int status = std::system(cmd.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

class Version : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("grtrace_version_cli_" + std::to_string(::getpid()));
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
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
    const ToolRun r = run_in(cwd, exe, "--version");
    EXPECT_EQ(r.exit_code, 0) << r.err;
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
    const ToolRun r = run_in(cwd, exe, "--version --no-such-option 1");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out, name + " " + std::string(grtrace::kVersion) + "\n");
    EXPECT_TRUE(fs::is_empty(cwd));
  }
}

TEST_F(Version, HelpListsIt) {
  for (const auto& [name, exe] : tools()) {
    if (name.rfind("grtrace-", 0) != 0) continue;  // the example scenes have no --help, only a usage line
    SCOPED_TRACE(name);
    const ToolRun r = run_in(root_, exe, "--help");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("--version"), std::string::npos) << r.out;
  }
}

}  // namespace
