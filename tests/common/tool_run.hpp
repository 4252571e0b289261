// tests/common/tool_run.hpp
// Runs a command line through the shell for the tool tests: its exit status and its stdout + stderr merged.
// One copy for every test program that drives a grtrace tool (the tests that still carry their own are listed
// in the session notes: move them here when touched).
#pragma once

#include <array>
#include <cstdio>
#include <map>
#include <sstream>
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

/// Takes "name=path|name=path" (CMake's grtrace_tool_paths); returns path by name.
inline std::map<std::string, std::string> named_paths(const std::string& joined) {
  std::map<std::string, std::string> out;
  std::stringstream ss(joined);
  for (std::string item; std::getline(ss, item, '|');)
    if (const auto eq = item.find('='); eq != std::string::npos) out[item.substr(0, eq)] = item.substr(eq + 1);
  return out;
}

}  // namespace grtrace::tool_tests
