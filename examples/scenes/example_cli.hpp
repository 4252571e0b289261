// examples/scenes/example_cli.hpp
// The little that the example programs share besides the library: their command line (--out FILE.exr, --size N
// and named numbers of their own, through the tools' CommandLine, so --help, --version, --config FILE and
// --write-config FILE work as in every tool), writing the frame as EXR + PNG with a one-line JSON summary, and the
// exit codes (2 for bad input, before anything is traced or written; 1 for anything else; 0 after --help,
// --version, --write-config). Kept apart so that each example's .cpp shows only its physics, and compiled once
// (example_cli.cpp, the static library grtrace_example_cli): the option parser, TOML, JSON, EXR and PNG code is
// not compiled again in every example (about 6 s of each example's compile time).
#pragma once

#include "grtrace/render/frame.hpp"
#include "grtrace/spectra/line_profile_result.hpp"

#include <functional>
#include <map>
#include <string>
#include <vector>

struct ExampleArgs {
  std::string out;                        ///< the EXR; the PNG goes beside it
  int size = 512;                         ///< width and height in pixels
  std::map<std::string, double> numbers;  ///< "--name value" options of the example, with their defaults
  /// further pictures beside the EXR, by suffix: "-orders" is NAME-orders.png (checked with the others before work)
  std::vector<std::string> more_pictures{};
};

/// Thrown by parse_example_args when --help, --version or --write-config was answered (already printed or
/// written): run_example exits 0 without the work.
struct NothingMoreToDo {};

/// Parses "--out FILE.exr --size N --<name> X ..." with the tools' CommandLine (examples/common/command_line.hpp:
/// also --name=value, --config FILE, --write-config FILE, --help, --version) and checks both output paths; throws
/// std::invalid_argument (or tools::UsageError) saying what to change, before any work; NothingMoreToDo when
/// --help, --version or --write-config was answered.
ExampleArgs parse_example_args(int argc, char** argv, ExampleArgs defaults);

/// Writes the EXR (all data channels) and its PNG preview as one set (both new or both old, render/output_file.hpp),
/// and prints {"out","png","seconds","status_counts"}.
void write_example_frame(const ExampleArgs& a, const grtrace::Frame& frame);

/// Writes `image` (any channels; R, G, B for its preview) as the EXR and its PNG preview, and `pictures` (one per
/// ExampleArgs::more_pictures, in order) beside them, as one set.
void write_example_image(const ExampleArgs& a, const grtrace::Image& image,
                         const std::vector<grtrace::LineChart>& pictures);

/// Runs an example's body: exits 0 after --help/--version/--write-config (NothingMoreToDo), 2 with the message
/// for bad input (std::invalid_argument, tools::UsageError), 1 for other failures.
int run_example(const char* program, const std::function<void()>& body);
