// examples/common/command_line.hpp
// Minimal, strict option parsing shared by the grtrace tools: `--name value`, `--name=value`, `--flag` and
// `--flag=BOOL` (true/false, yes/no, on/off, 1/0; anything else is refused).
// Every option is declared with its default and help text, so --help lists all of them; unknown options,
// missing values and malformed or non-finite numbers raise UsageError with a message that says what to change.
// Every tool also answers --help and --version ("<program> <version>", the CMake project version from the
// generated grtrace/version.hpp) on stdout and exits 0 before any other work.
// Scene files (config_file.hpp), for every tool and every option it declares: `--config FILE` reads the options
// from a TOML file (keys = option names, flags take booleans) or from the header of an EXR written by
// grtrace-render; options on the command line override it. `--write-config FILE` saves the effective
// configuration as TOML (given options as keys, the others as commented defaults) and exits 0 without the
// tool's work, after the tool has checked the options as for a run: a configuration the tool would refuse is
// refused, not saved.
// Why the hand tokenizer and not CLI11 (Debian 12's 2.1.2, tried on these three cases): CLI11 refuses the
// explicit empty value `--out=`, takes the next option as the value in `--out= --camera-r 3`, and turns
// `--status-map=` into true; this parser's contract (kept by tests and the fuzz corpus) is the opposite for all
// three, and its messages name the option and what to change.
#pragma once

#include "config_file.hpp"
#include "grtrace/core/memory_limit.hpp"
#include "grtrace/core/number_text.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/version.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <cstdlib>
#include <initializer_list>
#include <iostream>
#include <limits>
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

namespace detail {
/// Refuses (UsageError naming --option) an output path that cannot be written: empty, in a missing or
/// unwritable directory, or a directory itself (check_output_path). Creates nothing. Tools call
/// check_command_output, which adds the inputs: a writable path can still be the file the command reads.
inline void check_output_option(const std::string& option, const std::filesystem::path& path) {
  if (path.empty()) throw UsageError("--" + option + " needs a file name, got ''");
  try {
    check_output_path(path);
  } catch (const std::runtime_error& e) {
    throw UsageError("--" + option + ": " + e.what());
  }
}
}  // namespace detail

/// Refuses an output that would replace one of the inputs (the same file, or the same path before it exists).
inline void check_not_input(const std::string& option, const std::filesystem::path& output,
                            const std::string& input_option, const std::filesystem::path& input) {
  if (!input.empty() && same_file(output, input))
    throw UsageError("--" + option + " '" + output.string() + "' is the input given as --" + input_option +
                     "; choose another output file");
}

/// The environment a tool runs in, checked with its options (before any work), UsageError saying what to change:
/// GRTRACE_MEMORY_LIMIT a memory size (core/memory_limit.hpp; a tool that never sizes an image would otherwise
/// ignore a mistyped limit), OMP_NUM_THREADS whole numbers of threads from 1 to kMaxThreads (the OpenMP runtime
/// takes the variable as it is and crashes creating a million threads).
inline constexpr long kMaxThreads = 1024;
inline void check_environment() {
  try {
    (void)memory_limit_bytes();
  } catch (const MemoryLimitError& e) {
    throw UsageError(e.what());
  }
  const char* omp = std::getenv("OMP_NUM_THREADS");
  if (omp == nullptr || *omp == '\0') return;
  std::stringstream list{std::string(omp)};
  for (std::string item; std::getline(list, item, ',');) {  // one count per nesting level
    const ParsedWholeNumber n = parse_whole_number(item);
    if (n.result != NumberText::ok || n.value < 1 || n.value > kMaxThreads)
      throw UsageError("OMP_NUM_THREADS='" + std::string(omp) + "' is not a thread count from 1 to " +
                       std::to_string(kMaxThreads) + "; unset it (all cores) or give the count with --threads N "
                       "where the tool has it");
  }
}

class CommandLine;
/// The checks every output file of a command gets before any work (defined below CommandLine).
inline void check_command_output(const CommandLine& cli, const std::string& option,
                                 const std::filesystem::path& path,
                                 std::initializer_list<std::pair<const char*, std::string>> inputs);

class CommandLine {
 public:
  CommandLine(std::string program, std::string summary) : program_(std::move(program)), summary_(std::move(summary)) {}

  /// An option taking a value; `default_value` is shown in --help and used when absent ("" = no default).
  CommandLine& option(const std::string& name, const std::string& default_value, const std::string& help) {
    declare({name, default_value, help, true});
    return *this;
  }
  CommandLine& flag(const std::string& name, const std::string& help) {
    declare({name, "", help, false});
    return *this;
  }

  /// Takes the tool's arguments; returns false when --help or --version was asked for (the help text or
  /// "<program> <version>" is then printed to stdout; the tool exits 0). --write-config FILE is only noted here:
  /// the tool checks the options first and then saves them (write_config_if_asked).
  /// Throws UsageError for anything malformed on the command line or in the --config file, before any work.
  /// Assumes every option was declared before.
  bool parse(int argc, char** argv) {
    std::vector<std::pair<const Spec*, std::string>> assignments;  // the command line's, in order
    std::optional<std::string> config_path, write_path;
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
      const bool built_in = name == kConfigOption || name == kWriteConfigOption;
      const Spec* spec = find(name);
      if (!spec && !built_in) throw UsageError("unknown option '--" + name + "' (see --help for the list)");
      if (built_in || spec->takes_value) {
        if (!inline_value) {  // "--name=" is an explicit empty value, never the next argument
          if (i + 1 >= argc) throw UsageError("option --" + name + " needs a value");
          value = argv[++i];
        }
        if (name == kConfigOption) config_path = value;
        else if (name == kWriteConfigOption) write_path = value;
        else assignments.emplace_back(spec, value);
      } else if (!inline_value) {
        assignments.emplace_back(spec, "1");
      } else {
        const auto b = parse_bool(value);
        if (!b)
          throw UsageError("--" + name + "=" + value +
                           ": a flag takes true/false, yes/no, on/off or 1/0 (or no value at all)");
        assignments.emplace_back(spec, *b ? "1" : "0");
      }
    }
    values_.clear();
    defaults_.clear();
    config_file_ = config_path.value_or("");
    if (config_path) apply_config(*config_path);
    for (const auto& [spec, value] : assignments) assign(*spec, value);
    write_config_path_ = write_path;
    write_config_done_ = false;
    check_environment();
    return true;
  }

  /// True when --write-config FILE was given: the tool then checks its options as for a run and calls
  /// write_config_if_asked() before any work (run_tool makes sure it did).
  bool write_config_asked() const { return write_config_path_.has_value(); }
  /// Saves the effective options to the --write-config FILE, if one was given, and returns true (the tool then
  /// exits 0 without its work); false otherwise. Call it after every check of the options and before any work or
  /// side effect, so that only a configuration the tool would run is saved.
  bool write_config_if_asked() {
    if (!write_config_path_) return false;
    write_config(*write_config_path_);
    write_config_done_ = true;
    return true;
  }
  bool write_config_done() const { return write_config_done_; }

  bool given(const std::string& name) const { return values_.count(name) > 0; }
  /// Whether the tool declared an option of this name.
  bool declares(const std::string& name) const { return find(name) != nullptr; }
  /// The file --config read ("" if none): an input every output of the command is checked against.
  const std::string& config_file() const { return config_file_; }
  bool flag_set(const std::string& name) const { return given(name); }

  /// "true"/"yes"/"on"/"1" -> true, "false"/"no"/"off"/"0" -> false (any case), anything else -> nullopt.
  static std::optional<bool> parse_bool(std::string v) {
    for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (v == "true" || v == "yes" || v == "on" || v == "1") return true;
    if (v == "false" || v == "no" || v == "off" || v == "0") return false;
    return std::nullopt;
  }

  /// The option's effective text: given (command line or config file), else the default an EXR config recorded,
  /// else the declared default.
  std::string text(const std::string& name) const {
    if (auto it = values_.find(name); it != values_.end()) return it->second;
    const Spec* spec = find(name);
    if (!spec) throw std::logic_error("option --" + name + " was never declared");
    if (auto it = defaults_.find(name); it != defaults_.end()) return it->second;
    return spec->default_value;
  }

  double number(const std::string& name) const { return parse_number(name, text(name)); }

  long integer(const std::string& name) const { return parse_integer(name, text(name)); }

  /// A comma-separated list of exactly `count` numbers (count 0: any length).
  std::vector<double> numbers(const std::string& name, std::size_t count) const {
    return parse_numbers(name, text(name), count);
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
    const auto built_in = [](std::string left, const std::string& text) {  // aligned like the options above
      left.resize(30, ' ');
      return left + " " + text + "\n";
    };
    h += built_in("  --config FILE", "read options from a TOML scene file (keys: the option names above, flags");
    h += built_in("", "true/false) or an EXR's header; options given here override it");
    h += built_in("  --write-config FILE", "save the effective options as a TOML scene file and exit (-: print)");
    h += built_in("  --help", "print this help and exit");
    h += built_in("  --version", "print \"" + program_ + " <version>\" and exit");
    return h;
  }

  const std::string& program() const { return program_; }

  /// (name, effective value) of every option, given or defaulted, in declaration order; a flag's value is "true"
  /// or "false", so a header that records these (grtrace-render's option_<name>) can be read back by --config.
  std::vector<std::pair<std::string, std::string>> values() const {
    std::vector<std::pair<std::string, std::string>> out;
    for (const auto& s : specs_) out.emplace_back(s.name, s.takes_value ? text(s.name) : flag_set(s.name) ? "true" : "false");
    return out;
  }

  /// The options given (on the command line or in a config file, flags only when set), comma-separated in
  /// declaration order: what a header records beside values() so that --config of it tells given from default
  /// (several tools choose a default from other options when one is not given, e.g. the Kerr observer).
  std::string given_names() const {
    std::vector<std::string> names;
    for (const auto& s : specs_)
      if (given(s.name)) names.push_back(s.name);
    return join(names, ",");
  }

 private:
  struct Spec {
    std::string name, default_value, help;
    bool takes_value;
  };

  /// Takes a new option's spec; refuses (std::logic_error: a programming error) a name declared twice or one of
  /// the names every tool answers itself.
  void declare(Spec spec) {
    if (find(spec.name) || spec.name == kConfigOption || spec.name == kWriteConfigOption || spec.name == "help" ||
        spec.name == "version")
      throw std::logic_error("option --" + spec.name + " is declared twice or reserved");
    specs_.push_back(std::move(spec));
  }

  /// Takes a declared option and its command-line text (a flag: "1" set, "0" cleared); records it as given.
  void assign(const Spec& spec, const std::string& value) {
    if (spec.takes_value || value == "1") values_[spec.name] = value;
    else values_.erase(spec.name);
  }

  /// Reads the --config file and applies its entries before the command line's (which override them). Refuses
  /// (UsageError naming the file and the key) an unreadable or malformed file, a key that is no option of this
  /// tool, and a value of the wrong kind: a table, array or date anywhere, a string or number for a flag, a
  /// boolean for an option that takes a value.
  void apply_config(const std::string& path) {
    ConfigFile file;
    try {
      file = read_config_file(path);
    } catch (const ConfigError& e) {
      throw UsageError(e.what());
    }
    const std::string where = "--config '" + path + "'";
    for (const ConfigEntry& e : file.entries) {
      const std::string at = e.line > 0 ? " (line " + std::to_string(e.line) + ")" : "";
      const Spec* spec = find(e.key);
      if (!spec) {
        const std::string key = file.from_exr ? "option_" + e.key : e.key;
        throw UsageError(where + ": unknown key '" + key + "'" + at + ": " + program_ + " has no option --" + e.key +
                         (file.from_exr ? " (was this EXR written by another tool or version?)" : "") +
                         "; remove it or use an option name from --help, without the dashes");
      }
      if (e.kind == ConfigValueKind::unsupported)
        throw UsageError(where + ": key '" + e.key + "'" + at + " is " + e.type_name + "; give one value (" +
                         (spec->takes_value ? "a string or a number, e.g. " + e.key + " = \"...\""
                                            : "true or false, e.g. " + e.key + " = true") + ")");
      if (spec->takes_value) {
        if (e.kind == ConfigValueKind::boolean)
          throw UsageError(where + ": key '" + e.key + "'" + at + " takes a value, not true/false; write " + e.key +
                           " = \"...\" or a number (see --help)");
        // A NUL would cut the value short wherever it becomes a C string (a path handed to the system).
        if (e.text.find('\0') != std::string::npos)
          throw UsageError(where + ": key '" + e.key + "'" + at + " holds a NUL character (\\u0000); remove it");
        if (e.given) values_[e.key] = e.text;
        else defaults_[e.key] = e.text;
        continue;
      }
      std::optional<bool> set;
      if (e.kind == ConfigValueKind::boolean || e.kind == ConfigValueKind::header_text) set = parse_bool(e.text);
      if (!set)
        throw UsageError(where + ": key '" + e.key + "'" + at + " is a flag: write " + e.key + " = true or " + e.key +
                         " = false (a TOML boolean, without quotes)");
      if (*set) values_[e.key] = "1";
    }
  }

  /// Writes the effective configuration to `path` as TOML, whole or not at all (output_file.hpp), or to standard
  /// output for "-": the given options as keys, the others as commented-out defaults (uncommenting one makes it
  /// given, which can change a default some tool derives from other options). Refuses (UsageError) an unwritable
  /// path, one that is not a regular file (a device, a FIFO), or the --config file.
  void write_config(const std::string& path) const {
    auto write = [&](std::ostream& os) {
      os << "# " << program_ << " " << grtrace::kVersion << " scene file: " << program_ << " --config FILE\n"
         << "# Keys are option names (see --help); options on the command line override them.\n"
         << "# Commented lines are defaults: uncomment a line to set it.\n";
      for (const Spec& spec : specs_)
        os << (given(spec.name) ? "" : "# ") << spec.name << " = "
           << (spec.takes_value ? toml_value_text(text(spec.name)) : flag_set(spec.name) ? "true" : "false") << "\n";
      if (!os.flush()) throw std::runtime_error("cannot write '" + path + "'");
    };
    if (path == "-") return write(std::cout);
    check_command_output(*this, kWriteConfigOption, path, {});
    write_file_atomically(path, write);
  }

  const Spec* find(const std::string& name) const {
    for (const auto& s : specs_)
      if (s.name == name) return &s;
    return nullptr;
  }

 public:
  /// f(), its std::invalid_argument (a refusal of the input) rethrown as UsageError.
  template <class F>
  static auto as_usage_error(F&& f) {
    try {
      return f();
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }

  /// The number in `t` (grtrace/core/number_text.hpp: the same rules as scene files and camera-path CSVs, and the
  /// same refusal as the application library's and the Python module's), or UsageError naming --name. `from` is
  /// added to the message (e.g. " (from the frame's header)").
  static double parse_number(const std::string& name, const std::string& t, const std::string& from = "") {
    return as_usage_error([&] { return grtrace::option_number(name, t, from); });
  }
  /// The whole number in `t` (the same rules), or UsageError naming --name.
  static long parse_integer(const std::string& name, const std::string& t, const std::string& from = "") {
    return as_usage_error([&] { return grtrace::option_integer(name, t, from); });
  }
  /// The comma-separated numbers in `t`, exactly `count` of them (0: any number), each read as parse_number reads
  /// one, or UsageError naming --name.
  static std::vector<double> parse_numbers(const std::string& name, const std::string& t, std::size_t count) {
    return as_usage_error([&] { return grtrace::option_numbers(name, t, count); });
  }

  /// The options every tool answers itself: --config FILE and --write-config FILE.
  static constexpr const char* kConfigOption = "config";
  static constexpr const char* kWriteConfigOption = "write-config";

 private:
  std::string program_, summary_;
  std::string config_file_;
  std::optional<std::string> write_config_path_;
  bool write_config_done_ = false;
  std::vector<Spec> specs_;
  std::map<std::string, std::string> values_;    ///< given options (command line or config file); set flags: "1"
  std::map<std::string, std::string> defaults_;  ///< defaults recorded in an EXR given as --config (not given)
};

/// The checks every output file of a command gets before any work: a writable regular file or new name
/// (check_output_option), and not one of the command's inputs: the --config file, and each {option, path} of
/// `inputs` (empty paths skipped). UsageError naming both options. A command that only saves its options
/// (--write-config) writes none of its other outputs, so only that file is checked then: a configuration read
/// from a frame's header names the frame itself as --out, and saving it is fine.
inline void check_command_output(const CommandLine& cli, const std::string& option, const std::filesystem::path& path,
                                 std::initializer_list<std::pair<const char*, std::string>> inputs) {
  if (cli.write_config_asked() && option != CommandLine::kWriteConfigOption) return;
  detail::check_output_option(option, path);
  check_not_input(option, path, "config", cli.config_file());
  for (const auto& [input_option, input] : inputs) check_not_input(option, path, input_option, input);
}

/// Refuses (UsageError) an --out that does not name an EXR file: a file name ending in ".exr" with a name before it
/// (its PNG preview and a flight's frames are named after that stem: "dir/.exr" would make hidden ".png" files).
inline void check_exr_output_name(const std::string& option, const std::string& path) {
  const std::string name = std::filesystem::path(path).filename().string();
  if (name.size() < 5 || !name.ends_with(".exr"))
    throw UsageError("--" + option + " must name an .exr file (a name, then .exr), got '" + path + "'");
}

/// An option that means something only when the command's other options say so.
struct OptionCondition {
  const char* option;  ///< without the dashes
  bool applies;        ///< the condition holds in this command
  const char* needs;   ///< what makes it apply, for the message ("--metric kerr")
};

/// Refuses an option given (on the command line or in a config file) where it means nothing, instead of ignoring
/// it silently (a spin without Kerr, a disk's radius without the disk): UsageError naming the option and what it
/// needs, before any work.
inline void refuse_inapplicable_options(const CommandLine& cli, std::initializer_list<OptionCondition> conditions) {
  for (const OptionCondition& c : conditions)
    if (!c.applies && cli.given(c.option))
      throw UsageError(std::string("--") + c.option + " applies only with " + c.needs +
                       ", which this command does not have; leave it out or add " + c.needs);
}

/// Runs a tool's body with the exit-code convention every grtrace tool shares: 0 when done (or after --help),
/// 2 for bad input (UsageError, before any work; MemoryLimitError: a size from input above the memory limit),
/// 1 for any other failure (std::bad_alloc included, with a message instead of an abort); errors go to stderr as
/// "<program>: error: <what to change>". The body returns the exit code; it checks every option, then calls
/// cli.write_config_if_asked() (returning 0 when it saved) before any work.
template <class Body>
int run_tool(CommandLine& cli, int argc, char** argv, Body&& body) {
  try {
    if (!cli.parse(argc, argv)) return 0;
    const int code = body();
    if (cli.write_config_asked() && !cli.write_config_done())  // a tool that forgot: its work ran unasked
      throw std::logic_error(cli.program() + " ran its work instead of saving --write-config (a bug: it must call "
                                             "write_config_if_asked() after its checks)");
    return code;
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
