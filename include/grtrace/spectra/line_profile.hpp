// grtrace/spectra/line_profile.hpp
// The line profile of a thin disk: the flux a distant observer receives per energy bin from a line emitted at one
// energy by gas on circular orbits, integrated over the image plane on an adaptive mesh (not a histogram of a
// frame's pixels), in total and by image order n = 0, 1, 2, >= 3.
//
// Takes:   a disk map (the DiskMap concept below: a screen point (alpha, beta) in units of M -> the crossings of
//          its ray with the equatorial plane, each with its radius and redshift g = E_obs / E_emit), a
//          LineProfileSpec (the line's rest energy, the energy bins, the emissivity, opaque or transparent disk)
//          and a LineSampling (how fine the mesh may go). KerrDiskMap gives the map of a Kerr (or Schwarzschild:
//          spin 0) hole from the closed-form rays (exact/kerr_null_geodesic.hpp), for a static camera at any radius.
// Returns: a LineProfile: per bin the energy flux per unit energy, F_E = (1 / dE) int_bin dE int dalpha dbeta
//          I_E, which for a line of rest energy E_0 and emitted intensity eps(r) (gas frame) is
//            F_bin = (1 / dE) int g^4 eps(r) [g E_0 in bin] dalpha dbeta          (I_E / E^3 is invariant),
//          in units of eps times M^2 times the energy unit (a distant observer's flux times D^2 / M^2); the same
//          split by order (the bins of the four orders sum to the total); the flux that fell outside the bins;
//          how many rays and triangles it took.
// Method:  the image square is cut into right triangles; each is split in four (at its edges' midpoints) while its
//          three corners disagree about what their rays see (escaped or captured, and for every order: the disk,
//          inside its inner edge, or nothing), or while g or the weight g^4 eps J departs from linear by more than
//          the tolerance at the midpoints, down to a finest cell. On a settled triangle g and the weight are
//          linear, and the flux with g in [t1, t2] is exact for them: the triangle clipped by the lines g = t is a
//          triangle or a quadrilateral, the integral of a linear weight over it its area times the mean of its
//          corners (clipped_weight below). A triangle left mixed at the finest cell contributes its lit corners
//          with zero weight at the dark ones (first order in the cell's size, along the disk's edges only).
//          This is the adaptive sampling of the image plane by order that Cardenas-Avendano, Lupsasca & Zhu (AART,
//          2023) use for each lensing band; the line profile itself is Laor's (ApJ 376, 90, 1991) observable.
// Assumes: the observer is far enough that the screen coordinates alpha = r_o x, beta = r_o y of the camera's
//          tangent plane (x, y) are the impact parameters (J = (1 + x^2 + y^2)^-3/2 turns them into the solid
//          angle times r_o^2, exact for any r_o); the disk's image lies inside the square (checked: the square grows
//          until no ray on its rim sees the disk).
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/exact/kerr_null_geodesic.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/spectra/line_profile_result.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace grtrace {

/// The line's intensity in the gas's frame: a broken power law eps(r) = r^-q_inner inside r_break and
/// r_break^(q_outer - q_inner) r^-q_outer outside (continuous there). A plain power law: r_break = infinity.
struct LineEmissivity {
  double index_inner = 3.0;
  double index_outer = 3.0;
  double r_break = std::numeric_limits<double>::infinity();

  double operator()(double r) const {
    return r < r_break ? std::pow(r, -index_inner)
                       : std::pow(r_break, index_outer - index_inner) * std::pow(r, -index_outer);
  }
};

/// What to compute: the line, the bins and the disk's opacity.
struct LineProfileSpec {
  double line_energy = 6.4;  ///< in the gas's frame (any unit: the bins are in the same, keV for iron K-alpha)
  double energy_min = 0.0;   ///< the bins' range; both 0: around the energies the light arrives at
  double energy_max = 0.0;
  int bins = 200;
  LineEmissivity emissivity;
  /// false: the first crossing inside the disk's radii emits and ends the ray (an opaque disk); true: every
  /// crossing inside them emits and the ray goes on (an optically thin disk: AART's model).
  bool transparent = false;
};

/// How fine the image-plane mesh may go (lengths on the screen in units of the hole's mass M).
struct LineSampling {
  int base_cells = 64;        ///< cells per side of the image square to start with
  double central_cell = 1.0;  ///< cells within 12 M of the centre (the shadow and the n >= 1 rings) at most this big
  double finest_cell = 1.0 / 64.0;  ///< no triangle smaller
  /// g's departure from linear at a triangle's midpoints, in bins (times the bin's width over the line energy),
  /// and the weight's, relative: a triangle within both is settled
  double g_tolerance = 0.03;
  double weight_tolerance = 2e-3;
  /// A triangle on the disk's edge is split no further once its area times its brightest corner's weight is below
  /// this fraction of the disk's Newtonian flux 2 pi int eps r dr
  double edge_tolerance = 1e-7;
};

/// One ray's crossings of the equatorial plane, as a disk sees them.
struct DiskRaySample {
  static constexpr int kOrders = 6;  ///< crossings followed; higher orders carry < 1e-8 of the flux
  enum Where : signed char { nothing = 0, inside_edge = 1, on_disk = 2 };
  bool escaped = false;
  bool covered = true;                 ///< false: the map could not follow this ray (counted, seen as nothing)
  std::array<Where, kOrders> where{};  ///< nothing: no crossing, or beyond the outer edge
  std::array<double, kOrders> radius{}, redshift{};
};

template <class M>
concept DiskMap = requires(const M& map, double alpha, double beta) {
  { map.sample(alpha, beta) } -> std::same_as<DiskRaySample>;
  { map.r_in() } -> std::convertible_to<double>;
  { map.r_out() } -> std::convertible_to<double>;
  { map.camera_radius() } -> std::convertible_to<double>;
  { map.mass() } -> std::convertible_to<double>;  ///< the screen's lengths (LineSampling's cells) scale with it
};

/// The disk map of a Kerr hole (Boyer-Lindquist; spin 0: Schwarzschild) seen by a static camera at (r_o, theta_o):
/// each screen point's ray in closed form, its crossings' radii by one Jacobi function each and the redshift
/// against gas on Keplerian circular orbits (exact/kerr_exact.hpp's u^t and Omega: Bardeen, Press & Teukolsky 1972;
/// sense +1 towards +phi) from the ray's conserved k_t and k_phi: g = -1 / (u^t (k_t + Omega k_phi)), k scaled to
/// unit energy at the camera.
class KerrDiskMap {
 public:
  /// Throws std::invalid_argument (what to change) for a disk not outside the photon orbit of its sense (no
  /// circular orbit inside it), r_out <= r_in, a camera not outside the disk or on the axis (theta_o within 1e-4
  /// rad of it).
  KerrDiskMap(KerrMetric metric, double camera_r, double camera_theta, double r_in, double r_out, int sense = +1)
      : metric_(metric),
        r_in_(r_in),
        r_out_(r_out),
        orbit_((sense >= 0) == (metric.spin >= 0.0) ? exact::Orbit::prograde : exact::Orbit::retrograde) {
    const double photon_orbit = exact::photon_orbit_radius(metric.spin, orbit_, metric.mass);
    if (!(r_in > photon_orbit) || !(r_out > r_in) || !std::isfinite(r_out))
      throw std::invalid_argument("line profile: the disk needs photon orbit (" + std::to_string(photon_orbit) +
                                  " M for its sense) < r_in < r_out (finite), got r_in = " + std::to_string(r_in) +
                                  ", r_out = " + std::to_string(r_out));
    if (!(camera_r > 10.0 * r_out) || !std::isfinite(camera_r))
      throw std::invalid_argument("line profile: the camera must be far from the disk (r_o > 10 r_out); got r_o = " +
                                  std::to_string(camera_r));
    if (!(std::sin(camera_theta) > 1e-4))
      throw std::invalid_argument("line profile: the inclination must be off the axis (more than 1e-4 rad from it)");
    CameraSpec spec;
    spec.position = Vec4(0.0, camera_r, camera_theta, 0.0);
    spec.width = spec.height = 1;
    const Camera camera = make_camera(metric, spec);
    x0_ = camera.position();
    tetrad_ = camera.tetrad();
    r_o_ = camera_r;
    sky_ = 10.0 * camera_r;
    guard_ = (1.0 + 1e-6) * metric.horizon_radius();
  }

  double r_in() const { return r_in_; }
  double r_out() const { return r_out_; }
  double camera_radius() const { return r_o_; }
  double mass() const { return metric_.mass; }

  /// The ray of the screen point (alpha, beta) (M; beta towards the hole's north pole, alpha to the right).
  GeodesicState ray(double alpha, double beta) const {
    const double x = alpha / r_o_, y = beta / r_o_, n = std::sqrt(1.0 + x * x + y * y);
    const Vec4 k = (1.0 / n) * tetrad_.e[1] + (y / n) * tetrad_.e[2] + (x / n) * tetrad_.e[3] - tetrad_.e[0];
    return make_state(x0_, k);
  }

  DiskRaySample sample(double alpha, double beta) const {
    DiskRaySample s;
    const GeodesicState y0 = ray(alpha, beta);
    const KerrNullGeodesic geodesic(metric_, y0, sky_, guard_);
    if (!geodesic.supported()) {
      // Off-axis cameras far away meet only vortical rays here (eta <= 0), which never reach the plane.
      s.covered = false;
      return s;
    }
    s.escaped = geodesic.escapes();
    const Vec4 k_low = metric_.metric(y0.head<4>()) * y0.tail<4>();
    const double end = geodesic.end_mino_time();
    for (int n = 0; n < DiskRaySample::kOrders; ++n) {
      const double tau = geodesic.crossing_mino_time(n);
      if (!(tau < end)) break;
      const double r = geodesic.radius_at(tau);
      s.radius[static_cast<std::size_t>(n)] = r;
      if (r < r_in_) {
        s.where[static_cast<std::size_t>(n)] = DiskRaySample::inside_edge;
      } else if (r <= r_out_) {
        s.where[static_cast<std::size_t>(n)] = DiskRaySample::on_disk;
        s.redshift[static_cast<std::size_t>(n)] = redshift(r, k_low);
      }
    }
    return s;
  }

  /// g of the disk's gas on its circular orbit at r, for a ray of lowered momentum k_low.
  double redshift(double r, const Vec4& k_low) const {
    const double ut = exact::keplerian_ut(r, metric_.spin, orbit_, metric_.mass);
    const double omega = exact::keplerian_omega(r, metric_.spin, orbit_, metric_.mass);
    return -1.0 / (ut * (k_low[0] + omega * k_low[3]));
  }

 private:
  KerrMetric metric_;
  double r_in_, r_out_;
  exact::Orbit orbit_;
  Vec4 x0_;
  Tetrad tetrad_;
  double r_o_ = 0.0, sky_ = 0.0, guard_ = 0.0;
};

namespace line_detail {

/// A vertex of the mesh: its screen point and its ray's crossings, with the weight g^4 eps J of each lit order.
struct Vertex {
  DiskRaySample s;
  std::array<double, DiskRaySample::kOrders> weight{};
  std::array<bool, DiskRaySample::kOrders> lit{};  ///< this order emits light that reaches the camera
};

/// int over the part of the triangle where the linear g is <= t of the linear weight w (area: the triangle's).
inline double clipped_weight(const std::array<double, 3>& g, const std::array<double, 3>& w, double area, double t) {
  std::array<int, 3> o{0, 1, 2};
  std::sort(o.begin(), o.end(),
            [&](int i, int j) { return g[static_cast<std::size_t>(i)] < g[static_cast<std::size_t>(j)]; });
  const double ga = g[static_cast<std::size_t>(o[0])], gb = g[static_cast<std::size_t>(o[1])],
               gc = g[static_cast<std::size_t>(o[2])];
  const double wa = w[static_cast<std::size_t>(o[0])], wb = w[static_cast<std::size_t>(o[1])],
               wc = w[static_cast<std::size_t>(o[2])];
  const double whole = area * (wa + wb + wc) / 3.0;
  if (t <= ga) return 0.0;
  if (t >= gc) return whole;
  if (t <= gb) {  // a triangle at a: ga < t <= gb <= gc, so neither denominator is zero
    const double sab = (t - ga) / (gb - ga), sac = (t - ga) / (gc - ga);
    return area * sab * sac * (wa + (wa + sab * (wb - wa)) + (wa + sac * (wc - wa))) / 3.0;
  }
  // the whole less a triangle at c: ga <= gb < t < gc
  const double sca = (gc - t) / (gc - ga), scb = (gc - t) / (gc - gb);
  return whole - area * sca * scb * (wc + (wc + sca * (wa - wc)) + (wc + scb * (wb - wc))) / 3.0;
}

/// Per-row sums (summed in row order afterwards: the result does not depend on the threads' schedule).
struct Sums {
  std::array<std::vector<double>, LineProfile::kOrderChannels> bins;
  double outside = 0.0;
  double e_min = std::numeric_limits<double>::infinity(), e_max = 0.0;  ///< the energies that carried light
  long rays = 0, triangles = 0, unresolved = 0, uncovered = 0;
  explicit Sums(int n) {
    for (auto& b : bins) b.assign(static_cast<std::size_t>(n), 0.0);
  }
};

template <DiskMap Map>
class Mesher {
 public:
  /// The lattice: corner (i, j) at (origin + h i, origin + h j); `edges`: bins of width `bin_width`.
  Mesher(const Map& map, const LineProfileSpec& spec, const LineSampling& sampling, const std::vector<double>& edges,
         double bin_width, double flux_scale, double origin, double h)
      : map_(map),
        spec_(spec),
        sampling_(sampling),
        edges_(edges),
        flux_scale_(flux_scale),
        origin_(origin),
        h_(h),
        bin_width_(bin_width) {}

  Vertex vertex(double alpha, double beta, Sums& sums) const {
    Vertex v;
    v.s = map_.sample(alpha, beta);
    ++sums.rays;
    if (!v.s.covered) ++sums.uncovered;
    const double x = alpha / map_.camera_radius(), y = beta / map_.camera_radius();
    const double q = 1.0 + x * x + y * y, jacobian = 1.0 / (q * std::sqrt(q));
    bool seen = false;
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      if (v.s.where[n] != DiskRaySample::on_disk || (seen && !spec_.transparent)) continue;
      seen = true;
      v.lit[n] = true;
      const double g = v.s.redshift[n], g2 = g * g;
      v.weight[n] = g2 * g2 * spec_.emissivity(v.s.radius[n]) * jacobian;
    }
    return v;
  }

  /// Refines and integrates one triangle (corners in lattice units of the finest cell, origin at the square's
  /// corner); `cache` holds the vertices met so far in its start cell.
  void triangle(const std::array<std::array<long, 2>, 3>& p, std::unordered_map<std::uint64_t, Vertex>& cache,
                Sums& sums) const {
    std::array<const Vertex*, 3> v{};
    for (std::size_t i = 0; i < 3; ++i) v[i] = &at(p[i], cache, sums);
    const double size = static_cast<double>(std::max(std::abs(p[1][0] - p[0][0]), std::abs(p[2][0] - p[0][0]))) * h_,
                 area = 0.5 * size * size;
    const bool can_split = size > 1.5 * h_;
    const bool mixed = !same_view(*v[0], *v[1]) || !same_view(*v[0], *v[2]);
    const bool any_lit = lit_anywhere(*v[0]) || lit_anywhere(*v[1]) || lit_anywhere(*v[2]);
    if (can_split && size > sampling_.central_cell * map_.mass() && near_centre(p)) return split(p, cache, sums);
    if (mixed) {
      // Bands (the n >= 1 rings) may lie between dark corners: split those down to the finest cell; lit edges
      // only while they carry flux worth resolving.
      const double w = std::max({max_weight(*v[0]), max_weight(*v[1]), max_weight(*v[2])});
      if (can_split && (!any_lit || area * w > sampling_.edge_tolerance * flux_scale_)) return split(p, cache, sums);
      if (any_lit) ++sums.unresolved;
      return integrate(v, area, sums);
    }
    if (!any_lit) return;
    if (!can_split) return integrate(v, area, sums);
    // Uniform and lit: settled when the midpoints agree with the linear interpolation; then the four halves,
    // already sampled, are integrated.
    const std::array<std::array<long, 2>, 3> m = midpoints(p);
    std::array<const Vertex*, 3> mv{};
    for (std::size_t i = 0; i < 3; ++i) mv[i] = &at(m[i], cache, sums);
    bool settled = true;
    for (std::size_t i = 0; i < 3 && settled; ++i) {
      const Vertex &a = *v[i], &b = *v[(i + 1) % 3], &c = *mv[i];
      settled = same_view(a, c) && linear_enough(a, b, c);
    }
    if (!settled) return split(p, cache, sums);
    for (const auto& child : children(p, m)) {
      std::array<const Vertex*, 3> cv{};
      for (std::size_t i = 0; i < 3; ++i) cv[i] = &at(child[i], cache, sums);
      integrate(cv, 0.25 * area, sums);
    }
  }

  std::size_t order_channel(std::size_t n) const { return std::min<std::size_t>(n, LineProfile::kOrderChannels - 1); }

 private:
  const Vertex& at(const std::array<long, 2>& p, std::unordered_map<std::uint64_t, Vertex>& cache, Sums& sums) const {
    const std::uint64_t key = (static_cast<std::uint64_t>(p[0]) << 32) | static_cast<std::uint64_t>(p[1]);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    return cache
        .emplace(key, vertex(origin_ + h_ * static_cast<double>(p[0]), origin_ + h_ * static_cast<double>(p[1]), sums))
        .first->second;
  }

  static std::array<std::array<long, 2>, 3> midpoints(const std::array<std::array<long, 2>, 3>& p) {
    std::array<std::array<long, 2>, 3> m{};
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t d = 0; d < 2; ++d) m[i][d] = (p[i][d] + p[(i + 1) % 3][d]) / 2;
    return m;
  }
  static std::array<std::array<std::array<long, 2>, 3>, 4> children(const std::array<std::array<long, 2>, 3>& p,
                                                                    const std::array<std::array<long, 2>, 3>& m) {
    // m[0] on p0-p1, m[1] on p1-p2, m[2] on p2-p0
    return {{{p[0], m[0], m[2]}, {m[0], p[1], m[1]}, {m[2], m[1], p[2]}, {m[0], m[1], m[2]}}};
  }

  void split(const std::array<std::array<long, 2>, 3>& p, std::unordered_map<std::uint64_t, Vertex>& cache,
             Sums& sums) const {
    const auto m = midpoints(p);
    for (const auto& child : children(p, m)) triangle(child, cache, sums);
  }

  bool near_centre(const std::array<std::array<long, 2>, 3>& p) const {
    // the shadow (radius ~5.2 M, shifted by up to a) and the n >= 1 rings
    const double kCentre = 12.0 * map_.mass();
    double lo_a = 1e300, hi_a = -1e300, lo_b = 1e300, hi_b = -1e300;
    for (const auto& q : p) {
      const double a = origin_ + h_ * static_cast<double>(q[0]), b = origin_ + h_ * static_cast<double>(q[1]);
      lo_a = std::min(lo_a, a), hi_a = std::max(hi_a, a), lo_b = std::min(lo_b, b), hi_b = std::max(hi_b, b);
    }
    return hi_a > -kCentre && lo_a < kCentre && hi_b > -kCentre && lo_b < kCentre;
  }

  /// The two rays see the same: both escaped or both captured, and per order the disk, inside it, or nothing.
  bool same_view(const Vertex& a, const Vertex& b) const {
    if (a.s.escaped != b.s.escaped || a.s.covered != b.s.covered) return false;
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n)
      if (a.s.where[n] != b.s.where[n] || a.lit[n] != b.lit[n]) return false;
    return true;
  }
  static bool lit_anywhere(const Vertex& v) {
    return std::any_of(v.lit.begin(), v.lit.end(), [](bool b) { return b; });
  }
  static double max_weight(const Vertex& v) { return *std::max_element(v.weight.begin(), v.weight.end()); }

  /// c, the midpoint of a and b, agrees with their mean within the tolerances for every lit order.
  bool linear_enough(const Vertex& a, const Vertex& b, const Vertex& c) const {
    const double g_tol = sampling_.g_tolerance * bin_width_ / spec_.line_energy;
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      if (!c.lit[n]) continue;
      if (std::abs(c.s.redshift[n] - 0.5 * (a.s.redshift[n] + b.s.redshift[n])) > g_tol) return false;
      if (std::abs(c.weight[n] - 0.5 * (a.weight[n] + b.weight[n])) > sampling_.weight_tolerance * c.weight[n])
        return false;
    }
    return true;
  }

  /// The triangle's flux into the bins, order by order (a dark corner: weight 0, g the lit corners' mean).
  void integrate(const std::array<const Vertex*, 3>& v, double area, Sums& sums) const {
    ++sums.triangles;
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      std::array<double, 3> g{}, w{};
      int lit = 0;
      double g_sum = 0.0;
      for (std::size_t i = 0; i < 3; ++i)
        if (v[i]->lit[n]) ++lit, g_sum += v[i]->s.redshift[n];
      if (lit == 0) continue;
      for (std::size_t i = 0; i < 3; ++i) {
        g[i] = v[i]->lit[n] ? v[i]->s.redshift[n] : g_sum / lit;
        w[i] = v[i]->lit[n] ? v[i]->weight[n] : 0.0;
      }
      deposit(g, w, area, sums.bins[order_channel(n)], sums);
    }
  }

  void deposit(std::array<double, 3> g, const std::array<double, 3>& w, double area, std::vector<double>& bins,
               Sums& sums) const {
    for (double& x : g) x *= spec_.line_energy;  // energies from here on
    const double lo = std::min({g[0], g[1], g[2]}), hi = std::max({g[0], g[1], g[2]});
    const double whole = area * (w[0] + w[1] + w[2]) / 3.0;
    if (whole > 0.0) sums.e_min = std::min(sums.e_min, lo), sums.e_max = std::max(sums.e_max, hi);
    double& outside = sums.outside;
    const auto nb = static_cast<long>(bins.size());
    const long first = bin_of(lo), last = bin_of(hi);
    if (first == last) {
      if (first >= 0 && first < nb) bins[static_cast<std::size_t>(first)] += whole;
      else outside += whole;
      return;
    }
    double below = 0.0;  // the weight with energy below the current bin's upper edge
    for (long b = std::max(first, -1L); b <= std::min(last, nb); ++b) {
      const double upper =
          b < nb ? clipped_weight(g, w, area, b >= 0 ? edges_[static_cast<std::size_t>(b + 1)] : edges_.front())
                 : whole;
      const double part = upper - below;
      below = upper;
      if (b >= 0 && b < nb) bins[static_cast<std::size_t>(b)] += part;
      else outside += part;
    }
  }

  /// The bin of energy e: -1 below the first edge, bins() at or above the last.
  long bin_of(double e) const {
    const auto nb = static_cast<long>(edges_.size()) - 1;
    if (e < edges_.front()) return -1;
    if (e >= edges_.back()) return nb;
    return std::min(nb - 1, static_cast<long>((e - edges_.front()) / bin_width_));
  }

 private:
  const Map& map_;
  const LineProfileSpec& spec_;
  const LineSampling& sampling_;
  const std::vector<double>& edges_;
  double flux_scale_;
  double origin_, h_, bin_width_;
};

}  // namespace line_detail

/// Checks the spec and sampling; std::invalid_argument saying what to change.
inline void check_line_profile(const LineProfileSpec& spec, const LineSampling& sampling) {
  auto fail = [](const std::string& m) { throw std::invalid_argument("line profile: " + m); };
  if (!(spec.line_energy > 0.0) || !std::isfinite(spec.line_energy)) fail("the line energy must be positive");
  if (spec.bins < 1 || spec.bins > 1'000'000) fail("the number of bins must be in 1 .. 1e6");
  const bool automatic = spec.energy_min == 0.0 && spec.energy_max == 0.0;
  if (!automatic && !(spec.energy_min >= 0.0 && spec.energy_max > spec.energy_min && std::isfinite(spec.energy_max)))
    fail("the energy range needs 0 <= min < max (or both 0: around the energies the disk's light arrives at)");
  const LineEmissivity& e = spec.emissivity;
  if (!std::isfinite(e.index_inner) || !std::isfinite(e.index_outer) || !(e.r_break > 0.0))
    fail("the emissivity needs finite indices and a positive break radius");
  if (sampling.base_cells < 2 || sampling.base_cells > 4096) fail("base_cells must be in 2 .. 4096");
  if (!(sampling.finest_cell > 0.0) || !(sampling.central_cell >= sampling.finest_cell))
    fail("the cells need 0 < finest_cell <= central_cell");
  if (!(sampling.g_tolerance > 0.0) || !(sampling.weight_tolerance > 0.0) || !(sampling.edge_tolerance >= 0.0))
    fail("the tolerances must be positive");
}

/// The line profile of the map's disk (see the top of this file). Parallel over rows of start cells (OpenMP);
/// the sums do not depend on the number of threads' schedule.
template <DiskMap Map>
LineProfile line_profile(const Map& map, const LineProfileSpec& spec, const LineSampling& sampling = {}) {
  check_line_profile(spec, sampling);
  LineProfile out;
  const double mass = map.mass();
  // The scale edge_tolerance is relative to: the disk's flux seen face-on without gravity, 2 pi int eps r dr.
  double flux_scale = 0.0;
  {
    constexpr int kPanels = 400;
    const double l0 = std::log(map.r_in()), l1 = std::log(map.r_out()), dl = (l1 - l0) / kPanels;
    for (int i = 0; i < kPanels; ++i) {
      const double r = std::exp(l0 + (i + 0.5) * dl);
      flux_scale += 2.0 * std::numbers::pi * spec.emissivity(r) * r * r * dl;
    }
  }

  // The square: grown until no ray on its rim sees the disk (n = 0 lights the outermost image).
  double half = 1.1 * map.r_out() + 8.0 * mass;
  for (int tries = 0;; ++tries) {
    bool rim_lit = false;
    constexpr int kRim = 256;
    for (int i = 0; i < kRim && !rim_lit; ++i) {
      const double s = -half + 2.0 * half * i / kRim;
      for (const auto& [a, b] : {std::pair{s, -half}, std::pair{half, s}, std::pair{-s, half}, std::pair{-half, -s}}) {
        const DiskRaySample d = map.sample(a, b);
        rim_lit =
            rim_lit || std::any_of(d.where.begin(), d.where.end(), [](auto w) { return w == DiskRaySample::on_disk; });
      }
    }
    if (!rim_lit) break;
    if (tries == 8)
      throw std::runtime_error("line profile: the disk's image did not fit in a square 2 x " + std::to_string(half) +
                               " M wide");
    half *= 1.25;
  }
  out.half_width = half;

  // The lattice: the finest cell is 2^-depth of a start cell, every corner an integer point of it.
  const int base = sampling.base_cells;
  const double cell = 2.0 * half / base;
  int depth = 0;
  while (cell / std::ldexp(1.0, depth) > sampling.finest_cell * mass && depth < 24) ++depth;
  const long step = 1L << depth;

  // The bins: as asked, or around the range of g the start grid's corners and the centre's (the inner edge's
  // image) see; if light still arrives outside them, the mesh is made again over the range it arrived in.
  double e_lo = spec.energy_min, e_hi = spec.energy_max;
  const bool automatic = e_lo == 0.0 && e_hi == 0.0;
  if (automatic) {
    double g_lo = std::numeric_limits<double>::infinity(), g_hi = 0.0;
    auto look = [&](double a, double b) {
      const DiskRaySample d = map.sample(a, b);
      for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n)
        if (d.where[n] == DiskRaySample::on_disk)
          g_lo = std::min(g_lo, d.redshift[n]), g_hi = std::max(g_hi, d.redshift[n]);
    };
    for (int j = 0; j <= base; ++j)
      for (int i = 0; i <= base; ++i) look(-half + cell * i, -half + cell * j);
    constexpr int kCentre = 96;  // 0.25 M apart over the central 24 M
    for (int j = 0; j <= kCentre; ++j)
      for (int i = 0; i <= kCentre; ++i) look(mass * (-12.0 + 24.0 * i / kCentre), mass * (-12.0 + 24.0 * j / kCentre));
    if (!(g_hi > 0.0)) g_lo = 0.5, g_hi = 1.5;  // nothing seen: any range
    e_lo = std::max(0.0, g_lo - 0.1 * (g_hi - g_lo)) * spec.line_energy;
    e_hi = (g_hi + 0.1 * (g_hi - g_lo)) * spec.line_energy;
  }

  std::vector<line_detail::Sums> rows;
  double bin_width = 0.0;
  auto mesh = [&] {
    bin_width = (e_hi - e_lo) / spec.bins;
    out.edges.resize(static_cast<std::size_t>(spec.bins) + 1);
    for (int i = 0; i <= spec.bins; ++i) out.edges[static_cast<std::size_t>(i)] = e_lo + bin_width * i;
    out.edges.back() = e_hi;
    const line_detail::Mesher<Map> mesher(map, spec, sampling, out.edges, bin_width, flux_scale, -half,
                                          cell / static_cast<double>(step));
    rows.assign(static_cast<std::size_t>(base), line_detail::Sums(spec.bins));
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
    for (int j = 0; j < base; ++j) {
      line_detail::Sums& sums = rows[static_cast<std::size_t>(j)];
      std::unordered_map<std::uint64_t, line_detail::Vertex> cache;
      for (int i = 0; i < base; ++i) {
        cache.clear();
        const long x0 = i * step, y0 = j * step, x1 = x0 + step, y1 = y0 + step;
        mesher.triangle({{{x0, y0}, {x1, y0}, {x1, y1}}}, cache, sums);
        mesher.triangle({{{x0, y0}, {x1, y1}, {x0, y1}}}, cache, sums);
      }
    }
  };
  mesh();
  if (automatic) {
    double outside = 0.0, lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const auto& r : rows) outside += r.outside, lo = std::min(lo, r.e_min), hi = std::max(hi, r.e_max);
    if (outside > 0.0) {
      for (const auto& r : rows) out.rays += r.rays, out.triangles += r.triangles;  // the first mesh's cost
      const double margin = 1e-6 * (hi - lo);
      e_lo = std::max(0.0, lo - margin), e_hi = hi + margin;
      mesh();
    }
  }

  out.flux.assign(static_cast<std::size_t>(spec.bins), 0.0);
  for (auto& b : out.flux_by_order) b.assign(static_cast<std::size_t>(spec.bins), 0.0);
  for (const auto& s : rows) {
    for (std::size_t o = 0; o < LineProfile::kOrderChannels; ++o)
      for (std::size_t b = 0; b < out.flux.size(); ++b) out.flux_by_order[o][b] += s.bins[o][b];
    out.outside += s.outside;
    out.rays += s.rays;
    out.triangles += s.triangles;
    out.unresolved += s.unresolved;
    out.uncovered += s.uncovered;
  }
  for (std::size_t o = 0; o < LineProfile::kOrderChannels; ++o) {
    for (std::size_t b = 0; b < out.flux.size(); ++b) {
      out.total_by_order[o] += out.flux_by_order[o][b];
      out.flux_by_order[o][b] /= bin_width;
    }
    out.total += out.total_by_order[o];
  }
  for (std::size_t b = 0; b < out.flux.size(); ++b)
    for (std::size_t o = 0; o < LineProfile::kOrderChannels; ++o) out.flux[b] += out.flux_by_order[o][b];
  return out;
}

}  // namespace grtrace
