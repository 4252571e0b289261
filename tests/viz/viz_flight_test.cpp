// grtrace-view --flight: the camera flight's path exported (flight.vtp read back with VTK's XML reader) is the
// library's flight_path, sample for sample; the camera recorded is make_moving_camera at --flight-frame; the frame
// exported is the render of that camera; bad flight input exits 2 naming the option, before any work. The export
// cases need no display (DISPLAY unset); the screenshot case skips without one (run under xvfb-run).
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/flight_path.hpp"
#include "grtrace/observer/worldline_csv.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/auto_tracer.hpp"

#include "../common/tool_run.hpp"
#include "view_export_support.hpp"

#include <gtest/gtest.h>

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace grtrace;
using grtrace::tool_tests::ToolRun;
const auto run = grtrace::tool_tests::run_command;

constexpr int kW = 48, kH = 36, kFrames = 12, kFrame = 5;

using grtrace::view_tests::read_vtp;
using grtrace::view_tests::view;

/// Takes a file name; returns its path in this program's scratch directory.
fs::path scratch(const std::string& name) { return grtrace::view_tests::scratch("flight-test", name); }

/// The path grtrace-view flies for --flight seed --frames 12 with its defaults (M = 1, sky radius 400).
Worldline expected_path() {
  FlightPathSpec spec;
  spec.kind = "seed";
  spec.frames = kFrames;
  spec.sky_radius = 400.0;
  return flight_path(SchwarzschildMetric{1.0}, spec);
}

/// The camera of frame kFrame: grtrace-view's default --look/--up, the frame's size and --fov 55.
Camera expected_camera(const Worldline& path) {
  const WorldlineSample& s = path.samples[kFrame];
  return make_moving_camera(SchwarzschildMetric{1.0}, s.x, s.u, CameraView{{-1.0, 0.0, 0.0}, {0.0, -1.0, 0.0}, kW, kH, 55.0});
}

/// |a - b| within 1e-12 relative to max(1, |b|).
void expect_close(double a, double b, const std::string& what) {
  EXPECT_NEAR(a, b, 1e-12 * std::max(1.0, std::abs(b))) << what;
}

/// --flight seed --frames kFrames --flight-frame kFrame at kW x kH, exported once for the ViewFlightExport tests.
struct SeedFlightExport {
  static constexpr const char* program = "flight-test";
  static constexpr const char* name = "flight";
  static std::string options() {
    return "--flight seed --frames " + std::to_string(kFrames) + " --flight-frame " + std::to_string(kFrame) +
           " --width " + std::to_string(kW) + " --height " + std::to_string(kH) + " --bundle-size 3x3 --threads 2";
  }
};
using ViewFlightExport = grtrace::view_tests::ExportSuite<SeedFlightExport>;

TEST_F(ViewFlightExport, WritesTheFlightAndTheCollectionOpensIt) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  ASSERT_TRUE(fs::exists(dir_ / "flight.vtp")) << result_.output;
  const std::set<std::string> names = grtrace::view_tests::block_names(dir_ / "scene.vtm");
  EXPECT_TRUE(names.count("flight")) << result_.output;
  EXPECT_TRUE(names.count("rays"));
  EXPECT_TRUE(names.count("frame"));
}

TEST_F(ViewFlightExport, PointsAreTheLibrarysFlightPath) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  const Worldline path = expected_path();
  ASSERT_EQ(path.samples.size(), static_cast<std::size_t>(kFrames));
  auto flight = read_vtp(dir_ / "flight.vtp");
  ASSERT_EQ(flight->GetNumberOfPoints(), kFrames);
  vtkDataArray* tau = flight->GetPointData()->GetArray("tau");
  vtkDataArray* frame = flight->GetPointData()->GetArray("frame");
  vtkDataArray* coordinates = flight->GetPointData()->GetArray("coordinates");
  vtkDataArray* velocity = flight->GetPointData()->GetArray("momentum");
  ASSERT_NE(tau, nullptr);
  ASSERT_NE(frame, nullptr);
  ASSERT_NE(coordinates, nullptr);
  ASSERT_NE(velocity, nullptr);
  const SchwarzschildMetric metric{1.0};
  for (vtkIdType i = 0; i < kFrames; ++i) {
    const WorldlineSample& s = path.samples[static_cast<std::size_t>(i)];
    const Vec3 p = metric.to_cartesian(s.x);
    double got[3];
    flight->GetPoint(i, got);
    for (int c = 0; c < 3; ++c) expect_close(got[c], p[c], "point " + std::to_string(i));
    for (int mu = 0; mu < 4; ++mu) {
      expect_close(coordinates->GetComponent(i, mu), s.x[mu], "x^" + std::to_string(mu) + " of " + std::to_string(i));
      expect_close(velocity->GetComponent(i, mu), s.u[mu], "u^" + std::to_string(mu) + " of " + std::to_string(i));
    }
    expect_close(tau->GetComponent(i, 0), s.tau, "tau of " + std::to_string(i));
    EXPECT_EQ(frame->GetComponent(i, 0), static_cast<double>(i));
  }
}

TEST_F(ViewFlightExport, CameraIsTheMovingCameraOfTheFrame) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  const Worldline path = expected_path();
  const Camera want = expected_camera(path);
  for (const char* file : {"flight.vtp", "rays.vtp"}) {
    auto data = read_vtp(dir_ / file);
    vtkFieldData* fd = data->GetFieldData();
    ASSERT_NE(fd->GetArray("camera_position"), nullptr) << file;
    ASSERT_NE(fd->GetArray("camera_tetrad"), nullptr) << file;
    for (int mu = 0; mu < 4; ++mu) expect_close(fd->GetArray("camera_position")->GetComponent(0, mu), want.position()[mu], file);
    for (int a = 0; a < 4; ++a)
      for (int mu = 0; mu < 4; ++mu)
        expect_close(fd->GetArray("camera_tetrad")->GetComponent(0, 4 * a + mu),
                     want.tetrad().e[static_cast<std::size_t>(a)][mu], std::string(file) + " e_" + std::to_string(a));
    EXPECT_EQ(fd->GetArray("frame_size")->GetComponent(0, 0), kW);
    EXPECT_EQ(fd->GetArray("frame_size")->GetComponent(0, 1), kH);
  }
  const auto flight = read_vtp(dir_ / "flight.vtp");
  vtkFieldData* fd = flight->GetFieldData();
  ASSERT_NE(fd->GetArray("flight_frame"), nullptr);
  EXPECT_EQ(fd->GetArray("flight_frame")->GetComponent(0, 0), kFrame);
  expect_close(fd->GetArray("flight_frame_tau")->GetComponent(0, 0), path.samples[kFrame].tau, "flight_frame_tau");
  auto* kind = vtkStringArray::SafeDownCast(fd->GetAbstractArray("flight"));
  ASSERT_NE(kind, nullptr);
  EXPECT_EQ(kind->GetValue(0), "seed");
}

TEST_F(ViewFlightExport, FrameIsTheRenderOfThatCamera) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  const Camera camera = expected_camera(expected_path());
  // grtrace-view's defaults: dopri5 + PI, rtol 1e-8, atol 1e-10, sky radius 400, the disk 6 .. 20 M, exact
  // angle correction, the auto tracer with a table of 2048 rays.
  TraceSettings settings;
  settings.integrator.tolerance.rtol = 1e-8;
  settings.integrator.tolerance.atol = 1e-10;
  settings.escape_radius = 400.0;
  settings.max_steps = 100000;
  StandardSceneSpec spec;
  spec.name = "disk";
  spec.disk.r_in = 6.0;
  spec.disk.r_out = 20.0;
  RenderOptions options;
  options.threads = 2;
  options.progress = ProgressMode::never;
  std::optional<Frame> frame;
  with_standard_scene(spec, [&]<class Scene>(Scene scene) {
    with_auto_tracer<DormandPrince54, PIController>(SchwarzschildMetric{1.0}, settings, camera, AngleCorrection::exact,
                                                    scene, 2048, [&](const auto& tracer) {
                                                      frame.emplace(render_frame(camera, tracer, options));
                                                    });
  });
  const auto image = grtrace::view_tests::read_vti(dir_ / "frame.vti");
  int dims[3];
  image->GetDimensions(dims);
  ASSERT_EQ(dims[0], kW);
  ASSERT_EQ(dims[1], kH);
  for (const char* channel : {"R", "G", "B", "status"}) {
    vtkDataArray* a = image->GetPointData()->GetArray(channel);
    ASSERT_NE(a, nullptr) << channel;
    const std::vector<float>& want = frame->image.channel(channel);
    int differing = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x)
        if (a->GetComponent(x + static_cast<vtkIdType>(kW) * (kH - 1 - y), 0) != static_cast<double>(want[frame->image.index(x, y)]))
          ++differing;
    EXPECT_EQ(differing, 0) << channel;
  }
}

TEST(ViewFlightCsv, FollowsTheCsvAndItsFrameCountBoundsTheFrame) {
  // The seed path written as a camera-path CSV (observer/worldline_csv.hpp) and flown again: the same points.
  const Worldline path = expected_path();
  const fs::path csv = scratch("seed.csv");
  std::ofstream(csv) << worldline_csv(path);
  const fs::path dir = scratch("csv");
  fs::remove_all(dir);
  const std::string flight = "--flight csv --flight-csv " + csv.string() + " --width 16 --height 12 --bundle none";
  const ToolRun ok = run(view(flight + " --flight-frame " + std::to_string(kFrames - 1) + " --export " + dir.string()));
  ASSERT_EQ(ok.status, 0) << ok.output;
  const auto data = read_vtp(dir / "flight.vtp");
  ASSERT_EQ(data->GetNumberOfPoints(), kFrames);
  vtkDataArray* coordinates = data->GetPointData()->GetArray("coordinates");
  ASSERT_NE(coordinates, nullptr);
  for (vtkIdType i = 0; i < kFrames; ++i)
    for (int mu = 0; mu < 4; ++mu)
      expect_close(coordinates->GetComponent(i, mu), path.samples[static_cast<std::size_t>(i)].x[mu], "csv x");
  // One frame past the CSV's rows: refused after reading it, before anything is written.
  const fs::path refused = scratch("csv-refused");
  fs::remove_all(refused);
  const ToolRun bad = run(view(flight + " --flight-frame " + std::to_string(kFrames) + " --export " + refused.string()));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--flight-frame"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(refused));
}

TEST(ViewFlightRefusals, BadFlightInputExitsTwoNamingTheOptionAndWritesNothing) {
  const fs::path dir = scratch("refused");
  fs::remove_all(dir);
  struct Case {
    std::string args, option;
  };
  const std::vector<Case> cases = {
      {"--flight seed --frames 12 --flight-frame 12", "--flight-frame"},
      {"--flight seed --frames 12 --flight-frame -1", "--flight-frame"},
      {"--flight warp", "--flight"},
      {"--flight csv", "--flight-csv"},
      {"--flight csv --flight-csv " + (dir.parent_path() / "no-such.csv").string(), "--flight csv"},
      {"--flight-frame 3", "--flight-frame"},
      {"--frames 12", "--frames"},
      {"--frame-dtau 10", "--frame-dtau"},
      {"--flight seed --frames 0", "--frames"},
      {"--flight seed --velocity 0.1,0,0", "--velocity"},
      {"--flight seed --orbit", "--orbit"},
      {"--flight circular --camera-r 2.5", "--flight circular"},
      {"--flight seed --sky-radius 50", "--sky-radius"},
      {"--flight seed --chart orbit", "--chart"},
  };
  for (const Case& c : cases) {
    const ToolRun r = run(view(c.args + " --export " + dir.string() + " --width 16 --height 12 --bundle none"));
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.option), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir)) << c.args;
  }
}

TEST(ViewFlightScreenshot, DrawsTheFlight) {
  if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  const fs::path png = scratch("flight.png");
  const ToolRun r = run(std::string(GRTRACE_VIEW_EXE) + " --flight seed --frames 24 --flight-frame 6 --width 64 " +
                        "--height 48 --bundle-size 3x3 --size 640x320 --screenshot " + png.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_GT(fs::file_size(png), 1000u);
}

}  // namespace
