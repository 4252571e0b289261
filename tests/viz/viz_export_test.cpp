// ParaView export: grtrace-view --export DIR and grtrace-geodesic --vtp FILE, read back with VTK's XML readers.
// Checks the named point arrays (one value per point), that a ray's points are the tracer's path for its pixel,
// the horizon at r = 2M, the frame's size and orientation, the collection's blocks, and that bad paths are refused
// with exit 2 before anything is written. No display is needed (the export runs with DISPLAY unset).
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/tetrad.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/viz/traced_path.hpp"
#include "grtrace/viz/vtk_export.hpp"

#include "../common/tool_run.hpp"
#include "view_export_support.hpp"

#include <gtest/gtest.h>

#include <vtkAbstractArray.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkVariant.h>
#include <vtkXMLMultiBlockDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#ifndef GRTRACE_GEODESIC_EXE
#error "GRTRACE_GEODESIC_EXE (path of grtrace-geodesic) must be defined by the build"
#endif

namespace {

namespace fs = std::filesystem;
using namespace grtrace;

using grtrace::tool_tests::ToolRun;
const auto run = grtrace::tool_tests::run_command;

using grtrace::view_tests::read_vtp;
using grtrace::view_tests::view;
std::string geodesic(const std::string& args) { return std::string(GRTRACE_GEODESIC_EXE) + " " + args; }

fs::path scratch(const std::string& name) { return grtrace::view_tests::scratch("export-test", name); }

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

/// The named point arrays exist with one tuple per point (and `components` components).
void expect_point_arrays(vtkPolyData* poly) {
  const std::array<std::pair<const char*, int>, 5> arrays = {
      {{"affine_parameter", 1}, {"step_size", 1}, {"redshift", 1}, {"status", 1}, {"pixel", 2}}};
  for (const auto& [name, comps] : arrays) {
    vtkDataArray* a = poly->GetPointData()->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->GetNumberOfTuples(), poly->GetNumberOfPoints()) << name;
    EXPECT_EQ(a->GetNumberOfComponents(), comps) << name;
  }
}

// ---- grtrace-view --export -------------------------------------------------------------------------------

constexpr int kW = 48, kH = 36;

/// The default scene at kW x kH with a 3x3 bundle, exported once for the ViewExport tests.
struct DefaultSceneExport {
  static constexpr const char* program = "export-test";
  static constexpr const char* name = "scene";
  static std::string options() {
    return "--width " + std::to_string(kW) + " --height " + std::to_string(kH) + " --bundle-size 3x3 --threads 2";
  }
};
using ViewExport = grtrace::view_tests::ExportSuite<DefaultSceneExport>;

TEST_F(ViewExport, ExitsZeroWithoutADisplayAndWritesTheFiles) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  EXPECT_NE(result_.output.find("scene.vtm"), std::string::npos) << result_.output;
  const std::set<std::string> want = {"scene.vtm",  "rays.vtp", "horizon.vtp",        "photon_sphere.vtp",
                                      "isco.vtp",   "disk.vtp", "sky.vtp",            "camera_frustum.vtp",
                                      "camera_axes.vtp", "frame.vti"};
  EXPECT_EQ(listing(dir_), want);  // and no temporaries left behind
}

TEST_F(ViewExport, CollectionOpensEveryBlock) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  vtkNew<vtkXMLMultiBlockDataReader> r;
  r->SetFileName((dir_ / "scene.vtm").c_str());
  r->Update();
  auto* mb = vtkMultiBlockDataSet::SafeDownCast(r->GetOutput());
  ASSERT_NE(mb, nullptr);
  ASSERT_EQ(mb->GetNumberOfBlocks(), 9u);
  std::set<std::string> names;
  for (unsigned i = 0; i < mb->GetNumberOfBlocks(); ++i) {
    ASSERT_NE(mb->GetBlock(i), nullptr) << i;
    names.insert(mb->GetMetaData(i)->Get(vtkCompositeDataSet::NAME()));
  }
  EXPECT_EQ(names, (std::set<std::string>{"rays", "horizon", "photon_sphere", "isco", "disk", "sky",
                                          "camera_frustum", "camera_axes", "frame"}));
  for (unsigned i = 0; i < mb->GetNumberOfBlocks(); ++i) {
    const std::string name = mb->GetMetaData(i)->Get(vtkCompositeDataSet::NAME());
    if (name == "frame") EXPECT_NE(vtkImageData::SafeDownCast(mb->GetBlock(i)), nullptr);
    else EXPECT_NE(vtkPolyData::SafeDownCast(mb->GetBlock(i)), nullptr) << name;
  }
}

TEST_F(ViewExport, RaysCarryTheArraysAndAreTheTracersPaths) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  auto rays = read_vtp(dir_ / "rays.vtp");
  ASSERT_EQ(rays->GetNumberOfCells(), 9);
  expect_point_arrays(rays);
  for (const char* name : {"ray", "status", "pixel"}) EXPECT_NE(rays->GetCellData()->GetArray(name), nullptr) << name;

  // The camera recorded with the rays is the default one of the options (r = 35 M, theta = 84 deg, phi = 0).
  vtkFieldData* fd = rays->GetFieldData();
  ASSERT_NE(fd->GetArray("camera_position"), nullptr);
  ASSERT_NE(fd->GetArray("camera_tetrad"), nullptr);
  Vec4 x;
  for (int mu = 0; mu < 4; ++mu) x[mu] = fd->GetArray("camera_position")->GetComponent(0, mu);
  EXPECT_EQ(x, Vec4(0.0, 35.0, 84.0 * (std::numbers::pi / 180.0), 0.0));  // as the tool converts degrees
  Tetrad t;
  for (int a = 0; a < 4; ++a)
    for (int mu = 0; mu < 4; ++mu)
      t.e[static_cast<std::size_t>(a)][mu] = fd->GetArray("camera_tetrad")->GetComponent(0, 4 * a + mu);
  EXPECT_EQ(fd->GetArray("frame_size")->GetComponent(0, 0), kW);
  EXPECT_EQ(fd->GetArray("frame_size")->GetComponent(0, 1), kH);
  const Camera camera(x, t, kW, kH, fd->GetArray("camera_fov_degrees")->GetComponent(0, 0));

  // The tracer of grtrace-view's defaults: dopri5 + PI, rtol 1e-8, atol 1e-10, escape at the sky radius 400,
  // the disk (6 .. 20 M) as the event; 8 samples per step; redshift against the camera's e_0. As the frame's general
  // scene tracer integrates (the path and the pixel's outcome are one integration): an escaped ray, continued
  // exactly, ends at its last accepted step, not refined onto the sky sphere (with_escape_refinement).
  TraceSettings settings;
  settings.integrator.tolerance.rtol = 1e-8;
  settings.integrator.tolerance.atol = 1e-10;
  settings.escape_radius = 400.0;
  settings.max_steps = 100000;
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> tracer(
      SchwarzschildMetric{1.0}, with_escape_refinement<SchwarzschildMetric>(settings, AngleCorrection::exact));
  StandardSceneSpec spec;
  spec.name = "disk";
  spec.disk.r_in = 6.0;
  spec.disk.r_out = 20.0;

  vtkDataArray* pixel = rays->GetCellData()->GetArray("pixel");
  vtkDataArray* status = rays->GetCellData()->GetArray("status");
  vtkDataArray* lambda = rays->GetPointData()->GetArray("affine_parameter");
  vtkDataArray* h = rays->GetPointData()->GetArray("step_size");
  vtkDataArray* redshift = rays->GetPointData()->GetArray("redshift");
  std::set<int> statuses;
  for (vtkIdType cell : {vtkIdType{0}, vtkIdType{4}, vtkIdType{8}}) {  // corner, centre, corner
    const int px = static_cast<int>(pixel->GetComponent(cell, 0)), py = static_cast<int>(pixel->GetComponent(cell, 1));
    const viz::TracedPath path =
        viz::trace_path(tracer, camera.pixel_state(px, py), 8, camera.tetrad().e[0], spec.disk);
    vtkNew<vtkIdList> cell_ids;
    rays->GetCellPoints(cell, cell_ids);
    const vtkIdType n = cell_ids->GetNumberOfIds();
    const vtkIdType* ids = cell_ids->GetPointer(0);
    ASSERT_EQ(static_cast<std::size_t>(n), path.samples.size()) << "pixel " << px << "," << py;
    EXPECT_EQ(static_cast<int>(status->GetComponent(cell, 0)), static_cast<int>(path.status));
    statuses.insert(static_cast<int>(path.status));
    for (vtkIdType i = 0; i < n; ++i) {
      const auto& s = path.samples[static_cast<std::size_t>(i)];
      double p[3];
      rays->GetPoint(ids[i], p);
      const double scale = std::max(1.0, s.position.norm());
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(p[c], s.position[c], 1e-12 * scale) << "point " << i;
      EXPECT_NEAR(lambda->GetComponent(ids[i], 0), s.lambda, 1e-12 * std::max(1.0, std::abs(s.lambda)));
      EXPECT_NEAR(h->GetComponent(ids[i], 0), s.h, 1e-12 * std::max(1.0, std::abs(s.h)));
      EXPECT_NEAR(redshift->GetComponent(ids[i], 0), s.redshift, 1e-12 * std::max(1.0, std::abs(s.redshift)));
    }
  }
  EXPECT_GE(statuses.size(), 1u);
}

TEST_F(ViewExport, HorizonLiesAtTwoM) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  auto horizon = read_vtp(dir_ / "horizon.vtp");
  ASSERT_GT(horizon->GetNumberOfPoints(), 100);
  ASSERT_GT(horizon->GetNumberOfPolys(), 100);
  for (vtkIdType i = 0; i < horizon->GetNumberOfPoints(); ++i) {
    double p[3];
    horizon->GetPoint(i, p);
    ASSERT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 2.0, 1e-6) << i;
  }
  auto photon = read_vtp(dir_ / "photon_sphere.vtp");
  double p[3];
  photon->GetPoint(0, p);
  EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 3.0, 1e-6);
  auto isco = read_vtp(dir_ / "isco.vtp");
  isco->GetPoint(0, p);
  EXPECT_NEAR(std::hypot(p[0], p[1]), 6.0, 1e-6);
  EXPECT_NEAR(p[2], 0.0, 1e-12);
}

TEST_F(ViewExport, FrameImageHasTheFramesSizeChannelsAndOrientation) {
  ASSERT_EQ(result_.status, 0) << result_.output;
  const auto image = grtrace::view_tests::read_vti(dir_ / "frame.vti");
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], kW);
  EXPECT_EQ(dims[1], kH);
  EXPECT_EQ(dims[2], 1);
  vtkDataArray* rgb = image->GetPointData()->GetArray("rgb");
  ASSERT_NE(rgb, nullptr);
  EXPECT_EQ(rgb->GetNumberOfComponents(), 3);
  for (const char* c : {"R", "G", "B", "object", "status", "redshift", "sky_theta", "sky_phi", "steps", "order"}) {
    vtkDataArray* a = image->GetPointData()->GetArray(c);
    ASSERT_NE(a, nullptr) << c;
    EXPECT_EQ(a->GetNumberOfTuples(), static_cast<vtkIdType>(kW) * kH) << c;
  }
  // Each ray keeps its pixel's colour: the image point (x, H - 1 - y) holds it (VTK rows grow upwards).
  auto rays = read_vtp(dir_ / "rays.vtp");
  vtkDataArray* pixel = rays->GetPointData()->GetArray("pixel");
  vtkDataArray* color = rays->GetPointData()->GetArray("pixel_color");
  ASSERT_NE(color, nullptr);
  for (vtkIdType i = 0; i < rays->GetNumberOfPoints(); i += 97) {
    const int x = static_cast<int>(pixel->GetComponent(i, 0)), y = static_cast<int>(pixel->GetComponent(i, 1));
    const vtkIdType id = x + static_cast<vtkIdType>(kW) * (kH - 1 - y);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb->GetComponent(id, c), color->GetComponent(i, c)) << x << "," << y;
  }
}

TEST(ViewExportKerr, ErgosphereInsteadOfPhotonSphereAndHiddenLayersLeftOut) {
  const fs::path dir = scratch("kerr");
  fs::remove_all(dir);
  const ToolRun r = run(view("--export " + dir.string() +
                             " --metric kerr --spin 0.9 --width 16 --height 12 --bundle none --hide sky,camera"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(listing(dir), (std::set<std::string>{"scene.vtm", "horizon.vtp", "ergosphere.vtp", "isco.vtp", "disk.vtp",
                                                 "frame.vti"}));
  auto horizon = read_vtp(dir / "horizon.vtp");
  const double r_plus = 1.0 + std::sqrt(1.0 - 0.81);
  for (vtkIdType i = 0; i < horizon->GetNumberOfPoints(); i += 7) {
    double p[3];
    horizon->GetPoint(i, p);
    ASSERT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), r_plus, 1e-6) << i;
  }
}

TEST(ViewExportScreenshot, ExportAndScreenshotTogether) {
  if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  const fs::path dir = scratch("with-shot"), png = scratch("with-shot.png");
  fs::remove_all(dir);
  fs::remove(png);
  const ToolRun r = run(std::string(GRTRACE_VIEW_EXE) + " --export " + dir.string() + " --screenshot " +
                        png.string() + " --size 320x160 --width 24 --height 18 --bundle-size 2x2");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "scene.vtm"));
  EXPECT_TRUE(fs::is_regular_file(png));
}

TEST(ViewExportRefusals, BadDirectoriesExitTwoAndWriteNothing) {
  const fs::path base = scratch("refusals");
  fs::remove_all(base);
  fs::create_directories(base);
  const fs::path file = base / "a-file";
  std::ofstream(file) << "keep me\n";
  const auto before = listing(base);
  struct Case {
    std::string dir, mention;
  };
  const std::vector<Case> cases = {{file.string(), "not a directory"},
                                   {(file / "sub").string(), "cannot create"},
                                   {"/proc/grtrace-export-test", "cannot create"},
                                   {"''", "--export"}};
  for (const Case& c : cases) {
    const ToolRun r = run(view("--export " + c.dir + " --width 16 --height 12 --bundle none"));
    EXPECT_EQ(r.status, 2) << c.dir << "\n" << r.output;
    EXPECT_NE(r.output.find("--export"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(c.mention), std::string::npos) << c.dir << "\n" << r.output;
  }
  EXPECT_EQ(listing(base), before);
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "keep me");
  EXPECT_FALSE(fs::exists("/proc/grtrace-export-test"));
  // A bad option beside --export is refused before the directory is made.
  const fs::path fresh = base / "fresh";
  EXPECT_EQ(run(view("--export " + fresh.string() + " --mass -1")).status, 2);
  EXPECT_FALSE(fs::exists(fresh));
  EXPECT_EQ(run(view("--export " + fresh.string() + " --chart orbit")).status, 2);
  EXPECT_FALSE(fs::exists(fresh));
  // --export with --screenshot draws, so it needs a display: refused without one, and no directory is made.
  const ToolRun no_display = run(view("--export " + fresh.string() + " --screenshot " + (base / "s.png").string()));
  EXPECT_EQ(no_display.status, 2) << no_display.output;
  EXPECT_NE(no_display.output.find("xvfb-run"), std::string::npos) << no_display.output;
  EXPECT_FALSE(fs::exists(fresh));
}

// ---- grtrace-geodesic --vtp ------------------------------------------------------------------------------

std::vector<std::vector<double>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<double> row;
    for (std::string item; std::getline(ss, item, ',');) row.push_back(std::stod(item));
    rows.push_back(row);
  }
  return rows;
}

TEST(GeodesicVtp, PolylineIsTheToolsPath) {
  const fs::path csv = scratch("g.csv"), vtp = scratch("g.vtp");
  fs::remove(csv);
  fs::remove(vtp);
  const ToolRun r = run(geodesic("--position 0,20,1.4,0.3 --velocity -1,0.01,0.015 --path " + csv.string() +
                                 " --vtp " + vtp.string()));
  ASSERT_EQ(r.status, 0) << r.output;
  const auto rows = read_csv(csv);  // lambda, t, r, theta, phi, kt, kr, ktheta, kphi, h
  ASSERT_GT(rows.size(), 10u);
  auto poly = read_vtp(vtp);
  ASSERT_EQ(poly->GetNumberOfCells(), 1);
  ASSERT_EQ(poly->GetNumberOfPoints(), static_cast<vtkIdType>(rows.size()));
  expect_point_arrays(poly);
  vtkDataArray* lambda = poly->GetPointData()->GetArray("affine_parameter");
  vtkDataArray* h = poly->GetPointData()->GetArray("step_size");
  vtkDataArray* pixel = poly->GetPointData()->GetArray("pixel");
  vtkDataArray* redshift = poly->GetPointData()->GetArray("redshift");
  vtkNew<vtkIdList> cell_ids;
  poly->GetCellPoints(0, cell_ids);
  const vtkIdType n = cell_ids->GetNumberOfIds();
  const vtkIdType* ids = cell_ids->GetPointer(0);
  ASSERT_EQ(n, static_cast<vtkIdType>(rows.size()));
  for (vtkIdType i = 0; i < n; ++i) {
    const auto& row = rows[static_cast<std::size_t>(i)];
    const double rr = row[2], th = row[3], ph = row[4];
    double p[3];
    poly->GetPoint(ids[i], p);
    // The CSV prints 17 significant digits: the points agree to rounding.
    EXPECT_NEAR(p[0], rr * std::sin(th) * std::cos(ph), 1e-13 * rr) << i;
    EXPECT_NEAR(p[1], rr * std::sin(th) * std::sin(ph), 1e-13 * rr) << i;
    EXPECT_NEAR(p[2], rr * std::cos(th), 1e-13 * rr) << i;
    EXPECT_NEAR(lambda->GetComponent(ids[i], 0), row[0], 1e-15 * std::max(1.0, std::abs(row[0])));
    EXPECT_NEAR(h->GetComponent(ids[i], 0), row[9], 1e-15 * std::max(1.0, std::abs(row[9])));
    EXPECT_EQ(pixel->GetComponent(ids[i], 0), -1);
  }
  EXPECT_NEAR(redshift->GetComponent(ids[0], 0), 1.0, 1e-14);  // relative to the static observer at the start
  // The JSON's status is the one in the file.
  const std::string status_name = r.output.substr(r.output.find("\"status\":\"") + 10);
  vtkAbstractArray* names = poly->GetFieldData()->GetAbstractArray("status_names");
  ASSERT_NE(names, nullptr);
  const int st = static_cast<int>(poly->GetCellData()->GetArray("status")->GetComponent(0, 0));
  EXPECT_EQ(status_name.substr(0, status_name.find('"')), names->GetVariantValue(st).ToString());
}

TEST(GeodesicVtp, BadPathsExitTwoAndWriteNothing) {
  const fs::path csv = scratch("bad.csv");
  fs::remove(csv);
  const std::string ray = "--position 0,20,1.4,0.3 --velocity -1,0.01,0.015 ";
  for (const std::string& bad : {std::string("/nonexistent/dir/g.vtp"), std::string("''"), scratch("").string(),
                                 csv.string()}) {
    const ToolRun r = run(geodesic(ray + "--path " + csv.string() + " --vtp " + bad));
    EXPECT_EQ(r.status, 2) << bad << "\n" << r.output;
    EXPECT_NE(r.output.find("--vtp"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(csv)) << bad;  // refused before the trace: not even the CSV
  }
}

}  // namespace
