// Glowing matter in physical units: the thermal synchrotron fit against the emissivity integrated from first
// principles (medium/thermal_synchrotron.hpp), the angle of one mass at M87* and Sgr A* against the EHT's figures
// (core/physical_units.hpp), a frame's flux against the volume integral of its emission (render/medium_frame.hpp),
// and the RIAF (medium/riaf.hpp): its ISCO, its gas, its accretion rate and the order of its 230 GHz flux.
#include "grtrace/core/physical_units.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/medium/riaf.hpp"
#include "grtrace/medium/thermal_synchrotron.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/render/scale_bar.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace {

using namespace grtrace;

TEST(PhysicalUnits, OneMassSpansTheEhtsAngleAtM87AndSgrA) {
  // theta_g = G M / (c^2 D): 3.8 microarcseconds for M87* (EHT 2019, paper VI) and 4.8 for Sgr A* (EHT 2022,
  // paper I), as the papers round them.
  EXPECT_NEAR(SourceScale::m87().microarcseconds_per_m(), 3.8, 0.05);
  EXPECT_NEAR(SourceScale::sgr_a().microarcseconds_per_m(), 4.8, 0.05);
  // A jansky is 1e-23 cgs: a camera flux F at r_cam is F (r_cam / D)^2 at the telescope.
  const SourceScale s = SourceScale::sgr_a();
  const double d = s.distance_pc * cgs::parsec / s.gravitational_radius_cm();
  EXPECT_NEAR(s.janskys(2.0, 1000.0), 2.0 * (1000.0 / d) * (1000.0 / d) * 1e23, 1e-12 * s.janskys(2.0, 1000.0));
}

TEST(ThermalSynchrotron, TheBesselTableIsTheLibrarysFunction) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> log_theta(std::log(0.01), std::log(1e4));
  double worst = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double theta = std::exp(log_theta(rng));
    const double exact = std::cyl_bessel_k(2.0, 1.0 / theta);
    worst = std::max(worst, std::abs(maxwell_juttner_k2(theta) / exact - 1.0));
  }
  EXPECT_LT(worst, 1e-9);
}

/// Simpson's rule for f on [a, b] with n (even) intervals.
template <class F>
double simpson(const F& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = f(a) + f(b);
  for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * h);
  return sum * h / 3.0;
}

/// The synchrotron function F(x) = x integral_x^inf K_5/3(t) dt (t = x e^s: smooth in s).
double synchrotron_function(double x) {
  const double upper = std::log((x + 60.0) / x);
  return x * simpson(
                 [&](double s) {
                   const double t = x * std::exp(s);
                   return std::cyl_bessel_k(5.0 / 3.0, t) * t;
                 },
                 0.0, upper, 400);
}

/// The ultrarelativistic thermal emissivity from first principles: a Maxwell-Juttner distribution (gamma >> 1:
/// n(gamma) = n_e gamma^2 e^(-gamma / Theta) / (Theta K_2(1 / Theta))), each electron radiating
/// sqrt(3) e^3 B sin(theta) / (m_e c^2) F(nu / nu_cr) per unit frequency, nu_cr = (3/2) gamma^2 nu_c sin(theta),
/// towards the direction at the pitch angle theta, spread over 4 pi (the distribution is isotropic).
double emissivity_from_first_principles(double nu, double n_e, double theta_e, double b, double sin_theta) {
  const double e = cgs::electron_charge, m = cgs::electron_mass, c = cgs::speed_of_light;
  const double nu_c = e * b / (2.0 * std::numbers::pi * m * c);
  const double x_s = nu / ((2.0 / 9.0) * nu_c * theta_e * theta_e * sin_theta);
  const double upper = std::log(theta_e * (60.0 + 3.0 * std::cbrt(x_s)));
  const double integral = simpson(
      [&](double s) {
        const double gamma = std::exp(s);
        return gamma * gamma * gamma * std::exp(-gamma / theta_e) *
               synchrotron_function(nu / (1.5 * gamma * gamma * nu_c * sin_theta));
      },
      0.0, upper, 400);
  return n_e / (4.0 * std::numbers::pi * theta_e * std::cyl_bessel_k(2.0, 1.0 / theta_e)) * std::sqrt(3.0) * e * e * e *
         b * sin_theta / (m * c * c) * integral;
}

TEST(ThermalSynchrotron, TheFitIsTheEmissivityOfTheDistributionWithinTwoAndAHalfPercent) {
  // Leung, Gammie & Noble (2011) fit the harmonic sum; for relativistic electrons (Theta >= 3) it is the
  // synchrotron function integrated over the distribution. Measured: 0.3 % (X = 1e4) to 2.3 % (X = 1).
  const double b = 10.0, sin_theta = std::sin(std::numbers::pi / 3.0);
  for (const double theta : {3.0, 10.0, 30.0}) {
    for (const double x : {1.0, 10.0, 100.0, 1e3, 1e4}) {
      const double nu_c =
          cgs::electron_charge * b / (2.0 * std::numbers::pi * cgs::electron_mass * cgs::speed_of_light);
      const double nu = x * (2.0 / 9.0) * nu_c * theta * theta * sin_theta;
      const double fit = thermal_synchrotron(nu, 1e5, theta, b, sin_theta).emission;
      const double exact = emissivity_from_first_principles(nu, 1e5, theta, b, sin_theta);
      EXPECT_NEAR(fit / exact, 1.0, 0.025) << "Theta " << theta << " X " << x;
    }
  }
  // Kirchhoff: the source function is Planck's.
  const MediumCoefficients c = thermal_synchrotron(230e9, 1e6, 10.0, 20.0, 0.5);
  EXPECT_NEAR(c.emission / c.absorption, planck_intensity(230e9, 10.0), 1e-12 * planck_intensity(230e9, 10.0));
  EXPECT_EQ(thermal_synchrotron(230e9, 1e6, 0.5 * min_synchrotron_temperature, 20.0, 0.5).emission, 0.0);
}

/// A Gaussian ball of gas at rest in flat space: j = j0 exp(-r^2 / w^2), no absorption.
struct GaussianGas {
  static constexpr std::string_view kind = "gaussian-gas";
  static constexpr bool spherically_symmetric = true;
  double j0 = 1.0, width = 3.0;
  double outer_radius() const { return 12.0 * width; }
  template <class M>
  MediumCoefficients coefficients(const M& metric, const Vec4& x, double) const {
    const double r = metric.radius(x);
    return {j0 * std::exp(-r * r / (width * width)), 0.0};
  }
  template <class M>
  Vec4 fluid_velocity(const M&, const Vec4&) const {
    return Vec4(1.0, 0.0, 0.0, 0.0);
  }
};

TraceSettings settings(double rtol) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, rtol * 1e-2};
  s.escape_radius = 2000.0;
  s.max_steps = 100000;
  return s;
}

TEST(MediumFrameFlux, AFramesFluxIsTheVolumeIntegralOfItsEmission) {
  // Optically thin gas: the flux at distance D is (integral of j dV) / D^2 (j per steradian); a camera at r sees
  // sum I dOmega = (integral of j dV) / r^2 (its rays through the ball nearly parallel: (w / r)^2 = 1e-5 off).
  const SchwarzschildMetric flat{0.0};
  const GaussianGas gas{2.0, 3.0};
  const double r_cam = 1000.0;
  CameraSpec spec;
  spec.position = Vec4(0.0, r_cam, std::numbers::pi / 2, 0.0);
  spec.spherical_position = true;
  spec.width = spec.height = 64;  // even: no pixel's ray through the chart's origin
  spec.fov_degrees = 2.0 * std::atan(16.0 / r_cam) * 180.0 / std::numbers::pi;
  const Camera camera = make_camera(flat, spec);
  const GeneralMediumTracer<SchwarzschildMetric, Fehlberg78, IController, GaussianGas> tracer(
      flat, gas, settings(1e-10), camera.tetrad().e[0], 1.0);
  const Frame frame = render_medium_frame(camera, tracer);
  EXPECT_EQ(frame.stats.failures(), 0);
  const double volume_integral = gas.j0 * std::pow(std::numbers::pi, 1.5) * std::pow(gas.width, 3);
  EXPECT_NEAR(medium_frame_flux(camera, frame.image) * r_cam * r_cam, volume_integral, 1e-4 * volume_integral);
}

TEST(Riaf, ItsInnermostStableOrbitIsBardeenPressAndTeukolskys) {
  for (const double a : {0.0, 0.5, 0.9, 0.998}) {
    const KerrMetric metric{1.0, a};
    const RiafFlow<KerrMetric> flow(metric, RiafParameters{});
    EXPECT_NEAR(flow.isco(), exact::isco_radius(a, exact::Orbit::prograde), 1e-6) << a;
  }
}

TEST(Riaf, ItsGasMovesOnUnitVelocitiesInfallingInsideTheIsco) {
  const KerrMetric metric{1.0, 0.9};
  const RiafFlow<KerrMetric> flow(metric, RiafParameters::m87());
  for (const double r : {1.5, 2.0, 2.3, 3.0, 6.0, 40.0}) {
    for (const double theta : {0.3, 1.0, std::numbers::pi / 2, 2.5}) {
      const Vec4 x(0.0, r, theta, 0.0);
      const Vec4 u = flow.fluid_velocity(metric, x);
      EXPECT_NEAR(inner_product(metric, x, u, u), 1.0, 1e-12) << r << " " << theta;
      EXPECT_GT(u[0], 0.0);
      if (r < flow.isco() && theta == std::numbers::pi / 2) {
        EXPECT_LT(u[1], 0.0) << r;
      }
      if (r > flow.isco()) {
        EXPECT_EQ(u[1], 0.0) << r;
      }
    }
  }
  // Continuous across the ISCO on the equator (the plunge starts from the circular orbit at rest in r).
  const double r = flow.isco();
  const Vec4 out = flow.fluid_velocity(metric, Vec4(0.0, r * (1 + 1e-9), std::numbers::pi / 2, 0.0));
  const Vec4 in = flow.fluid_velocity(metric, Vec4(0.0, r * (1 - 1e-9), std::numbers::pi / 2, 0.0));
  EXPECT_LT((out - in).norm(), 1e-3);
}

TEST(Riaf, ItsAccretionRateIsTheMassFluxThroughTwoMasses) {
  // Independently of the flow's own solid-angle sum: Simpson in theta (it sums in cos theta).
  RiafParameters p = RiafParameters::sgr_a();
  const KerrMetric metric{1.0, 0.5};
  for (const double h : {0.3, 1.0}) {
    p.thickness = h;
    const RiafFlow<KerrMetric> flow(metric, p);
    const double r_g = p.mass_solar * cgs::solar_gravitational_radius;
    const double flux_per_steradian =
        simpson([&](double theta) { return flow.density(Vec4(0.0, 2.0, theta, 0.0)) * std::sin(theta); }, 1e-9,
                std::numbers::pi - 1e-9, 20000);
    const double mdot = cgs::proton_mass * p.inflow_speed * cgs::speed_of_light * 2.0 * std::numbers::pi *
                        flux_per_steradian * 4.0 * r_g * r_g;
    const double expected = p.accretion_rate * cgs::solar_mass / cgs::year;
    EXPECT_NEAR(mdot, expected, 1e-6 * expected) << h;
  }
  EXPECT_THROW(RiafFlow<KerrMetric>(metric,
                                    [] {
                                      RiafParameters q;
                                      q.beta = 0.0;
                                      return q;
                                    }()),
               std::invalid_argument);
}

TEST(Riaf, M87AndSgrAShineAt230GHzWithTheFluxTheEhtMeasuresWithinAFactorOfTwo) {
  // The EHT's compact 230 GHz fluxes: about 0.5 Jy for M87* (2017) and 2.4 Jy for Sgr A*; the defaults give 0.3 and
  // 2.3 at a = 0.9 seen from 17 degrees (a 24 x 24 frame 40 M wide; finer frames move them by about 1 %).
  const KerrMetric metric{1.0, 0.9};
  struct Case {
    RiafParameters p;
    SourceScale scale;
    double measured;
  };
  for (const Case& c : {Case{RiafParameters::m87(), SourceScale::m87(), 0.5},
                        Case{RiafParameters::sgr_a(), SourceScale::sgr_a(), 2.4}}) {
    const RiafFlow<KerrMetric> flow(metric, c.p);
    const double r_cam = 1000.0;
    CameraSpec spec;
    spec.position = Vec4(0.0, r_cam, 17.0 * std::numbers::pi / 180.0, 0.0);
    spec.spherical_position = true;
    spec.width = spec.height = 24;
    spec.fov_degrees = 2.0 * std::atan(20.0 / r_cam) * 180.0 / std::numbers::pi;
    const Camera camera = make_camera(metric, spec);
    const GeneralMediumTracer<KerrMetric, Fehlberg78, IController, RiafFlow<KerrMetric>> tracer(
        metric, flow, settings(1e-8), camera.tetrad().e[0], 230e9);
    const Frame frame = render_medium_frame(camera, tracer);
    EXPECT_EQ(frame.stats.failures(), 0);
    const double jy = c.scale.janskys(medium_frame_flux(camera, frame.image), r_cam);
    EXPECT_GT(jy, c.measured / 2.0) << c.p.mass_solar;
    EXPECT_LT(jy, c.measured * 2.0) << c.p.mass_solar;
  }
}

TEST(Riaf, ItsSpectrumInOnePassIsEachFrequencysOwnTraceAndItsSpectralFormItsOwn) {
  // Sgr A* from 1000 M at 17 degrees at five frequencies from 43 GHz (optically thick at the centre) to 690 GHz (thin)
  // in one pass: the flow's coefficients at all five at once are its coefficients at each (the density, temperature,
  // field and angle shared), bit for bit; each band's light is its own trace's within the integration's error.
  const KerrMetric metric{1.0, 0.9};
  const RiafFlow<KerrMetric> flow(metric, RiafParameters::sgr_a());
  const std::array<double, 5> nu{43e9, 86e9, 230e9, 345e9, 690e9};
  CameraSpec spec;
  spec.position = Vec4(0.0, 1000.0, 17.0 * std::numbers::pi / 180.0, 0.0);
  spec.spherical_position = true;
  spec.width = spec.height = 9;
  spec.fov_degrees = 2.0 * std::atan(12.0 / 1000.0) * 180.0 / std::numbers::pi;
  const Camera camera = make_camera(metric, spec);
  const Vec4 u_cam = camera.tetrad().e[0];
  double worst = 0.0, tau_43 = 0.0;
  int asked = 0;
  for (int row = 0; row < 9; row += 2) {
    for (int col = 0; col < 9; col += 2) {
      const GeodesicState y0 = camera.pixel_state(col + 0.5, row + 0.5);
      const double e_cam = camera_photon_energy(metric, y0, u_cam);
      const SpectralEmissionResult<5> all =
          trace_kerr_mino_emission<Verner65, IController>(metric, flow, settings(1e-10), y0, e_cam, nu);
      tau_43 = std::max(tau_43, all.optical_depth[0]);
      for (std::size_t k = 0; k < 5; ++k) {
        const EmissionResult one =
            trace_kerr_mino_emission<Verner65, IController>(metric, flow, settings(1e-10), y0, e_cam, nu[k]);
        ASSERT_GT(one.intensity, 0.0);
        EXPECT_NEAR(all.intensity[k], one.intensity, 1e-7 * one.intensity) << row << " " << col << " " << k;
        worst = std::max(worst, std::abs(all.intensity[k] / one.intensity - 1.0));
      }
      // The spectral form at the ray's start moved into the gas (r = 6, on the equator).
      GeodesicState y = y0;
      y[1] = 6.0;
      y[2] = std::numbers::pi / 2 - 0.1 * row / 9.0;
      y[3] = 0.3 * col;
      const Vec4 x = y.head<4>(), k = y.tail<4>(), u = flow.fluid_velocity(metric, x);
      const std::array<MediumCoefficients, 5> c = flow.coefficients(metric, x, k, u, nu);
      for (std::size_t i = 0; i < 5; ++i) {
        const MediumCoefficients one = flow.coefficients(metric, x, k, u, nu[i]);
        EXPECT_EQ(c[i].emission, one.emission);
        EXPECT_EQ(c[i].absorption, one.absorption);
        asked += one.emission > 0.0;
      }
    }
  }
  EXPECT_EQ(asked, 125);
  EXPECT_GT(tau_43, 1.0);  // a band optically thick at the centre
  std::printf(
      "Sgr A* at 5 frequencies in one pass against one each: worst %.2e of a pixel's intensity, tau(43 GHz) "
      "up to %.3g\n",
      worst, tau_43);
}

TEST(ScaleBar, ARoundLengthAtMostAQuarterOfTheWidth) {
  EXPECT_EQ(round_scale_length(38.4), 20.0);
  EXPECT_EQ(round_scale_length(50.0), 50.0);
  EXPECT_EQ(round_scale_length(0.99), 0.5);
  Image image(192, 96);
  std::fill(image.channel("redshift").begin(), image.channel("redshift").end(), 0.5f);
  const double length = draw_scale_bar(image, 0.8);  // a quarter: 38.4 uas
  EXPECT_EQ(length, 20.0);
  EXPECT_EQ(image.metadata.at("scale_bar_microarcseconds"), "20");
  // The bar: 25 white pixels (20 / 0.8) on the row above the bottom margin, in R, G and B; the data untouched.
  const int row = 96 - 3 - 1;
  int white = 0;
  for (int x = 0; x < 192; ++x) white += image.channel("G")[image.index(x, row)] == 1.0f ? 1 : 0;
  EXPECT_EQ(white, 25);
  EXPECT_EQ(image.channel("redshift")[image.index(10, row)], 0.5f);
  Image small(20, 12);
  EXPECT_EQ(draw_scale_bar(small, 0.8), 0.0);
  EXPECT_EQ(draw_scale_bar(image, std::nan("")), 0.0);
}

}  // namespace
