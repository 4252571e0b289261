// tests/gpu/ptx_null_calls.hpp
// Finds calls through a null function pointer in unoptimised PTX: what nvcc emits, without a diagnostic, where device
// code reaches a function it could not compile for the device (std::optional's in-place constructor, Eigen's
// asDiagonal() assignment: core/optional.hpp). Such a call stops the GPU with "invalid program counter" when the
// code is unoptimised; optimised, cicc drops it as unreachable and the kernel computes nonsense or never ends, so
// only the -O0 PTX shows it.
//
// Takes:   PTX text as cicc -O0 writes it: a register set by `mov.u64 %rdN, 0;` and then called (`call %rdN, ...`,
//          with or without a (retval) list, target on the call's line or the next one).
// Returns: the functions (mangled names, as in the PTX) that make such a call, once each, in order.
// Assumes: registers are per function (reset at each .func or .entry); a register written again by any other
//          instruction no longer holds the null pointer.
#pragma once

#include <cctype>
#include <istream>
#include <set>
#include <string>
#include <vector>

namespace gpu_test {

inline std::string trimmed(const std::string& s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

/// The first token of s (up to white space or a comma).
inline std::string first_token(const std::string& s) {
  const std::string t = trimmed(s);
  std::size_t end = 0;
  while (end < t.size() && !std::isspace(static_cast<unsigned char>(t[end])) && t[end] != ',') ++end;
  return t.substr(0, end);
}

inline bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

inline std::vector<std::string> ptx_null_calls(std::istream& ptx) {
  std::vector<std::string> lines;
  for (std::string line; std::getline(ptx, line);) lines.push_back(trimmed(line));
  std::vector<std::string> found;
  std::string function;
  std::set<std::string> null_registers;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (starts_with(line, ".func") || starts_with(line, ".visible .func") || starts_with(line, ".weak .func") ||
        starts_with(line, ".entry") || starts_with(line, ".visible .entry")) {
      std::string name = line.substr(line.find_last_of(" \t") + 1);
      if (!name.empty() && name.back() == '(') name.pop_back();
      function = name;
      null_registers.clear();
      continue;
    }
    if (starts_with(line, "call")) {
      // The target: after "call[.uni]" and an optional "(retval...)," list, on this line or the next ones.
      std::string rest =
          line.substr(line.find_first_of(" \t") == std::string::npos ? line.size() : line.find_first_of(" \t"));
      for (std::size_t j = i + 1; j < lines.size() && j <= i + 3; ++j) rest += " " + lines[j];
      rest = trimmed(rest);
      if (starts_with(rest, "(retval")) rest = rest.substr(rest.find(')') + 1);
      if (starts_with(trimmed(rest), ",")) rest = trimmed(rest).substr(1);
      const std::string target = first_token(rest);
      if (null_registers.count(target) && (found.empty() || found.back() != function)) found.push_back(function);
      continue;
    }
    // An instruction writing a 64-bit register: "op %rdN, ...;". A zero makes it a null pointer, anything else not.
    const std::size_t space = line.find_first_of(" \t");
    if (space == std::string::npos || line[0] == '.' || line[0] == '/') continue;
    const std::string destination = first_token(line.substr(space));
    if (!starts_with(destination, "%rd")) continue;
    const std::string op = line.substr(0, space);
    const std::string source = trimmed(line.substr(line.find(',') + 1));
    if ((op == "mov.u64" || op == "mov.b64") && source == "0;") null_registers.insert(destination);
    else null_registers.erase(destination);
  }
  return found;
}

}  // namespace gpu_test
