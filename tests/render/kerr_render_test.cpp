// Kerr frames through the open scene layer, each judged against an exact reference:
//  (a) Kerr with a = 0 is Schwarzschild: same camera, same scene (disk included), same outcome per pixel;
//  (b) the Boyer-Lindquist and Kerr-Schild charts give the same sky map for the same camera (placed in BL
//      coordinates), static and ZAMO observers, a = 0.9 (the ZAMO is the Boyer-Lindquist one in both charts:
//      before make_camera defined observers in the spherical chart, the KS "ZAMO" was the observer normal to the
//      KS slices and this test saw sky directions 3 rad apart);
//  (c) the shadow seen from r = 1000 M against Bardeen's closed-form critical curve (a = 0.5, 0.94, 0.998;
//      inclinations 17, 60, 90 degrees): every ray more than one pixel from the curve is captured inside it and
//      escapes outside it, and the flattened edge lies on the side of the co-rotating photons;
//  (d) the Keplerian disk's redshift at each hit against g = 1 / (u^t (1 - Omega xi)) (BPT 1972) from the hit's own
//      conserved quantities, times the camera's factor, prograde and retrograde, a = 0.9;
//  (e) cameras the geometry forbids are refused with messages that say why; ZAMO = static for a = 0.
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace kerr_render_test {

using namespace grtrace;

namespace {

constexpr double kPi = std::numbers::pi;
using Tableau = DormandPrince54;
using Control = PIController;

/// Trace settings with rtol (atol = rtol / 100) and the sky sphere at `sky`.
TraceSettings settings(double sky, double rtol = 1e-10) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-2 * rtol};
  s.escape_radius = sky;
  return s;
}

RenderOptions quiet() {
  RenderOptions o;
  o.progress = ProgressMode::never;
  return o;
}

/// A camera spec at Boyer-Lindquist (r, theta in degrees, phi = 0), looking at the hole, north up.
CameraSpec bl_camera(double r, double theta_deg, int size, double fov, ObserverKind observer) {
  CameraSpec spec;
  spec.position = Vec4(0.0, r, theta_deg * kPi / 180.0, 0.0);
  spec.spherical_position = true;
  spec.observer = observer;
  spec.width = spec.height = size;
  spec.fov_degrees = fov;
  return spec;
}

/// Message of the std::invalid_argument that f throws ("" when it throws none).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// ---- (a) a = 0 is Schwarzschild ------------------------------------------------------------------------------

TEST(KerrFrame, ZeroSpinEqualsSchwarzschildPixelByPixel) {
  const SchwarzschildMetric schw{1.0};
  const KerrMetric kerr = KerrMetric::checked(1.0, 0.0);
  StandardSceneSpec preset;
  preset.name = "disk";  // sky, horizon and a Keplerian disk: three objects and three kinds of emitter
  const CameraSpec spec = bl_camera(40.0, 80.0, 28, 60.0, ObserverKind::static_observer);
  const Camera cs = make_camera(schw, spec), ck = make_camera(kerr, spec);
  const auto ts = make_general_tracer<Tableau, Control>(schw, settings(400.0, 1e-12), AngleCorrection::flat,
                                                        disk_scene(preset));
  const auto tk = make_general_tracer<Tableau, Control>(kerr, settings(400.0, 1e-12), AngleCorrection::flat,
                                                        disk_scene(preset));
  const Frame fs = render_frame(cs, ts, quiet()), fk = render_frame(ck, tk, quiet());
  EXPECT_EQ(fs.image.channel("object"), fk.image.channel("object"));
  double worst_dir = 0.0, worst_z = 0.0;
  long hits = 0, escaped = 0, captured = 0;
  for (int row = 0; row < cs.height(); ++row)
    for (int col = 0; col < cs.width(); ++col) {
      const RayOutcome a = ts.trace(cs.pixel_state(col, row)), b = tk.trace(ck.pixel_state(col, row));
      ASSERT_EQ(a.object, b.object) << col << "," << row;
      worst_z = std::max(worst_z, std::abs(a.redshift - b.redshift) / std::abs(a.redshift));
      if (a.status == RayStatus::escaped) worst_dir = std::max(worst_dir, angular_distance(a.where, b.where));
      hits += a.status == RayStatus::hit;
      escaped += a.status == RayStatus::escaped;
      captured += a.status == RayStatus::captured;
    }
  std::printf("a = 0 vs Schwarzschild (28x28, rtol 1e-12): %ld hit, %ld escaped, %ld captured; worst direction "
              "%.2e rad, worst redshift %.2e (relative)\n",
              hits, escaped, captured, worst_dir, worst_z);
  EXPECT_GT(hits, 50);
  EXPECT_GT(escaped, 50);
  EXPECT_GT(captured, 10);
  EXPECT_LT(worst_dir, 1e-9);
  EXPECT_LT(worst_z, 1e-9);
}

// ---- (b) Boyer-Lindquist and Kerr-Schild ---------------------------------------------------------------------

TEST(KerrFrame, BoyerLindquistAndKerrSchildGiveTheSameSkyMap) {
  const double spin = 0.9, sky = 400.0;
  const KerrMetric bl = KerrMetric::checked(1.0, spin);
  KerrSchildMetric ks = KerrSchildMetric::checked(1.0, spin);
  ks.slicing = KerrSchildSlicing::outgoing;  // camera rays are past-directed (named_metrics.hpp does the same)
  StandardSceneSpec preset;  // checker: sky and horizon
  for (ObserverKind observer : {ObserverKind::static_observer, ObserverKind::zamo}) {
    const CameraSpec spec = bl_camera(25.0, 70.0, 32, 50.0, observer);
    const Camera cb = make_camera(bl, spec), ck = make_camera(ks, spec);
    const auto tb = make_general_tracer<Tableau, Control>(bl, settings(sky), AngleCorrection::flat,
                                                          background_scene(preset));
    const auto tk = make_general_tracer<Tableau, Control>(ks, settings(sky), AngleCorrection::flat,
                                                          background_scene(preset));
    long silhouettes = 0, escaped = 0, captured = 0;
    double worst_where = 0.0, worst_state = 0.0, worst_z = 0.0;
    for (int row = 0; row < cb.height(); ++row)
      for (int col = 0; col < cb.width(); ++col) {
        const RayOutcome a = tb.trace(cb.pixel_state(col, row)), b = tk.trace(ck.pixel_state(col, row));
        ASSERT_FALSE(is_failure(a.status) || is_failure(b.status)) << col << "," << row;
        if (a.object != b.object) {
          ++silhouettes;  // a ray grazing the shadow's edge, decided differently by the two charts' step sequences
          continue;
        }
        if (a.status != RayStatus::escaped) {
          ++captured;
          continue;
        }
        ++escaped;
        // The frame's own sky directions: the flat continuation of the chart's embedded velocity at r = 400 M.
        // The charts' embeddings differ there (x + i y = (r - i a) sin th e^{i phi_KS}, phi_KS - phi_BL = -a int
        // dr / Delta), which the flat correction does not remove: this part is chart-dependent, not an error of
        // either trace.
        worst_where = std::max(worst_where, angular_distance(a.where, b.where));
        // The same end state mapped to Boyer-Lindquist and continued the same way: the traces themselves.
        const SkyDirection bk = continued_direction(bl, ks_to_bl(ks, b.state), ks_to_bl(ks, b.state),
                                                    AngleCorrection::flat);
        const SkyDirection bb = continued_direction(bl, a.state, a.state, AngleCorrection::flat);
        worst_state = std::max(worst_state, angular_distance(bb, bk));
        worst_z = std::max(worst_z, std::abs(a.redshift - b.redshift) / a.redshift);
      }
    std::printf("BL vs KS (a = 0.9, r = 25, %s, 32x32): %ld escaped, %ld captured, %ld silhouette pixels; frame "
                "directions %.2e rad, end states in BL %.2e rad, sky redshift %.2e\n",
                observer == ObserverKind::zamo ? "zamo" : "static", escaped, captured, silhouettes, worst_where,
                worst_state, worst_z);
    EXPECT_GT(captured, 30);
    EXPECT_GT(escaped, 500);
    EXPECT_LE(silhouettes, 2);
    EXPECT_LT(worst_state, 5e-7);   // measured 9.0e-8 (static), 1.4e-8 (ZAMO) at rtol 1e-10
    EXPECT_LT(worst_where, 2e-5);   // measured 5.8e-6 (both observers)
    EXPECT_LT(worst_z, 1e-8);
  }
}

// ---- (c) the shadow against Bardeen's critical curve ---------------------------------------------------------

/// Bardeen's critical curve as a closed polygon in the (alpha, beta) plane: upper branch from r1 to r2, lower
/// branch back (critical_curve returns the +beta and -beta points of each radius in turn).
std::vector<std::array<double, 2>> critical_polygon(double spin, double inclination) {
  const auto pts = exact::critical_curve(spin, inclination, 600);
  std::vector<std::array<double, 2>> poly;
  for (std::size_t i = 0; i < pts.size(); i += 2) poly.push_back({pts[i].alpha, pts[i].beta});
  for (std::size_t i = pts.size(); i >= 2; i -= 2) poly.push_back({pts[i - 1].alpha, pts[i - 1].beta});
  return poly;
}

/// True when (a, b) lies inside the closed polygon (even-odd rule).
bool inside(const std::vector<std::array<double, 2>>& poly, double a, double b) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& p = poly[i];
    const auto& q = poly[j];
    if ((p[1] > b) != (q[1] > b) && a < (q[0] - p[0]) * (b - p[1]) / (q[1] - p[1]) + p[0]) in = !in;
  }
  return in;
}

/// Distance from (a, b) to the polygon's edges.
double distance_to(const std::vector<std::array<double, 2>>& poly, double a, double b) {
  double best = 1e300;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const double ex = poly[i][0] - poly[j][0], ey = poly[i][1] - poly[j][1];
    const double len2 = ex * ex + ey * ey;
    const double t = len2 > 0.0 ? std::clamp(((a - poly[j][0]) * ex + (b - poly[j][1]) * ey) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(a - poly[j][0] - t * ex, b - poly[j][1] - t * ey));
  }
  return best;
}

/// The celestial coordinates of a ray from its constants of motion: alpha = -xi / sin i, |beta| =
/// sqrt(eta + a^2 cos^2 i - xi^2 cot^2 i) (Bardeen 1973). Whether a ray that starts inward from far away is captured
/// depends on (xi, eta) alone, so these coordinates judge the trace exactly, whatever the camera's projection.
std::array<double, 2> celestial(const KerrMetric& m, const GeodesicState& y0, double inclination) {
  const double e = m.energy(y0), xi = m.angular_momentum(y0) / e, eta = m.carter_constant(y0) / (e * e);
  const double si = std::sin(inclination), ci = std::cos(inclination);
  const double b2 = eta + m.spin * m.spin * ci * ci - xi * xi * ci * ci / (si * si);
  return {-xi / si, std::sqrt(std::max(0.0, b2))};
}

TEST(KerrShadow, DistantObserverSeesBardeensCriticalCurve) {
  const double r_obs = 1000.0;
  constexpr int kSize = 128;          // the frame whose pixels "one pixel" refers to
  const double half_width = 8.0;      // M across half the frame at the hole: pixel = 16 M / 127
  const double fov = 2.0 * std::atan(half_width / r_obs) * 180.0 / kPi;
  const double pixel = 2.0 * half_width / (kSize - 1);
  long judged = 0, wrong = 0;
  for (double spin : {0.5, 0.94, 0.998}) {
    for (double incl_deg : {17.0, 60.0, 90.0}) {
      const double incl = incl_deg * kPi / 180.0;
      const KerrMetric m = KerrMetric::checked(1.0, spin);
      const Camera cam = make_camera(m, bl_camera(r_obs, incl_deg, kSize, fov, ObserverKind::static_observer));
      const auto tracer = make_general_tracer<Tableau, Control>(m, settings(2.0 * r_obs, 1e-10),
                                                                AngleCorrection::flat, background_scene({}));
      // Which way +alpha (+phi) runs on the picture: the sign of the camera's right axis along d_phi.
      const double right = cam.tetrad().e[3].dot(m.metric(cam.position()) * Vec4::Unit(3)) < 0.0 ? 1.0 : -1.0;
      const double centre = 0.5 * (kSize - 1);
      // Pixel (fractional) at celestial offset (alpha, beta) from the hole, to first order in M / r_obs.
      auto pixel_of = [&](double alpha, double beta) {
        return std::array<double, 2>{centre + right * alpha / pixel, centre - beta / pixel};
      };
      auto captured = [&](double col, double row) {
        const RayOutcome o = tracer.trace(cam.pixel_state(col, row));
        EXPECT_FALSE(is_failure(o.status)) << col << "," << row;
        return o.status == RayStatus::captured;
      };
      const auto poly = critical_polygon(spin, incl);
      double a_min = 1e300, a_max = -1e300;
      for (const auto& p : poly) {
        a_min = std::min(a_min, p[0]);
        a_max = std::max(a_max, p[0]);
      }
      const double a_mid = 0.5 * (a_min + a_max);
      // Rays along 32 directions from the shadow's middle, 1.5 and 3 pixels inside and outside the curve.
      for (int k = 0; k < 32; ++k) {
        const double psi = 2.0 * kPi * (k + 0.25) / 32.0, c = std::cos(psi), s = std::sin(psi);
        double lo = 0.0, hi = 20.0;  // the curve's radius from the middle along psi, by bisection on `inside`
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (lo + hi);
          (inside(poly, a_mid + mid * c, mid * s) ? lo : hi) = mid;
        }
        for (double off : {-3.0, -1.5, 1.5, 3.0}) {
          const double rho = lo + off * pixel;
          const auto px = pixel_of(a_mid + rho * c, rho * s);
          const auto ab = celestial(m, cam.pixel_state(px[0], px[1]), incl);
          if (distance_to(poly, ab[0], ab[1]) <= pixel) continue;  // within one pixel: not judged
          ++judged;
          const bool expect_in = inside(poly, ab[0], ab[1]), got_in = captured(px[0], px[1]);
          if (expect_in != got_in) ++wrong;
          EXPECT_EQ(expect_in, got_in) << "a = " << spin << ", i = " << incl_deg << ", psi = " << psi
                                       << ", alpha = " << ab[0] << ", beta = " << ab[1];
        }
      }
      // The edges on the line beta = 0 (the picture's middle row), by bisection in the column, and the half-height
      // of the shadow 0.6 M inside each edge: the co-rotating side (alpha < 0 for a > 0) is the flattened one.
      auto edge = [&](double col_in, double col_out) {
        for (int it = 0; it < 14; ++it) {
          const double mid = 0.5 * (col_in + col_out);
          (captured(mid, centre) ? col_in : col_out) = mid;
        }
        return celestial(m, cam.pixel_state(col_in, centre), incl)[0];
      };
      const double mid_col = pixel_of(a_mid, 0.0)[0];
      const double edge_co = edge(mid_col, pixel_of(a_min - 3.0, 0.0)[0]);
      const double edge_counter = edge(mid_col, pixel_of(a_max + 3.0, 0.0)[0]);
      EXPECT_NEAR(edge_co, a_min, pixel) << "a = " << spin << ", i = " << incl_deg;
      EXPECT_NEAR(edge_counter, a_max, pixel) << "a = " << spin << ", i = " << incl_deg;
      auto height = [&](double alpha) {  // traced half-height at alpha, and the curve's
        const double col = pixel_of(alpha, 0.0)[0];
        double in = centre, out = pixel_of(alpha, 8.0)[1];
        for (int it = 0; it < 14; ++it) {
          const double mid = 0.5 * (in + out);
          (captured(col, mid) ? in : out) = mid;
        }
        double lo = 0.0, hi = 10.0;
        for (int it = 0; it < 60; ++it) (inside(poly, alpha, 0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
        return std::array<double, 2>{celestial(m, cam.pixel_state(col, in), incl)[1], lo};
      };
      const auto h_co = height(a_min + 0.6), h_counter = height(a_max - 0.6);
      // Judged by the traced edge point's distance to the curve (its alpha is that of the column, to O(M / r)).
      EXPECT_LT(distance_to(poly, a_min + 0.6, h_co[0]), pixel) << "a = " << spin << ", i = " << incl_deg;
      EXPECT_LT(distance_to(poly, a_max - 0.6, h_counter[0]), pixel) << "a = " << spin << ", i = " << incl_deg;
      if (h_co[1] - h_counter[1] > 2.0 * pixel) {
        EXPECT_GT(h_co[0], h_counter[0]);
      }
      std::printf("a = %.3f, i = %2.0f deg: edges alpha %.4f (curve %.4f) and %.4f (curve %.4f); half-height 0.6 M "
                  "inside them %.3f (curve %.3f) co-rotating, %.3f (curve %.3f) counter-rotating; pixel %.3f M\n",
                  spin, incl_deg, edge_co, a_min, edge_counter, a_max, h_co[0], h_co[1], h_counter[0], h_counter[1],
                  pixel);
    }
  }
  std::printf("shadow: %ld rays judged (more than one pixel from the curve), %ld on the wrong side\n", judged, wrong);
  EXPECT_GT(judged, 9 * 100);
}

TEST(KerrShadow, FlatteningIsOnTheCoRotatingSideOfThePicture) {
  // The same hole spun the other way mirrors the picture: the flattened edge follows the rotation, it is not a
  // fixed side of the frame. a = +-0.998, i = 90 degrees: along the middle row, the captured run of pixels lies
  // nearer the co-rotating side, where the hole's surface approaches the camera.
  const double r_obs = 1000.0, half_width = 8.0;
  constexpr int kSize = 65;
  const double fov = 2.0 * std::atan(half_width / r_obs) * 180.0 / kPi;
  double shift[2] = {0.0, 0.0};
  for (int n = 0; n < 2; ++n) {
    const double spin = n == 0 ? 0.998 : -0.998;
    const KerrMetric m = KerrMetric::checked(1.0, spin);
    const Camera cam = make_camera(m, bl_camera(r_obs, 90.0, kSize, fov, ObserverKind::static_observer));
    const auto tracer = make_general_tracer<Tableau, Control>(m, settings(2.0 * r_obs, 1e-9), AngleCorrection::flat,
                                                              background_scene({}));
    double sum_col = 0.0, count = 0.0, xi_first = 0.0;
    const int row = kSize / 2;
    for (int col = 0; col < kSize; ++col) {
      const GeodesicState y0 = cam.pixel_state(col, row);
      if (tracer.trace(y0).status != RayStatus::captured) continue;
      sum_col += col;
      count += 1.0;
      if (count == 1.0) xi_first = m.angular_momentum(y0) / m.energy(y0);
    }
    ASSERT_GT(count, 10.0);
    // Mean column of the shadow relative to the centre, signed so that + points to the co-rotating side
    // (where the leftmost captured pixel's xi has the hole's sign, the left side is co-rotating).
    const double co_left = (xi_first * spin > 0.0) ? 1.0 : -1.0;
    shift[n] = co_left * ((kSize - 1) / 2.0 - sum_col / count);
    std::printf("a = %+.3f: shadow's mean column %.2f (centre %d), xi at its left edge %.3f\n", spin, sum_col / count,
                (kSize - 1) / 2, xi_first);
  }
  // The shadow is displaced away from the co-rotating side: the co-rotating edge is the near, flattened one.
  // Bardeen: alpha in [-2.0, 6.99] for a = 0.998 at i = 90, middle 2.5 M ~ 10 pixels of 0.25 M.
  EXPECT_LT(shift[0], -5.0);
  EXPECT_LT(shift[1], -5.0);
}

// ---- (d) the disk's redshift against BPT ----------------------------------------------------------------------

// The same Keplerian disk drawn in Kerr-Schild (ThinDisk in a Cartesian chart: the plane z = 0 between the quadric's
// radii, the Boyer-Lindquist orbits pushed forward) and in Boyer-Lindquist: the same pixels hit it, at the same
// radius and with the same redshift, prograde and retrograde, a = 0.9; and the Kerr-Schild hits' redshifts against
// the Keplerian closed form g = 1 / (u^t (1 - Omega L_z / E)) from the hit's own conserved quantities.
TEST(KerrDisk, KerrSchildDrawsTheSameDiskAsBoyerLindquist) {
  const double spin = 0.9, sky = 400.0;
  const KerrMetric bl = KerrMetric::checked(1.0, spin);
  const KerrSchildMetric ks = kerr_schild_for_camera_rays(1.0, spin);
  for (const int sense : {+1, -1}) {
    StandardSceneSpec preset;
    preset.name = "disk";
    preset.disk.sense = sense;
    preset.disk.r_in = exact::isco_radius(spin, sense > 0 ? exact::Orbit::prograde : exact::Orbit::retrograde);
    preset.disk.r_out = 20.0;
    check_disk_orbits(ks, preset.disk);  // the Boyer-Lindquist checks, through the chart's spherical_chart()
    const CameraSpec spec = bl_camera(40.0, 75.0, 40, 45.0, ObserverKind::zamo);
    const Camera cb = make_camera(bl, spec), ck = make_camera(ks, spec);
    const auto tb = make_general_tracer<Tableau, Control>(bl, settings(sky), AngleCorrection::flat, disk_scene(preset));
    const auto tk = make_general_tracer<Tableau, Control>(ks, settings(sky), AngleCorrection::flat, disk_scene(preset));
    long hits = 0, silhouettes = 0;
    double worst_r = 0.0, worst_g = 0.0, worst_kepler = 0.0;
    for (int row = 0; row < cb.height(); ++row)
      for (int col = 0; col < cb.width(); ++col) {
        const RayOutcome a = tb.trace(cb.pixel_state(col, row)), b = tk.trace(ck.pixel_state(col, row));
        ASSERT_FALSE(is_failure(a.status) || is_failure(b.status)) << col << "," << row;
        if (a.object != b.object) {
          ++silhouettes;
          continue;
        }
        if (a.object < kFirstSceneObject) continue;
        ++hits;
        EXPECT_NEAR(b.state[3], 0.0, 1e-9) << "a Kerr-Schild hit lies in z = 0";
        worst_r = std::max(worst_r, std::abs(b.radius / a.radius - 1.0));
        worst_g = std::max(worst_g, std::abs(b.redshift / a.redshift - 1.0));
        // Keplerian closed form at the KS hit: Omega = sense / (r^(3/2) + sense a), u^t from g(u, u) = 1 in BL.
        const GeodesicState y = ks_to_bl(ks, b.state);
        const double r = y[1], omega = sense / (std::pow(r, 1.5) + sense * spin);
        const Mat4 g = bl.metric(y.head<4>());
        const double ut = 1.0 / std::sqrt(g(0, 0) + 2.0 * g(0, 3) * omega + g(3, 3) * omega * omega);
        const double e = ks.energy(b.state), lz = ks.angular_momentum(b.state);
        // The camera's pixel momentum has g(e_0, k) = -1, so the redshift is 1 / (u . p) with p = -k at the hit.
        const double kepler = -1.0 / (ut * (e - omega * lz));
        worst_kepler = std::max(worst_kepler, std::abs(b.redshift / kepler - 1.0));
      }
    std::printf("KS vs BL disk (a = 0.9, sense %+d, 40x40): %ld hits, %ld silhouette pixels; radius %.2e, redshift "
                "%.2e, Keplerian closed form %.2e (relative)\n",
                sense, hits, silhouettes, worst_r, worst_g, worst_kepler);
    EXPECT_GT(hits, 100);
    EXPECT_LE(silhouettes, 8);
    EXPECT_LT(worst_r, 1e-6);
    EXPECT_LT(worst_g, 1e-7);
    EXPECT_LT(worst_kepler, 1e-9);
  }
}

TEST(KerrDisk, RedshiftAtEveryHitMatchesKeplerianClosedForm) {
  const double spin = 0.9;
  const KerrMetric m = KerrMetric::checked(1.0, spin);
  for (exact::Orbit orbit : {exact::Orbit::prograde, exact::Orbit::retrograde}) {
    StandardSceneSpec preset;
    preset.name = "disk";
    preset.disk.sense = orbit == exact::Orbit::prograde ? +1 : -1;  // a > 0: prograde turns towards +phi
    preset.disk.r_in = exact::isco_radius(spin, orbit);
    preset.disk.r_out = 20.0;
    check_disk_orbits(m, preset.disk);
    for (ObserverKind observer : {ObserverKind::static_observer, ObserverKind::zamo}) {
      const Camera cam = make_camera(m, bl_camera(50.0, 80.0, 40, 60.0, observer));
      const auto tracer = make_general_tracer<Tableau, Control>(m, settings(400.0), AngleCorrection::exact,
                                                                disk_scene(preset));
      long hits = 0;
      double worst = 0.0, g_min = 1e300, g_max = 0.0;
      for (int row = 0; row < cam.height(); ++row)
        for (int col = 0; col < cam.width(); ++col) {
          const GeodesicState y0 = cam.pixel_state(col, row);
          const RayOutcome o = tracer.trace(y0);
          if (o.status != RayStatus::hit) continue;
          ++hits;
          const GeodesicState& y = o.state;
          // Received at infinity: g_inf = 1 / (u^t (1 - Omega xi)), xi = L_z / E of the photon at the hit.
          const double xi = m.angular_momentum(y) / m.energy(y);
          const double g_inf = exact::keplerian_redshift(y[1], xi, spin, orbit);
          // The camera at r = 50 measures the photon's energy as -g(e_0, k) = 1 against E_inf = -p_t (k is
          // past-directed): f_cam / f_inf = 1 / (-E).
          const double g = g_inf / (-m.energy(y0));
          worst = std::max(worst, std::abs(o.redshift - g) / g);
          g_min = std::min(g_min, o.redshift);
          g_max = std::max(g_max, o.redshift);
        }
      std::printf("disk a = 0.9 %s (r_in = %.4f), %s camera: %ld hits, g in [%.3f, %.3f], worst relative %.2e\n",
                  orbit == exact::Orbit::prograde ? "prograde" : "retrograde", preset.disk.r_in,
                  observer == ObserverKind::zamo ? "zamo" : "static", hits, g_min, g_max, worst);
      EXPECT_GT(hits, 120);
      EXPECT_LT(worst, 1e-10);
      EXPECT_GT(g_max, 1.0);  // the approaching side is blueshifted
      EXPECT_LT(g_min, 0.7);  // the receding side and the inner edge are redshifted
    }
  }
}

// ---- (e) cameras the geometry forbids ---------------------------------------------------------------------------

TEST(KerrCamera, RefusesWhatTheGeometryForbids) {
  const KerrMetric m = KerrMetric::checked(1.0, 0.9);  // r_+ = 1.436, r_E(90 deg) = 2
  KerrSchildMetric ks = KerrSchildMetric::checked(1.0, 0.9);
  ks.slicing = KerrSchildSlicing::outgoing;
  // Static observer inside the ergosphere (r = 1.8 < 2 on the equator): refused in both charts, saying why.
  for (const std::string& msg :
       {refusal([&] { make_camera(m, bl_camera(1.8, 90.0, 4, 60.0, ObserverKind::static_observer)); }),
        refusal([&] { make_camera(ks, bl_camera(1.8, 90.0, 4, 60.0, ObserverKind::static_observer)); })}) {
    EXPECT_NE(msg.find("ergosphere"), std::string::npos) << msg;
    EXPECT_NE(msg.find("zamo"), std::string::npos) << msg;  // and what to do instead
  }
  // ... while the ZAMO exists there, and a static observer just outside the static limit.
  EXPECT_NO_THROW(make_camera(m, bl_camera(1.8, 90.0, 4, 60.0, ObserverKind::zamo)));
  EXPECT_NO_THROW(make_camera(ks, bl_camera(1.8, 90.0, 4, 60.0, ObserverKind::zamo)));
  EXPECT_NO_THROW(make_camera(m, bl_camera(2.01, 90.0, 4, 60.0, ObserverKind::static_observer)));
  // Near the pole the static limit is lower: r = 1.8 at theta = 10 degrees is outside it (r_E = 1.46).
  EXPECT_LT(m.ergosphere_radius(10.0 * kPi / 180.0), 1.8);
  EXPECT_NO_THROW(make_camera(m, bl_camera(1.8, 10.0, 4, 60.0, ObserverKind::static_observer)));
  // Inside the outer horizon: refused for every observer.
  for (ObserverKind obs : {ObserverKind::static_observer, ObserverKind::zamo}) {
    const std::string msg = refusal([&] { make_camera(m, bl_camera(1.2, 60.0, 4, 60.0, obs)); });
    EXPECT_NE(msg.find("horizon"), std::string::npos) << msg;
  }
  // |a| >= M and a NaN spin make no black hole.
  for (double a : {1.0, -1.0, 1.5, std::nan("")}) {
    EXPECT_NE(refusal([&] { (void)KerrMetric::checked(1.0, a); }).find("|a| < M"), std::string::npos) << a;
    EXPECT_NE(refusal([&] { (void)KerrSchildMetric::checked(1.0, a); }), "") << a;
    MetricSpec spec;
    spec.name = "kerr";
    spec.spin = a;
    EXPECT_NE(refusal([&] { check_metric_spec(spec); }).find("--spin"), std::string::npos) << a;
  }
}

TEST(KerrCamera, ZamoIsTheStaticObserverWithoutSpin) {
  const KerrMetric m = KerrMetric::checked(1.0, 0.0);
  for (double theta : {30.0, 90.0, 150.0}) {
    const Camera s = make_camera(m, bl_camera(7.0, theta, 4, 60.0, ObserverKind::static_observer));
    const Camera z = make_camera(m, bl_camera(7.0, theta, 4, 60.0, ObserverKind::zamo));
    for (std::size_t a = 0; a < 4; ++a)
      EXPECT_LT((s.tetrad().e[a] - z.tetrad().e[a]).norm(), 1e-14) << "theta " << theta << ", e" << a;
  }
  // With spin they differ by the frame dragging: the ZAMO turns with omega = 2 M a r / A.
  const KerrMetric spun = KerrMetric::checked(1.0, 0.9);
  const Camera z = make_camera(spun, bl_camera(7.0, 90.0, 4, 60.0, ObserverKind::zamo));
  const Vec4 u = z.tetrad().e[0];
  EXPECT_NEAR(u[3] / u[0], spun.frame_dragging(7.0, kPi / 2.0), 1e-14);
}

}  // namespace

}  // namespace kerr_render_test
