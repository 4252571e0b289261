// examples/common/command_line.hpp
// Minimal, strict option parsing shared by the grtrace tools: `--name value`, `--name=value`, `--flag` and
// `--flag=BOOL` (true/false, yes/no, on/off, 1/0; anything else is refused).
// Every option is declared with its default and help text, so --help lists all of them; unknown options,
// missing values and malformed or non-finite numbers raise UsageError with a message that says what to change.
// Every tool also answers --help and --version ("<program> <version>", the CMake project version from the
// generated grtrace/version.hpp) on stdout and exits 0 before any other work.
#pragma once

#include "grtrace/core/memory_limit.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/version.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace grtrace::tools {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// "a|b|c" from a list of names (appends, which also keeps GCC 12's -Wrestrict false positive away).
template <class Names>
std::string join(const Names& names, std::string_view separator) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out.append(separator);
    out.append(n);
  }
  return out;
}

/// What --version prints: "<program> <version>\n" (the CMake project version).
inline std::string version_line(std::string_view program) {
  return std::string(program) + " " + std::string(grtrace::kVersion) + "\n";
}

class CommandLine {
 public:
  CommandLine(std::string program, std::string summary) : program_(std::move(program)), summary_(std::move(summary)) {}

  /// An option taking a value; `default_value` is shown in --help and used when absent ("" = no default).
  CommandLine& option(const std::string& name, const std::string& default_value, const std::string& help) {
    specs_.push_back({name, default_value, help, true});
    return *this;
  }
  CommandLine& flag(const std::string& name, const std::string& help) {
    specs_.push_back({name, "", help, false});
    return *this;
  }

  /// Returns false when --help or --version was asked for (the help text or "<program> <version>" is then already
  /// printed to stdout; the tool exits 0).
  bool parse(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
      std::string arg = argv[i];
      if (arg == "--help" || arg == "-h") {
        std::fputs(help().c_str(), stdout);
        return false;
      }
      if (arg == "--version") {
        std::fputs(version_line(program_).c_str(), stdout);
        return false;
      }
      if (arg.rfind("--", 0) != 0) throw UsageError("unexpected argument '" + arg + "' (options start with --)");
      std::string name = arg.substr(2), value;
      const bool inline_value = name.find('=') != std::string::npos;
      if (auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      const Spec* spec = find(name);
      if (!spec) throw UsageError("unknown option '--" + name + "' (see --help for the list)");
      if (spec->takes_value) {
        if (!inline_value) {  // "--name=" is an explicit empty value, never the next argument
          if (i + 1 >= argc) throw UsageError("option --" + name + " needs a value");
          value = argv[++i];
        }
        values_[name] = value;
      } else if (!inline_value) {
        values_[name] = "1";
      } else {
        const auto b = parse_bool(value);
        if (!b)
          throw UsageError("--" + name + "=" + value +
                           ": a flag takes true/false, yes/no, on/off or 1/0 (or no value at all)");
        if (*b) values_[name] = "1";
        else values_.erase(name);
      }
    }
    return true;
  }

  bool given(const std::string& name) const { return values_.count(name) > 0; }
  bool flag_set(const std::string& name) const { return given(name); }

  /// "true"/"yes"/"on"/"1" -> true, "false"/"no"/"off"/"0" -> false (any case), anything else -> nullopt.
  static std::optional<bool> parse_bool(std::string v) {
    for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (v == "true" || v == "yes" || v == "on" || v == "1") return true;
    if (v == "false" || v == "no" || v == "off" || v == "0") return false;
    return std::nullopt;
  }

  std::string text(const std::string& name) const {
    if (auto it = values_.find(name); it != values_.end()) return it->second;
    const Spec* spec = find(name);
    if (!spec) throw std::logic_error("option --" + name + " was never declared");
    return spec->default_value;
  }

  double number(const std::string& name) const { return parse_number(name, text(name)); }

  long integer(const std::string& name) const {
    const std::string t = text(name);
    char* end = nullptr;
    const long v = std::strtol(t.c_str(), &end, 10);
    if (t.empty() || *end != '\0') throw UsageError("--" + name + " expects a whole number, got '" + t + "'");
    return v;
  }

  /// A comma-separated list of exactly `count` numbers (count 0: any length).
  std::vector<double> numbers(const std::string& name, std::size_t count) const {
    std::vector<double> out;
    std::stringstream ss(text(name));
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(parse_number(name, item));
    if (count != 0 && out.size() != count)
      throw UsageError("--" + name + " expects " + std::to_string(count) + " comma-separated numbers, got '" +
                       text(name) + "'");
    return out;
  }

  std::string help() const {
    std::string h = "Usage: " + program_ + " [options]\n" + summary_ + "\n\nOptions:\n";
    for (const auto& s : specs_) {
      std::string left = "  --" + s.name + (s.takes_value ? " VALUE" : "");
      if (left.size() < 30) left.resize(30, ' ');
      h += left + " " + s.help;
      if (s.takes_value && !s.default_value.empty()) h += " (default: " + s.default_value + ")";
      h += "\n";
    }
    h += "  --help                         print this help and exit\n";
    h += "  --version                      print \"" + program_ + " <version>\" and exit\n";
    return h;
  }

  const std::string& program() const { return program_; }

  /// (name, effective value) of every option that takes a value, given or defaulted, in declaration order.
  std::vector<std::pair<std::string, std::string>> values() const {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& s : specs_)
      if (s.takes_value) out.emplace_back(s.name, text(s.name));
    return out;
  }

 private:
  struct Spec {
    std::string name, default_value, help;
    bool takes_value;
  };

  const Spec* find(const std::string& name) const {
    for (const auto& s : specs_)
      if (s.name == name) return &s;
    return nullptr;
  }

  static double parse_number(const std::string& name, const std::string& t) {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0') throw UsageError("--" + name + " expects a number, got '" + t + "'");
    if (!std::isfinite(v)) throw UsageError("--" + name + " must be finite, got '" + t + "'");
    return v;
  }

  std::string program_, summary_;
  std::vector<Spec> specs_;
  std::map<std::string, std::string> values_;
};

/// Refuses (UsageError naming --option) an output path that cannot be written: empty, in a missing or
/// unwritable directory, or a directory itself (check_output_path). Creates nothing.
inline void check_output_option(const std::string& option, const std::filesystem::path& path) {
  if (path.empty()) throw UsageError("--" + option + " needs a file name, got ''");
  try {
    check_output_path(path);
  } catch (const std::runtime_error& e) {
    throw UsageError("--" + option + ": " + e.what());
  }
}

/// Refuses an output that would replace one of the inputs (the same file, or the same path before it exists).
inline void check_not_input(const std::string& option, const std::filesystem::path& output,
                            const std::string& input_option, const std::filesystem::path& input) {
  if (!input.empty() && same_file(output, input))
    throw UsageError("--" + option + " '" + output.string() + "' is the input given as --" + input_option +
                     "; choose another output file");
}

/// Runs a tool's body with the exit-code convention every grtrace tool shares: 0 when done (or after --help),
/// 2 for bad input (UsageError, before any work; MemoryLimitError: a size from input above the memory limit),
/// 1 for any other failure (std::bad_alloc included, with a message instead of an abort); errors go to stderr as
/// "<program>: error: <what to change>". The body returns the exit code.
template <class Body>
int run_tool(CommandLine& cli, int argc, char** argv, Body&& body) {
  try {
    if (!cli.parse(argc, argv)) return 0;
    return body();
  } catch (const UsageError& e) {
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 2;
  } catch (const MemoryLimitError& e) {  // a size that came from input (options or a file)
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << cli.program() << ": error: out of memory; use a smaller size (image, grid, step count) or a "
              << "machine with more memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace grtrace::tools
