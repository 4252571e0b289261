// Mirror-symmetric frames (render/mirror_symmetry.hpp): render_frame traces half or a quarter of the pixels of a
// frame whose metric, scene and camera are unchanged by a reflection, and reflects the outcomes into the rest.
//  (a) the reflected frame equals the frame traced pixel by pixel (RenderOptions::mirror_symmetry = false): the
//      same status and object in every pixel; for escaped rays and object hits the direction (of the sky, or of
//      the hit point) within 1e-8 rad and the redshift within one rounding of its float channel (1e-5 for the
//      general tracer's sky, read on its dense output, see the test) (the mirrored
//      pixel's direction differs from the exact mirror image by a rounding of the pixel coordinate, and the
//      adaptive integrator's steps by as much); for the general, planar and reduced Kerr tracers, even and odd
//      frame sizes. Captured rays are compared by status only (see compare_frames);
//  (b) each reflection is used exactly where it holds: both for a Schwarzschild sky from the equator, the equator
//      only for Kerr and for the (orbiting) disk, none off the equator, neither for a camera tilted or rolled,
//      none for a moving camera with a velocity across the plane, none in a Cartesian chart;
//  (c) the reflection of an outcome: angles into their ranges, the end state reflected.
#include "grtrace/metric/examples/ellis_wormhole.hpp"
#include "grtrace/metric/examples/schwarzschild_de_sitter.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/mirror_symmetry.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/auto_tracer.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include "../common/trace_settings.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace mirror_symmetry_test {

using namespace grtrace;

namespace {

constexpr double kPi = std::numbers::pi;

TraceSettings settings(double rtol) { return test_settings::settings_at(rtol, 400.0); }

CameraSpec camera_spec(double r, double theta_deg, int width, int height, double fov = 60.0) {
  CameraSpec cs;
  cs.position = Vec4(0.0, r, theta_deg * kPi / 180.0, 0.7);
  cs.spherical_position = true;
  cs.width = width;
  cs.height = height;
  cs.fov_degrees = fov;
  return cs;
}

struct Comparison {
  int status_or_object_differs = 0;
  int captured = 0;
  double sky = 0.0, radius = 0.0, redshift = 0.0;
  long traced = 0, rays = 0;
  std::string mirrors;
};

/// The frame with its mirrors against the same frame traced pixel by pixel.
template <class Tracer>
Comparison compare_frames(const Camera& camera, const Tracer& tracer) {
  std::vector<SkyDirection> mirrored_dirs, full_dirs;
  RenderOptions with, without;
  with.progress = without.progress = ProgressMode::never;
  without.mirror_symmetry = false;
  const Frame mirrored = render_frame(camera, tracer, with, &mirrored_dirs);
  const Frame full = render_frame(camera, tracer, without, &full_dirs);
  Comparison c;
  c.traced = mirrored.stats.traced_rays;
  c.rays = mirrored.stats.rays;
  c.mirrors = mirrored.image.metadata.at("mirrors");
  EXPECT_EQ(full.stats.traced_rays, full.stats.rays);
  EXPECT_EQ(full.image.metadata.at("mirrors"), "none");
  EXPECT_EQ(mirrored.stats.status_counts, full.stats.status_counts);
  const auto& sm = mirrored.image.channel("status");
  const auto& sf = full.image.channel("status");
  const auto& om = mirrored.image.channel("object");
  const auto& of = full.image.channel("object");
  const auto& zm = mirrored.image.channel("redshift");
  const auto& zf = full.image.channel("redshift");
  for (std::size_t i = 0; i < mirrored.image.pixel_count(); ++i) {
    if (sm[i] != sf[i] || om[i] != of[i]) {
      ++c.status_or_object_differs;
      continue;
    }
    // Where a captured ray meets the horizon guard is not compared: in Boyer-Lindquist phi grows like
    // log(r - r_+) there, so that point moves with any perturbation of the step sequence (a tolerance changed in
    // the last digit moves it as much); escaped rays and object hits are well conditioned.
    if (sf[i] == static_cast<float>(RayStatus::captured)) {
      ++c.captured;
      continue;
    }
    if (std::isfinite(full_dirs[i].theta)) c.sky = std::max(c.sky, angular_distance(mirrored_dirs[i], full_dirs[i]));
    if (std::isfinite(zf[i]) && zf[i] != 0.0f)
      c.redshift = std::max(c.redshift, static_cast<double>(std::abs(zm[i] - zf[i]) / std::abs(zf[i])));
  }
  return c;
}

// ---- (a) the reflected frame is the traced frame -------------------------------------------------------------

TEST(MirrorSymmetry, SchwarzschildSkyFromTheEquatorIsTracedOnAQuarter) {
  const SchwarzschildMetric metric{1.0};
  const auto scene = background_scene(StandardSceneSpec{});
  for (const auto& [w, h] : {std::pair{48, 36}, std::pair{49, 37}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    const Camera camera = make_camera(metric, camera_spec(30.0, 90.0, w, h));
    const auto general = make_general_tracer<Fehlberg78, IController>(metric, settings(1e-10), AngleCorrection::exact, scene);
    const Comparison g = compare_frames(camera, general);
    EXPECT_EQ(g.mirrors, "equator,meridian");
    EXPECT_EQ(g.traced, static_cast<long>((w + 1) / 2) * ((h + 1) / 2));
    EXPECT_EQ(g.rays, static_cast<long>(w) * h);
    EXPECT_EQ(g.status_or_object_differs, 0);
    EXPECT_LE(g.sky, 1e-8);
    // The general tracer reads an escaped ray's redshift where its dense output puts the sky sphere (the crossing is
    // not refined: TraceSettings::refine_escape), which wanders by ~1e-6 relative from pixel to pixel as the steps
    // fall; the planar table's sky is exact.
    EXPECT_LE(g.redshift, 1e-5);
    std::printf("general %dx%d: traced %ld of %ld, worst sky %.2e rad, redshift %.2e\n", w, h, g.traced, g.rays, g.sky,
                g.redshift);

    const PlanarSceneTracer<SchwarzschildMetric, Fehlberg78, IController, BackgroundScene> planar(
        metric, settings(1e-10), camera, AngleCorrection::exact, scene, 512);
    const Comparison p = compare_frames(camera, planar);
    EXPECT_EQ(p.mirrors, "equator,meridian");
    EXPECT_EQ(p.status_or_object_differs, 0);
    EXPECT_LE(p.sky, 1e-8);
    EXPECT_LE(p.redshift, 1.2e-7);
    std::printf("planar %dx%d: traced %ld of %ld, worst sky %.2e rad, redshift %.2e\n", w, h, p.traced, p.rays, p.sky,
                p.redshift);
  }
}

TEST(MirrorSymmetry, KerrDiskFromTheEquatorIsTracedOnHalfTheRows) {
  const KerrMetric metric{1.0, 0.9};
  StandardSceneSpec spec;
  spec.name = "disk";
  spec.disk.r_in = 2.32;  // just outside the prograde ISCO (2.3209 M)
  spec.disk.r_out = 20.0;
  const DiskScene scene = disk_scene(spec);
  CameraSpec cs = camera_spec(25.0, 90.0, 40, 31, 50.0);
  cs.observer = ObserverKind::zamo;
  cs.look = Vec3(-1.0, 0.0, 0.05);  // off the hole sideways: still symmetric under theta -> pi - theta
  const Camera camera = make_camera(metric, cs);
  const auto mino = make_kerr_mino_tracer<Fehlberg78, IController>(metric, settings(1e-10), AngleCorrection::flat, scene);
  const Comparison c = compare_frames(camera, mino);
  EXPECT_EQ(c.mirrors, "equator");
  EXPECT_EQ(c.traced, 40L * 16);
  EXPECT_EQ(c.status_or_object_differs, 0);
  EXPECT_LE(c.sky, 1e-8);
  EXPECT_LE(c.redshift, 1.2e-7);
  std::printf("kerr-mino 40x31: traced %ld of %ld, worst sky %.2e rad, redshift %.2e\n", c.traced, c.rays, c.sky,
              c.redshift);

  // The disk's own colour and radius: the hit pixels agree in R, G, B to float rounding.
  RenderOptions with, without;
  with.progress = without.progress = ProgressMode::never;
  without.mirror_symmetry = false;
  const Frame a = render_frame(camera, mino, with), b = render_frame(camera, mino, without);
  const auto& obj = b.image.channel("object");
  int disk_pixels = 0;
  for (std::size_t i = 0; i < b.image.pixel_count(); ++i) {
    if (obj[i] != static_cast<float>(kFirstSceneObject)) continue;
    ++disk_pixels;
    for (const char* ch : {"R", "G", "B"})
      EXPECT_NEAR(a.image.channel(ch)[i], b.image.channel(ch)[i], 1e-5f * std::max(1.0f, b.image.channel(ch)[i]));
  }
  EXPECT_GT(disk_pixels, 100);
}

// ---- (b) each reflection where it holds, and only there ------------------------------------------------------

/// A scene tracer that does not name its metric and scene types.
struct OpaqueTracer {
  static constexpr const char* name = "opaque";
  BackgroundScene s = background_scene(StandardSceneSpec{});
  RayOutcome trace(const GeodesicState&) const { return {}; }
  const BackgroundScene& scene() const { return s; }
};

template <class Metric, class SceneT>
std::string mirrors_of(const Metric& metric, const CameraSpec& cs) {
  return frame_mirrors<Metric, SceneT>(metric, make_camera(metric, cs)).names();
}

TEST(MirrorSymmetry, EachReflectionIsUsedOnlyWhereMetricSceneAndCameraHaveIt) {
  const SchwarzschildMetric s{1.0};
  const KerrMetric k{1.0, 0.9};
  const CameraSpec equator = camera_spec(30.0, 90.0, 32, 32);
  EXPECT_EQ((mirrors_of<SchwarzschildMetric, BackgroundScene>(s, equator)), "equator,meridian");
  EXPECT_EQ((mirrors_of<SchwarzschildMetric, DiskScene>(s, equator)), "equator");  // the gas orbits in phi
  EXPECT_EQ((mirrors_of<KerrMetric, BackgroundScene>(k, equator)), "equator");     // the hole rotates
  CameraSpec zamo = equator;
  zamo.observer = ObserverKind::zamo;
  EXPECT_EQ((mirrors_of<KerrMetric, DiskScene>(k, zamo)), "equator");

  EXPECT_EQ((mirrors_of<SchwarzschildMetric, BackgroundScene>(s, camera_spec(30.0, 80.0, 32, 32))), "meridian");
  EXPECT_EQ((mirrors_of<KerrMetric, BackgroundScene>(k, camera_spec(30.0, 90.0 - 1e-9, 32, 32))), "none");

  CameraSpec tilted = equator;  // looking a little up: rows no longer mirror; columns still do
  tilted.look = Vec3(-1.0, -0.1, 0.0);
  EXPECT_EQ((mirrors_of<SchwarzschildMetric, BackgroundScene>(s, tilted)), "meridian");
  CameraSpec sideways = equator;  // looking a little right: columns no longer mirror; rows still do
  sideways.look = Vec3(-1.0, 0.0, 0.1);
  EXPECT_EQ((mirrors_of<SchwarzschildMetric, BackgroundScene>(s, sideways)), "equator");
  CameraSpec rolled = equator;
  rolled.up = Vec3(0.0, -1.0, 0.05);
  EXPECT_EQ((mirrors_of<SchwarzschildMetric, BackgroundScene>(s, rolled)), "none");

  CameraSpec moving = equator;  // along r: both still hold; across the plane: the rows do not
  moving.velocity = Vec3(-0.4, 0.0, 0.0);
  EXPECT_EQ((mirrors_of<SchwarzschildMetric, BackgroundScene>(s, moving)), "equator,meridian");
  moving.velocity = Vec3(-0.4, 0.2, 0.0);
  EXPECT_EQ((mirrors_of<SchwarzschildMetric, BackgroundScene>(s, moving)), "meridian");
  moving.velocity = Vec3(-0.4, 0.0, 0.2);
  EXPECT_EQ((mirrors_of<SchwarzschildMetric, BackgroundScene>(s, moving)), "equator");

  // The example metrics of metric/examples declare both (spherically symmetric, written as AutoMetric components).
  const AutoEllisWormhole ellis{EllisWormhole{1.0}};
  EXPECT_EQ((mirrors_of<AutoEllisWormhole, BackgroundScene>(ellis, equator)), "equator,meridian");
  const AutoSchwarzschildDeSitter sds{SchwarzschildDeSitter{1.0, 1e-4}};
  EXPECT_EQ((mirrors_of<AutoSchwarzschildDeSitter, BackgroundScene>(sds, equator)), "equator,meridian");

  const KerrSchildMetric ks = kerr_schild_for_camera_rays(1.0, 0.9);  // a Cartesian chart: no theta to reflect
  EXPECT_EQ((mirrors_of<KerrSchildMetric, BackgroundScene>(ks, equator)), "none");

  // A tracer that does not name its metric is never mirrored (render_frame cannot check it).
  EXPECT_FALSE(frame_mirrors_of(OpaqueTracer{}, make_camera(s, equator), RenderOptions{}).any());
}

// ---- (c) the reflection of one outcome -----------------------------------------------------------------------

TEST(MirrorSymmetry, ReflectedOutcomesKeepTheirAnglesInRange) {
  RayOutcome o;
  o.status = RayStatus::escaped;
  o.where = {0.3, 3.0};
  o.state << 1.0, 50.0, 0.3, 3.0, -1.0, 0.2, 0.01, -0.02;
  const RayOutcome e = reflected_in_equator(o);
  EXPECT_DOUBLE_EQ(e.where.theta, kPi - 0.3);
  EXPECT_EQ(e.where.phi, 3.0);
  EXPECT_DOUBLE_EQ(e.state[2], kPi - 0.3);
  EXPECT_EQ(e.state[6], -0.01);
  EXPECT_EQ(e.state[7], -0.02);
  // phi -> 2 phi_c - phi, back into (-pi, pi]: 2 * 0.7 - 3.0 = -1.6; 2 * 2.0 - (-3.0) = 7 -> 7 - 2 pi.
  EXPECT_NEAR(reflected_in_meridian(o, 0.7).where.phi, -1.6, 1e-15);
  o.where.phi = -3.0;
  EXPECT_NEAR(reflected_in_meridian(o, 2.0).where.phi, 7.0 - 2.0 * kPi, 1e-15);
  o.where.phi = 0.0;
  EXPECT_EQ(reflected_in_meridian(o, -kPi / 2).where.phi, kPi);  // -pi is reported as pi
  // A camera phi far outside (-pi, pi] (one turn is not enough): reduced exactly, into range.
  o.where.phi = 2.5;
  for (const double phi_c : {20.0, -20.0, 7.5 * kPi}) {
    const double phi = reflected_in_meridian(o, phi_c).where.phi;
    EXPECT_GT(phi, -kPi) << phi_c;
    EXPECT_LE(phi, kPi) << phi_c;
    EXPECT_NEAR(std::remainder(phi - (2.0 * phi_c - 2.5), 2.0 * kPi), 0.0, 1e-14) << phi_c;
  }
  o.where.phi = 0.0;
  const RayOutcome m = reflected_in_meridian(o, 0.7);
  EXPECT_EQ(m.state[3], 2 * 0.7 - 3.0);
  EXPECT_EQ(m.state[7], 0.02);
  EXPECT_EQ(m.state[6], 0.01);
  EXPECT_EQ(m.status, o.status);
}

}  // namespace

}  // namespace mirror_symmetry_test
