// tests/common/tool_run.hpp
// The one harness for the tests that run a grtrace tool. Takes a tool (tool_path: the path CMake gave, else the
// build's examples/ folder) with its arguments, each quoted here (quoted()), or a whole command line, and an
// optional environment prefix; returns a ToolRun: the exit status (or the signal that ended the tool), stdout and
// stderr merged, or apart with stderr through a temporary file in the test's scratch directory. ScratchDir gives
// each test a directory of its own, removed when the test ends; files_in() lists what a run left in a directory.
// Every test program that drives a tool uses this copy, so a fix to quoting or capture reaches all of them.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace grtrace::tool_tests {

/// ToolRun::status of a command that never ran (the shell could not be started, no temporary file for stderr).
inline constexpr int kNotRun = -1000;

struct ToolRun {
  int status = kNotRun;  ///< the exit code; minus the signal's number if a signal ended the tool (-11: SIGSEGV)
  std::string output;    ///< stdout and stderr: interleaved as written (run_command), or stdout then stderr
  std::string out;       ///< stdout alone (run_separated, run_tool; empty from run_command)
  std::string err;       ///< stderr alone (likewise)
};

/// Takes a string; returns it quoted for /bin/sh: one word whatever it holds (spaces, quotes, an empty string).
/// Call it qualified, tool_tests::quoted: unqualified, a non-const std::string finds std::quoted (<iomanip>) by ADL.
inline std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Takes the status word of pclose(); returns ToolRun::status. A crash must not read as a refusal: a signal gives
/// a negative status, never an exit code a test compares with (0, 2).
inline int decode_status(int wait_status) {
  if (wait_status == -1) return kNotRun;
  if (WIFEXITED(wait_status)) return WEXITSTATUS(wait_status);
  if (WIFSIGNALED(wait_status)) return -WTERMSIG(wait_status);
  return kNotRun;
}

/// Takes the path CMake defined for a tool (nullptr or "" when it defined none), the tool's folder under
/// examples/ and its name; returns the path to run: CMake's, else <build>/examples/<folder>/<name>, found from
/// this test program's own path <build>/tests/<subfolder>/<test> (the render tests' layout).
inline std::filesystem::path tool_path(const char* defined, const char* folder, const char* name) {
  if (defined != nullptr && *defined != '\0') return std::filesystem::path(defined);
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe");
  return self.parent_path().parent_path().parent_path() / "examples" / folder / name;
}

/// Takes a binary, its arguments and an environment prefix (shell words before the binary: "env -u DISPLAY",
/// "GRTRACE_MEMORY_LIMIT=1K", "cd 'dir' &&"; "" for none); returns the command line, binary and arguments quoted.
inline std::string command_line(const std::filesystem::path& binary, const std::vector<std::string>& args,
                                const std::string& env = "") {
  std::string cmd = env + (env.empty() ? "" : " ") + tool_tests::quoted(binary.string());
  for (const auto& a : args) cmd += " " + tool_tests::quoted(a);
  return cmd;
}

namespace detail {

/// Everything left to read from `p` (fread, not fgets: a NUL byte in the output must not cut it short).
inline std::string read_all(FILE* p) {
  std::string s;
  std::array<char, 4096> buf{};
  for (std::size_t n; (n = std::fread(buf.data(), 1, buf.size(), p)) > 0;) s.append(buf.data(), n);
  return s;
}

}  // namespace detail

/// Takes a file; returns its bytes ("" if it cannot be read): what a tool wrote, or a file it must not have touched.
inline std::string file_contents(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Runs `command` (shell words) with stderr merged into stdout; ToolRun::output holds both, in the order written.
inline ToolRun run_command(const std::string& command) {
  ToolRun r;
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (!p) return r;
  r.output = detail::read_all(p);
  r.status = decode_status(::pclose(p));
  return r;
}

/// Runs `command` (shell words) with stdout and stderr apart: stderr goes to a temporary file of its own in
/// `scratch` (mkstemp: runs never share one), read back and removed. `scratch` must exist and be a directory the
/// test does not list for files left behind.
inline ToolRun run_separated(const std::string& command, const std::filesystem::path& scratch) {
  ToolRun r;
  std::string err_file = (scratch / "stderr-XXXXXX").string();
  const int fd = ::mkstemp(err_file.data());
  if (fd < 0) {
    r.err = "tool_run.hpp: no temporary file for stderr in " + scratch.string();
    r.output = r.err;
    return r;
  }
  ::close(fd);
  FILE* p = ::popen((command + " 2>" + tool_tests::quoted(err_file)).c_str(), "r");
  if (p) {
    r.out = detail::read_all(p);
    r.status = decode_status(::pclose(p));
  }
  r.err = file_contents(err_file);
  std::error_code ec;
  std::filesystem::remove(err_file, ec);
  r.output = r.out + r.err;
  return r;
}

/// Runs `binary` with `args` (each quoted) after the environment prefix `env`, stdout and stderr apart
/// (run_separated, stderr's temporary file in `scratch`).
inline ToolRun run_tool(const std::filesystem::path& binary, const std::vector<std::string>& args,
                        const std::filesystem::path& scratch, const std::string& env = "") {
  return run_separated(command_line(binary, args, env), scratch);
}

/// Takes a directory; returns the names of what is in it (files, links, folders), sorted: for the checks that a
/// refused run left no file behind, or exactly the files expected. Throws if the directory does not exist (a
/// missing directory must not pass for an empty one).
/// The number after "key": in a one-line JSON object (NaN if absent).
inline double json_number(const std::string& json, const std::string& key) {
  const auto at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return std::nan("");
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

inline std::vector<std::string> files_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// A directory of the running test's own: <parent>/<prefix>_<pid>_<suite>.<test> (characters other than letters,
/// digits, '-', '_' and '.' made '_': typed tests' names hold '/'), emptied and created when constructed, removed
/// with all it holds when destroyed. The pid and the test's name keep parallel test programs and successive tests
/// apart; the removal keeps the system's temp directory clean whether the test passes or not.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& prefix,
                      const std::filesystem::path& parent = std::filesystem::temp_directory_path()) {
    std::string name = prefix + "_" + std::to_string(::getpid());
    if (const auto* info = ::testing::UnitTest::GetInstance()->current_test_info())
      name += "_" + std::string(info->test_suite_name()) + "." + info->name();
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    path_ = parent / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::filesystem::path& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Takes "name=path|name=path" (CMake's grtrace_tool_paths); returns path by name.
inline std::map<std::string, std::string> named_paths(const std::string& joined) {
  std::map<std::string, std::string> out;
  std::stringstream ss(joined);
  for (std::string item; std::getline(ss, item, '|');)
    if (const auto eq = item.find('='); eq != std::string::npos) out[item.substr(0, eq)] = item.substr(eq + 1);
  return out;
}

}  // namespace grtrace::tool_tests
