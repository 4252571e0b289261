// The example programs' command line, frame files and exit codes, compiled once (see example_cli.hpp).
#include "example_cli.hpp"

#include "command_line.hpp"
#include "json_writer.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/frame_files.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/render/png_preview.hpp"

#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>

ExampleArgs parse_example_args(int argc, char** argv, ExampleArgs defaults) {
  const std::string program = std::filesystem::path(argv[0]).filename().string();
  grtrace::tools::CommandLine cli(program, "An example scene of grtrace (examples/scenes): writes an EXR and a PNG.");
  cli.option("out", defaults.out, "output EXR; the PNG preview goes beside it")
      .option("size", std::to_string(defaults.size), "width and height in pixels, 8 .. 4096");
  for (const auto& [name, value] : defaults.numbers)
    cli.option(name, grtrace::tools::config_detail::shortest_text(value), "this example's " + name);
  if (!cli.parse(argc, argv)) throw NothingMoreToDo{};
  ExampleArgs a = defaults;
  a.out = cli.text("out");
  grtrace::tools::check_exr_output_name("out", a.out);
  const long size = cli.integer("size");
  if (!(size >= 8 && size <= 4096)) throw std::invalid_argument("--size must be 8 .. 4096 pixels, got " + cli.text("size"));
  a.size = static_cast<int>(size);
  for (auto& [name, value] : a.numbers) value = cli.number(name);
  // Before any work: a missing or unwritable directory, a directory in the way, the --config file read.
  std::vector<std::string> paths{a.out, a.out.substr(0, a.out.size() - 4) + ".png"};
  for (const std::string& suffix : a.more_pictures)
    paths.push_back(a.out.substr(0, a.out.size() - 4) + suffix + ".png");
  for (const std::string& path : paths) grtrace::tools::check_command_output(cli, "out", path, {});
  if (cli.write_config_if_asked()) throw NothingMoreToDo{};  // checked as for a run: saved, nothing rendered
  return a;
}

void write_example_frame(const ExampleArgs& a, const grtrace::Frame& frame) {
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

void write_example_image(const ExampleArgs& a, const grtrace::Image& image,
                         const std::vector<grtrace::LineChart>& pictures) {
  if (pictures.size() != a.more_pictures.size())
    throw std::logic_error("write_example_image: one picture per ExampleArgs::more_pictures");
  const std::string stem = a.out.substr(0, a.out.size() - 4);
  grtrace::OutputSet files;
  grtrace::write_exr_and_preview(files, a.out, stem + ".png", image);
  for (std::size_t i = 0; i < pictures.size(); ++i)
    grtrace::write_png_rgb8(files, stem + a.more_pictures[i] + ".png", pictures[i].width, pictures[i].height,
                            pictures[i].rgb);
  files.commit();
}

int run_example(const char* program, const std::function<void()>& body) {
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
