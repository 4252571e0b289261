// examples/scenes/example_cli.hpp
// The little that the example programs share besides the library: their command line (--out FILE.exr, --size N
// and named numbers of their own, through the tools' CommandLine, so --help, --version, --config FILE and
// --write-config FILE work as in every tool), writing the frame as EXR + PNG with a one-line JSON summary, and the
// exit codes (2 for bad input, before anything is traced or written; 1 for anything else; 0 after --help,
// --version, --write-config). Kept apart so that each example's .cpp shows only its physics.
#pragma once

#include "command_line.hpp"
#include "json_writer.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/frame_files.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/version.hpp"

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

struct ExampleArgs {
  std::string out;                        ///< the EXR; the PNG goes beside it
  int size = 512;                         ///< width and height in pixels
  std::map<std::string, double> numbers;  ///< "--name value" options of the example, with their defaults
};

/// Thrown by parse_example_args when --help, --version or --write-config was answered (already printed or
/// written): run_example exits 0 without the work.
struct NothingMoreToDo {};

/// Parses "--out FILE.exr --size N --<name> X ..." with the tools' CommandLine (examples/common/command_line.hpp:
/// also --name=value, --config FILE, --write-config FILE, --help, --version) and checks both output paths; throws
/// std::invalid_argument (or tools::UsageError) saying what to change, before any work; NothingMoreToDo when
/// --help, --version or --write-config was answered.
inline ExampleArgs parse_example_args(int argc, char** argv, ExampleArgs defaults) {
  const std::string program = std::filesystem::path(argv[0]).filename().string();
  grtrace::tools::CommandLine cli(program, "An example scene of grtrace (examples/scenes): writes an EXR and a PNG.");
  cli.option("out", defaults.out, "output EXR; the PNG preview goes beside it")
      .option("size", std::to_string(defaults.size), "width and height in pixels, 8 .. 4096");
  for (const auto& [name, value] : defaults.numbers)
    cli.option(name, grtrace::tools::config_detail::shortest_text(value), "this example's " + name);
  if (!cli.parse(argc, argv)) throw NothingMoreToDo{};
  ExampleArgs a = defaults;
  a.out = cli.text("out");
  if (a.out.size() <= 4 || !a.out.ends_with(".exr")) throw std::invalid_argument("--out must name an .exr file, got '" + a.out + "'");
  const double size = cli.number("size");
  if (!(size >= 8 && size <= 4096)) throw std::invalid_argument("--size must be 8 .. 4096 pixels, got " + cli.text("size"));
  a.size = static_cast<int>(size);
  for (auto& [name, value] : a.numbers) value = cli.number(name);
  for (const std::string& path : {a.out, a.out.substr(0, a.out.size() - 4) + ".png"}) {
    try {  // before any work: a missing or unwritable directory, a directory in the way
      grtrace::check_output_path(path);
    } catch (const std::runtime_error& e) {
      throw std::invalid_argument(e.what());
    }
  }
  return a;
}

/// Writes the EXR (all data channels) and its PNG preview as one set (both new or both old, render/output_file.hpp),
/// and prints {"out","png","seconds","status_counts"}.
inline void write_example_frame(const ExampleArgs& a, const grtrace::Frame& frame) {
  const std::string png = a.out.substr(0, a.out.size() - 4) + ".png";
  grtrace::OutputSet files;
  grtrace::write_exr_and_preview(files, a.out, png, frame.image);
  files.commit();
  grtrace::tools::JsonObject counts, json;
  for (std::size_t i = 0; i < grtrace::kRayStatusCount; ++i)
    counts.add(grtrace::kRayStatusNames[i], frame.stats.status_counts[i]);
  json.add("out", a.out).add("png", png).add("seconds", frame.stats.seconds).add("status_counts", counts);
  std::cout << json.str() << "\n";
}

/// Runs an example's body: exits 0 after --help/--version/--write-config (NothingMoreToDo), 2 with the message
/// for bad input (std::invalid_argument, tools::UsageError), 1 for other failures.
template <class Body>
int run_example(const char* program, Body&& body) {
  try {
    body();
    return 0;
  } catch (const NothingMoreToDo&) {
    return 0;
  } catch (const grtrace::tools::UsageError& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 1;
  }
}
