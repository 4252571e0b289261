// grtrace-render --flight: numbered frames with their PNGs and one JSON line, a re-run that
// skips the frames written whole (and renders again those of another flight), the MP4 from ffmpeg, the frames'
// headers (proper time, camera on the orbit), and bad input refused before any work (exit 2, nothing written).
#include "grtrace/render/exr_io.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef GRTRACE_RENDER_BINARY
#error "GRTRACE_RENDER_BINARY must name the grtrace-render executable"
#endif

namespace {

namespace fs = std::filesystem;
using grtrace::tool_tests::run_command;
using grtrace::tool_tests::json_number;
using grtrace::tool_tests::ToolRun;

struct TempDir {
  fs::path path;
  TempDir() {
    char tmpl[] = "/tmp/grtrace-flight-cli-XXXXXX";
    path = ::mkdtemp(tmpl);
  }
  ~TempDir() { fs::remove_all(path); }
  std::size_t files() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(path), {})); }
};

ToolRun render(const std::string& args) { return run_command(std::string(GRTRACE_RENDER_BINARY) + " " + args); }

const std::string kSmall = "--width 24 --height 16 --fov 50 --threads 2 ";

TEST(FlightCli, SeedFlightWritesNumberedFramesAndResumes) {
  TempDir dir;
  const std::string out = (dir.path / "orbit.exr").string();
  const std::string args = kSmall + "--scene disk --flight seed --frames 3 --out " + out;
  const ToolRun first = render(args);
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_EQ(json_number(first.output, "frames"), 3.0) << first.output;
  EXPECT_EQ(json_number(first.output, "frames_rendered"), 3.0);
  EXPECT_EQ(json_number(first.output, "frames_skipped"), 0.0);
  EXPECT_NE(first.output.find("\"tracer\":\"planar\""), std::string::npos) << first.output;
  for (const char* name : {"orbit-0000.exr", "orbit-0000.png", "orbit-0001.exr", "orbit-0001.png", "orbit-0002.exr",
                           "orbit-0002.png"})
    EXPECT_TRUE(fs::is_regular_file(dir.path / name)) << name;
  EXPECT_EQ(dir.files(), 6u);  // no temporaries left behind

  // Frames spaced evenly in proper time over one revolution; each header records its tau and its camera.
  const double dtau = json_number(first.output, "proper_time_step");
  EXPECT_GT(dtau, 1000.0);  // the seed orbit's period is ~3.6e3 M of proper time: a third of it per frame
  for (int i = 0; i < 3; ++i) {
    const grtrace::Image image = grtrace::read_exr(dir.path / ("orbit-000" + std::to_string(i) + ".exr"));
    EXPECT_EQ(std::stod(image.metadata.at("flight_tau")), i * dtau);
    EXPECT_EQ(image.metadata.at("flight"), "seed");
    EXPECT_EQ(image.metadata.at("tracer"), "planar");
    std::stringstream position(image.metadata.at("camera_position"));
    double t = 0, r = 0;
    char comma = 0;
    position >> t >> comma >> r;
    if (i == 0) EXPECT_EQ(r, 100.0);
    else EXPECT_LT(r, 100.0);  // falling towards periapsis
  }

  // A re-run of the same flight skips every frame and leaves the files as they were.
  const auto before = fs::last_write_time(dir.path / "orbit-0001.exr");
  const ToolRun second = render(args);
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(json_number(second.output, "frames_rendered"), 0.0) << second.output;
  EXPECT_EQ(json_number(second.output, "frames_skipped"), 3.0);
  EXPECT_EQ(fs::last_write_time(dir.path / "orbit-0001.exr"), before);

  // A lost frame is rendered again, alone.
  fs::remove(dir.path / "orbit-0001.png");
  const ToolRun third = render(args);
  ASSERT_EQ(third.status, 0) << third.output;
  EXPECT_EQ(json_number(third.output, "frames_rendered"), 1.0) << third.output;
  EXPECT_TRUE(fs::is_regular_file(dir.path / "orbit-0001.png"));

  // Another flight into the same names (a different look) renders every frame again.
  const ToolRun other = render(args + " --look -1,0.1,0");
  ASSERT_EQ(other.status, 0) << other.output;
  EXPECT_EQ(json_number(other.output, "frames_rendered"), 3.0) << other.output;
}

TEST(FlightCli, Mp4HasEveryFrame) {
  if (run_command("ffprobe -version").status != 0) GTEST_SKIP() << "ffprobe missing (bash cmake/install-deps.sh)";
  TempDir dir;
  const std::string out = (dir.path / "circle.exr").string();
  const ToolRun run = render(kSmall + "--flight circular --camera-r 30 --frames 4 --mp4 --fps 12 --out " + out);
  ASSERT_EQ(run.status, 0) << run.output;
  const fs::path mp4 = dir.path / "circle.mp4";
  ASSERT_TRUE(fs::is_regular_file(mp4)) << run.output;
  EXPECT_NE(run.output.find("\"mp4\":"), std::string::npos);
  const ToolRun probe = run_command("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                    "stream=nb_read_frames,width,height -of csv=p=0 " + mp4.string());
  ASSERT_EQ(probe.status, 0) << probe.output;
  EXPECT_EQ(probe.output.substr(0, probe.output.find('\n')), "24,16,4") << probe.output;
  EXPECT_EQ(dir.files(), 9u);  // 4 EXR + 4 PNG + the MP4
}

// When ffmpeg fails, its message is passed on naming the video asked for, never the temporary it was writing, and
// nothing but the frames is left. (A stand-in ffmpeg on PATH that fails as a full disk would.)
TEST(FlightCli, AFailingFfmpegIsReportedWithTheVideosName) {
  TempDir dir;
  const fs::path bin = dir.path / "bin";
  fs::create_directory(bin);
  std::ofstream(bin / "ffmpeg") << "#!/bin/sh\nfor last; do :; done\n"  // $last: the output file
                                << "echo \"$last: No space left on device\" >&2\nexit 1\n";
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  const std::string out = (dir.path / "circle.exr").string();
  const ToolRun run = run_command("PATH=" + bin.string() + ":$PATH " + std::string(GRTRACE_RENDER_BINARY) + " " +
                                  kSmall + "--flight circular --camera-r 30 --frames 2 --mp4 --out " + out);
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_NE(run.output.find("assembling " + (dir.path / "circle.mp4").string() + ": " +
                            (dir.path / "circle.mp4").string() + ": No space left on device"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find(".tmp-"), std::string::npos) << run.output;
  EXPECT_EQ(dir.files(), 5u) << "bin/ and the two frames' EXR and PNG, no video, no temporary";
}

// A camera path from a CSV: the frames are the rows.
TEST(FlightCli, CsvPathGivesOneFramePerRow) {
  TempDir dir;
  const fs::path csv = dir.path / "path.csv";
  // Static cameras at r = 50 and r = 60 (u = d_t / sqrt(1 - 2/r)).
  std::ofstream(csv) << std::setprecision(17) << "tau,t,r,theta,phi,ut,ur,utheta,uphi\n"
                     << "0,0,50,1.5707963267948966,0," << 1.0 / std::sqrt(1.0 - 2.0 / 50.0) << ",0,0,0\n"
                     << "1,0,60,1.5707963267948966,0," << 1.0 / std::sqrt(1.0 - 2.0 / 60.0) << ",0,0,0\n";
  const ToolRun run = render(kSmall + "--flight csv --flight-csv " + csv.string() + " --out " +
                             (dir.path / "c.exr").string());
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(json_number(run.output, "frames"), 2.0);
  EXPECT_TRUE(fs::is_regular_file(dir.path / "c-0001.exr"));
  EXPECT_FALSE(fs::exists(dir.path / "c-0002.exr"));
}

// With --chart ks a fall continues through the horizon (the ingoing Kerr-Schild slicing): the last frames are taken
// inside r = 2M, and every ray of every frame ends on the sky or the horizon (none fails, none is NaN).
TEST(FlightCli, KerrSchildInfallContinuesThroughTheHorizon) {
  TempDir dir;
  const std::string out = (dir.path / "fall.exr").string();
  const ToolRun run = render(kSmall + "--metric kerr --spin 0 --chart ks --flight infall --camera-r 6 --frames 4 "
                                      "--look -1,0,1 --up 1,0,0 --out " + out);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(json_number(run.output, "frames"), 4.0) << run.output;
  for (const char* failure : {"max_steps", "step_underflow", "non_finite"})
    EXPECT_EQ(json_number(run.output, failure), 0.0) << failure << "\n" << run.output;
  EXPECT_GT(json_number(run.output, "escaped"), 0.0) << run.output;
  EXPECT_GT(json_number(run.output, "captured"), 0.0) << run.output;
  const grtrace::Image last = grtrace::read_exr(dir.path / "fall-0003.exr");
  EXPECT_EQ(last.metadata.at("kerr_schild_slicing"), "ingoing");
  EXPECT_EQ(last.metadata.at("chart"), "ks");
  std::stringstream position(last.metadata.at("camera_position"));  // Kerr-Schild (t, x, y, z): on the +x axis
  double t = 0, x = 0;
  char comma = 0;
  position >> t >> comma >> x;
  EXPECT_NEAR(x, 1.65, 1e-6);  // the automatic fall ends at 1.1 r_c, r_c = 1.5 M: inside the horizon
  for (const char* channel : {"R", "G", "B"})
    for (const float v : last.channel(channel)) ASSERT_TRUE(std::isfinite(v)) << channel;
}

// A flight split into parts (as the tasks of a Slurm job array would render it) gives the frames of one whole run:
// each part renders only its frames, the parts share one signature, and a last run without a range finds all done.
TEST(FlightCli, FrameRangesSplitAFlightIntoPartsOfTheSameFrames) {
  TempDir whole, parts;
  const std::string args = kSmall + "--scene disk --flight seed --frames 5 --out ";
  ASSERT_EQ(render(args + (whole.path / "f.exr").string()).status, 0);
  const ToolRun second = render(args + (parts.path / "f.exr").string() + " --frame-range 3:5");
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(json_number(second.output, "frames_rendered"), 2.0) << second.output;
  EXPECT_EQ(json_number(second.output, "frames_skipped"), 0.0) << second.output;
  EXPECT_NE(second.output.find("\"frame_range\":\"3:5\""), std::string::npos) << second.output;
  EXPECT_EQ(parts.files(), 4u) << "frames 3 and 4 only";
  EXPECT_FALSE(fs::exists(parts.path / "f-0000.exr"));
  const ToolRun first = render(args + (parts.path / "f.exr").string() + " --frame-range 0:4");
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_EQ(json_number(first.output, "frames_rendered"), 3.0) << "frame 3 is on disk already: " << first.output;
  EXPECT_EQ(json_number(first.output, "frames_skipped"), 1.0) << first.output;
  const ToolRun all = render(args + (parts.path / "f.exr").string());
  ASSERT_EQ(all.status, 0) << all.output;
  EXPECT_EQ(json_number(all.output, "frames_rendered"), 0.0) << all.output;
  EXPECT_EQ(json_number(all.output, "frames_skipped"), 5.0) << all.output;
  for (int i = 0; i < 5; ++i) {
    const std::string name = "f-000" + std::to_string(i) + ".exr";
    const grtrace::Image a = grtrace::read_exr(whole.path / name), b = grtrace::read_exr(parts.path / name);
    for (const char* channel : {"R", "G", "B", "status", "redshift", "sky_theta"}) {  // bit for bit (NaN too)
      const std::vector<float>& x = a.channel(channel);
      const std::vector<float>& y = b.channel(channel);
      ASSERT_EQ(x.size(), y.size());
      EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << name << " " << channel;
    }
  }
}

TEST(FlightCli, BadInputIsRefusedBeforeAnyWork) {
  TempDir dir;
  const std::string out = " --out " + (dir.path / "f.exr").string();
  const std::pair<std::string, std::string> cases[] = {
      {"--flight loop", "unknown --flight 'loop'"},
      {"--flight seed --frames 0", "--frames must be in 1 .. 100000"},
      {"--flight seed --frame-dtau -1", "--frame-dtau must be >= 0"},
      {"--flight seed --velocity 0,0,0.1", "--velocity sets a single frame's camera"},
      {"--flight csv", "--flight csv goes with --flight-csv"},
      {"--flight csv --flight-csv " + (dir.path / "none.csv").string(), "cannot read the camera path"},
      {"--frames 10", "--frames needs --flight"},
      {"--mp4", "--mp4 needs --flight"},
      {"--flight infall --camera-r 20 --frames 5 --frame-dtau 40", "the camera's path ends (captured"},
      {"--flight circular --camera-r 2.5", "no timelike circular orbit at r = 2.5"},
      {"--flight circular --metric kerr --spin 0.5 --chart ks", "a circular flight is stated in the spherical chart"},
      {"--flight seed --metric kerr --spin 0.5 --chart ks", "the automatic step of a seed flight counts a revolution"},
      {"--flight seed --error-map", "--error-map is for single frames"},
      {"--flight seed --tracer symmetric", "--tracer symmetric is retired"},
      {"--frame-range 0:2", "--frame-range needs --flight"},
      {"--flight seed --frames 4 --frame-range 3:1", "--frame-range 3:1 must satisfy 0 <= A < B <= 4"},
      {"--flight seed --frames 4 --frame-range 0:5", "--frame-range 0:5 must satisfy 0 <= A < B <= 4"},
      {"--flight seed --frames 4 --frame-range 2", "--frame-range expects A:B"},
      {"--flight seed --frames 4 --frame-range 1.5:3", "--frame-range expects A:B"},
      {"--flight seed --frames 4 --frame-range 0:2 --mp4", "--mp4 assembles every frame of the flight"},
  };
  for (const auto& [args, says] : cases) {
    const ToolRun r = render(kSmall + args + out);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(dir.files(), 0u) << args;
  }
  // The video's tool is looked for before the first frame: without ffmpeg on PATH, nothing is traced or written.
  const ToolRun no_ffmpeg = run_command("PATH=/nonexistent " + std::string(GRTRACE_RENDER_BINARY) + " " + kSmall +
                                        "--flight seed --frames 3 --mp4" + out);
  EXPECT_EQ(no_ffmpeg.status, 2) << no_ffmpeg.output;
  EXPECT_NE(no_ffmpeg.output.find("--mp4 needs ffmpeg, which is not on PATH"), std::string::npos) << no_ffmpeg.output;
  EXPECT_EQ(dir.files(), 0u);
}

// --status-map with a flight: one status map per frame, and a frame a previous run wrote is not traced again to
// inspect it (its map is drawn from the frame on disk, the same bytes). The JSON names the frames with failed rays.
TEST(FlightCli, StatusMapsOfAFlightComeFromItsFramesOnDisk) {
  TempDir dir;
  const std::string out = (dir.path / "f.exr").string();
  const std::string args = kSmall + "--flight circular --camera-r 30 --frames 2 --out " + out;
  const ToolRun first = render(args + " --status-map");
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_NE(first.output.find("\"frames_with_failed_rays\":[]"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("\"first_status_map\":\"" + (dir.path / "f-0000-status.png").string()),
            std::string::npos)
      << first.output;
  for (const char* name : {"f-0000-status.png", "f-0001-status.png"})
    ASSERT_TRUE(fs::is_regular_file(dir.path / name)) << name;
  EXPECT_EQ(dir.files(), 6u);
  const std::string map = grtrace::tool_tests::file_contents(dir.path / "f-0001-status.png");
  fs::remove(dir.path / "f-0001-status.png");
  const ToolRun again = render(args + " --status-map");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(json_number(again.output, "frames_rendered"), 0.0) << again.output;
  EXPECT_EQ(grtrace::tool_tests::file_contents(dir.path / "f-0001-status.png"), map);
  // Without --status-map the frames are the same frames (the maps are not part of what they show): skipped too.
  const ToolRun plain = render(args);
  ASSERT_EQ(plain.status, 0) << plain.output;
  EXPECT_EQ(json_number(plain.output, "frames_skipped"), 2.0) << plain.output;
  // A flight whose rays run out of steps names its frames.
  const ToolRun failing = render(kSmall + "--flight circular --camera-r 30 --frames 2 --max-steps 3 --out " +
                                 (dir.path / "g.exr").string());
  ASSERT_EQ(failing.status, 0) << failing.output;
  EXPECT_NE(failing.output.find("\"frames_with_failed_rays\":[0,1]"), std::string::npos) << failing.output;
  // A part of the flight names its own frames and maps, not the flight's first and last.
  const ToolRun part = render(kSmall + "--flight circular --camera-r 30 --frames 4 --frame-range 2:3 --status-map " +
                              "--out " + (dir.path / "h.exr").string());
  ASSERT_EQ(part.status, 0) << part.output;
  for (const char* named : {"\"first_frame\":\"", "\"last_frame\":\""})
    EXPECT_NE(part.output.find(named + (dir.path / "h-0002.exr").string()), std::string::npos) << part.output;
  for (const char* named : {"\"first_status_map\":\"", "\"last_status_map\":\""})
    EXPECT_NE(part.output.find(named + (dir.path / "h-0002-status.png").string()), std::string::npos) << part.output;
}

// SIGTERM while ffmpeg writes the video: the program is killed and reaped before the temporary is removed, so it
// cannot create the file again afterwards (ffmpeg reopens its output by name for +faststart's second pass).
TEST(FlightCli, SigtermWhileFfmpegRunsLeavesNoTemporary) {
  TempDir dir;
  const fs::path bin = dir.path / "bin", started = dir.path / "ffmpeg-started";
  fs::create_directory(bin);
  std::ofstream(bin / "ffmpeg") << "#!/bin/sh\nfor last; do :; done\n"  // $last: the output file
                                << "touch '" << started.string() << "'\nsleep 2\necho video > \"$last\"\n";
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
  const std::string out = (dir.path / "v.exr").string();
  const std::string command = "PATH=" + bin.string() + ":$PATH exec " + std::string(GRTRACE_RENDER_BINARY) + " " +
                              kSmall + "--flight circular --camera-r 30 --frames 2 --mp4 --out " + out +
                              " >/dev/null 2>&1";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  for (int i = 0; i < 6000 && !fs::exists(started); ++i) ::usleep(10000);
  ASSERT_TRUE(fs::exists(started)) << "ffmpeg never started";
  ::kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  ::sleep(3);  // an ffmpeg left running would have written its file by now
  for (const auto& e : fs::directory_iterator(dir.path)) {
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp-"), std::string::npos) << "left behind: " << name;
    EXPECT_NE(name, "v.mp4");
  }
}

}  // namespace
