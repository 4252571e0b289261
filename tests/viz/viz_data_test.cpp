// grtrace::viz data conversion, without rendering: recorded paths against the tracer and the exact orbit,
// polydata arrays against the recorded values, reference surfaces, camera glyph, the seed orbit.
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/initial_data.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/static_frame.hpp"
#include "grtrace/observer/tetrad.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/viz/bundles.hpp"
#include "grtrace/viz/camera_glyph.hpp"
#include "grtrace/viz/geodesic_data.hpp"
#include "grtrace/viz/orbits.hpp"
#include "grtrace/viz/surfaces.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace {

using namespace grtrace;
using namespace grtrace::viz;

using Tracer = GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController>;

TraceSettings tight_settings(double escape = 60.0) {
  TraceSettings s;
  s.integrator.tolerance = {1e-11, 1e-13};
  s.escape_radius = escape;
  return s;
}

/// Independent record of the accepted steps, as grtrace-geodesic writes them.
struct StepLog {
  std::vector<GeodesicState>* states;
  std::vector<double>* steps;
  template <class Integrator>
  void operator()(const Integrator& integ, double theta_end) const {
    if (states->empty()) states->push_back(integ.previous_state());
    states->push_back(theta_end == 1.0 ? integ.state() : integ.dense(theta_end));
    steps->push_back(integ.last_step());
  }
};

TEST(VizPath, StepEndsAreTheTracersStates) {
  const SchwarzschildMetric metric{1.0};
  const Tracer tracer(metric, tight_settings());
  const GeodesicState y0 = incoming_photon(7.0, 50.0);
  std::vector<GeodesicState> states;
  std::vector<double> steps;
  const TraceResult ref = tracer.trace_observed(y0, StepLog{&states, &steps});

  const int per_step = 6;
  const TracedPath path = trace_path(tracer, y0, per_step, std::nullopt);
  EXPECT_EQ(path.status, ref.status);
  ASSERT_EQ(path.steps.size(), states.size());
  ASSERT_EQ(path.samples.size(), 1 + per_step * (states.size() - 1));
  for (std::size_t i = 0; i < states.size(); ++i) {
    EXPECT_EQ(path.steps[i].state, states[i]) << "step " << i;
    EXPECT_EQ(path.steps[i].h, i == 0 ? 0.0 : steps[i - 1]);
    // Every step's last sample is the accepted state itself, in the embedding of the metric.
    const PathSample& s = path.samples[i * per_step];
    EXPECT_EQ(s.state, states[i]);
    EXPECT_EQ(s.step, static_cast<int>(i));
    EXPECT_LT((s.position - metric.to_cartesian(states[i].head<4>())).norm(), 1e-12);
  }
  // The path ends on the step's dense output at the located crossing; the tracer's final state is that crossing
  // refined on the step map (geodesic_tracer.hpp): they differ by the interpolant's error only.
  EXPECT_LT((path.samples.back().state - ref.final_state).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_NEAR(path.samples.back().lambda, ref.lambda, 1e-9 * std::abs(ref.lambda));
  // lambda grows along the samples, and each sample's h is its step's.
  for (std::size_t i = 1; i < path.samples.size(); ++i) {
    EXPECT_GT(path.samples[i].lambda, path.samples[i - 1].lambda);
    EXPECT_EQ(path.samples[i].h, steps[static_cast<std::size_t>(path.samples[i].step) - 1]);
  }
}

TEST(VizPath, DenseSamplesLieOnTheExactOrbit) {
  // A photon with impact parameter b passes periapsis and escapes; every sample (not only step ends) must sit on
  // the exact orbit phi(u) from the elliptic integral (exact/schwarzschild_exact.hpp).
  const double M = 1.0, b = 7.0, r0 = 50.0;
  const Tracer tracer(SchwarzschildMetric{M}, tight_settings(r0 * 1.001));
  const TracedPath path = trace_path(tracer, incoming_photon(b, r0, M), 10, std::nullopt);
  ASSERT_EQ(path.status, RayStatus::escaped);
  const double u0 = 1.0 / r0, u_peri = 1.0 / exact::periapsis_from_impact(b, M);
  const double phi_peri = exact::phi_from_infinity(b, u_peri, M) - exact::phi_from_infinity(b, u0, M);
  double worst = 0.0;
  int between_step_ends = 0;
  for (const auto& s : path.samples) {
    const double u = 1.0 / s.state[1];
    const bool inbound = s.state[5] < 0.0;
    const double phi_exact = inbound ? exact::phi_from_infinity(b, u, M) - exact::phi_from_infinity(b, u0, M)
                                     : 2.0 * phi_peri + exact::phi_from_infinity(b, u0, M) -
                                           exact::phi_from_infinity(b, u, M);
    // Near periapsis phi(u) is flat in u: compare in the embedding instead (distance to the exact point).
    const Vec3 exact_point = s.state[1] * Vec3(std::cos(phi_exact), std::sin(phi_exact), 0.0);
    worst = std::max(worst, (s.position - exact_point).norm() / s.state[1]);
    between_step_ends += s.step > 0 && s.lambda != path.steps[static_cast<std::size_t>(s.step)].lambda;
  }
  EXPECT_GT(between_step_ends, 100);
  EXPECT_LT(worst, 1e-6);
  // The samples stay in the equatorial plane (z = 0).
  for (const auto& s : path.samples) EXPECT_NEAR(s.position[2], 0.0, 1e-9 * s.state[1]);
}

TEST(VizPath, RedshiftAgainstStaticObservers) {
  // A static camera at r_c sending a ray radially inward: f_cam / f_static(r) = sqrt(1 - 2M/r) / sqrt(1 - 2M/r_c).
  const double M = 1.0, rc = 20.0;
  const SchwarzschildMetric metric{M};
  const Tracer tracer(metric, tight_settings());
  const Vec4 x(0.0, rc, std::numbers::pi / 2.0, 0.3);
  const auto k = complete_time_component(metric, x, Vec4(0.0, -1.0, 0.0, 0.0), 0.0);
  ASSERT_TRUE(k);
  Vec4 kk = *k;
  kk[0] = -kk[0];  // past-directed, as cameras trace
  const Vec4 u_cam(1.0 / std::sqrt(1.0 - 2.0 * M / rc), 0.0, 0.0, 0.0);
  const TracedPath path = trace_path(tracer, make_state(x, kk), 4, u_cam);
  EXPECT_EQ(path.status, RayStatus::captured);
  for (const auto& s : path.samples) {
    const double expected = std::sqrt(1.0 - 2.0 * M / s.state[1]) / std::sqrt(1.0 - 2.0 * M / rc);
    EXPECT_NEAR(s.redshift, expected, 1e-9);
  }
}

TEST(VizPolyData, PointsAndArraysMatchTheSamples) {
  const SchwarzschildMetric metric{1.0};
  const Tracer tracer(metric, tight_settings());
  std::vector<TracedPath> paths;
  paths.push_back(trace_path(tracer, incoming_photon(7.0, 50.0), 5, std::nullopt));
  paths.push_back({});  // empty: no cell
  paths.push_back(trace_path(tracer, incoming_photon(3.0, 50.0), 5, Vec4(1.0, 0.0, 0.0, 0.0)));
  paths[2].color = Rgb8{10, 20, 30};
  ASSERT_EQ(paths[0].status, RayStatus::escaped);
  ASSERT_EQ(paths[2].status, RayStatus::captured);

  const auto poly = paths_to_polydata(paths);
  ASSERT_EQ(poly->GetNumberOfPoints(), static_cast<vtkIdType>(paths[0].samples.size() + paths[2].samples.size()));
  ASSERT_EQ(poly->GetNumberOfLines(), 2);
  vtkPointData* pd = poly->GetPointData();
  for (const char* name : {"lambda", "h", "step", "status", "redshift", "pixel_color"})
    ASSERT_NE(pd->GetArray(name), nullptr) << name;
  vtkDataArray* ray = poly->GetCellData()->GetArray("ray");
  ASSERT_NE(ray, nullptr);
  EXPECT_EQ(ray->GetComponent(0, 0), 0.0);
  EXPECT_EQ(ray->GetComponent(1, 0), 2.0);

  vtkIdType id = 0;
  for (std::size_t p : {std::size_t{0}, std::size_t{2}}) {
    for (const auto& s : paths[p].samples) {
      double xyz[3];
      poly->GetPoint(id, xyz);
      EXPECT_EQ(Vec3(xyz[0], xyz[1], xyz[2]), s.position);
      EXPECT_EQ(pd->GetArray("lambda")->GetComponent(id, 0), s.lambda);
      EXPECT_EQ(pd->GetArray("h")->GetComponent(id, 0), s.h);
      EXPECT_EQ(pd->GetArray("step")->GetComponent(id, 0), s.step);
      EXPECT_EQ(pd->GetArray("status")->GetComponent(id, 0), static_cast<double>(paths[p].status));
      const double z = pd->GetArray("redshift")->GetComponent(id, 0);
      if (p == 0) EXPECT_TRUE(std::isnan(z));
      else EXPECT_EQ(z, s.redshift);
      const double grey = p == 0 ? 128.0 : 10.0;
      EXPECT_EQ(pd->GetArray("pixel_color")->GetComponent(id, 0), grey);
      ++id;
    }
  }
  // The polyline of path 2 visits its points in order.
  vtkNew<vtkIdList> ids;
  poly->GetCellPoints(1, ids);
  ASSERT_EQ(ids->GetNumberOfIds(), static_cast<vtkIdType>(paths[2].samples.size()));
  EXPECT_EQ(ids->GetId(0), static_cast<vtkIdType>(paths[0].samples.size()));

  // Without redshift or colours the optional arrays are absent.
  const std::vector<TracedPath> plain(paths.begin(), paths.begin() + 1);
  const auto poly2 = paths_to_polydata(plain);
  EXPECT_EQ(poly2->GetPointData()->GetArray("redshift"), nullptr);
  EXPECT_EQ(poly2->GetPointData()->GetArray("pixel_color"), nullptr);
}

TEST(VizPolyData, ScalarFieldNames) {
  for (const char* n : {"none", "pixel", "redshift", "h", "lambda", "status"}) {
    const auto f = scalar_field_from_string(n);
    ASSERT_TRUE(f) << n;
    EXPECT_EQ(to_string(*f), n);
  }
  EXPECT_FALSE(scalar_field_from_string("colour"));
}

TEST(VizSurfaces, Geometry) {
  auto sphere = make_sphere(2.0);
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); i += 7) {
    double p[3];
    sphere->GetPoint(i, p);
    EXPECT_NEAR(Vec3(p[0], p[1], p[2]).norm(), 2.0, 1e-9);
  }
  auto ring = make_ring(6.0, 64);
  EXPECT_EQ(ring->GetNumberOfLines(), 1);
  for (vtkIdType i = 0; i < ring->GetNumberOfPoints(); ++i) {
    double p[3];
    ring->GetPoint(i, p);
    EXPECT_NEAR(std::hypot(p[0], p[1]), 6.0, 1e-12);
    EXPECT_EQ(p[2], 0.0);
  }
  auto disk = make_annulus(6.0, 20.0);
  double b[6];
  disk->GetBounds(b);
  EXPECT_NEAR(b[1], 20.0, 1e-9);
  EXPECT_NEAR(b[5], 0.0, 1e-12);
  for (vtkIdType i = 0; i < disk->GetNumberOfPoints(); ++i) {
    double p[3];
    disk->GetPoint(i, p);
    EXPECT_GE(std::hypot(p[0], p[1]), 6.0 - 1e-9);
  }
  EXPECT_THROW(make_annulus(10.0, 5.0), std::invalid_argument);
}

TEST(VizSurfaces, CheckerboardParityFollowsThetaPhi) {
  const int nt = 4, np = 8;
  const Rgb8 a{255, 0, 0}, b{0, 0, 255};
  auto s = make_checkered_sphere(2.0, nt, np, a, b, 3);
  auto* colors = vtkUnsignedCharArray::SafeDownCast(s->GetCellData()->GetScalars());
  ASSERT_NE(colors, nullptr);
  ASSERT_EQ(colors->GetNumberOfTuples(), s->GetNumberOfCells());
  for (vtkIdType c = 0; c < s->GetNumberOfCells(); ++c) {
    vtkNew<vtkIdList> ids;
    s->GetCellPoints(c, ids);
    Vec3 centre = Vec3::Zero();
    for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i) {
      double p[3];
      s->GetPoint(ids->GetId(i), p);
      centre += Vec3(p[0], p[1], p[2]);
    }
    const double theta = std::acos(centre.normalized()[2]);
    double phi = std::atan2(centre[1], centre[0]);
    if (phi < 0) phi += 2.0 * std::numbers::pi;
    const int i = static_cast<int>(theta / (std::numbers::pi / nt)), j = static_cast<int>(phi / (2.0 * std::numbers::pi / np));
    const Rgb8 want = (i + j) % 2 == 0 ? a : b;
    EXPECT_EQ(colors->GetValue(3 * c), want[0]) << "cell " << c;
    EXPECT_EQ(colors->GetValue(3 * c + 2), want[2]) << "cell " << c;
  }
}

TEST(VizCamera, StaticTetradPushedIntoTheEmbedding) {
  // Static camera at (r, theta = pi/2, phi = 0) looking at the hole: e_1 = -sqrt(f) d_r, e_2 = -(1/r) d_theta (up = +z),
  // e_3 = right-handed partner. The embedded forward is -x, up +z.
  const double M = 1.0, r = 30.0, f = 1.0 - 2.0 * M / r;
  const SchwarzschildMetric metric{M};
  const Vec4 x(0.0, r, std::numbers::pi / 2.0, 0.0);
  const std::array<Vec4, 4> e = {Vec4(1.0 / std::sqrt(f), 0, 0, 0), Vec4(0, -std::sqrt(f), 0, 0),
                                 Vec4(0, 0, -1.0 / r, 0), Vec4(0, 0, 0, -1.0 / r)};
  const CameraGlyph g = make_camera_glyph(metric, x, e, 90.0, 200, 100);
  EXPECT_LT((g.position - Vec3(r, 0, 0)).norm(), 1e-9);
  EXPECT_LT((g.forward - Vec3(-1, 0, 0)).norm(), 1e-6);
  EXPECT_LT((g.up - Vec3(0, 0, 1)).norm(), 1e-6);
  EXPECT_LT((g.right - Vec3(0, -1, 0)).norm(), 1e-6);
  EXPECT_LT(g.velocity.norm(), 1e-9);
  // The corner rays open at the field of view: horizontal half-angle 45 degrees (in the local frame, which
  // the embedding distorts only by the radial factor sqrt(f)).
  for (const Vec3& c : g.corners) EXPECT_NEAR(c.norm(), 1.0, 1e-12);
  EXPECT_LT(g.corners[0][2], 0.0);  // bottom-left: below and to the left (+y)
  EXPECT_GT(g.corners[0][1], 0.0);
  EXPECT_GT(g.corners[2][2], 0.0);  // top-right
  EXPECT_LT(g.corners[2][1], 0.0);
  auto frustum = make_camera_frustum(g, 5.0);
  EXPECT_EQ(frustum->GetNumberOfLines(), 5);
  auto axes = make_camera_axes(g, 3.0);
  EXPECT_EQ(axes->GetNumberOfLines(), 3);  // a static camera has no velocity axis
}

Camera test_camera(double r, int W, int H) {
  const SchwarzschildMetric metric{1.0};
  const Vec4 x(0.0, r, 1.3, 0.2);
  const StaticFrame frame(metric.metric(x));
  const Tetrad t = make_tetrad(metric.metric(x), frame.velocity(Vec3::Zero()), frame.spatial(Vec3(-1, 0, 0)),
                               frame.spatial(Vec3(0, -1, 0)));
  return Camera(x, t, W, H, 60.0);
}

TEST(VizBundle, PixelGridSpreadsOverTheFrame) {
  const auto g = pixel_grid(100, 50, 5, 3);
  ASSERT_EQ(g.size(), 15u);
  EXPECT_EQ(g.front(), (std::array<int, 2>{0, 0}));
  EXPECT_EQ(g[2], (std::array<int, 2>{50, 0}));
  EXPECT_EQ(g.back(), (std::array<int, 2>{99, 49}));
  EXPECT_EQ(pixel_grid(100, 50, 1, 1).front(), (std::array<int, 2>{49, 24}));
  for (const auto& p : pixel_row(100, 50, 4)) EXPECT_EQ(p[1], 24);
  for (const auto& p : pixel_column(100, 50, 4)) EXPECT_EQ(p[0], 49);
}

TEST(VizBundle, APathsMemoryIsBoundedByTheLimit) {
  // rays x steps x samples is unbounded by the options alone: each path, and the bundle, is held to
  // GRTRACE_MEMORY_LIMIT as it grows, with a message that says what to lower.
  const Camera cam = test_camera(15.0, 40, 30);
  const SchwarzschildMetric metric{1.0};
  TraceSettings s;
  s.integrator.tolerance = {1e-10, 1e-12};
  s.escape_radius = 80.0;
  const Tracer tracer(metric, s);
  const auto pixels = pixel_grid(40, 30, 6, 5);
  const auto state = [&](int x, int y) { return cam.pixel_state(x, y); };
  const auto paths = trace_pixels(tracer, state, pixels, 4, std::nullopt, nullptr);
  double held = 0.0;
  for (const TracedPath& p : paths) held += path_bytes(p.samples.capacity(), p.steps.capacity());
  ::setenv("GRTRACE_MEMORY_LIMIT", std::to_string(static_cast<long>(held / 2.0)).c_str(), 1);
  try {
    (void)trace_pixels(tracer, state, pixels, 4, std::nullopt, nullptr);
    ADD_FAILURE() << "the bundle went past the limit";
  } catch (const MemoryLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("rays at 4 samples a step (fewer rays or fewer samples a step)"),
              std::string::npos) << e.what();
  }
  ::setenv("GRTRACE_MEMORY_LIMIT", "20K", 1);  // one path of 1000 samples a step: its own arrays
  try {
    (void)trace_path(tracer, cam.pixel_state(20, 15), 1000, std::nullopt);
    ADD_FAILURE() << "the path went past the limit";
  } catch (const MemoryLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("samples a step (fewer samples a step or a shorter ray)"), std::string::npos)
        << e.what();
  }
  ::unsetenv("GRTRACE_MEMORY_LIMIT");
  EXPECT_EQ(trace_pixels(tracer, state, pixels, 4, std::nullopt, nullptr).size(), pixels.size());
}

TEST(VizBundle, CameraRaysCarryTheirPixelAndTheTracersRedshift) {
  // Rays through a camera's pixels: each path starts at the pixel's state, keeps its frame colour, and its
  // redshift at the end equals the scene tracer's f_obs / f_src for the static emitters (sky, horizon).
  const int W = 40, H = 30;
  const Camera cam = test_camera(15.0, W, H);
  const SchwarzschildMetric metric{1.0};
  TraceSettings s;
  s.integrator.tolerance = {1e-10, 1e-12};
  s.escape_radius = 80.0;
  const Tracer tracer(metric, s);
  const auto scene =
      make_general_tracer<DormandPrince54, PIController>(metric, s, AngleCorrection::none, background_scene({}));
  Rgb8Image frame(W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      frame.set(x, y, {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), 7});
  const auto pixels = pixel_grid(W, H, 5, 4);
  const auto paths = trace_pixels(tracer, [&](int x, int y) { return cam.pixel_state(x, y); }, pixels, 4,
                                  cam.tetrad().e[0], &frame);
  ASSERT_EQ(paths.size(), pixels.size());
  int captured = 0, escaped = 0;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const TracedPath& p = paths[i];
    const auto [x, y] = pixels[i];
    EXPECT_EQ(p.pixel_x, x);
    EXPECT_EQ(p.pixel_y, y);
    ASSERT_TRUE(p.color);
    EXPECT_EQ(*p.color, (Rgb8{static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y), 7}));
    EXPECT_EQ(p.samples.front().state, cam.pixel_state(x, y));
    EXPECT_NEAR(p.samples.front().redshift, 1.0, 1e-12);  // the camera is static: f_obs = f_static there
    const RayOutcome o = scene.trace(cam.pixel_state(x, y));
    EXPECT_EQ(p.status, o.status);
    EXPECT_NEAR(p.samples.back().redshift, o.redshift, 1e-9 * o.redshift) << "pixel " << x << "," << y;
    captured += p.status == RayStatus::captured;
    escaped += p.status == RayStatus::escaped;
  }
  EXPECT_GT(captured, 0);
  EXPECT_GT(escaped, 0);
}

TEST(VizBundle, ParallelBeamIsParallel) {
  const auto beam = parallel_fan(1.0, 5, 10.0, 60.0);
  ASSERT_EQ(beam.size(), 5u);
  const MinkowskiSpherical flat;
  for (std::size_t i = 0; i < beam.size(); ++i) {
    const Vec3 p = flat.to_cartesian(beam[i].head<4>());
    EXPECT_NEAR(p[1], -10.0 + 5.0 * static_cast<double>(i), 1e-9);  // impact parameter = y offset
    // Direction: the spatial velocity pushed into the embedding points along -x.
    const auto J = embedding_jacobian(flat, Vec4(beam[i].head<4>()));
    const Vec3 v = (J * Vec4(beam[i].tail<4>())).normalized();
    EXPECT_NEAR(v[0], -1.0, 2e-2);  // the start radius is finite: sqrt(1 - 2M/r) bends the radial part a little
  }
}

TEST(VizOrbit, SeedOrbitPrecesses) {
  const OrbitSpec spec = seed_orbit();
  const GeodesicState y0 = orbit_initial_state(spec);
  const SchwarzschildMetric metric{spec.mass};
  EXPECT_NEAR(inner_product(metric, Vec4(y0.head<4>()), Vec4(y0.tail<4>()), Vec4(y0.tail<4>())), 1.0, 1e-14);
  EXPECT_EQ(y0[7], 0.00075);

  TraceSettings s;
  s.integrator.tolerance = {1e-9, 1e-11};
  s.escape_radius = 1000.0;
  OrbitSpec two = spec;
  two.revolutions = 2.0;
  const TracedPath path = trace_orbit(Tracer(metric, s), two, 4);
  ASSERT_EQ(path.status, RayStatus::hit);
  EXPECT_NEAR(path.samples.back().state[3], 4.0 * std::numbers::pi, 1e-9);
  // Periapsis from the conserved E and L: the turning points solve (E^2 - f(r)(1 + L^2/r^2)) = 0.
  const double E = metric.energy(y0), L = metric.angular_momentum(y0);
  double r_min = 1e9;
  for (const auto& smp : path.samples) r_min = std::min(r_min, smp.state[1]);
  const auto V = [&](double r) { return (1.0 - 2.0 / r) * (1.0 + L * L / (r * r)) - E * E; };
  double lo = 10.0, hi = 99.0;  // V(lo) > 0 > V(hi) bracket the periapsis
  for (int i = 0; i < 200; ++i) ((V(0.5 * (lo + hi)) > 0.0) ? lo : hi) = 0.5 * (lo + hi);
  EXPECT_NEAR(r_min, lo, 1e-4);
  EXPECT_GT(r_min, 30.0);
  EXPECT_LT(r_min, 45.0);
  for (const auto& st : path.steps) EXPECT_NEAR(st.norm, 1.0, 1e-7);
}

TEST(VizOrbit, RefusesBadInput) {
  OrbitSpec s;
  s.r0 = 1.5;
  EXPECT_THROW(orbit_initial_state(s), std::invalid_argument);
  s = {};
  s.revolutions = 0.0;
  EXPECT_THROW(orbit_initial_state(s), std::invalid_argument);
  s = {};
  s.mass = -1.0;
  EXPECT_THROW(orbit_initial_state(s), std::invalid_argument);
}

}  // namespace
