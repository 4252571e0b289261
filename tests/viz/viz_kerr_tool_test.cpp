// grtrace-view --metric kerr as a program: bad Kerr input is refused (exit 2, a message naming the
// option), and a Kerr scene (frame by the general tracer, rays, outer horizon, ergosphere, ISCO) is drawn offscreen.
// grtrace-render's Kerr options in the viewer (examples/common/kerr_options.hpp): --chart bl|ks (rays and surfaces
// exported in one picture; a Kerr-Schild ray lies on the Boyer-Lindquist ray of the same pixel mapped into KS
// coordinates), --observer static refused in the ergosphere with grtrace-render's message, --disk-retrograde and
// the ISCO bound of --disk-inner, --plot beside its older spelling --chart orbit|norm|step, and a --frame rendered
// with --chart ks. The rendering cases skip without DISPLAY (run under xvfb-run); the export cases need none.
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "view_export_support.hpp"

#include <gtest/gtest.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace {

using grtrace::tool_tests::ToolRun;
using grtrace::view_tests::read_vtp;
using grtrace::view_tests::scratch;
using grtrace::view_tests::view;

constexpr double kSpin = 0.9;

/// Runs grtrace-view with `args` (shell words); returns the exit status and the merged output.
ToolRun run(const std::string& args) { return grtrace::tool_tests::run_command(std::string(GRTRACE_VIEW_EXE) + " " + args); }

/// Runs grtrace-view without a display (the --export runs and the refusals).
ToolRun run_headless(const std::string& args) { return grtrace::tool_tests::run_command(view(args)); }

std::filesystem::path dir_of(const std::string& name) { return scratch("viz_kerr_tool_test", name); }

double outer_horizon() { return 1.0 + std::sqrt(1.0 - kSpin * kSpin); }

/// The Kerr-Schild chart grtrace-view and grtrace-render trace camera rays in (outgoing slicing).
grtrace::KerrSchildMetric ks_chart() { return grtrace::kerr_schild_for_camera_rays(1.0, kSpin); }

/// One exported ray: per point its position, affine parameter, chart coordinates and momentum.
struct Ray {
  std::array<int, 2> pixel{};
  std::vector<grtrace::Vec3> position;
  std::vector<double> lambda;
  std::vector<grtrace::Vec4> x, k;
};

/// Takes a rays.vtp; returns its rays (polylines; single-point rays skipped) by pixel.
std::map<std::array<int, 2>, Ray> read_rays(const std::filesystem::path& file) {
  auto poly = read_vtp(file);
  std::map<std::array<int, 2>, Ray> out;
  vtkDataArray* pixel = poly->GetCellData()->GetArray("pixel");
  vtkDataArray* lambda = poly->GetPointData()->GetArray("affine_parameter");
  vtkDataArray* coords = poly->GetPointData()->GetArray("coordinates");
  vtkDataArray* momentum = poly->GetPointData()->GetArray("momentum");
  if (!pixel || !lambda || !coords || !momentum) return out;
  for (vtkIdType c = 0; c < poly->GetNumberOfCells(); ++c) {
    vtkNew<vtkIdList> ids;
    poly->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() < 2) continue;
    Ray r;
    r.pixel = {static_cast<int>(pixel->GetComponent(c, 0)), static_cast<int>(pixel->GetComponent(c, 1))};
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i) {
      const vtkIdType id = ids->GetId(i);
      double p[3];
      poly->GetPoint(id, p);
      r.position.emplace_back(p[0], p[1], p[2]);
      r.lambda.push_back(lambda->GetComponent(id, 0));
      grtrace::Vec4 x, k;
      for (int mu = 0; mu < 4; ++mu) {
        x[mu] = coords->GetComponent(id, mu);
        k[mu] = momentum->GetComponent(id, mu);
      }
      r.x.push_back(x);
      r.k.push_back(k);
    }
    out[r.pixel] = r;
  }
  return out;
}

/// Takes a BL ray and an affine parameter inside its range; returns its event there by cubic Hermite interpolation
/// between the samples around it (dx/dlambda = k: fourth order, far below the tolerances used here).
grtrace::Vec4 bl_event_at(const Ray& ray, double lambda) {
  const auto it = std::upper_bound(ray.lambda.begin(), ray.lambda.end(), lambda);
  const std::size_t b = std::clamp<std::size_t>(static_cast<std::size_t>(it - ray.lambda.begin()), 1, ray.lambda.size() - 1);
  const std::size_t a = b - 1;
  const double d = ray.lambda[b] - ray.lambda[a], s = (lambda - ray.lambda[a]) / d;
  const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s), h01 = s * s * (3 - 2 * s),
               h11 = s * s * (s - 1);
  return h00 * ray.x[a] + h10 * d * ray.k[a] + h01 * ray.x[b] + h11 * d * ray.k[b];
}

/// Takes a .vtp; returns its points.
std::vector<grtrace::Vec3> points_of(const std::filesystem::path& file) {
  auto poly = read_vtp(file);
  std::vector<grtrace::Vec3> out;
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    double p[3];
    poly->GetPoint(i, p);
    out.emplace_back(p[0], p[1], p[2]);
  }
  return out;
}

// ---- refusals --------------------------------------------------------------------------------------------------

TEST(ViewKerr, BadKerrInputExitsWithTwo) {
  const std::array<std::pair<const char*, const char*>, 13> cases = {{
      {"--metric kerr --spin 1", "--spin"},
      {"--metric kerr --spin nan", "--spin"},
      {"--metric kerr --spin 0.9 --camera-r 1.3", "horizon"},
      {"--metric kerr --spin 0.9 --bundle beam", "--bundle beam"},
      {"--metric kerr --spin 0.9 --orbit", "--orbit"},
      {"--metric kerr --spin 0.9 --disk-inner 1.4", "disk"},
      {"--metric kerr --spin 0.9 --observer moving", "--observer"},
      {"--metric kerr --spin 0.9 --chart ks --scene disk --disk-inner 1.4", "disk"},
      {"--metric kerr --spin 0.9 --chart ks --flight circular --camera-r 12", "--flight"},
      {"--metric kerr --spin 0.9 --plot orbit", "--plot"},
      {"--metric kerr --spin 0.9 --chart orbit", "--chart"},
      {"--chart xy", "orbit, norm or step"},
      {"--plot ks", "--chart ks"},
  }};
  for (const auto& [args, says] : cases) {
    const ToolRun r = run_headless(std::string(args) + " --screenshot /tmp/never-written.png");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(says), std::string::npos) << args << "\n" << r.output;
  }
}

TEST(ViewKerr, MixingPlotAndChartNamesBoth) {
  for (const char* args : {"--chart orbit --plot norm", "--chart ks --metric kerr --spin 0.9 --plot orbit",
                           "--chart bl --plot step"}) {
    const ToolRun r = run_headless(std::string(args) + " --screenshot /tmp/never-written.png");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("--plot"), std::string::npos) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("--chart"), std::string::npos) << args << "\n" << r.output;
  }
}

// --chart ks is Kerr's chart: with --metric schwarzschild both tools refuse it (it used to be silently ignored).
TEST(ViewKerr, KerrSchildChartWithoutKerrIsRefusedByBothTools) {
  const auto dir = dir_of("ks-without-kerr");
  std::filesystem::remove_all(dir);
  const ToolRun r = run_headless("--metric schwarzschild --chart ks --scene checker --export " + dir.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("goes with --metric kerr"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir));
#ifdef GRTRACE_RENDER_EXE
  const auto exr = dir_of("ks-without-kerr.exr");
  const ToolRun render = grtrace::tool_tests::run_command(std::string(GRTRACE_RENDER_EXE) +
                                                          " --chart ks --width 8 --height 8 --out " + exr.string());
  EXPECT_EQ(render.status, 2) << render.output;
  EXPECT_NE(render.output.find("goes with --metric kerr"), std::string::npos) << render.output;
  EXPECT_FALSE(std::filesystem::exists(exr));
#endif
}

// A static observer cannot exist inside the ergosphere (r_E = 2M on the equator): refused before anything is
// written, in both charts, with the message grtrace-render gives for the same camera.
TEST(ViewKerr, StaticObserverInsideTheErgosphereIsRefusedAsByRender) {
  const std::string camera = "--metric kerr --spin 0.9 --camera-r 1.9 --camera-theta 90 --observer static";
  std::string render_message;
#ifdef GRTRACE_RENDER_EXE
  const auto exr = dir_of("static-never.exr");
  const ToolRun render = grtrace::tool_tests::run_command(std::string(GRTRACE_RENDER_EXE) + " " + camera +
                                                          " --width 8 --height 8 --out " + exr.string());
  EXPECT_EQ(render.status, 2) << render.output;
  EXPECT_FALSE(std::filesystem::exists(exr));
  render_message = render.output.substr(render.output.find("observer:"));
  render_message = render_message.substr(0, render_message.find('\n'));
#endif
  for (const char* chart : {"bl", "ks"}) {
    const auto dir = dir_of(std::string("static-") + chart);
    std::filesystem::remove_all(dir);
    const ToolRun r = run_headless(camera + " --chart " + chart + " --scene checker --export " + dir.string());
    EXPECT_EQ(r.status, 2) << chart << "\n" << r.output;
    EXPECT_NE(r.output.find("no static observer exists"), std::string::npos) << chart << "\n" << r.output;
    if (!render_message.empty()) {
      EXPECT_NE(r.output.find(render_message), std::string::npos) << r.output;
    }
    EXPECT_FALSE(std::filesystem::exists(dir)) << chart;
  }
  // The ZAMO (Kerr's default observer) exists there: the same camera is drawn.
  const auto dir = dir_of("zamo-in-ergosphere");
  std::filesystem::remove_all(dir);
  const ToolRun zamo = run_headless("--metric kerr --spin 0.9 --camera-r 1.9 --camera-theta 90 --chart ks "
                                    "--width 8 --height 6 --bundle-size 2x2 --export " + dir.string());
  EXPECT_EQ(zamo.status, 0) << zamo.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "rays.vtp")) << zamo.output;
}

// --disk-inner inside the ISCO of the disk's sense: refused (prograde 2.32 M, retrograde 8.72 M at a = 0.9).
TEST(ViewKerr, DiskInnerInsideTheIscoIsRefused) {
  for (const char* args : {"--disk-inner 2.0", "--disk-retrograde --disk-inner 5"}) {
    const ToolRun r = run_headless(std::string("--metric kerr --spin 0.9 ") + args + " --screenshot /tmp/never.png");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("inside the ISCO"), std::string::npos) << args << "\n" << r.output;
  }
}

// ---- Boyer-Lindquist and Kerr-Schild views of one camera --------------------------------------------------------

/// One camera (a = 0.9, r = 12 M, theta = 80 deg) exported in both charts, with a pick; the checker scene so that
/// both charts trace the same rays (the disk needs the spherical chart).
class KerrCharts : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string camera = "--metric kerr --spin 0.9 --camera-r 12 --camera-theta 80 --fov 60 --width 40 "
                               "--height 30 --scene checker --bundle-size 5x4 --rtol 1e-10 --atol 1e-12 "
                               "--pick 20,15 --export ";
    for (const char* chart : {"bl", "ks"}) {
      const auto dir = dir_of(std::string("charts-") + chart);
      std::filesystem::remove_all(dir);
      runs_[chart] = run_headless(camera + dir.string() + " --chart " + chart);
      dirs_[chart] = dir;
    }
  }
  inline static std::map<std::string, ToolRun> runs_;
  inline static std::map<std::string, std::filesystem::path> dirs_;
};

TEST_F(KerrCharts, BothChartsRunAndExportTheSameRays) {
  for (const char* chart : {"bl", "ks"}) {
    ASSERT_EQ(runs_[chart].status, 0) << chart << "\n" << runs_[chart].output;
    EXPECT_NE(runs_[chart].output.find("pick "), std::string::npos) << runs_[chart].output;
    EXPECT_EQ(read_vtp(dirs_[chart] / "rays.vtp")->GetNumberOfCells(), 21) << chart;  // 5x4 bundle + 1 pick
  }
  const auto bl = read_rays(dirs_["bl"] / "rays.vtp"), ks = read_rays(dirs_["ks"] / "rays.vtp");
  EXPECT_EQ(bl.size(), ks.size());
  for (const auto& [pixel, ray] : bl) EXPECT_TRUE(ks.count(pixel)) << pixel[0] << "," << pixel[1];
}

// The physical check of the chart: each Kerr-Schild ray is the Boyer-Lindquist ray of its pixel (same affine
// parameter: the camera's k is the same vector in both charts) mapped into KS coordinates, away from the horizon
// where BL coordinates fail; and only the KS rays go inside the outer horizon r_+.
TEST_F(KerrCharts, KerrSchildRaysAreTheBoyerLindquistRaysMapped) {
  ASSERT_EQ(runs_["bl"].status, 0) << runs_["bl"].output;
  ASSERT_EQ(runs_["ks"].status, 0) << runs_["ks"].output;
  const auto bl = read_rays(dirs_["bl"] / "rays.vtp"), ks = read_rays(dirs_["ks"] / "rays.vtp");
  const grtrace::KerrSchildMetric chart = ks_chart();
  const double rp = outer_horizon();
  long compared = 0;
  int ks_inside = 0;
  double worst = 0.0;
  for (const auto& [pixel, k_ray] : ks) {
    ASSERT_TRUE(bl.count(pixel));
    const Ray& b_ray = bl.at(pixel);
    for (const grtrace::Vec4& x : b_ray.x) EXPECT_GT(x[1], rp) << "a BL ray inside r_+";
    double ks_min_r = 1e300;
    for (std::size_t i = 0; i < k_ray.x.size(); ++i) {
      const double r = chart.radius(k_ray.x[i]);
      ks_min_r = std::min(ks_min_r, r);
      // Positions are the chart's Cartesian x, y, z.
      EXPECT_NEAR((k_ray.position[i] - k_ray.x[i].tail<3>()).norm(), 0.0, 1e-12);
      const double l = k_ray.lambda[i];
      if (r < 1.5 * rp || l < b_ray.lambda.front() || l > b_ray.lambda.back()) continue;
      const grtrace::Vec4 mapped = grtrace::bl_to_ks_position(chart, bl_event_at(b_ray, l));
      const double miss = (mapped.tail<3>() - k_ray.position[i]).norm();
      worst = std::max(worst, miss);
      EXPECT_LT(miss, 1e-5) << "pixel " << pixel[0] << "," << pixel[1] << " lambda " << l << " r " << r;
      ++compared;
    }
    if (ks_min_r < rp) ++ks_inside;
  }
  EXPECT_GT(compared, 500) << "too few points compared";
  EXPECT_GT(ks_inside, 0) << "no Kerr-Schild ray crossed the horizon";
  std::cout << "compared " << compared << " KS points with the mapped BL rays: largest distance " << worst
            << " M; " << ks_inside << " KS rays went inside r_+\n";
}

// The surfaces share the rays' picture: in BL the horizon is the sphere |p| = r_+ and the prograde ISCO ring has
// radius r_isco; in KS both are r = const surfaces of the quadric (the horizon an oblate spheroid with equatorial
// radius sqrt(r_+^2 + a^2)), the ring of radius sqrt(r_isco^2 + a^2).
TEST_F(KerrCharts, SurfacesAreDrawnInTheRaysChart) {
  ASSERT_EQ(runs_["bl"].status, 0) << runs_["bl"].output;
  ASSERT_EQ(runs_["ks"].status, 0) << runs_["ks"].output;
  const double rp = outer_horizon();
  const double isco = grtrace::exact::isco_radius(kSpin, grtrace::exact::Orbit::prograde);
  const auto bl_horizon = points_of(dirs_["bl"] / "horizon.vtp"), ks_horizon = points_of(dirs_["ks"] / "horizon.vtp");
  ASSERT_GT(bl_horizon.size(), 100u);
  ASSERT_EQ(ks_horizon.size(), bl_horizon.size());
  double ks_equator = 0.0;
  for (const auto& p : bl_horizon) EXPECT_NEAR(p.norm(), rp, 1e-9);
  for (const auto& p : ks_horizon) {
    EXPECT_NEAR(ks_chart().radius(grtrace::Vec4(0.0, p[0], p[1], p[2])), rp, 1e-9);
    ks_equator = std::max(ks_equator, std::hypot(p[0], p[1]));
  }
  EXPECT_NEAR(ks_equator, std::sqrt(rp * rp + kSpin * kSpin), 1e-3);
  for (const auto& p : points_of(dirs_["bl"] / "isco.vtp")) EXPECT_NEAR(p.norm(), isco, 1e-9);
  const auto ks_ring = points_of(dirs_["ks"] / "isco.vtp");
  ASSERT_FALSE(ks_ring.empty());
  for (const auto& p : ks_ring) {
    EXPECT_NEAR(std::hypot(p[0], p[1]), std::sqrt(isco * isco + kSpin * kSpin), 1e-9);
    EXPECT_NEAR(p[2], 0.0, 1e-12);
  }
  // The ergosphere touches the horizon at the poles and reaches r = 2M on the equator, in KS too.
  for (const auto& p : points_of(dirs_["ks"] / "ergosphere.vtp")) {
    const double r = ks_chart().radius(grtrace::Vec4(0.0, p[0], p[1], p[2]));
    const double c = r > 0.0 ? p[2] / r : 0.0;
    EXPECT_NEAR(r, 1.0 + std::sqrt(1.0 - kSpin * kSpin * c * c), 1e-9);
  }
}

// --disk-retrograde: the disk turns against the hole, its inner edge and the ISCO ring move to the retrograde ISCO.
TEST(ViewKerr, DiskRetrogradeMovesTheIscoRingAndTheInnerEdge) {
  for (const bool retro : {false, true}) {
    const auto dir = dir_of(retro ? "disk-retro" : "disk-pro");
    std::filesystem::remove_all(dir);
    const ToolRun r = run_headless(std::string("--metric kerr --spin 0.9 --camera-r 30 --width 16 --height 12 "
                                               "--bundle none ") + (retro ? "--disk-retrograde " : "") +
                                   "--export " + dir.string());
    ASSERT_EQ(r.status, 0) << r.output;
    const double isco =
        grtrace::exact::isco_radius(kSpin, retro ? grtrace::exact::Orbit::retrograde : grtrace::exact::Orbit::prograde);
    const auto ring = points_of(dir / "isco.vtp");
    ASSERT_FALSE(ring.empty());
    for (const auto& p : ring) EXPECT_NEAR(p.norm(), isco, 1e-9) << (retro ? "retrograde" : "prograde");
    double inner = 1e300;
    for (const auto& p : points_of(dir / "disk.vtp")) inner = std::min(inner, p.norm());
    EXPECT_NEAR(inner, isco, 1e-6) << (retro ? "retrograde" : "prograde");
  }
}

// ---- a frame rendered with --chart ks ---------------------------------------------------------------------------

#ifdef GRTRACE_RENDER_EXE
TEST(ViewKerr, ReadsAFrameRenderedInKerrSchild) {
  const auto exr = dir_of("ks-frame.exr");
  const ToolRun render = grtrace::tool_tests::run_command(
      std::string(GRTRACE_RENDER_EXE) + " --metric kerr --spin 0.9 --chart ks --camera-r 12 --camera-theta 80 "
      "--fov 60 --width 24 --height 18 --scene checker --out " + exr.string());
  ASSERT_EQ(render.status, 0) << render.output;
  const auto dir = dir_of("ks-frame-export");
  std::filesystem::remove_all(dir);
  const ToolRun r = run_headless("--frame " + exr.string() + " --bundle-size 3x3 --pick 12,9 --export " + dir.string());
  ASSERT_EQ(r.status, 0) << r.output;
  auto rays = read_vtp(dir / "rays.vtp");
  EXPECT_EQ(rays->GetNumberOfCells(), 10);
  // The camera is the frame's, at Kerr-Schild r = 12 M; the surfaces are drawn in KS (the horizon a spheroid).
  vtkDataArray* position = rays->GetFieldData()->GetArray("camera_position");
  ASSERT_NE(position, nullptr);
  const grtrace::Vec4 x(position->GetComponent(0, 0), position->GetComponent(0, 1), position->GetComponent(0, 2),
                        position->GetComponent(0, 3));
  EXPECT_NEAR(ks_chart().radius(x), 12.0, 1e-9);
  for (const auto& p : points_of(dir / "horizon.vtp"))
    EXPECT_NEAR(ks_chart().radius(grtrace::Vec4(0.0, p[0], p[1], p[2])), outer_horizon(), 1e-9);
  // The frame's chart and camera are its own: a different chart or observer is refused.
  for (const char* args : {"--chart bl", "--observer static"}) {
    const ToolRun bad = run_headless("--frame " + exr.string() + " " + args + " --export " + (dir / "never").string());
    EXPECT_EQ(bad.status, 2) << args << "\n" << bad.output;
    EXPECT_NE(bad.output.find(std::string(args).substr(0, std::string(args).find(' '))), std::string::npos) << bad.output;
  }
}
#endif

// A glowing torus (grtrace-render's --scene torus and its options): the export writes its emission on the cube
// (medium.vti, peaked on the equator near the pressure maximum at 10 M), the picked ray lists the light it
// collected and carries it in rays.vtp, and --hide medium leaves the gas out; a torus around a hole it cannot circle is
// refused as by grtrace-render.
TEST(ViewKerr, ATorusIsExportedAsItsGasAndAPickedRayListsItsLight) {
  const std::string scene =
      "--scene torus --metric kerr --spin 0.9 --torus-opacity 0.5 --camera-r 60 "
      "--camera-theta 75 --fov 40 --width 16 --height 16 --bundle none --pick 8,8 ";
  const auto dir = dir_of("torus");
  const ToolRun r = run_headless(scene + "--export " + dir.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const std::size_t at = r.output.find("light collected ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_GT(std::stod(r.output.substr(at + 16)), 0.0) << r.output;
  // The picked ray in rays.vtp carries the light it collects, from none at the camera to all of it at its end.
  const auto rays = read_vtp(dir / "rays.vtp");
  vtkDataArray* light = rays->GetPointData()->GetArray("light");
  ASSERT_NE(light, nullptr);
  EXPECT_EQ(light->GetTuple1(0), 0.0);
  EXPECT_EQ(light->GetTuple1(light->GetNumberOfTuples() - 1), 1.0);
  for (vtkIdType i = 1; i < light->GetNumberOfTuples(); ++i) EXPECT_GE(light->GetTuple1(i), light->GetTuple1(i - 1));
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName((dir / "medium.vti").c_str());
  reader->Update();
  vtkImageData* gas = reader->GetOutput();
  int dims[3];
  gas->GetDimensions(dims);
  EXPECT_EQ(dims[0], 72);
  vtkDataArray* emission = gas->GetPointData()->GetArray("emission");
  ASSERT_NE(emission, nullptr);
  vtkIdType best = 0;
  for (vtkIdType i = 0; i < emission->GetNumberOfTuples(); ++i)
    if (emission->GetTuple1(i) > emission->GetTuple1(best)) best = i;
  double p[3];
  gas->GetPoint(best, p);
  const double spacing = gas->GetSpacing()[0];
  EXPECT_NEAR(std::hypot(p[0], p[1]), 10.0, spacing);
  EXPECT_LT(std::abs(p[2]), spacing);
  const auto hidden = dir_of("torus-hidden");
  ASSERT_EQ(run_headless(scene + "--hide medium --export " + hidden.string()).status, 0);
  EXPECT_FALSE(std::filesystem::exists(hidden / "medium.vti"));
  const ToolRun schwarzschild = run_headless("--scene torus --metric schwarzschild --export " + dir.string());
  EXPECT_EQ(schwarzschild.status, 2) << schwarzschild.output;
  EXPECT_NE(schwarzschild.output.find("flows around a Kerr hole"), std::string::npos) << schwarzschild.output;
}

// ---- drawing (needs a display) ----------------------------------------------------------------------------------

TEST(ViewKerr, DrawsAKerrSceneOffscreen) {
  if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  for (const char* chart : {"bl", "ks"}) {
    const auto png = dir_of(std::string("kerr-") + chart + ".png");
    const ToolRun r = run("--metric kerr --spin 0.9 --camera-r 30 --camera-theta 80 --width 40 --height 30 "
                          "--bundle-size 4x3 --rtol 1e-7 --atol 1e-9 --size 400x200 --chart " + std::string(chart) +
                          " --screenshot " + png.string());
    EXPECT_EQ(r.status, 0) << chart << "\n" << r.output;
    EXPECT_TRUE(std::filesystem::exists(png)) << r.output;
    EXPECT_NE(r.output.find("wrote"), std::string::npos) << r.output;
  }
}

// --plot orbit|norm|step, and --chart orbit still draws the same chart (its older spelling).
TEST(ViewKerr, PlotAndItsOlderSpellingChartDrawTheOrbitChart) {
  if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  for (const char* option : {"--plot", "--chart"}) {
    const auto png = dir_of(std::string("orbit") + (option + 2) + ".png");
    const ToolRun r = run(std::string(option) + " orbit --orbit-revolutions 1 --size 300x300 --screenshot " + png.string());
    EXPECT_EQ(r.status, 0) << option << "\n" << r.output;
    EXPECT_TRUE(std::filesystem::exists(png)) << option << "\n" << r.output;
    EXPECT_NE(r.output.find("r0 = 100 M"), std::string::npos) << r.output;  // the orbit chart's note
  }
}

}  // namespace
