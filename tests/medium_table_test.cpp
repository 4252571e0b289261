// A spherically symmetric medium's frame from one table of rays (trace/medium_tracers.hpp) against the general
// tracer, which integrates every pixel's ray with its light: the same statuses and the same intensity, for gas at
// rest and in free fall, Schwarzschild and Reissner-Nordstrom, a static and a falling camera; a medium with a
// spectrum seen by a moving camera is left to the general tracer, pixel for pixel.
#include "grtrace/medium/spherical_accretion.hpp"
#include "grtrace/metric/auto_metric.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace {

using namespace grtrace;

TraceSettings settings(double rtol) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, rtol * 1e-2};
  s.escape_radius = 2000.0;
  s.max_steps = 1'000'000;
  return s;
}

/// A camera at r = 1000 M on the equator looking at the hole, the shadow (b_c = 5.2 M) filling half of the frame;
/// `speed` towards the hole in the static frame.
template <class M>
Camera camera_of(const M& metric, int size, double speed = 0.0) {
  CameraSpec spec;
  spec.position = Vec4(0.0, 1000.0, std::numbers::pi / 2, 0.0);
  spec.spherical_position = true;
  spec.width = spec.height = size;
  spec.fov_degrees = 1.2;
  spec.velocity = Vec3(-speed, 0.0, 0.0);
  return make_camera(metric, spec);
}

struct Difference {
  double worst = 0.0;          ///< the largest |I_table - I_general| / I_general over the frame
  double worst_peak = 0.0;     ///< the largest |I_table - I_general| over the frame's brightest I_general
  double interpolation = 0.0;  ///< the largest |I_table - I_node| / I_node, I_node the table's own ray at the pixel
  double redshift = 0.0;       ///< the largest |g_table - g_general| of the emission-weighted redshifts
  long status_mismatches = 0, pixels = 0;
};

template <class A, class B>
Difference compare(const Camera& camera, const A& table, const B& general) {
  Difference d;
  double peak = 0.0, worst_absolute = 0.0;
  for (int y = 0; y < camera.height(); ++y)
    for (int x = 0; x < camera.width(); ++x) {
      const GeodesicState y0 = camera.pixel_state(x, y);
      const MediumSample t = table.trace(y0), g = general.trace(y0);
      ++d.pixels;
      if (t.status != g.status) ++d.status_mismatches;
      peak = std::max(peak, g.intensity);
      worst_absolute = std::max(worst_absolute, std::abs(t.intensity - g.intensity));
      if (g.intensity > 0.0) d.worst = std::max(d.worst, std::abs(t.intensity - g.intensity) / g.intensity);
      if (g.intensity > 0.0) d.redshift = std::max(d.redshift, std::abs(t.redshift - g.redshift));
      if (table.table() != nullptr && camera.tetrad().e[0][1] == 0.0) {  // a static camera: the node is the pixel
        const double node = table.table()->trace_node(planar_geometry(table.metric(), y0).delta).intensity;
        if (node > 0.0) d.interpolation = std::max(d.interpolation, std::abs(t.intensity - node) / node);
      }
    }
  d.worst_peak = worst_absolute / peak;
  return d;
}

TEST(MediumTable, SphericalAccretionFromOneTableIsTheGeneralTracersFrame) {
  // At rtol 1e-12: the general tracer's own error at rtol 1e-10 (1.8e-7 measured at the worst pixel, a ray grazing
  // the photon sphere, against 2.5e-9 at 1e-12) would hide the table's.
  const SchwarzschildMetric metric{1.0};
  const TraceSettings s = settings(1e-12);
  for (const auto gas : {SphericalAccretion::Gas::at_rest, SphericalAccretion::Gas::free_fall}) {
    SCOPED_TRACE(gas == SphericalAccretion::Gas::at_rest ? "at rest" : "free fall");
    SphericalAccretion medium;
    medium.gas = gas;
    medium.outer = 1e6;  // beyond the sky sphere: the light is a smooth function of the ray's angle
    for (const double speed : {0.0, 0.5}) {
      SCOPED_TRACE(speed);
      const Camera camera = camera_of(metric, 25, speed);
      const SphericalMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SphericalAccretion> table(
          metric, medium, s, camera, 1.0);
      const GeneralMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SphericalAccretion> general(
          metric, medium, s, camera.tetrad().e[0], 1.0);
      const Difference d = compare(camera, table, general);
      EXPECT_EQ(d.status_mismatches, 0);
      EXPECT_LT(d.worst, 1e-8);
      EXPECT_LT(d.interpolation, 1e-9);
      EXPECT_LT(d.redshift, 1e-8);  // a moving camera's too: every g along the ray scaled by its Doppler factor
      EXPECT_EQ(table.fallback_rays(), 0);
    }
  }
}

TEST(MediumTable, ReissnerNordstromToo) {
  AutoReissnerNordstrom metric;
  metric.mass = 1.0;
  metric.charge = 0.6;
  const TraceSettings s = settings(1e-12);
  SphericalAccretion medium;
  medium.outer = 1e6;
  const Camera camera = camera_of(metric, 21);
  const SphericalMediumTracer<AutoReissnerNordstrom, Fehlberg78, IController, SphericalAccretion> table(metric, medium,
                                                                                                        s, camera, 1.0);
  const GeneralMediumTracer<AutoReissnerNordstrom, Fehlberg78, IController, SphericalAccretion> general(
      metric, medium, s, camera.tetrad().e[0], 1.0);
  const Difference d = compare(camera, table, general);
  EXPECT_EQ(d.status_mismatches, 0);
  EXPECT_LT(d.worst, 1e-8);
  EXPECT_LT(d.interpolation, 1e-9);
}

TEST(MediumTable, AMediumsEdgeIsIntegratedNotInterpolated) {
  // Gas cut at 8 M (inside the frame, which reaches b = 10 M): the light grows as sqrt(b_e - b) inside the ray that
  // grazes the edge, which the table's polynomials misread (17 % off); pixels near it are integrated instead.
  const SchwarzschildMetric metric{1.0};
  const TraceSettings s = settings(1e-12);
  SphericalAccretion medium;
  medium.outer = 8.0;
  const Camera camera = camera_of(metric, 25);
  const SphericalMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SphericalAccretion> table(metric, medium, s,
                                                                                                      camera, 1.0);
  const GeneralMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SphericalAccretion> general(
      metric, medium, s, camera.tetrad().e[0], 1.0);
  const Difference d = compare(camera, table, general);
  EXPECT_EQ(d.status_mismatches, 0);
  EXPECT_LT(d.worst_peak, 1e-8);
  EXPECT_LT(d.worst, 3e-8);  // measured 1.2e-8 (the integration's own, at rays that graze the edge)
  EXPECT_GT(table.fallback_rays(), 0);
  EXPECT_LT(table.fallback_rays(), 25 * 25 / 2);  // only those near the edge
}

/// Gas at rest with a power-law spectrum j_nu ~ nu^-1: a moving camera sees each pixel at its own frequency in the
/// static frame, which one table cannot hold.
struct SpectralGas {
  static constexpr std::string_view kind = "spectral-gas";
  static constexpr bool spherically_symmetric = true;
  double outer_radius() const { return 1e6; }
  template <class M>
  MediumCoefficients coefficients(const M& metric, const Vec4& x, double nu) const {
    const double r = metric.radius(x);
    return {1.0 / (r * r * nu), 0.0};
  }
  template <class M>
  Vec4 fluid_velocity(const M& metric, const Vec4& x) const {
    return Vec4(1.0 / std::sqrt(metric.metric(x)(0, 0)), 0.0, 0.0, 0.0);
  }
};

TEST(MediumTable, AMediumWithASpectrumSeenByAMovingCameraIsTracedPixelByPixel) {
  const SchwarzschildMetric metric{1.0};
  const TraceSettings s = settings(1e-12);
  const Camera moving = camera_of(metric, 9, 0.3);
  const SphericalMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SpectralGas> table(metric, {}, s, moving,
                                                                                               2.0);
  EXPECT_EQ(table.table(), nullptr);
  const GeneralMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SpectralGas> general(
      metric, {}, s, moving.tetrad().e[0], 2.0);
  const Difference d = compare(moving, table, general);
  EXPECT_EQ(d.worst, 0.0);
  EXPECT_EQ(table.fallback_rays(), 81);
  // A static camera: the table holds the static observer's frequency, which is the camera's.
  const Camera still = camera_of(metric, 21);
  const SphericalMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SpectralGas> t2(metric, {}, s, still, 2.0);
  ASSERT_NE(t2.table(), nullptr);
  const GeneralMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SpectralGas> g2(metric, {}, s,
                                                                                          still.tetrad().e[0], 2.0);
  const Difference d2 = compare(still, t2, g2);
  EXPECT_LT(d2.worst, 1e-8);
  EXPECT_LT(d2.interpolation, 1e-9);
  EXPECT_EQ(t2.fallback_rays(), 0);
}

TEST(MediumTable, TheFrameHoldsTheIntensityAndAPicture) {
  const SchwarzschildMetric metric{1.0};
  SphericalAccretion medium;
  medium.outer = 1e6;
  const Camera camera = camera_of(metric, 33);
  const TraceSettings s = settings(1e-9);
  const SphericalMediumTracer<SchwarzschildMetric, Fehlberg78, IController, SphericalAccretion> table(metric, medium, s,
                                                                                                      camera, 1.0);
  RenderOptions options;
  options.progress = ProgressMode::never;
  const Frame frame = render_medium_frame(camera, table, options);
  const Image& image = frame.image;
  ASSERT_TRUE(image.has_channel("intensity") && image.has_channel("optical_depth"));
  // The brightest pixel is white, the picture's scale is the frame's peak, and the shadow's centre is dim.
  const std::vector<float>& intensity = image.channel("intensity");
  const auto peak = std::max_element(intensity.begin(), intensity.end());
  const auto i = static_cast<std::size_t>(peak - intensity.begin());
  EXPECT_EQ(image.channel("R")[i], 1.0f);
  EXPECT_EQ(image.channel("B")[i], 1.0f);
  EXPECT_EQ(std::stod(image.metadata.at("intensity_peak")), static_cast<double>(*peak));
  const MediumSample centre = table.trace(camera.pixel_state(16, 16));
  EXPECT_EQ(centre.status, RayStatus::captured);
  EXPECT_LT(centre.intensity, 0.2 * static_cast<double>(*peak));
  EXPECT_EQ(frame.stats.count(RayStatus::captured) + frame.stats.count(RayStatus::escaped), 33 * 33);
}

}  // namespace
