// The GPU path's host side, on any machine: what a GPU thread runs for a pixel (trace_quietly, core/host_device.hpp)
// is the CPU's trace bit for bit, and a frame assembled from outcomes traced elsewhere (render_frame_traced_by,
// render/frame.hpp: traced region, note_escaped, shading, mirrors) is render_frame's frame bit for bit, header
// included (the flat continuation's error estimate comes from the noted escapes). The same functions compiled by
// nvcc for the device are compared with these on a GPU in tests/gpu/gpu_frame_test.cu.
#include "../common/quiet_trace.hpp"

#include "grtrace/core/elliptic.hpp"
#include "grtrace/exact/schwarzschild_exact.hpp"
#include "grtrace/grtrace.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace gpu_host_side_test {

namespace {

using namespace grtrace;

template <class M>
Camera camera_at(const M& metric, double r, double theta_degrees, int width, int height) {
  CameraSpec cs;
  cs.position = Vec4(0.0, r, theta_degrees * std::numbers::pi / 180.0, 0.0);
  cs.spherical_position = true;
  cs.width = width;
  cs.height = height;
  cs.fov_degrees = 50.0;
  return make_camera(metric, cs);
}

/// The frame from outcomes traced "elsewhere" by trace_quietly, pixel by pixel, against render_frame's.
template <class Tracer>
void expect_frame_from_quiet_outcomes(const Camera& camera, const Tracer& tracer, int expected_traced_rows) {
  int rows = 0;
  const Frame elsewhere = render_frame_traced_by(camera, tracer, [&](int width, int height) {
    rows = height;
    return testing_support::trace_quietly_here(camera, tracer, width, height);
  });
  const Frame here = render_frame(camera, tracer);
  EXPECT_EQ(rows, expected_traced_rows);
  for (const char* c : Image::kStandardChannels) {
    const auto& x = elsewhere.image.channel(c);
    const auto& y = here.image.channel(c);
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "channel " << c;
  }
  // The header is render_frame's, but for the two clock readings.
  auto header = [](const Frame& f) {
    auto m = f.image.metadata;
    for (const char* timing : {"render_seconds", "rays_per_second"}) EXPECT_EQ(m.erase(timing), 1u) << timing;
    return m;
  };
  EXPECT_EQ(header(elsewhere), header(here));
  EXPECT_EQ(elsewhere.stats.traced_rays, here.stats.traced_rays);
}

TEST(GpuFrameHostSide, QuietTraceIsTheTraceAndOutcomesTracedElsewhereMakeTheSameFrame) {
  TraceSettings settings;
  settings.escape_radius = 400.0;
  StandardSceneSpec disk;
  disk.name = "disk";
  // Schwarzschild, camera on the equator: mirror symmetric, only the top half (11 of 21 rows) is traced.
  const SchwarzschildMetric schwarzschild{1.0};
  expect_frame_from_quiet_outcomes(
      camera_at(schwarzschild, 30.0, 90.0, 17, 21),
      make_general_tracer<Fehlberg78, IController>(schwarzschild, settings, AngleCorrection::exact, disk_scene(disk)),
      11);
  // The flat continuation: its error estimate in the header comes from the escapes noted afterwards.
  StandardSceneSpec checker;
  expect_frame_from_quiet_outcomes(camera_at(schwarzschild, 30.0, 70.0, 17, 13),
                                   make_general_tracer<Fehlberg78, IController>(
                                       schwarzschild, settings, AngleCorrection::flat, background_scene(checker)),
                                   13);
  // Kerr on its separated equations, and Reissner-Nordstrom differentiated by dual numbers.
  const KerrMetric kerr{1.0, 0.9};
  expect_frame_from_quiet_outcomes(
      camera_at(kerr, 50.0, 80.0, 17, 13),
      make_kerr_mino_tracer<Fehlberg78, IController>(kerr, settings, AngleCorrection::exact, disk_scene(disk)), 13);
  AutoReissnerNordstrom rn;
  rn.charge = 0.6;
  expect_frame_from_quiet_outcomes(
      camera_at(rn, 30.0, 80.0, 17, 13),
      make_general_tracer<Fehlberg78, IController>(rn, settings, AngleCorrection::exact, disk_scene(disk)), 13);
}

TEST(GpuFrameHostSide, OutcomesOfTheWrongRegionAreRefused) {
  const SchwarzschildMetric metric{1.0};
  const Camera camera = camera_at(metric, 30.0, 70.0, 8, 6);
  const auto tracer = make_general_tracer<Fehlberg78, IController>(metric, TraceSettings{}, AngleCorrection::exact,
                                                                   background_scene(StandardSceneSpec{}));
  const std::vector<RayOutcome> too_few(5);
  EXPECT_THROW(render_frame(camera, tracer, {}, nullptr, &too_few), std::invalid_argument);
}

// Legendre's F(phi, k) by Carlson's R_F (core/elliptic.hpp, what the GPU computes the Schwarzschild sky with) against
// the standard library's independent std::ellint_1, over the moduli and amplitudes the exact continuation uses.
TEST(GpuFrameHostSide, EllipticIntegralOfTheFirstKindMatchesTheStandardLibrary) {
  double worst = 0.0;
  for (int i = 0; i <= 100; ++i)
    for (int j = 0; j <= 200; ++j) {
      const double k = 0.999 * i / 100.0, phi = std::numbers::pi * j / 200.0;
      const double reference = std::ellint_1(k, phi);
      worst = std::max(worst, std::abs(elliptic_f(phi, k) - reference) / std::max(1e-300, std::abs(reference)));
    }
  EXPECT_LT(worst, 1e-14);
  EXPECT_NEAR(complete_elliptic_f(0.5), std::comp_ellint_1(0.5), 1e-15);
  // The Schwarzschild deflection through it, against Darwin's closed form on std::ellint_1 (exact/).
  for (const double r0 : {3.01, 3.5, 5.0, 10.0, 100.0})
    EXPECT_NEAR(exact::deflection_angle_from_periapsis(r0), exact::deflection_angle_darwin(r0), 2e-13) << r0;
}

}  // namespace

}  // namespace gpu_host_side_test
