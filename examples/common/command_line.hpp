// examples/common/command_line.hpp
// Minimal, strict option parsing shared by the grtrace tools: `--name value` and `--flag`.
// Every option is declared with its default and help text, so --help lists all of them; unknown options,
// missing values and malformed or non-finite numbers raise UsageError with a message that says what to change.
#pragma once

#include <cmath>
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

  /// Returns false when --help was asked for (the help text is then already printed to stdout).
  bool parse(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
      std::string arg = argv[i];
      if (arg == "--help" || arg == "-h") {
        std::fputs(help().c_str(), stdout);
        return false;
      }
      if (arg.rfind("--", 0) != 0) throw UsageError("unexpected argument '" + arg + "' (options start with --)");
      std::string name = arg.substr(2), value;
      if (auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
      }
      const Spec* spec = find(name);
      if (!spec) throw UsageError("unknown option '--" + name + "' (see --help for the list)");
      if (spec->takes_value) {
        if (value.empty()) {
          if (i + 1 >= argc) throw UsageError("option --" + name + " needs a value");
          value = argv[++i];
        }
        values_[name] = value;
      } else {
        values_[name] = "1";
      }
    }
    return true;
  }

  bool given(const std::string& name) const { return values_.count(name) > 0; }
  bool flag_set(const std::string& name) const { return given(name); }

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

/// Runs a tool's body with the exit-code convention every grtrace tool shares: 0 when done (or after --help),
/// 2 for bad input (UsageError, before any work), 1 for any other failure; errors go to stderr as
/// "<program>: error: <what to change>". The body returns the exit code.
template <class Body>
int run_tool(CommandLine& cli, int argc, char** argv, Body&& body) {
  try {
    if (!cli.parse(argc, argv)) return 0;
    return body();
  } catch (const UsageError& e) {
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << cli.program() << ": error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace grtrace::tools
