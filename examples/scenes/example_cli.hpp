// examples/scenes/example_cli.hpp
// The little that the example programs share besides the library: their command line (--out FILE.exr, --size N
// and named numbers of their own), writing the frame as EXR + PNG with a one-line JSON summary, and the exit codes
// (2 for bad input, before anything is traced or written; 1 for anything else; --version prints "<program>
// <version>" and exits 0 before any work). Kept apart so that each example's .cpp shows only its physics.
#pragma once

#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/frame_files.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/version.hpp"

#include <cstdlib>
#include <exception>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

struct ExampleArgs {
  std::string out;                        ///< the EXR; the PNG goes beside it
  int size = 512;                         ///< width and height in pixels
  std::map<std::string, double> numbers;  ///< "--name value" options of the example, with their defaults
};

/// Thrown by parse_example_args for --version; run_example prints "<program> <version>" and exits 0.
struct VersionRequested {};

/// Parses "--out FILE.exr --size N --<name> X ..." and checks both output paths; throws std::invalid_argument with
/// the usage (or what is wrong with the path) on anything else, before any work. "--version" in an option's place
/// throws VersionRequested (handled by run_example).
inline ExampleArgs parse_example_args(int argc, char** argv, ExampleArgs defaults) {
  for (int i = 1; i < argc; i += 2)
    if (std::string(argv[i]) == "--version") throw VersionRequested{};
  std::string usage = std::string("usage: ") + argv[0] + " [--out FILE.exr] [--size 8..4096] [--version]";
  for (const auto& [name, value] : defaults.numbers) usage += " [--" + name + " X]";
  auto number = [&](const std::string& text) {  // the whole text must be a number
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0') throw std::invalid_argument("'" + text + "' is not a number; " + usage);
    return v;
  };
  ExampleArgs a = defaults;
  for (int i = 1; i < argc; i += 2) {
    const std::string key = argv[i], value = i + 1 < argc ? argv[i + 1] : "";
    if (key == "--out" && value.size() > 4 && value.ends_with(".exr")) a.out = value;
    else if (key == "--size" && number(value) >= 8 && number(value) <= 4096) a.size = static_cast<int>(number(value));
    else if (key.starts_with("--") && a.numbers.count(key.substr(2)) && i + 1 < argc) a.numbers[key.substr(2)] = number(value);
    else throw std::invalid_argument(usage);
  }
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
  std::cout << "{\"out\":\"" << a.out << "\",\"png\":\"" << png << "\",\"seconds\":" << frame.stats.seconds
            << ",\"status_counts\":" << frame.image.metadata.at("status_counts") << "}\n";
}

/// Runs an example's body: --version prints "<program> <version>" and exits 0, bad input (std::invalid_argument)
/// exits 2 with its message, other failures exit 1.
template <class Body>
int run_example(const char* program, Body&& body) {
  try {
    body();
    return 0;
  } catch (const VersionRequested&) {
    std::cout << program << " " << grtrace::kVersion << "\n";
    return 0;
  } catch (const std::invalid_argument& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return 1;
  }
}
