// Kerr's light rays in closed form (exact/kerr_null_geodesic.hpp) and the tracer built on them
// (trace/kerr_closed_form_tracer.hpp), against independent computations:
//  (a) the special functions (core/jacobi_elliptic.hpp) against their defining integrals by Gauss-Legendre
//      quadrature (F, Pi with n < 1 and the principal value beyond the pole, R1 across the spurious pole) and
//      against their definitions (F(am(u)) = u; sn^2 + cn^2 = 1; dn^2 + m sn^2 = 1; R_C and R_J by their
//      integrals), for negative parameters too; R_C and R_J against 40-digit values to 1e-15; the four-lane loop
//      against each integral alone; the kept Jacobi means against jacobi();
//  (b) the n = 0, 1, 2 equatorial crossings against the reduced Kerr tracer (trace/kerr_mino_tracer.hpp, rkf78 at
//      rtol 1e-12), which is made to accept exactly that crossing (a disk a hair wide around the closed form's
//      radius, counting the crossings it is offered): the same order n, radius and redshift within 1e-9, for
//      cameras near (r = 6 M) and far (1000 M), above and below the plane, spins 0, 0.5, 0.9, -0.9, 0.998, and
//      rays that pass within a few degrees of the polar axis;
//  (c) the state at any Mino time against a direct integration of the separated equations (tested here, not the
//      library's system: its time is slowed near the axis);
//  (c') the direction at infinity of inward and outward rays (the leg to infinity by Carlson's addition theorem)
//      against the reduced Kerr tracer continued to u = 0;
//  (d) whole disk frames equal to the reduced Kerr tracer's: the same object at every pixel but silhouettes
//      (counted), hit radius and redshift within 1e-8 relative, sky directions within 1e-8 rad (rtol 1e-12), and
//      the same order (crossings before the end) at every pixel, the sky's and the horizon's too;
//  (e) the disk-light frame (render/disk_light_frame.hpp: KerrDiskRays' crossings with their Keplerian redshift from
//      exact/kerr_exact.hpp) against this tracer's frame of the same opaque disk (its object, order, and
//      g^p eps(r) from its hit's radius and redshift through circular_orbits.hpp), and its transparent disk
//      against its opaque one.
#include "common/trace_settings.hpp"
#include "grtrace/core/jacobi_elliptic.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/exact/kerr_null_geodesic.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/disk_light_frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/scene/thin_disk.hpp"
#include "grtrace/spectra/kerr_disk_map.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/auto_tracer.hpp"
#include "grtrace/trace/kerr_closed_form_tracer.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

using namespace grtrace;

namespace {

constexpr double kPi = std::numbers::pi;

// Composite 10-point Gauss-Legendre on [lo, hi].
double quadrature(const std::function<double(double)>& f, double lo, double hi, int panels = 200) {
  return exact::kerr_detail::gauss_legendre(f, lo, hi, panels);
}

// ---- (a) the special functions -----------------------------------------------------------------------------

TEST(JacobiElliptic, CarlsonIntegralsEqualTheirDefinitions) {
  // t = x (1 - v^2) / v^2 maps v in (0, 1] onto [0, inf) and leaves smooth integrands:
  //   R_C(x, y) = sqrt(x) int_0^1 dv / (x + (y - x) v^2),
  //   R_J(x, y, z, p) = 3 sqrt(x) int_0^1 v^2 dv / ((x + (p - x) v^2) sqrt((x + (y - x) v^2)(x + (z - x) v^2))).
  auto rc = [](double x, double y) {
    return std::sqrt(x) * quadrature([&](double v) { return 1.0 / (x + (y - x) * v * v); }, 0.0, 1.0, 4000);
  };
  auto rj = [](double x, double y, double z, double p) {
    return 3.0 * std::sqrt(x) *
           quadrature(
               [&](double v) {
                 const double v2 = v * v;
                 return v2 / ((x + (p - x) * v2) * std::sqrt((x + (y - x) * v2) * (x + (z - x) * v2)));
               },
               0.0, 1.0);
  };
  for (const auto& [x, y] : {std::pair{2.0, 1.0}, std::pair{1.0, 2.0}, std::pair{0.3, 0.3000001}, std::pair{4.0, 0.01}})
    EXPECT_NEAR(carlson_rc(x, y) / rc(x, y), 1.0, 1e-13) << x << " " << y;
  for (const auto& v : {std::array{1.0, 2.0, 3.0, 4.0}, std::array{0.3, 0.7, 5.0, 0.01}, std::array{2.0, 3.0, 4.0, 9.0},
                        std::array{0.5, 1.0, 1.5, 1.0}})
    EXPECT_NEAR(carlson_rj(v[0], v[1], v[2], v[3]) / rj(v[0], v[1], v[2], v[3]), 1.0, 1e-13);
}

TEST(JacobiElliptic, CarlsonAndCompleteIntegralsEqualFortyDigitValues) {
  // References: mpmath's elliprc and elliprj at 40 digits (Carlson's algorithms in arbitrary precision), rounded to
  // 20. Where x and y of R_C agree to a few parts in 1e3, arccos(sqrt(x / y)) magnifies the rounding of its
  // argument (4e-14 here); R_J's first duplication level meets such an R_C wherever p is near x, y and z, so Legendre's
  // Pi of moderate amplitude lost 8e-14 that way (the three R_J below). The arctangent forms keep a few ulps.
  struct Rc {
    double x, y, value;
  };
  for (const Rc& c :
       {Rc{1.0, 1.002, 0.99933413219225106349}, Rc{1.0015, 1.0, 0.99975016859948398658},
        Rc{0.3, 0.3004, 1.8249310660596807}, Rc{1.0, 1.5, 0.87041975136710319747}, Rc{1.9, 1.0, 0.8903053070774893731},
        Rc{0.0, 2.0, 1.1107207345395915618}, Rc{4e5, 1.0, 0.011293703723483946471}})
    EXPECT_NEAR(carlson_rc(c.x, c.y) / c.value, 1.0, 1e-15) << c.x << " " << c.y;
  struct Rj {
    double x, y, z, p, value;
  };
  for (const Rj& c : {Rj{0.70582542536609894, 13.302414872878604, 1.0, 1.0813093270311016, 0.39381330730912165837},
                      Rj{0.43962992569147941, 1.7130774499297454, 1.0, 1.402799591959643, 0.84529702068699406126},
                      Rj{0.40878287384627487, 0.40882572220268759, 1.0, 0.86676787318478932, 1.8023760377388242367},
                      Rj{0.0, 0.19, 1.0, 0.7, 5.4510155846308086525}, Rj{0.0, 31.0, 1.0, 2.5, 0.27511988684165520798}})
    EXPECT_NEAR(carlson_rj(c.x, c.y, c.z, c.p) / c.value, 1.0, 1e-15) << c.x << " " << c.y << " " << c.p;
  // The complete integrals by the arithmetic-geometric mean (K always; Pi for -1 <= n <= 0.9, the edges included)
  // and by Carlson's forms beyond (n = -3, 0.99), against mpmath's ellipk and ellippi at 40 digits.
  struct Complete {
    double n, m, value;
  };
  for (const Complete& c :
       {Complete{0.5, -20.0, 0.806791719001363747187}, Complete{0.85, -300.0, 0.405230271544664288156},
        Complete{-0.9, 0.999999, 4.74429844038114542612}, Complete{0.2, 0.5, 2.09295658273187553864},
        Complete{0.9, -1e4, 0.0973806138347798137456}, Complete{-1.0, -3.0, 0.80869336781236621329},
        Complete{-3.0, 0.3, 0.832067842419923944795}, Complete{0.99, -2.0, 9.48401068373450817606}})
    EXPECT_NEAR(complete_pi(c.n, c.m) / c.value, 1.0, 2e-15) << "n " << c.n << " m " << c.m;
  for (const auto& [m, value] :
       {std::pair{-1e4, 0.0599133976727871168075}, std::pair{-2.5, 1.12088100360300672423},
        std::pair{0.5, 1.85407467730137191843}, std::pair{0.999999999999, 15.20181598007012028}})
    EXPECT_NEAR(complete_f(m) / value, 1.0, 2e-15) << "m " << m;
}

TEST(JacobiElliptic, LegendreIntegralsEqualTheirDefinitionsForAnyAmplitude) {
  for (const double m : {-20.0, -2.0, 0.0, 0.3, 0.95, 0.999999})
    for (const double phi : {0.7, 2.5, -4.0, 11.3}) {
      auto root = [&](double t) { return std::sqrt(1.0 - m * std::sin(t) * std::sin(t)); };
      const int panels = m > 0.99 ? 40000 : 400;  // near m = 1 the integrand peaks at pi / 2 (width ~ sqrt(1 - m))
      EXPECT_NEAR(legendre_f(phi, m), quadrature([&](double t) { return 1.0 / root(t); }, 0.0, phi, panels),
                  (m > 0.99 ? 1e-12 : 1e-13) * std::abs(legendre_f(phi, m)))  // the sum of 4e5 terms
          << "m " << m << " phi " << phi;
      for (const double n : {-3.0, 0.5, 0.99}) {
        const double ref = quadrature([&](double t) { return 1.0 / ((1.0 - n * std::sin(t) * std::sin(t)) * root(t)); },
                                      0.0, phi, panels * 4);
        EXPECT_NEAR(legendre_pi(n, phi, m) / ref, 1.0, 1e-12) << "n " << n << " m " << m << " phi " << phi;
      }
    }
  // n > 1: the principal value. Differences over intervals between the poles (sin^2 = 1/n) are plain integrals.
  for (const double n : {1.5, 4.0, 40.0})
    for (const double m : {0.3, 0.95}) {
      const double pole = std::asin(1.0 / std::sqrt(n));
      auto f = [&](double t) {
        const double s2 = std::sin(t) * std::sin(t);
        return 1.0 / ((1.0 - n * s2) * std::sqrt(1.0 - m * s2));
      };
      for (const auto& [lo, hi] : {std::pair{0.1, pole - 0.05}, std::pair{pole + 0.01, kPi - pole - 0.02},
                                   std::pair{pole + 0.3, 0.5 * kPi}, std::pair{kPi - pole + 0.1, kPi + pole - 0.1},
                                   std::pair{2.0 * kPi + pole + 0.05, 3.0 * kPi - pole - 0.05}}) {
        if (!(hi > lo)) continue;
        const double ref = quadrature(f, lo, hi, 2000);
        EXPECT_NEAR(legendre_pi(n, hi, m) - legendre_pi(n, lo, m), ref, 1e-11 * std::max(1.0, std::abs(ref)))
            << "n " << n << " m " << m << " [" << lo << ", " << hi << "]";
      }
    }
}

TEST(JacobiElliptic, TwoPiOfOneAmplitudeTogetherEqualEachAlone) {
  // legendre_pi_pair_sc duplicates R_F's arguments once for both characteristics (the loop runs to the stricter of
  // the two stopping rules): each value as legendre_pi computes it alone, near the pole of n > 1 as well (where the
  // pair falls back to two calls).
  for (const double m : {-5.0, 0.0, 0.6, 0.999999})
    for (const double phi : {-1.5, -0.4, 0.05, 0.9, 1.5707963})
      for (const auto& [n1, n2] :
           {std::pair{-2.0, 0.5}, std::pair{0.9, 3.0}, std::pair{1.2, 40.0}, std::pair{-30.0, 1.01}}) {
        const PiPair pair = legendre_pi_pair_sc(n1, n2, std::sin(phi), std::cos(phi), m);
        EXPECT_NEAR(pair.first, legendre_pi(n1, phi, m), 4e-15 * std::max(1.0, std::abs(pair.first)))
            << "n " << n1 << " m " << m << " phi " << phi;
        EXPECT_NEAR(pair.second, legendre_pi(n2, phi, m), 4e-15 * std::max(1.0, std::abs(pair.second)))
            << "n " << n2 << " m " << m << " phi " << phi;
      }
}

TEST(JacobiElliptic, FourLanesEqualEachIntegralAlone) {
  // carlson_rf_rj_lanes runs four argument sets in one loop, until the slowest lane meets its rule: each lane's R_F
  // and R_J as carlson_rf_rj_n computes that set alone, to a few ulps (a lane duplicated further than it needed is
  // the same value). The sets: a Pi pair of an amplitude near pi/2 (the slowest), arguments that agree to 1e-3
  // (none needed), a lane whose first levels leave R_C's series (|e| > 1e-3, p far from x, y, z), and ones.
  const double xs[4] = {0.0123, 400.1, 0.9, 1.0}, ys[4] = {0.31, 400.3, 3.0, 1.0}, zs[4] = {1.0, 401.5, 5.0, 1.0};
  const double p0[4] = {0.004, 400.7, 40.0, 1.0}, p1[4] = {2.7, 400.2, 0.02, 1.0};
  using A4 = Eigen::Array4d;
  const A4 p[2] = {A4(p0[0], p0[1], p0[2], p0[3]), A4(p1[0], p1[1], p1[2], p1[3])};
  A4 rf, rj[2];
  carlson_rf_rj_lanes<2>(A4(xs[0], xs[1], xs[2], xs[3]), A4(ys[0], ys[1], ys[2], ys[3]), A4(zs[0], zs[1], zs[2], zs[3]),
                         p, rf, rj);
  for (int l = 0; l < 4; ++l) {
    const double ps[2] = {p0[l], p1[l]};
    double alone[2];
    const double rf_alone = detail::carlson_rf_rj_n<2>(xs[l], ys[l], zs[l], ps, alone);
    EXPECT_NEAR(rf[l], rf_alone, 4e-16 * rf_alone) << "lane " << l;
    EXPECT_NEAR(rj[0][l], alone[0], 1e-15 * alone[0]) << "lane " << l;
    EXPECT_NEAR(rj[1][l], alone[1], 1e-15 * alone[1]) << "lane " << l;
  }
}

TEST(JacobiElliptic, OneParameterServesManyArguments) {
  // JacobiParameter keeps the means of one m: its functions are jacobi's bit for bit, its K is complete_f's to an
  // ulp, and Pi from the half turns and (-1)^turns (sn, cn) (legendre_pi_turns, no arctangent) is Pi of am.
  for (const double m : {-400.0, -3.0, 0.0, 0.5, 0.999}) {
    const JacobiParameter parameter(m);
    EXPECT_NEAR(parameter.complete_f(), complete_f(m), 2e-16 * complete_f(m)) << "m " << m;
    for (const double u : {-9.1, -0.3, 0.0, 0.7, 2.2, 13.5}) {
      const JacobiValues kept = parameter(u), alone = jacobi(u, m);
      EXPECT_EQ(kept.sn, alone.sn);
      EXPECT_EQ(kept.cn, alone.cn);
      EXPECT_EQ(kept.dn, alone.dn);
      EXPECT_EQ(kept.am, alone.am);
      const double turn = std::fmod(kept.turns, 2.0) == 0.0 ? 1.0 : -1.0;
      for (const double n : {-2.0, 0.4, 0.93}) {
        const double by_turns = legendre_pi_turns(n, kept.turns, turn * kept.sn, turn * kept.cn, m, complete_pi(n, m));
        EXPECT_NEAR(by_turns, legendre_pi(n, kept.am, m), 1e-14 * std::max(1.0, std::abs(by_turns)))
            << "m " << m << " u " << u << " n " << n;
      }
    }
  }
}

TEST(JacobiElliptic, JacobiFunctionsInvertTheAmplitude) {
  for (const double m : {-30.0, -0.5, 0.0, 0.3, 0.9, 1.0 - 1e-6})
    for (const double u : {0.3, 1.7, -2.9, 7.5, 40.0}) {
      const JacobiValues j = jacobi(u, m);
      // F' = 1 / dn, up to 1 / sqrt(1 - m) = 1000 for the last m: am's rounding is magnified that much in F(am).
      EXPECT_NEAR(legendre_f(j.am, m), u, (m > 0.99 ? 1e-11 : 1e-13) * std::max(1.0, std::abs(u)))
          << "m " << m << " u " << u;
      // sn and am come by different roads (Bulirsch's recursion, an arctangent): they agree to am's own rounding,
      // a unit in its last place being 1.4e-14 at am = 116 (m = -30, u = 40).
      EXPECT_NEAR(j.sn, std::sin(j.am), 1e-15 * std::max(1.0, std::abs(j.am))) << "m " << m << " u " << u;
      EXPECT_NEAR(j.sn * j.sn + j.cn * j.cn, 1.0, 1e-15);
      EXPECT_NEAR(j.dn * j.dn + m * j.sn * j.sn, 1.0, 1e-13);
    }
}

TEST(JacobiElliptic, R1IsTheIntegralOfOneOverOnePlusAlphaCn) {
  for (const double m : {0.3, 0.9})
    for (const double alpha : {0.4, -0.7, 1.6, -2.5, 6.0})
      for (const double u : {0.5, 1.0, 2.0, -1.3, 3.5}) {
        // Only paths that avoid the integrand's pole (cn = -1 / alpha) have an integral.
        bool pole = false;
        for (int i = 0; i <= 400 && !pole; ++i) pole = 1.0 + alpha * jacobi(u * i / 400.0, m).cn <= 0.02;
        if (pole) continue;
        const double ref = quadrature([&](double v) { return 1.0 / (1.0 + alpha * jacobi(v, m).cn); }, 0.0, u, 400);
        EXPECT_NEAR(jacobi_r1(alpha, u, m), ref, 1e-12 * std::max(1.0, std::abs(ref)))
            << "alpha " << alpha << " m " << m << " u " << u;
      }
}

// ---- (b) the crossings against the reduced Kerr tracer -----------------------------------------------------

struct CameraCase {
  double spin, r, theta, fov;
};

std::string describe(const CameraCase& c) {
  char b[120];
  std::snprintf(b, sizeof b, "a = %g, camera r = %g, theta = %g", c.spin, c.r, c.theta);
  return b;
}

Camera camera_of(const KerrMetric& metric, const CameraCase& c, int pixels) {
  CameraSpec cs;
  cs.position = Vec4(0.0, c.r, c.theta, 0.4);
  cs.spherical_position = true;
  cs.observer = ObserverKind::zamo;
  cs.width = cs.height = pixels;
  cs.fov_degrees = c.fov;
  return make_camera(metric, cs);
}

// A thin disk that counts the crossings it is offered (the tracer asks each located crossing once).
struct CountingDisk : ThinDisk {
  int* offered = nullptr;
  template <MetricPolicy M>
  bool accepts(const M& metric, const GeodesicState& y) const {
    ++*offered;
    return ThinDisk::accepts(metric, y);
  }
};

const std::vector<CameraCase>& camera_cases() {
  static const std::vector<CameraCase> cases = {
      {0.9, 1000.0, 1.3, 2.2}, {0.9, 30.0, 0.5, 60.0},   {0.0, 50.0, 1.2, 40.0},  {0.5, 6.0, 1.5707963, 120.0},
      {-0.9, 20.0, 2.4, 70.0}, {0.998, 200.0, 0.3, 8.0}, {0.9, 300.0, 0.06, 5.0},
  };
  return cases;
}

TEST(KerrClosedForm, CrossingsOfOrdersZeroOneTwoEqualTheReducedTracers) {
  int compared[3] = {0, 0, 0};
  double radius_err = 0.0, redshift_err = 0.0;
  for (const CameraCase& c : camera_cases()) {
    const KerrMetric metric{1.0, c.spin};
    const int pixels = 15;
    const Camera cam = camera_of(metric, c, pixels);
    const TraceSettings s = test_settings::settings_at(1e-12, 2000.0);
    const double guard = (1.0 + s.horizon_epsilon) * metric.horizon_radius();
    for (int row = 0; row < pixels; ++row)
      for (int col = 0; col < pixels; ++col) {
        const GeodesicState y0 = cam.pixel_state(col + 0.5, row + 0.5);
        const KerrNullGeodesic ray(metric, y0, s.escape_radius, guard);
        if (!ray.supported()) continue;
        for (int n = 0; n <= 2 && ray.crossing_mino_time(n) < ray.end_mino_time(); ++n) {
          const GeodesicState y = ray.crossing_state(n);
          const double r = y[1];
          EXPECT_NEAR(y[2], 0.5 * kPi, 1e-15);
          int offered = 0;
          CountingDisk disk;
          disk.r_in = r * (1.0 - 1e-7);
          disk.r_out = r * (1.0 + 1e-7);
          disk.offered = &offered;
          const auto scene = make_scene(StarFieldSky{}, HorizonPaint{}, disk);
          const auto mino = make_kerr_mino_tracer<Fehlberg78, IController>(metric, s, AngleCorrection::exact, scene);
          const RayOutcome o = mino.trace(y0);
          ASSERT_EQ(o.status, RayStatus::hit)
              << describe(c) << " pixel " << col << "," << row << " n " << n << " r " << r;
          EXPECT_EQ(offered, n + 1) << "order; " << describe(c) << " pixel " << col << "," << row;
          // The order the tracing loop counts (the equatorial crossings before the hit) is the closed form's n.
          EXPECT_EQ(o.order, n) << describe(c) << " pixel " << col << "," << row;

          radius_err = std::max(radius_err, std::abs(o.radius - r) / r);
          EXPECT_NEAR(o.radius, r, 1e-9 * r) << describe(c) << " n " << n;
          const double g = redshift_at(metric, disk.emitter_velocity(metric, y.head<4>()), y);
          if (std::isfinite(o.redshift) || std::isfinite(g)) {
            EXPECT_NEAR(g, o.redshift, 1e-9 * std::abs(o.redshift)) << describe(c) << " n " << n;
            redshift_err = std::max(redshift_err, std::abs(g - o.redshift) / std::abs(o.redshift));
          }
          // phi winds as int a r / Delta: within a few tenths of M of the horizon the integration's error grows with
          // it (2e-5 rad at r = 1.87 for a = 0.5, where the closed form agrees with a fixed-step integration of the
          // separated equations to 1e-9), so phi is compared away from it.
          const double delta = r * r - 2.0 * r + c.spin * c.spin;
          if (delta > 0.05 * r * r) {
            EXPECT_NEAR(std::remainder(y[3] - o.state[3], 2.0 * kPi), 0.0, 1e-8) << describe(c);
          }
          for (int i = 4; i < 8; ++i) EXPECT_NEAR(y[i], o.state[i], 1e-8 * std::max(1.0, std::abs(y[i]))) << i;
          ++compared[n];
        }
      }
  }
  std::printf("crossings compared: n = 0: %d, n = 1: %d, n = 2: %d; worst radius %.1e, redshift %.1e\n", compared[0],
              compared[1], compared[2], radius_err, redshift_err);
  EXPECT_GT(compared[0], 500);
  EXPECT_GT(compared[1], 50);
  EXPECT_GT(compared[2], 5);
}

// ---- (c) the state at any Mino time -------------------------------------------------------------------------

// The separated equations in Mino time with E = 1 (second-order forms, through the turning points), integrated by
// the classical Runge-Kutta method with a fixed step: z = (r, theta, phi, dr/dtau, dtheta/dtau).
struct SeparatedEquations {
  double a, lambda, eta, phi_sign;
  Vector<5> operator()(const Vector<5>& z) const {
    const double r = z[0], s = std::sin(z[1]), c = std::cos(z[1]), a2 = a * a;
    const double w = r * r + a2 - a * lambda, k = eta + (lambda - a) * (lambda - a), delta = r * r - 2.0 * r + a2;
    Vector<5> d;
    d << z[3], z[4], phi_sign * (a * w / delta - a + lambda / (s * s)), 2.0 * r * w - (r - 1.0) * k,
        c * s * (lambda * lambda / (s * s * s * s) - a2);
    return d;
  }
};

TEST(KerrClosedForm, StateAtAnyMinoTimeEqualsTheSeparatedEquationsIntegrated) {
  int compared = 0;
  double worst = 0.0;
  for (const CameraCase& c : {CameraCase{0.9, 40.0, 1.2, 50.0}, CameraCase{-0.7, 8.0, 2.5, 90.0},
                              CameraCase{0.0, 20.0, 1.0, 60.0}, CameraCase{0.5, 5.0, 1.5707963, 100.0}}) {
    const KerrMetric metric{1.0, c.spin};
    const Camera cam = camera_of(metric, c, 7);
    for (int row = 0; row < 7; ++row)
      for (int col = 0; col < 7; ++col) {
        const GeodesicState y0 = cam.pixel_state(col + 0.5, row + 0.5);
        const KerrNullGeodesic ray(metric, y0, 1000.0, 1.001 * metric.horizon_radius());
        if (!ray.supported()) continue;
        const double e = metric.energy(y0), abs_e = std::abs(e);
        const double sigma0 = y0[1] * y0[1] + c.spin * c.spin * std::cos(y0[2]) * std::cos(y0[2]);
        Vector<5> z;
        z << y0[1], y0[2], y0[3], sigma0 * y0[5] / abs_e, sigma0 * y0[6] / abs_e;
        const SeparatedEquations f{c.spin, ray.lambda(), ray.eta(), e > 0.0 ? 1.0 : -1.0};
        auto integrate = [&](double target, int steps) {
          Vector<5> x = z;
          const double h = target / steps;
          for (int i = 0; i < steps; ++i) {
            const Vector<5> k1 = f(x), k2 = f(x + 0.5 * h * k1), k3 = f(x + 0.5 * h * k2), k4 = f(x + h * k3);
            x += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
          }
          return x;
        };
        for (const double part : {0.2, 0.45, 0.7, 0.9}) {
          const double tau = part * ray.end_mino_time();
          // Twice, with 4000 and 8000 steps: their difference bounds the finer one's error (fourth order: 1/15 of
          // it), which near-critical rays (long Mino times, steep r'') make larger than the closed form's.
          const Vector<5> coarse = integrate(tau, 4000), fine = integrate(tau, 8000);
          if (std::abs(std::sin(fine[1])) < 0.05) continue;  // the fixed step does not resolve a pass by the axis
          const GeodesicState y = ray.state_at(tau);
          auto ours = [&](const Vector<5>& x) {
            const double sigma = x[0] * x[0] + c.spin * c.spin * std::cos(x[1]) * std::cos(x[1]);
            return std::array{std::abs(y[1] - x[0]) / x[0], std::abs(y[2] - x[1]),
                              std::abs(std::remainder(y[3] - x[2], 2.0 * kPi)),
                              std::abs(y[5] - x[3] * abs_e / sigma) / std::max(1e-3, std::abs(y[5])),
                              std::abs(y[6] - x[4] * abs_e / sigma) / std::max(1e-3, std::abs(y[6]))};
          };
          const auto err = ours(fine), spread = ours(coarse);
          for (std::size_t i = 0; i < err.size(); ++i) {
            const double reference_error = std::abs(spread[i] - err[i]);
            EXPECT_LT(err[i], 1e-10 + reference_error)
                << describe(c) << " pixel " << col << "," << row << " tau " << tau << " component " << i;
            if (reference_error < 1e-11) worst = std::max(worst, err[i]);
          }
          ++compared;
        }
      }
  }
  std::printf("states compared: %d, worst where the integration is converged to 1e-11: %.1e\n", compared, worst);
  EXPECT_GT(compared, 100);
}

// ---- (d) whole frames ------------------------------------------------------------------------------------------

// The disk of the frame tests: from the prograde ISCO to 25 M.
template <class Disk>
Disk frame_disk(double spin) {
  Disk disk;
  disk.r_in = exact::isco_radius(spin, exact::Orbit::prograde);
  disk.r_out = 25.0;
  return disk;
}

TEST(KerrClosedForm, DirectionAtInfinityEqualsTheIntegratedContinuation) {
  // The direction at infinity takes the radial integral from the camera to infinity by Carlson's addition theorem
  // (one leg's change D; 2 H(F_inf) - D for a ray that turns at r4, -D for one that starts outwards) and runs its
  // three integrals in one lane loop; rays through the axis and Pi near its pole take the two primitives instead.
  // Each against the reduced Kerr tracer (rkf78 at rtol 1e-12, the sky continued to u = 1 / r = 0 by the Mino-time
  // system: trace/sky_continuation.hpp) on an empty scene: inward rays of a camera's frame, the same rays turned
  // outwards (k^r negated: still null, the metric is diagonal in r), near and far cameras, both spins' signs. Within
  // 1e-8 rad, as the frames below: ~1e-12 for most rays, up to 1e-9 beside the shadow's edge, where the direction at
  // infinity changes fastest with the ray and the integration's error is magnified the most.
  struct Case {
    double spin, r, theta;
  };
  const TraceSettings s = test_settings::settings_at(1e-12, 2000.0);
  for (const Case& c : {Case{0.9, 50.0, 1.3}, Case{-0.7, 8.0, 0.6}, Case{0.998, 300.0, 1.5}, Case{0.3, 4.0, 2.2}}) {
    const KerrMetric metric(1.0, c.spin);
    const auto mino = make_kerr_mino_tracer<Fehlberg78, IController>(metric, s, AngleCorrection::exact,
                                                                     make_scene(StarFieldSky{}, HorizonPaint{}));
    const Camera cam = camera_of(metric, CameraCase{c.spin, c.r, c.theta, 70.0}, 24);
    int compared[2] = {0, 0};
    double worst[2] = {0.0, 0.0};
    for (int row = 0; row < 24; ++row)
      for (int col = 0; col < 24; ++col)
        for (int outward = 0; outward < 2; ++outward) {
          GeodesicState y0 = cam.pixel_state(col, row);
          if (outward) y0[5] = -y0[5];
          const KerrNullGeodesic ray(metric, y0, s.escape_radius, (1.0 + s.horizon_epsilon) * metric.horizon_radius());
          if (!ray.supported() || !ray.escapes()) continue;
          double theta = 0.0, phi = 0.0;
          ray.direction_at_infinity(theta, phi);
          const RayOutcome ref = mino.trace(y0);
          ASSERT_EQ(ref.status, RayStatus::escaped);
          const double d = angular_distance(SkyDirection{theta, phi}, ref.where);
          worst[outward] = std::max(worst[outward], d);
          ++compared[outward];
          EXPECT_LT(d, 1e-8) << "a = " << c.spin << ", r = " << c.r << ", pixel " << col << ", " << row
                             << (outward ? " outward" : " inward");
        }
    if (c.r > 5.0) {  // at 4 M every inward ray of this frame falls in
      EXPECT_GT(compared[0], 100);
    }
    EXPECT_GT(compared[1], 100);
    std::printf("a = %g, camera r = %g: %d inward rays, worst %.1e rad; %d outward, worst %.1e rad\n", c.spin, c.r,
                compared[0], worst[0], compared[1], worst[1]);
  }
}

TEST(KerrClosedForm, DiskFramesEqualTheReducedTracers) {
  for (const CameraCase& c : camera_cases()) {
    const KerrMetric metric{1.0, c.spin};
    const int pixels = 40;
    const Camera cam = camera_of(metric, c, pixels);
    const TraceSettings s = test_settings::settings_at(1e-12, 2000.0);
    const auto scene = make_scene(StarFieldSky{}, HorizonPaint{}, frame_disk<ThinDisk>(c.spin));
    const auto closed = make_kerr_closed_form_tracer<Fehlberg78, IController>(metric, s, AngleCorrection::exact, scene);
    const auto mino = make_kerr_mino_tracer<Fehlberg78, IController>(metric, s, AngleCorrection::exact, scene);
    int differ = 0, hits = 0, sky = 0, captured = 0, order_differs = 0;
    int by_order[4] = {0, 0, 0, 0};  // pixels on the disk by the order of its image: 0, 1, 2, >= 3
    double radius_err = 0.0, redshift_err = 0.0, sky_err = 0.0;
    for (int row = 0; row < pixels; ++row)
      for (int col = 0; col < pixels; ++col) {
        const GeodesicState y0 = cam.pixel_state(col + 0.5, row + 0.5);
        const RayOutcome a = closed.trace(y0), b = mino.trace(y0);
        ASSERT_FALSE(is_failure(a.status)) << describe(c);
        if (a.object != b.object) {
          ++differ;
          continue;
        }
        // Every ray's order: the crossings the closed form enumerates against those the integration counted (the
        // sky's and the horizon's rays too: every crossing before the sky sphere or the guard).
        if (a.order != b.order) ++order_differs;
        if (a.status == RayStatus::hit) ++by_order[std::min(a.order, 3)];
        const double dr = std::abs(a.radius - b.radius) / b.radius;
        const double dg = std::abs(a.redshift - b.redshift) / std::abs(b.redshift);
        if (a.status == RayStatus::hit) {
          ++hits;
          radius_err = std::max(radius_err, dr);
          redshift_err = std::max(redshift_err, dg);
        } else if (a.status == RayStatus::escaped) {
          ++sky;
          redshift_err = std::max(redshift_err, dg);
          const double d = std::hypot(a.where.theta - b.where.theta,
                                      std::sin(b.where.theta) * std::remainder(a.where.phi - b.where.phi, 2.0 * kPi));
          sky_err = std::max(sky_err, d);
        } else {
          ++captured;
        }
      }
    std::printf(
        "%s: %d hits (orders %d, %d, %d, %d+), %d sky, %d captured, %d differ, %ld fallbacks; radius %.1e, redshift "
        "%.1e, sky %.1e rad\n",
        describe(c).c_str(), hits, by_order[0], by_order[1], by_order[2], by_order[3], sky, captured, differ,
        closed.fallback_rays(), radius_err, redshift_err, sky_err);
    EXPECT_EQ(order_differs, 0) << describe(c);
    EXPECT_GT(by_order[0], 0) << describe(c);
    EXPECT_LE(differ, pixels * pixels / 400) << describe(c);
    EXPECT_LT(radius_err, 1e-8) << describe(c);
    EXPECT_LT(redshift_err, 1e-8) << describe(c);
    EXPECT_LT(sky_err, 1e-8) << describe(c);
  }
}

// A disk of which only the half y > 0 (sin phi > 0) exists: where it is depends on phi, so it does not declare itself
// axisymmetric, and the closed-form tracer must test its crossings with phi (an axisymmetric object's are tested
// without it, and phi computed at the hit alone).
struct HalfDisk : ThinDisk {
  static constexpr bool axisymmetric = false;
  template <MetricPolicy M>
  bool accepts(const M& metric, const GeodesicState& y) const {
    return ThinDisk::accepts(metric, y) && std::sin(y[3]) > 0.0;
  }
};

TEST(KerrClosedForm, AnObjectWhoseExtentReadsPhiIsTestedWithIt) {
  static_assert(object_is_axisymmetric<ThinDisk>() && !object_is_axisymmetric<HalfDisk>());
  for (const CameraCase& c : {CameraCase{0.9, 30.0, 1.2, 60.0}, CameraCase{-0.5, 60.0, 1.45, 40.0}}) {
    const KerrMetric metric{1.0, c.spin};
    const int pixels = 30;
    const Camera cam = camera_of(metric, c, pixels);
    const TraceSettings s = test_settings::settings_at(1e-12, 2000.0);
    const HalfDisk disk = frame_disk<HalfDisk>(c.spin);
    const auto scene = make_scene(StarFieldSky{}, HorizonPaint{}, disk);
    const auto closed = make_kerr_closed_form_tracer<Fehlberg78, IController>(metric, s, AngleCorrection::exact, scene);
    const auto mino = make_kerr_mino_tracer<Fehlberg78, IController>(metric, s, AngleCorrection::exact, scene);
    int hits = 0, differ = 0, through_the_missing_half = 0;
    for (int row = 0; row < pixels; ++row)
      for (int col = 0; col < pixels; ++col) {
        const GeodesicState y0 = cam.pixel_state(col + 0.5, row + 0.5);
        const RayOutcome a = closed.trace(y0), b = mino.trace(y0);
        if (a.object != b.object) ++differ;
        if (a.status != RayStatus::hit) {
          // A ray that crosses the plane between the disk's radii first where the disk is missing.
          const KerrNullGeodesic ray(metric, y0, s.escape_radius, (1.0 + s.horizon_epsilon) * metric.horizon_radius());
          if (ray.supported() && ray.crossing_mino_time(0) < ray.end_mino_time()) {
            const GeodesicState y = ray.crossing_state(0);
            if (y[1] >= disk.r_in && y[1] <= disk.r_out) ++through_the_missing_half;
          }
          continue;
        }
        ++hits;
        EXPECT_GT(std::sin(a.state[3]), 0.0);
        EXPECT_NEAR(a.radius, b.radius, 1e-8 * b.radius);
      }
    std::printf("%s: %d hits on the half disk, %d rays through its missing half, %d differ\n", describe(c).c_str(),
                hits, through_the_missing_half, differ);
    EXPECT_GT(hits, 20) << describe(c);
    EXPECT_GT(through_the_missing_half, 20) << describe(c);
    EXPECT_LE(differ, pixels * pixels / 300) << describe(c);
  }
}

// ---- (e) the disk-light frame ----------------------------------------------------------------------------------

TEST(KerrDiskLight, OpaqueFrameIsTheClosedFormTracersDiskAndTransparentAddsTheOrdersBehind) {
  int behind_all = 0;  // pixels where a transparent disk shows more than the opaque one (none for the a = -0.9 case:
                       // its disk starts at the retrograde ISCO, 8.7 M, outside the radii its rays cross again at)
  DiskLight light;
  light.emissivity.index_inner = 3.0;
  light.redshift_power = 3.0;
  for (const CameraCase& c : {CameraCase{0.9, 1000.0, 1.3, 2.2}, CameraCase{0.9, 30.0, 0.5, 60.0},
                              CameraCase{0.0, 50.0, 1.2, 40.0}, CameraCase{-0.9, 20.0, 2.4, 70.0}}) {
    const KerrMetric metric{1.0, c.spin};
    const int pixels = 48;
    const Camera cam = camera_of(metric, c, pixels);
    const TraceSettings s = test_settings::settings_at(1e-10, 2000.0);
    ThinDisk disk;  // turning towards +phi: against the hole's spin for a < 0
    disk.r_in = exact::isco_radius(c.spin, c.spin >= 0.0 ? exact::Orbit::prograde : exact::Orbit::retrograde);
    disk.r_out = 25.0;
    const KerrDiskRays rays(metric, disk.r_in, disk.r_out, +1, s.escape_radius);
    light.transparent = false;
    const DiskLightFrame opaque = render_disk_light_frame(cam, rays, light);
    light.transparent = true;
    const DiskLightFrame clear = render_disk_light_frame(cam, rays, light);
    const auto closed = make_kerr_closed_form_tracer<Fehlberg78, IController>(
        metric, s, AngleCorrection::exact, make_scene(StarFieldSky{}, HorizonPaint{}, disk));
    const Image &a = opaque.frame.image, &b = clear.frame.image;
    int hits = 0, rings = 0, behind = 0, edges = 0;
    double worst = 0.0;
    for (int row = 0; row < pixels; ++row)
      for (int col = 0; col < pixels; ++col) {
        const std::size_t i = a.index(col, row);
        const RayOutcome o = closed.trace(cam.pixel_state(col, row));
        const PixelSample p = a.sample(col, row);
        // Not followed in closed form (vortical rays): the tracer falls back to an integration there.
        if (p.status == RayStatus::max_steps) continue;
        // Both follow the same closed form, but decide the disk's edges on radii computed apart (a hair).
        if (o.object != p.object) {
          const double r = o.object == kFirstSceneObject ? o.radius : disk.r_in;
          EXPECT_LT(std::min(std::abs(r / disk.r_in - 1.0), std::abs(r / disk.r_out - 1.0)), 1e-9) << describe(c);
          ++edges;
          continue;
        }
        EXPECT_EQ(p.status, o.status) << describe(c) << " pixel " << col << "," << row;
        EXPECT_EQ(p.order, o.status == RayStatus::hit ? o.order : -1) << describe(c) << " pixel " << col << "," << row;
        // Every order's channel sums to the total, in the frame's own float additions.
        for (const Image* im : {&a, &b}) {
          float sum = 0.0f;
          for (const char* name : kOrderIntensityChannels) sum += im->channel(name)[i];
          EXPECT_EQ(sum, im->channel("intensity")[i]);
        }
        if (o.status != RayStatus::hit) {
          EXPECT_EQ(a.channel("intensity")[i], 0.0f);
          continue;
        }
        ++hits;
        if (o.order >= 1) ++rings;
        const double expected = std::pow(o.redshift, 3.0) * std::pow(o.radius, -3.0);
        const float got = a.channel(kOrderIntensityChannels[static_cast<std::size_t>(std::min(o.order, 3))])[i];
        worst = std::max(worst, std::abs(static_cast<double>(got) / expected - 1.0));
        EXPECT_NEAR(got, expected, 1e-6 * expected) << describe(c) << " pixel " << col << "," << row;
        EXPECT_EQ(got, a.channel("intensity")[i]) << "an opaque disk shows one order";
        // A transparent disk shows the same first image and adds what lies behind it, never less.
        const auto first = static_cast<std::size_t>(std::min(o.order, 3));
        EXPECT_EQ(b.channel(kOrderIntensityChannels[first])[i] >= got, true);
        if (b.channel("intensity")[i] > got) ++behind;
      }
    std::printf(
        "%s: %d disk pixels (%d of order >= 1), %d edge pixels, %ld not followed; worst g^3 eps %.1e; "
        "transparent adds light at %d\n",
        describe(c).c_str(), hits, rings, edges, opaque.uncovered, worst, behind);
    EXPECT_GT(hits, 50) << describe(c);
    EXPECT_LE(edges, pixels * pixels / 400) << describe(c);
    behind_all += behind;
    EXPECT_LE(opaque.uncovered, pixels * pixels / 400) << describe(c);
    EXPECT_EQ(opaque.uncovered, opaque.frame.stats.count(RayStatus::max_steps));
  }
  EXPECT_GT(behind_all, 100);
}

}  // namespace
