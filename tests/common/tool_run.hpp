// tests/common/tool_run.hpp
// Runs a command line through the shell for the tool tests: its exit status and its stdout + stderr merged.
// One copy for every test program that drives a grtrace tool (the tests that still carry their own are listed
// in the session notes: move them here when touched).
#pragma once

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace grtrace::tool_tests {

struct ToolRun {
  int status = -1;     ///< the exit status; -1 if the command could not run or died from a signal
  std::string output;  ///< stdout and stderr, merged
};

/// Runs `command` (shell words; stderr is redirected into stdout here).
inline ToolRun run_command(const std::string& command) {
  ToolRun r;
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) r.output += buf.data();
  const int w = ::pclose(p);
  r.status = WIFEXITED(w) ? WEXITSTATUS(w) : -1;
  return r;
}

}  // namespace grtrace::tool_tests
