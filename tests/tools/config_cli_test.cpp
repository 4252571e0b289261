// Scene files: every option of every tool from `--config FILE` (TOML, or the header of an EXR
// written by grtrace-render), command-line options over it, `--write-config FILE` saving the effective
// configuration; a frame rendered again from its EXR header or from a written config equals the first bit for bit;
// bad config files are refused with exit code 2, a message naming the key or file, and no output. Also the JSON
// writer (nlohmann-json underneath): numbers read back as the same doubles, non-finite ones as null.
#include "command_line.hpp"
#include "json_writer.hpp"

#include "grtrace/render/exr_io.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using grtrace::tool_tests::run_command;
using grtrace::tool_tests::ToolRun;

/// The tools built on CommandLine, by name (from CMake).
std::map<std::string, std::string> tools() { return grtrace::tool_tests::named_paths(GRTRACE_CONFIG_TOOLS); }

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

class ConfigCli : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("grtrace_config_cli_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path at(const std::string& name) const { return dir_ / name; }
  static ToolRun tool(const std::string& name, const std::string& args) {
    return run_command("env -u DISPLAY " + tools().at(name) + " " + args);
  }
  static ToolRun render(const std::string& args) { return tool("grtrace-render", args); }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }
  fs::path dir_;
};

/// Every channel of `b` has the bytes of the same channel of `a` (and both have the same channels).
void expect_same_pixels(const fs::path& a, const fs::path& b) {
  const grtrace::Image ia = grtrace::read_exr(a), ib = grtrace::read_exr(b);
  ASSERT_EQ(ia.width(), ib.width());
  ASSERT_EQ(ia.height(), ib.height());
  ASSERT_EQ(ia.channel_names(), ib.channel_names());
  for (const auto& name : ia.channel_names()) {
    const auto &x = ia.channel(name), &y = ib.channel(name);
    ASSERT_EQ(x.size(), y.size()) << name;
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "channel " << name << " differs";
  }
}

/// The header's option_<name> attributes.
std::map<std::string, std::string> recorded_options(const fs::path& exr) {
  std::map<std::string, std::string> out;
  for (const auto& [key, value] : grtrace::read_exr(exr).metadata)
    if (key.rfind("option_", 0) == 0) out[key] = value;
  return out;
}

// ---- the frame round trip -------------------------------------------------------------------------------

TEST_F(ConfigCli, FrameFromItsExrHeaderAndFromAWrittenConfigIsBitForBit) {
  // Schwarzschild disk turning backwards (a flag), and Kerr, whose observer and inner disk edge are defaults
  // derived from other options when not given: both must come back as they were.
  const std::vector<std::string> scenes = {
      "--scene disk --camera-r 30 --camera-theta 80 --fov 50 --disk-retrograde --velocity 0,0,0.2",
      "--metric kerr --spin 0.9 --scene disk --camera-r 40 --camera-theta 82 --fov 40 --rtol 1e-8"};
  for (const std::string& scene : scenes) {
    SCOPED_TRACE(scene);
    const fs::path first = at("first.exr"), from_exr = at("from-exr.exr"), from_toml = at("from-toml.exr");
    const fs::path toml = at("scene.toml");
    const ToolRun a = render(scene + " --width 48 --height 32 --threads 2 --out " + first.string());
    ASSERT_EQ(a.status, 0) << a.output;
    const ToolRun b = render("--config " + first.string() + " --out " + from_exr.string());
    ASSERT_EQ(b.status, 0) << b.output;
    expect_same_pixels(first, from_exr);
    const ToolRun w = render("--config " + first.string() + " --write-config " + toml.string());
    ASSERT_EQ(w.status, 0) << w.output;
    EXPECT_TRUE(w.output.empty()) << "--write-config does no work and prints nothing: " << w.output;
    const ToolRun c = render("--config " + toml.string() + " --out " + from_toml.string());
    ASSERT_EQ(c.status, 0) << c.output << "\n" << slurp(toml);
    expect_same_pixels(first, from_toml);
    // The three headers record the same options (the output path aside).
    auto ra = recorded_options(first), rb = recorded_options(from_exr), rc = recorded_options(from_toml);
    for (auto* r : {&ra, &rb, &rc}) r->erase("option_out");
    EXPECT_EQ(ra, rb);
    EXPECT_EQ(ra, rc);
    EXPECT_EQ(grtrace::read_exr(first).metadata.at("options_given"),
              grtrace::read_exr(from_toml).metadata.at("options_given"));
    for (const auto& p : {first, from_exr, from_toml}) fs::remove(p);
  }
}

TEST_F(ConfigCli, CommandLineOverridesTheConfig) {
  write_text(at("scene.toml"), "width = 24\nheight = 16\nfov = 50\nscene = \"disk\"\nstatus-map = true\n"
                               "camera-r = 30.5\nvelocity = \"0,0,0.1\"\n");
  const fs::path exr = at("frame.exr");
  const ToolRun r = render("--config " + at("scene.toml").string() + " --fov 60 --status-map=false --out " + exr.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto options = recorded_options(exr);
  EXPECT_EQ(options.at("option_fov"), "60");  // the command line wins
  EXPECT_EQ(options.at("option_width"), "24");
  EXPECT_EQ(options.at("option_scene"), "disk");
  EXPECT_EQ(options.at("option_camera-r"), "30.5");
  EXPECT_EQ(options.at("option_velocity"), "0,0,0.1");
  EXPECT_EQ(options.at("option_status-map"), "false");  // a flag cleared on the command line
  EXPECT_FALSE(fs::exists(at("frame-status.png")));
  EXPECT_NE(r.output.find("\"width\":24"), std::string::npos) << r.output;
}

TEST_F(ConfigCli, WrittenConfigReadsBackToTheSameValues) {
  const fs::path one = at("one.toml"), two = at("two.toml");
  const std::string given = "--scene sky --fov 33.5 --rtol 2e-9 --velocity 0,0,0.25 --width 48 --status-map "
                            "--out '" + at("quote\"d.exr").string() + "'";
  ASSERT_EQ(render(given + " --write-config " + one.string()).status, 0);
  const std::string text = slurp(one);
  EXPECT_NE(text.find("\nfov = 33.5\n"), std::string::npos) << text;  // numbers stay numbers
  EXPECT_NE(text.find("\nrtol = \"2e-9\"\n"), std::string::npos) << text;  // kept exactly as typed
  EXPECT_NE(text.find("\nvelocity = \"0,0,0.25\"\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\nstatus-map = true\n"), std::string::npos) << text;
  EXPECT_NE(text.find("quote\\\"d.exr\"\n"), std::string::npos) << "a quote in a string is escaped: " << text;
  EXPECT_NE(text.find("\n# height = 1024\n"), std::string::npos) << "defaults are written, commented: " << text;
  EXPECT_NE(text.find("\n# error-map = false\n"), std::string::npos) << text;
  ASSERT_EQ(render("--config " + one.string() + " --write-config " + two.string()).status, 0);
  EXPECT_EQ(slurp(two), text) << "reading a written config and writing it again changes nothing";
  // Writing does no work: no frame.
  EXPECT_EQ(listing().size(), 2u);
}

// ---- bad config files -----------------------------------------------------------------------------------

TEST_F(ConfigCli, BadConfigFilesAreRefusedNamingTheKeyAndWriteNothing) {
  struct Case {
    std::string toml, named;
  };
  const std::vector<Case> cases = {
      {"width = 24\nwidht = 24\n", "'widht'"},                   // unknown key
      {"config = \"other.toml\"\n", "'config'"},                 // no nesting
      {"width = [24, 16]\n", "'width'"},                         // an array where a value is wanted
      {"[camera]\nfov = 60\n", "'camera'"},                      // a table
      {"status-map = \"yes\"\n", "'status-map'"},                // a string for a flag
      {"status-map = 1\n", "'status-map'"},                      // a number for a flag
      {"fov = true\n", "'fov'"},                                 // a boolean for a value
      {"fov = 60\nfov = 70\n", "line 2"},                        // TOML: a key twice
      {"fov = = 60\n", "line 1"},                                // TOML syntax
      {"scene = \"disk\n", "line 1"},                            // unterminated string
  };
  const fs::path exr = at("frame.exr"), toml = at("bad.toml");
  for (const Case& c : cases) {
    SCOPED_TRACE(c.toml);
    write_text(toml, c.toml);
    const ToolRun r = render("--config " + toml.string() + " --width 16 --height 16 --out " + exr.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("grtrace-render: error: --config '" + toml.string() + "'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.named), std::string::npos) << r.output;
    EXPECT_EQ(listing().size(), 1u) << "only the bad config: no frame, no temporary";
    // The same with --write-config: refused too, nothing written.
    EXPECT_EQ(render("--config " + toml.string() + " --write-config " + at("out.toml").string()).status, 2);
    EXPECT_FALSE(fs::exists(at("out.toml")));
  }
  fs::remove(toml);
  for (const std::string& missing : {at("missing.toml").string(), dir_.string()}) {
    const ToolRun r = render("--config " + missing + " --out " + exr.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("--config '" + missing + "'"), std::string::npos) << r.output;
  }
  EXPECT_TRUE(listing().empty());
  // A flag's value is checked as on the command line, and --config needs a file.
  EXPECT_EQ(render("--config").status, 2);
  EXPECT_EQ(render("--write-config " + (dir_ / "no-dir" / "x.toml").string()).status, 2);
}

TEST_F(ConfigCli, WriteConfigSavesOnlyWhatTheToolWouldRun) {
  // The options are checked as for a run before anything is saved: a value the tool would refuse, an option that
  // means nothing in the command, or a fractional whole number is refused with the run's message, nothing written.
  const fs::path toml = at("saved.toml");
  const std::pair<const char*, const char*> refused[] = {
      {"--width abc", "--width expects a whole number, got 'abc'"},
      {"--width 12.5", "--width expects a whole number, got '12.5'"},
      {"--spin 0.5", "--spin applies only with"},
      {"--metric kerr --spin 2", "--spin"},
      {"--rtol -1", "--rtol"},
  };
  for (const auto& [args, says] : refused) {
    SCOPED_TRACE(args);
    const ToolRun r = render(std::string(args) + " --write-config " + toml.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(toml));
  }
  const ToolRun print = render("--width 1e400 --write-config -");
  EXPECT_EQ(print.status, 2) << print.output;
  EXPECT_EQ(print.output.find("width ="), std::string::npos) << "nothing printed: " << print.output;
  ASSERT_EQ(render("--metric kerr --spin 0.5 --write-config " + toml.string()).status, 0);
  EXPECT_NE(slurp(toml).find("\nspin = 0.5\n"), std::string::npos) << slurp(toml);
}

TEST_F(ConfigCli, OutputsThatAreNotRegularFilesAreRefusedAndDashPrintsTheConfig) {
  // A device, a FIFO or a name longer than the directory allows: exit 2 before any work, the entry untouched.
  const ToolRun null_config = render("--write-config /dev/null");
  EXPECT_EQ(null_config.status, 2) << null_config.output;
  EXPECT_NE(null_config.output.find("'/dev/null': it is a character device, not a regular file"), std::string::npos)
      << null_config.output;
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  const fs::path fifo = at("pipe.exr");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const ToolRun to_fifo = render("--width 8 --height 8 --out " + fifo.string());
  EXPECT_EQ(to_fifo.status, 2) << to_fifo.output;
  EXPECT_NE(to_fifo.output.find("it is a FIFO (named pipe), not a regular file"), std::string::npos) << to_fifo.output;
  EXPECT_TRUE(fs::is_fifo(fifo));
  const ToolRun long_name = render("--width 8 --height 8 --out " + at(std::string(300, 'x') + ".exr").string());
  EXPECT_EQ(long_name.status, 2) << long_name.output;
  EXPECT_NE(long_name.output.find("its file name is 304 bytes long"), std::string::npos) << long_name.output;
  EXPECT_EQ(listing(), std::vector<std::string>{"pipe.exr"}) << "nothing written beside the FIFO";
  // "-" prints the scene file; it reads back as the same configuration.
  const ToolRun printed = render("--width 12 --spin 0.5 --metric kerr --write-config -");
  ASSERT_EQ(printed.status, 0) << printed.output;
  EXPECT_NE(printed.output.find("\nwidth = 12\n"), std::string::npos) << printed.output;
  write_text(at("printed.toml"), printed.output);
  const ToolRun again = render("--config " + at("printed.toml").string() + " --write-config -");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(again.output, printed.output);
}

TEST_F(ConfigCli, AnOutputIsNeverTheConfigItReadOrAnotherOutput) {
  // grtrace-render: a frame rendered again from its own header into the same file would replace its input.
  const fs::path frame = at("frame.exr");
  ASSERT_EQ(render("--width 8 --height 8 --out " + frame.string()).status, 0);
  const std::string before = slurp(frame);
  const ToolRun again = render("--config " + frame.string() + " --out " + frame.string());
  EXPECT_EQ(again.status, 2) << again.output;
  EXPECT_NE(again.output.find("is the input given as --config"), std::string::npos) << again.output;
  EXPECT_EQ(slurp(frame), before);
  // grtrace-view: its screenshot over its --config, or over a file its --export writes.
  const fs::path toml = at("view.toml");
  ASSERT_EQ(tool("grtrace-view", "--write-config " + toml.string()).status, 0);
  const std::string config = slurp(toml);
  const ToolRun shot = tool("grtrace-view", "--config " + toml.string() + " --screenshot " + toml.string());
  EXPECT_EQ(shot.status, 2) << shot.output;
  EXPECT_NE(shot.output.find("is the input given as --config"), std::string::npos) << shot.output;
  EXPECT_EQ(slurp(toml), config);
  fs::create_directories(at("export"));
  const ToolRun both = tool("grtrace-view", "--export " + at("export").string() + " --screenshot " +
                                                (at("export") / "scene.vtm").string());
  EXPECT_EQ(both.status, 2) << both.output;
  EXPECT_NE(both.output.find("is a name --export writes VTK files under"), std::string::npos) << both.output;
  EXPECT_TRUE(fs::is_empty(at("export")));
}

TEST_F(ConfigCli, AnExrOfAnotherToolIsRefusedNamingTheKey) {
  const fs::path exr = at("frame.exr");
  ASSERT_EQ(render("--width 8 --height 8 --out " + exr.string()).status, 0);
  const ToolRun r = tool("grtrace-geodesic", "--config " + exr.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("unknown key 'option_"), std::string::npos) << r.output;
  // A damaged EXR header (an attribute name that never ends) is refused, not read past its end.
  write_text(at("junk.toml"), std::string("\x76\x2f\x31\x01\x02\x00\x00\x00name", 12));
  EXPECT_EQ(render("--config " + at("junk.toml").string()).status, 2);
}

// ---- every tool ----------------------------------------------------------------------------------------

TEST_F(ConfigCli, EveryToolWritesAndReadsItsConfig) {
  ASSERT_GE(tools().size(), 2u);
  for (const auto& [name, path] : tools()) {
    SCOPED_TRACE(name);
    const fs::path one = at(name + ".toml"), two = at(name + "-2.toml");
    const ToolRun help = tool(name, "--help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.output.find("--config FILE"), std::string::npos);
    EXPECT_NE(help.output.find("--write-config FILE"), std::string::npos);
    // A configuration is saved only when the tool would run it: grtrace-geodesic needs its ray.
    const std::string needs = name == "grtrace-geodesic" ? "--impact 7 " : "";
    if (!needs.empty()) {
      const ToolRun refused = tool(name, "--write-config " + one.string());
      EXPECT_EQ(refused.status, 2) << refused.output;
      EXPECT_NE(refused.output.find("give --impact B"), std::string::npos) << refused.output;
      EXPECT_FALSE(fs::exists(one));
    }
    const ToolRun w = tool(name, needs + "--write-config " + one.string());
    ASSERT_EQ(w.status, 0) << w.output;
    ASSERT_TRUE(fs::exists(one));
    const ToolRun r = tool(name, "--config " + one.string() + " --write-config " + two.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_EQ(slurp(one), slurp(two));
    write_text(at("bad.toml"), "no-such-option = 1\n");
    const ToolRun bad = tool(name, "--config " + at("bad.toml").string());
    EXPECT_EQ(bad.status, 2) << bad.output;
    EXPECT_NE(bad.output.find("'no-such-option'"), std::string::npos) << bad.output;
  }
}

TEST_F(ConfigCli, NoToolWritesOverTheConfigItReads) {
  // Each tool's output option named as the --config file it reads: refused (exit 2), the file unchanged. The
  // examples' --out must end in .exr; a TOML scene file may be called anything.
  const std::map<std::string, std::pair<std::string, std::string>> outputs = {
      {"grtrace-geodesic", {"--impact 7 ", "--path"}},
      {"grtrace-work-precision", {"", "--out-csv"}},
      {"grtrace-orbit-drift", {"--no-png ", "--csv"}},
      {"star_beside_hole", {"", "--out"}},
      {"reissner_nordstrom", {"", "--out"}},
      {"terrell_rotation", {"", "--out"}},
  };
  for (const auto& [name, use] : outputs) {
    if (!tools().count(name)) continue;
    SCOPED_TRACE(name);
    const fs::path config = at(name + ".exr");
    ASSERT_EQ(tool(name, use.first + "--write-config " + config.string()).status, 0);
    const std::string before = slurp(config);
    const ToolRun r = tool(name, use.first + "--config " + config.string() + " " + use.second + " " + config.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("is the input given as --config"), std::string::npos) << r.output;
    EXPECT_EQ(slurp(config), before);
  }
}

TEST_F(ConfigCli, AFrameOfAnySizeIsAConfig) {
  // Its header is at the start of the file: a frame far above the 1 MiB a TOML scene file may have reads back.
  const fs::path frame = at("big.exr");
  ASSERT_EQ(render("--width 400 --height 300 --exr-compression none --out " + frame.string()).status, 0);
  ASSERT_GT(fs::file_size(frame), 2u << 20);
  const ToolRun r = render("--config " + frame.string() + " --write-config -");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("width = 400"), std::string::npos) << r.output;
  write_text(at("big.toml"), "# " + std::string((1u << 20) + 10, 'x') + "\n");
  const ToolRun big = render("--config " + at("big.toml").string());
  EXPECT_EQ(big.status, 2) << big.output;
  EXPECT_NE(big.output.find("is larger than 1 MiB"), std::string::npos) << big.output;
}

TEST_F(ConfigCli, ValuesANulOrATrailingCommaWouldCutShortAreRefused) {
  write_text(at("nul.toml"), "scene = \"disk\\u0000checker\"\n");
  const ToolRun nul = render("--config " + at("nul.toml").string());
  EXPECT_EQ(nul.status, 2) << nul.output;
  EXPECT_NE(nul.output.find("key 'scene' (line 1) holds a NUL character"), std::string::npos) << nul.output;
  const ToolRun comma = render("--look -1,0,0, --out " + at("c.exr").string());
  EXPECT_EQ(comma.status, 2) << comma.output;
  EXPECT_NE(comma.output.find("--look '-1,0,0,' ends with a comma"), std::string::npos) << comma.output;
  EXPECT_TRUE(listing().size() == 1u) << "only nul.toml";
}

TEST_F(ConfigCli, EveryToolChecksItsEnvironmentBeforeAnyWork) {
  // A mistyped memory limit is refused by every tool, not only by those that size an image; an OpenMP thread count
  // the runtime would crash on (it creates the threads it is told to) is refused before any parallel region.
  for (const auto& [name, path] : tools()) {
    SCOPED_TRACE(name);
    const std::string needs = name == "grtrace-geodesic" ? "--impact 7 " : "";
    const std::string out = at(name + ".toml").string();
    const ToolRun limit = run_command("env -u DISPLAY GRTRACE_MEMORY_LIMIT=16Q " + path + " " + needs +
                                      "--write-config " + out);
    EXPECT_EQ(limit.status, 2) << limit.output;
    EXPECT_NE(limit.output.find("GRTRACE_MEMORY_LIMIT='16Q' is not a memory size"), std::string::npos)
        << limit.output;
    const ToolRun threads = run_command("env -u DISPLAY OMP_NUM_THREADS=100000000 " + path + " " + needs +
                                        "--write-config " + out);
    EXPECT_EQ(threads.status, 2) << threads.output;
    EXPECT_NE(threads.output.find("OMP_NUM_THREADS='100000000' is not a thread count from 1 to 1024"),
              std::string::npos)
        << threads.output;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST_F(ConfigCli, ViewTakesItsOptionsFromAConfig) {
  if (!tools().count("grtrace-view")) GTEST_SKIP() << "grtrace-view not built";
  write_text(at("view.toml"), "width = 24\nheight = 16\nbundle-size = \"3x2\"\nthreads = 2\ncamera-r = 25\n");
  const fs::path scene = at("scene");
  const ToolRun r = tool("grtrace-view", "--config " + at("view.toml").string() + " --export " + scene.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("6 rays"), std::string::npos) << "the bundle size came from the config: " << r.output;
  EXPECT_TRUE(fs::exists(scene / "scene.vtm"));
  write_text(at("bad.toml"), "bundle-size = [3, 2]\n");
  const ToolRun bad = tool("grtrace-view", "--config " + at("bad.toml").string() + " --export " + at("x").string());
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("'bundle-size'"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(at("x")));
}

// ---- in process: CommandLine and JsonObject --------------------------------------------------------------

/// Parses `args` with a CommandLine like a small tool's.
grtrace::tools::CommandLine parsed(std::vector<std::string> args, bool* went_on = nullptr) {
  grtrace::tools::CommandLine cli("t", "test");
  cli.option("width", "1024", "w").option("observer", "static", "o").flag("json", "j");
  args.insert(args.begin(), "t");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  const bool on = cli.parse(static_cast<int>(argv.size()), argv.data());
  if (went_on) *went_on = on;
  return cli;
}

TEST_F(ConfigCli, ConfigValuesCountAsGivenAndTheCommandLineClearsFlags) {
  write_text(at("c.toml"), "width = 48\njson = true\n");
  const auto cli = parsed({"--config", at("c.toml").string()});
  EXPECT_TRUE(cli.given("width"));
  EXPECT_EQ(cli.integer("width"), 48);
  EXPECT_TRUE(cli.flag_set("json"));
  EXPECT_FALSE(cli.given("observer"));
  EXPECT_EQ(cli.given_names(), "width,json");
  const auto cleared = parsed({"--json=no", "--config=" + at("c.toml").string(), "--width", "7"});
  EXPECT_FALSE(cleared.flag_set("json"));
  EXPECT_EQ(cleared.text("width"), "7");
  const auto values = cleared.values();
  ASSERT_EQ(values.size(), 3u);
  EXPECT_EQ(values[2], (std::pair<std::string, std::string>{"json", "false"}));
  // Any text survives a written config, a line break and a quote too (one-line TOML strings, never multi-line).
  bool went_on = false;
  auto saving = parsed({"--width", "4\n8 \"x\"", "--write-config", at("w.toml").string()}, &went_on);
  EXPECT_TRUE(went_on) << "--write-config is only noted: the tool checks its options first";
  EXPECT_TRUE(saving.write_config_asked());
  EXPECT_FALSE(fs::exists(at("w.toml"))) << "nothing saved before the tool's checks";
  EXPECT_TRUE(saving.write_config_if_asked());
  EXPECT_EQ(parsed({"--config", at("w.toml").string()}).text("width"), "4\n8 \"x\"") << slurp(at("w.toml"));
}

TEST(JsonWriter, NumbersReadBackAsTheSameDoublesAndNonFiniteIsNull) {
  const double samples[] = {0.0, -0.0, 1e-8, 2e-9, 0.1, 1.0 / 3.0, 48.0, 5e-324, 1.7976931348623157e308,
                            -2.785293563405, 123456789.123456789};
  for (const double v : samples) {
    grtrace::tools::JsonObject j;
    j.add("v", v);
    const std::string s = j.str();
    ASSERT_EQ(s.rfind("{\"v\":", 0), 0u) << s;
    const double back = std::strtod(s.c_str() + 5, nullptr);
    EXPECT_EQ(std::memcmp(&back, &v, sizeof v), 0) << s;
  }
  grtrace::tools::JsonObject j, inner;
  inner.add("b", 2).add("a", 1L);
  j.add("nan", std::nan("")).add("inf", std::numeric_limits<double>::infinity()).add("n", inner).add("t", true);
  j.add("s", "q\"\\\n\x01").add_null("z");
  EXPECT_EQ(j.str(), "{\"nan\":null,\"inf\":null,\"n\":{\"b\":2,\"a\":1},\"t\":true,\"s\":\"q\\\"\\\\\\n\\u0001\",\"z\":null}");
}

}  // namespace
