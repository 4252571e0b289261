// grtrace::viz for Kerr: the ergosphere surface lies on the static limit r_E(theta) =
// M + sqrt(M^2 - a^2 cos^2 theta) of KerrMetric (where g_tt = 0), and the scene view of a spinning hole has the
// ergosphere layer, the horizon at r_+ and no photon sphere; the medium layer's iso-surfaces lie where the gas
// falls to their levels. Data only (no pixels): runs with or without a display.
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/viz/scene_view.hpp"
#include "grtrace/viz/surfaces.hpp"

#include <gtest/gtest.h>
#include <vtkActor.h>
#include <vtkBoundingBox.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace {

using namespace grtrace;
using namespace grtrace::viz;

TEST(VizKerr, ErgospherePointsLieOnTheStaticLimit) {
  for (double spin : {0.3, 0.9, -0.998}) {
    const double mass = 1.5;
    const KerrMetric m = KerrMetric::checked(mass, spin * mass);
    const auto poly = make_ergosphere(mass, spin * mass, 24, 32);
    ASSERT_EQ(poly->GetNumberOfPoints(), 25 * 33);
    EXPECT_EQ(poly->GetNumberOfPolys(), 24 * 32);
    double worst_radius = 0.0, worst_gtt = 0.0;
    for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
      double p[3];
      poly->GetPoint(i, p);
      const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      const double theta = std::acos(std::clamp(p[2] / r, -1.0, 1.0));
      // Against the metric's own static limit, and against g_tt = 0 there (the definition).
      worst_radius = std::max(worst_radius, std::abs(r - m.ergosphere_radius(theta)));
      worst_gtt = std::max(worst_gtt, std::abs(m.metric(Vec4(0.0, r, theta, 0.3))(0, 0)));
    }
    EXPECT_LT(worst_radius, 1e-12 * mass) << spin;
    EXPECT_LT(worst_gtt, 1e-12) << spin;
    // Oblate: 2M across the equator, r_+ at the poles (the first and last rows of the grid).
    double bounds[6], pole[3];
    poly->GetBounds(bounds);
    EXPECT_NEAR(bounds[1], 2.0 * mass, 1e-12);
    poly->GetPoint(0, pole);
    EXPECT_NEAR(pole[2], exact::outer_horizon(spin * mass, mass), 1e-12);
    poly->GetPoint(poly->GetNumberOfPoints() - 1, pole);
    EXPECT_NEAR(pole[2], -exact::outer_horizon(spin * mass, mass), 1e-12);
  }
  EXPECT_THROW(make_ergosphere(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(make_ergosphere(1.0, std::nan("")), std::invalid_argument);
}

// to_kerr_schild puts a BL surface of constant r where the Kerr-Schild chart has that r (an oblate spheroid), and
// a point at BL (r, theta, phi) where bl_to_ks_position puts it, up to the phi shift that only moves a surface of
// revolution along itself (phi_KS is kept as the azimuth).
TEST(VizKerr, KerrSchildSurfacesLieOnTheirRadius) {
  const double a = 0.9;
  for (const KerrSchildSlicing slicing : {KerrSchildSlicing::ingoing, KerrSchildSlicing::outgoing}) {
    const KerrSchildMetric ks = KerrSchildMetric::checked(1.0, a, slicing);
    for (const double r : {ks.outer_horizon(), 2.32, 6.0}) {
      auto sphere = to_kerr_schild(make_sphere(r, 24), a, slicing);
      vtkPoints* pts = sphere->GetPoints();
      ASSERT_GT(pts->GetNumberOfPoints(), 50);
      double equator = 0.0;
      for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i) {
        double p[3];
        pts->GetPoint(i, p);
        EXPECT_NEAR(ks.radius(Vec4(0.0, p[0], p[1], p[2])), r, 1e-9 * r);
        equator = std::max(equator, std::hypot(p[0], p[1]));
      }
      EXPECT_NEAR(equator, std::sqrt(r * r + a * a), 1e-2 * r);  // the spheroid's equator (a 24-gon's corners)
    }
    // One point: BL (r, theta, phi) against the library's map with the phi shift removed.
    const double r = 5.0, th = 1.1, ph = 0.7;
    auto ring = to_kerr_schild(make_ring(1.0, 8), a, slicing);  // a polydata to move one point with
    ring->GetPoints()->SetPoint(0, r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th));
    to_kerr_schild(ring, a, slicing);
    double p[3];
    ring->GetPoints()->GetPoint(0, p);
    const Vec4 want = bl_to_ks_position(ks, Vec4(0.0, r, th, ph - kerr_schild_detail::phi_shift(ks, r)));
    EXPECT_NEAR(p[0], want[1], 1e-12);
    EXPECT_NEAR(p[1], want[2], 1e-12);
    EXPECT_NEAR(p[2], want[3], 1e-12);
  }
}

TEST(VizKerr, SceneViewOfASpinningHole) {
  SceneLayout layout;
  layout.spin = 0.9;
  layout.isco_radius = exact::isco_radius(0.9, exact::Orbit::prograde);
  const SceneView view(layout);
  EXPECT_TRUE(view.has(Layer::ergosphere));
  EXPECT_TRUE(view.has(Layer::horizon));
  EXPECT_TRUE(view.has(Layer::isco));
  EXPECT_FALSE(view.has(Layer::photon_sphere));  // no single photon sphere in Kerr
  EXPECT_EQ(layer_from_string("ergosphere"), Layer::ergosphere);
  const SceneView schwarzschild(SceneLayout{});
  EXPECT_FALSE(schwarzschild.has(Layer::ergosphere));
  EXPECT_TRUE(schwarzschild.has(Layer::photon_sphere));
  SceneLayout bad;
  bad.spin = 1.0;
  EXPECT_THROW(SceneView{bad}, std::invalid_argument);
}

}  // namespace

namespace {

TEST(VizMedium, TheMediumsIsoSurfacesLieAtTheirLevels) {
  // A Gaussian ball of gas, exp(-r^2 / w^2), sampled on 41^3 points: each of the medium layer's surfaces is the
  // sphere where it falls to its level, r = w sqrt(-ln level), to the trilinear sampling's error.
  const double w = 4.0, half = 10.0;
  MediumField field;
  field.n = 41;
  field.half_width = half;
  const double h = 2.0 * half / (field.n - 1);
  for (int k = 0; k < field.n; ++k)
    for (int j = 0; j < field.n; ++j)
      for (int i = 0; i < field.n; ++i) {
        const double x = -half + i * h, y = -half + j * h, z = -half + k * h;
        field.values.push_back(static_cast<float>(std::exp(-(x * x + y * y + z * z) / (w * w))));
      }
  field.peak = 1.0;
  SceneView view(SceneLayout{});
  EXPECT_FALSE(view.has(Layer::medium));
  view.set_medium(field);
  ASSERT_TRUE(view.has(Layer::medium));
  EXPECT_EQ(layer_from_string("medium"), Layer::medium);
  vtkPolyData* surfaces = view.medium_surfaces();
  ASSERT_NE(surfaces, nullptr);
  vtkDataArray* level = surfaces->GetPointData()->GetArray("level");
  ASSERT_NE(level, nullptr);
  std::array<int, kMediumLevels.size()> points{};
  double worst = 0.0;
  for (vtkIdType i = 0; i < surfaces->GetNumberOfPoints(); ++i) {
    double p[3];
    surfaces->GetPoint(i, p);
    const double l = level->GetTuple1(i);
    const double expected = w * std::sqrt(-std::log(l));
    worst = std::max(worst, std::abs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - expected));
    for (std::size_t n = 0; n < kMediumLevels.size(); ++n) points[n] += std::abs(l - kMediumLevels[n]) < 1e-6;
  }
  EXPECT_LT(worst, 0.1 * h);
  for (const int n : points) EXPECT_GT(n, 100);
  std::printf("medium iso-surfaces: worst radius error %.3g M (spacing %.3g M)\n", worst, h);
  field.peak = 0.0;  // nothing glows: no layer
  view.set_medium(field);
  EXPECT_FALSE(view.has(Layer::medium));
  EXPECT_EQ(view.medium_surfaces(), nullptr);
}

}  // namespace
