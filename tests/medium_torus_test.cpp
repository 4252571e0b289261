// The Polish doughnut (medium/polish_doughnut.hpp) around a Kerr hole: its structure against closed forms (the
// pressure maximum where its angular momentum is Keplerian, the Keplerian angular velocity of Bardeen, Press &
// Teukolsky 1972 there, the outer edge bounding the gas), its light in the optically thick limit against the surface
// of the same shape shaded by g^3 times the source function, and its thin light converging with the tolerance.
#include "grtrace/medium/polish_doughnut.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/emission_system.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace {

using namespace grtrace;
using Torus = PolishDoughnut<KerrMetric>;

constexpr double kSpin = 0.9;

KerrMetric kerr() { return KerrMetric{1.0, kSpin}; }

Vec4 at(double r, double theta) { return Vec4(0.0, r, theta, 0.0); }

TEST(PolishDoughnut, ItsPressureMaximumIsWhereItsAngularMomentumIsKeplerian) {
  const Torus torus(kerr(), 6.0, 10.0, 3.0);
  // Density along the equator: largest at r_c (golden section on a function known only by evaluation).
  const auto rho = [&](double r) { return torus.density(at(r, std::numbers::pi / 2)); };
  double lo = torus.inner_edge(), hi = torus.outer_radius();
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-10; ++i) {
    const double a = hi - phi * (hi - lo), b = lo + phi * (hi - lo);
    (rho(a) > rho(b) ? hi : lo) = rho(a) > rho(b) ? b : a;
  }
  EXPECT_NEAR(0.5 * (lo + hi), 10.0, 1e-5);  // a maximum's location: sqrt of the rounding
  EXPECT_NEAR(rho(10.0), 1.0, 1e-15);
  // The gas's angular velocity there is the prograde Keplerian one, Omega = 1 / (r^(3/2) + a) (BPT 1972).
  const Vec4 u = torus.fluid_velocity(kerr(), at(10.0, std::numbers::pi / 2));
  EXPECT_NEAR(u[3] / u[0], 1.0 / (std::pow(10.0, 1.5) + kSpin), 1e-14);
  // Its edges: nothing inside r_in, nothing beyond the outer edge, gas just inside both.
  EXPECT_EQ(rho(6.0 * (1.0 - 1e-9)), 0.0);
  EXPECT_GT(rho(6.0 * (1.0 + 1e-6)), 0.0);
  EXPECT_EQ(rho(torus.outer_radius() * (1.0 + 1e-9)), 0.0);
  EXPECT_GT(rho(torus.outer_radius() * (1.0 - 1e-6)), 0.0);
  // The outer radius bounds the gas off the equator too (what outer_radius() promises the tracer).
  for (int i = 1; i < 90; ++i)
    for (int j = 0; j < 40; ++j) {
      const double theta = i * std::numbers::pi / 90.0, r = torus.outer_radius() * (1.0 + 0.05 * j);
      ASSERT_EQ(torus.density(at(r, theta)), 0.0) << r << " " << theta;
    }
}

TEST(PolishDoughnut, TheGasMovesOnCirclesOfOneAngularMomentum) {
  const KerrMetric m = kerr();
  const Torus torus(m, 6.0, 10.0);
  int inside = 0;
  for (const double r : {7.0, 10.0, 14.0, 18.0})
    for (const double theta : {1.2, 1.4, std::numbers::pi / 2, 1.9}) {
      const Vec4 x = at(r, theta), u = torus.fluid_velocity(m, x);
      const Mat4 g = m.metric(x);
      EXPECT_NEAR(u.dot(g * u), 1.0, 1e-13);
      if (torus.density(x) > 0.0) {
        ++inside;
        const Vec4 lowered = g * u;
        EXPECT_NEAR(-lowered[3] / lowered[0], torus.angular_momentum(), 1e-12 * torus.angular_momentum());
      }
    }
  EXPECT_GT(inside, 6);
}

/// The torus's surface as a scene object: the general scene tracer locates where a ray meets it and gives the
/// redshift of the gas there.
struct TorusSurface {
  static constexpr std::string_view kind = "torus";
  const Torus* torus;
  double operator()(const GeodesicState& y) const {
    return std::min(1.0,
                    torus->potential(y.head<4>()) - torus->potential(at(torus->inner_edge(), std::numbers::pi / 2)));
  }
  Vec4 emitter_velocity(const KerrMetric& m, const Vec4& x) const { return torus->fluid_velocity(m, x); }
  Rgb colour(const SurfaceHit&) const { return {1.0f, 1.0f, 1.0f}; }
};

TraceSettings settings(double rtol) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, rtol * 1e-2};
  s.escape_radius = 200.0;
  s.max_steps = 1'000'000;
  return s;
}

Camera camera() {
  CameraSpec spec;
  spec.position = Vec4(0.0, 60.0, 70.0 * std::numbers::pi / 180.0, 0.0);
  spec.spherical_position = true;
  spec.observer = ObserverKind::zamo;
  spec.width = spec.height = 9;
  spec.fov_degrees = 40.0;
  return make_camera(kerr(), spec);
}

TEST(PolishDoughnut, OpticallyThickItShinesAsItsSurfaceShadedByGCubedTimesItsSourceFunction) {
  // j = kappa rho, alpha = kappa rho: source function 1. With kappa large the light comes from a thin layer under
  // the surface, so I -> g^3 at the surface. n = 1 (rho ~ depth): the layer's depth falls as kappa^(-1/2), and so
  // does the difference (measured at the worst pixel: 2.4e-2 at kappa 1e2, 2.5e-4 at 1e6; steps end on the surface,
  // where rho has a kink: without that, the integration's own error there was 1.5e-3 at 1e6).
  const KerrMetric m = kerr();
  const Camera cam = camera();
  const Torus shape(m, 6.0, 10.0, 1.0);
  const auto scene = make_scene(CheckerSky{}, HorizonPaint{}, TorusSurface{&shape});
  const GeneralSceneTracer<KerrMetric, Fehlberg78, IController, decltype(scene)> surface(m, settings(1e-11), {},
                                                                                         AngleCorrection::none, scene);
  int hits = 0;
  double worst_thin = 0.0, worst_thick = 0.0;
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const GeodesicState y0 = cam.pixel_state(col, row);
      const RayOutcome hit = surface.trace(y0);
      if (hit.status != RayStatus::hit) continue;
      ++hits;
      const double shaded = std::pow(hit.redshift, 3);
      const auto light = [&](double kappa) {
        const Torus gas(m, 6.0, 10.0, 1.0, kappa, kappa);
        return trace_emission_seen_by<Fehlberg78, IController>(m, gas, settings(1e-10), y0, cam.tetrad().e[0], 1.0)
            .intensity;
      };
      worst_thin = std::max(worst_thin, std::abs(light(1e2) - shaded) / shaded);
      worst_thick = std::max(worst_thick, std::abs(light(1e6) - shaded) / shaded);
    }
  EXPECT_GT(hits, 10);
  EXPECT_LT(worst_thick, 5e-4) << "kappa 1e2: " << worst_thin;
  EXPECT_LT(worst_thick, 0.03 * worst_thin) << worst_thick;  // kappa^(-1/2): 0.01
}

TEST(PolishDoughnut, ARayAlongItsSurfaceGoesOn) {
  // This pixel's ray (examples/scenes/kerr_torus at 512 x 512) runs along the torus's surface at r = 25 M: the
  // steps' cuts on the boundary found it again at the start of every step and the ray stood still (max_steps).
  const KerrMetric m = kerr();
  const Torus gas(m, 6.0, 10.0, 3.0, 1.0, 0.3);
  CameraSpec spec;
  spec.position = Vec4(0.0, 100.0, 75.0 * std::numbers::pi / 180.0, 0.0);
  spec.spherical_position = true;
  spec.observer = ObserverKind::zamo;
  spec.width = spec.height = 512;
  spec.fov_degrees = 36.0;
  const Camera cam = make_camera(m, spec);
  TraceSettings s = settings(1e-8);
  s.escape_radius = 1000.0;
  s.max_steps = 1000;
  const EmissionResult r =
      trace_emission_seen_by<Fehlberg78, IController>(m, gas, s, cam.pixel_state(381, 151), cam.tetrad().e[0], 1.0);
  EXPECT_EQ(r.trace.status, RayStatus::escaped);
  EXPECT_GT(r.optical_depth, 0.0);  // it went through the gas
}

TEST(PolishDoughnut, ItsThinLightConvergesWithTheTolerance) {
  // Optically thin (kappa = 0, n = 3): the light of rays through the torus at rtol 1e-6 and 1e-9 against 1e-12; the
  // error falls with the tolerance (the intensity is inside the step control).
  const KerrMetric m = kerr();
  const Camera cam = camera();
  const Torus gas(m, 6.0, 10.0, 3.0);
  double coarse = 0.0, fine = 0.0;
  int lit = 0;
  for (int row = 0; row < cam.height(); row += 2)
    for (int col = 0; col < cam.width(); col += 2) {
      const GeodesicState y0 = cam.pixel_state(col, row);
      const auto light = [&](double rtol) {
        return trace_emission_seen_by<Fehlberg78, IController>(m, gas, settings(rtol), y0, cam.tetrad().e[0], 1.0)
            .intensity;
      };
      const double reference = light(1e-12);
      if (!(reference > 0.0)) continue;
      ++lit;
      coarse = std::max(coarse, std::abs(light(1e-6) - reference) / reference);
      fine = std::max(fine, std::abs(light(1e-9) - reference) / reference);
    }
  EXPECT_GT(lit, 5);
  EXPECT_LT(fine, 1e-6);
  EXPECT_LT(fine, coarse / 30.0) << coarse << " -> " << fine;
}

}  // namespace
