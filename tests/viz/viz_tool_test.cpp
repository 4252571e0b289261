// grtrace-view as a program: --help, refusals of bad input (exit 2, a message naming the option), offscreen
// screenshots of the requested size, the three charts. Rendering cases skip without DISPLAY.
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/static_frame.hpp"
#include "grtrace/observer/tetrad.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/viz/viewer_window.hpp"

#include "../common/tool_run.hpp"

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#ifndef GRTRACE_VIEW_EXE
#error "GRTRACE_VIEW_EXE (path of grtrace-view) must be defined by the build"
#endif

namespace {

using grtrace::tool_tests::ToolRun;

/// Runs grtrace-view with `args` (shell words); returns the exit status and the merged output.
ToolRun run(const std::string& args) { return grtrace::tool_tests::run_command(std::string(GRTRACE_VIEW_EXE) + " " + args); }

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("grtrace-view-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

TEST(ViewTool, HelpListsOptionsWithDefaults) {
  const ToolRun r = run("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* s : {"--screenshot", "--size", "--chart", "--frame", "--camera-r", "--fov", "--mass", "--sky-radius",
                        "--bundle", "--color-by", "--orbit", "--hide", "(default: 1)", "(default: 9x7)"})
    EXPECT_NE(r.output.find(s), std::string::npos) << s;
}

TEST(ViewTool, BadInputExitsWithTwo) {
  const std::array<std::pair<const char*, const char*>, 28> cases = {{
      // The camera and metric groups shared with grtrace-render (examples/common/camera_options.hpp,
      // metric_options.hpp): the same refusals, worded once.
      {"--spin 0.5", "--spin applies only with --metric kerr"},
      {"--metric rn", "--metric must be schwarzschild or kerr, got 'rn'"},
      {"--metric kerr --spin 1", "--spin must satisfy |a| < M"},
      {"--look 1,0", "--look expects 3 comma-separated numbers"},
      {"--camera-theta 181", "--camera-theta"},
      {"--up -1,0,0", "up"},
      {"--scene disk --disk-inner 2", "disk"},
      {"--size 0x10", "--size"},
      {"--size big", "--size"},
      {"--chart pie", "--chart"},
      {"--mass -1", "--mass"},
      {"--fov 180", "--fov"},
      {"--camera-r 1.5", "--camera-r"},
      {"--color-by rainbow", "--color-by"},
      {"--hide horizon,moon", "moon"},
      {"--bundle sphere", "--bundle"},
      {"--tableau nope", "tableau"},
      {"--frame /nonexistent/frame.exr", "--frame"},
      {"--screenshot /nonexistent/dir/x.png", "--screenshot"},
      // Options that mean nothing with the others given, refused instead of ignored: grtrace-render's scene rules
      // (read by the application library) and the viewer's own.
      {"--scene sky --disk-inner 8", "--disk-inner applies only with --scene disk"},
      {"--scene checker --disk-retrograde", "--disk-retrograde applies only with --scene disk"},
      {"--bundle grid --beam-width 3", "--beam-width applies only with --bundle beam"},
      {"--bundle none --bundle-size 3x3", "--bundle-size applies only with --bundle grid, row, column or beam"},
      {"--orbit-r 50", "--orbit-r applies only with --orbit or --plot"},
      {"--orbit-tableau rk4", "--orbit-tableau applies only with --orbit or --plot"},
      {"--orbit-dr 0.01", "--orbit-dr applies only with --orbit, --plot or --flight orbit"},
      {"--plot orbit --bundle-size 3x3", "--bundle-size belongs to the 3D view; not with --plot orbit"},
      {"--tableau rk4 --control fixed --step 1 --rtol 1e-6", "--rtol applies only with an adaptive --control"},
  }};
  for (const auto& [args, mention] : cases) {
    const ToolRun r = run(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(mention), std::string::npos) << args << "\n" << r.output;
  }
  const ToolRun unknown = run("--frobnicate 1");
  EXPECT_EQ(unknown.status, 2);
}

/// A frame as grtrace-render writes it: colours plus the camera in the header.
std::filesystem::path write_frame(int W, int H) {
  using namespace grtrace;
  Image image(W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      PixelSample s;
      s.rgb = {static_cast<float>(x) / static_cast<float>(W), 0.3f, static_cast<float>(y) / static_cast<float>(H)};
      s.status = RayStatus::escaped;
      image.set(x, y, s);
    }
  const SchwarzschildMetric metric{1.0};
  const Vec4 x(0.0, 25.0, 1.4, 0.5);
  const StaticFrame frame(metric.metric(x));
  const Tetrad t = make_tetrad(metric.metric(x), frame.velocity(Vec3::Zero()), frame.spatial(Vec3(-1, 0, 0)),
                               frame.spatial(Vec3(0, -1, 0)));
  auto four = [](const Vec4& v) {
    return std::to_string(v[0]) + "," + std::to_string(v[1]) + "," + std::to_string(v[2]) + "," + std::to_string(v[3]);
  };
  image.metadata["scene"] = "checker";
  image.metadata["metric"] = "schwarzschild";
  image.metadata["mass"] = "1";
  image.metadata["camera_position"] = four(x);
  for (int a = 0; a < 4; ++a) image.metadata["tetrad_e" + std::to_string(a)] = four(t.e[static_cast<std::size_t>(a)]);
  image.metadata["fov_degrees"] = "70";
  image.metadata["sky_radius"] = "100";
  image.metadata["rtol"] = "1e-6";
  image.metadata["atol"] = "1e-8";
  const auto file = scratch("frame.exr");
  write_exr(file, image);
  write_png_preview(scratch("frame.png"), image);
  return file;
}

TEST(ViewTool, FrameFromAnExrIsShownWithItsPreviewColours) {
  if (!grtrace::viz::display_available()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  const int W = 40, H = 30;
  const auto exr = write_frame(W, H);
  const auto shot = scratch("with-frame.png");
  const ToolRun r = run("--frame " + exr.string() + " --bundle-size 3x2 --screenshot " + shot.string() + " --size 400x200");
  ASSERT_EQ(r.status, 0) << r.output;
  const grtrace::PngRgb8 png = grtrace::read_png_rgb8(shot);
  const grtrace::PngRgb8 preview = grtrace::read_png_rgb8(scratch("frame.png"));
  ASSERT_EQ(png.width, 400);
  // The frame viewport is the right half (200 x 200); the 40 x 30 frame is scaled by 5 and centred.
  const double scale = 5.0;
  int checked = 0;
  for (int y = 4; y < H; y += 5)
    for (int x = 3; x < W; x += 6) {
      const double vx = 100.0 + (x - 0.5 * (W - 1)) * scale, vy = 100.0 + ((H - 1 - y) - 0.5 * (H - 1)) * scale;
      const int wx = 200 + static_cast<int>(vx), row = 199 - static_cast<int>(vy);
      const auto o = static_cast<std::size_t>(3 * (row * 400 + wx)), p = static_cast<std::size_t>(3 * (y * W + x));
      // Skip pixels under a bundle marker (a 3x2 grid: columns 0, 20, 39; rows 0, 29).
      if ((x <= 2 || (x >= 18 && x <= 22) || x >= 37) && (y <= 2 || y >= 27)) continue;
      EXPECT_EQ(png.rgb[o], preview.rgb[p]) << x << "," << y;
      EXPECT_EQ(png.rgb[o + 1], preview.rgb[p + 1]) << x << "," << y;
      EXPECT_EQ(png.rgb[o + 2], preview.rgb[p + 2]) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 20);
  // The frame's camera is used: giving another one is refused.
  const ToolRun conflict = run("--frame " + exr.string() + " --camera-r 40 --screenshot " + shot.string());
  EXPECT_EQ(conflict.status, 2);
  EXPECT_NE(conflict.output.find("conflicts with --frame"), std::string::npos) << conflict.output;
  std::filesystem::remove_all(exr.parent_path());
}

TEST(ViewTool, ScreenshotHasTheRequestedSize) {
  if (!grtrace::viz::display_available()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  const auto file = scratch("view.png");
  const ToolRun r = run("--screenshot " + file.string() + " --size 480x240 --width 48 --height 27 --bundle-size 4x3");
  ASSERT_EQ(r.status, 0) << r.output;
  const grtrace::PngRgb8 png = grtrace::read_png_rgb8(file);
  EXPECT_EQ(png.width, 480);
  EXPECT_EQ(png.height, 240);
  std::filesystem::remove_all(file.parent_path());
}

TEST(ViewTool, ChartsAreWritten) {
  if (!grtrace::viz::display_available()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  for (const char* chart : {"orbit", "norm", "step"}) {
    const auto file = scratch(std::string("chart-") + chart + ".png");
    const ToolRun r = run(std::string("--chart ") + chart + " --orbit-revolutions 2 --screenshot " + file.string() +
                      " --size 400x300");
    ASSERT_EQ(r.status, 0) << r.output;
    const grtrace::PngRgb8 png = grtrace::read_png_rgb8(file);
    EXPECT_EQ(png.width, 400);
    EXPECT_EQ(png.height, 300);
  }
  std::filesystem::remove_all(scratch("x").parent_path());
}

// ---- --pick: a frame pixel's ray traced at start-up, as a click on the frame does -----------------------------

TEST(ViewTool, PicksAreTracedPrintedAndExported) {
  // --export alone needs no display.
  const auto dir = scratch("picked-scene");
  const ToolRun r = run("--export " + dir.string() + " --width 48 --height 36 --bundle-size 2x2 --pick 24,10/5,30");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* line : {"pick pixel (24, 10): ", "pick pixel (5, 30): ", " steps\n", "+ 2 picked"})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  // rays.vtp: the 4 bundle rays, then the 2 picked ones with their pixels.
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir / "rays.vtp").c_str());
  reader->Update();
  vtkPolyData* rays = reader->GetOutput();
  ASSERT_EQ(rays->GetNumberOfCells(), 6);
  vtkDataArray* pixel = rays->GetCellData()->GetArray("pixel");
  ASSERT_NE(pixel, nullptr);
  ASSERT_EQ(pixel->GetNumberOfComponents(), 2);
  EXPECT_EQ(pixel->GetComponent(4, 0), 24);
  EXPECT_EQ(pixel->GetComponent(4, 1), 10);
  EXPECT_EQ(pixel->GetComponent(5, 0), 5);
  EXPECT_EQ(pixel->GetComponent(5, 1), 30);
  std::filesystem::remove_all(dir.parent_path());
}

/// Pixels of the 3D half of a screenshot drawn in the picks' magenta.
int magenta_pixels(const grtrace::PngRgb8& png) {
  int n = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width / 2; ++x) {
      const auto o = static_cast<std::size_t>(3 * (y * png.width + x));
      n += png.rgb[o] > 230 && png.rgb[o + 1] > 40 && png.rgb[o + 1] < 90 && png.rgb[o + 2] > 190 && png.rgb[o + 2] < 240;
    }
  return n;
}

TEST(ViewTool, PickedRaysAppearInTheScreenshot) {
  if (!grtrace::viz::display_available()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  const auto with = scratch("picked.png"), without = scratch("unpicked.png");
  const std::string common = " --size 400x200 --width 48 --height 36 --bundle none";
  const ToolRun r = run("--screenshot " + with.string() + common + " --pick 24,10");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("pick pixel (24, 10): "), std::string::npos) << r.output;
  const ToolRun plain = run("--screenshot " + without.string() + common);
  ASSERT_EQ(plain.status, 0) << plain.output;
  EXPECT_GT(magenta_pixels(grtrace::read_png_rgb8(with)), 20);
  EXPECT_EQ(magenta_pixels(grtrace::read_png_rgb8(without)), 0);
  std::filesystem::remove_all(with.parent_path());
}

TEST(ViewTool, BadPicksAreRefusedBeforeAnyWork) {
  const auto dir = scratch("refused-scene");
  std::filesystem::remove_all(dir);
  for (const char* pick : {"48,0", "0,36", "-1,3", "12", "a,b", "1,2,3", "1,2x", "3,4//5,6", "''"}) {
    const ToolRun r = run("--export " + dir.string() + " --width 48 --height 36 --pick " + pick);
    EXPECT_EQ(r.status, 2) << pick << "\n" << r.output;
    EXPECT_NE(r.output.find("--pick"), std::string::npos) << pick << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir)) << pick;
  }
  const ToolRun chart = run("--chart orbit --pick 1,1 --screenshot " + scratch("chart.png").string());
  EXPECT_EQ(chart.status, 2) << chart.output;
  EXPECT_NE(chart.output.find("--pick"), std::string::npos) << chart.output;
  EXPECT_FALSE(std::filesystem::exists(scratch("chart.png")));
  std::filesystem::remove_all(dir.parent_path());
}

}  // namespace
