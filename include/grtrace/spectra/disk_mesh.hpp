// grtrace/spectra/disk_mesh.hpp
// The image plane of a thin disk cut into triangles that follow what each image order sees: the mesh under the
// line profile (spectra/line_profile.hpp) and the ring image (spectra/ring_image.hpp). A Sink says what a piece of
// the image plane's light adds to (energy bins, pixels); this file finds the pieces.
//
// Takes:   a DiskMap (a screen point (alpha, beta) in units of M -> the crossings of its ray with the equatorial
//          plane, each with its radius and redshift g = E_obs / E_emit; spectra/kerr_disk_map.hpp is Kerr's), the
//          light (the gas frame's intensity eps(r), the power p of g in the observed intensity g^p eps, opaque or
//          transparent disk), a DiskSampling and a Sink.
// Gives:   to the sink, for each image order n (channel min(n, 3)) a set of triangles in the screen plane, each with
//          g and the weight g^p eps J at its corners (J = (1 + x^2 + y^2)^-3/2 turns the tangent plane's area into
//          the solid angle times r_o^2), such that a weight linear over each triangle is the order's image.
// Method:  a square's start cells, cut into right triangles; a triangle is split in four (at its edges'
//          midpoints) while its corners disagree about what an order sees (inside the disk's inner edge, on the
//          disk, beyond it or hidden), or while g or the weight departs from linear by more than the tolerance at
//          the midpoints, down to the finest cell. A triangle still mixed there is, with edge_precision > 0, cut
//          along its edges (without, its corners alone give the light: first order in the cell): on each edge
//          whose ends disagree about an order, the points where that order's view changes are found by bisection
//          (to edge_precision), and the order's lit polygon (the corners it lights and those points, with the
//          weights sampled just inside them) is handed on in a fan of triangles. The edges of an image are then
//          straight within a finest cell (second order in its size) where a plain split would leave them ragged
//          (first order); an order's band narrower than the cell is found from its edges' ends alone (a corner
//          inside the disk's image at one end and beyond it at the other). Cardenas-Avendano, Lupsasca & Zhu (AART,
//          2023) sample each lensing band of the image plane on its own grid; this mesh refines one plane by all
//          orders at once.
// Assumes: an order's image crosses a finest cell's edge at most twice (its inner and outer edge) and is straight
//          within the cell; orders above DiskRaySample::kOrders carry no light worth following.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace grtrace {

/// The disk's intensity in the gas's frame: a broken power law eps(r) = r^-q_inner inside r_break and
/// r_break^(q_outer - q_inner) r^-q_outer outside (continuous there). A plain power law: r_break = infinity.
struct DiskEmissivity {
  double index_inner = 3.0;
  double index_outer = 3.0;
  double r_break = std::numeric_limits<double>::infinity();

  double operator()(double r) const {
    return r < r_break ? std::pow(r, -index_inner)
                       : std::pow(r_break, index_outer - index_inner) * std::pow(r, -index_outer);
  }
};

/// How fine the image-plane mesh may go (lengths on the screen in units of the hole's mass M).
struct DiskSampling {
  int base_cells = 64;        ///< cells per side of the image square to start with
  double central_cell = 1.0;  ///< cells within 12 M of the centre (the shadow and the n >= 1 rings) at most this big
  double finest_cell = 1.0 / 64.0;  ///< no triangle smaller: a mixed one is cut along its edges here
  /// g's departure from linear at a triangle's midpoints (the line profile: in bins, times the bin's width over the
  /// line energy), and the weight's, relative: a triangle within both is settled
  double g_tolerance = 0.03;
  double weight_tolerance = 2e-3;
  /// A triangle on an image's edge is split no further once its area times its brightest corner's weight is below
  /// this fraction of the disk's Newtonian flux 2 pi int eps r dr
  double edge_tolerance = 1e-7;
  /// Where an image's edge crosses the edges of a mixed triangle at its last size: bisected until the bracket is
  /// this short (M). 0: not cut, the corners alone give the light (lit ones with their weight, dark ones with none:
  /// first order in the cell's size, enough for a line profile's bins). The cut is second order for an edge
  /// straight within the cell, but it takes the weight as linear between the points it finds, which a band
  /// narrower than the cell is not (its radius runs from r_in to r_out across it): such bands are integrated along
  /// radial cuts instead (spectra/ring_image.hpp)
  double edge_precision = 0.0;
};

/// One ray's crossings of the equatorial plane, as a disk sees them.
struct DiskRaySample {
  static constexpr int kOrders = 6;  ///< crossings followed; higher orders carry < 1e-8 of the flux
  enum Where : signed char { nothing = 0, inside_edge = 1, on_disk = 2, beyond_edge = 3 };
  bool escaped = false;
  bool covered = true;                 ///< false: the map could not follow this ray (counted, seen as nothing)
  std::array<Where, kOrders> where{};  ///< nothing: the ray ends before this crossing
  std::array<double, kOrders> radius{}, redshift{};
};

template <class M>
concept DiskMap = requires(const M& map, double alpha, double beta) {
  { map.sample(alpha, beta) } -> std::same_as<DiskRaySample>;
  { map.r_in() } -> std::convertible_to<double>;
  { map.r_out() } -> std::convertible_to<double>;
  { map.camera_radius() } -> std::convertible_to<double>;
  { map.mass() } -> std::convertible_to<double>;  ///< the screen's lengths (DiskSampling's cells) scale with it
};

/// What the disk emits and how it is seen: the observed intensity of order n is g^redshift_power eps(r) (4: the
/// energy flux of a line, I_E / E^3 invariant and integrated over the line; 3: the specific intensity at a fixed
/// frequency of a source flat in frequency).
struct DiskLight {
  DiskEmissivity emissivity;
  double redshift_power = 4.0;
  /// false: the first crossing inside the disk's radii emits and ends the ray (an opaque disk); true: every
  /// crossing inside them emits and the ray goes on (an optically thin disk: AART's model).
  bool transparent = false;
  /// The orders that emit, from n = 0 (the ring image meshes orders 0 and 1 and takes the rings along radial cuts)
  int orders = DiskRaySample::kOrders;

  /// The observed intensity g^redshift_power eps(r) of a crossing at radius r seen with redshift g.
  double intensity(double g, double r) const { return std::pow(g, redshift_power) * emissivity(r); }
};

namespace disk_mesh {

inline constexpr int kOrderChannels = 4;  ///< n = 0, 1, 2 and >= 3
inline std::size_t order_channel(std::size_t n) { return std::min<std::size_t>(n, kOrderChannels - 1); }

struct ScreenPoint {
  double alpha = 0.0, beta = 0.0;
};

/// A ray as the mesh sees it: per order a view (0: inside the inner edge's image or captured before this crossing,
/// 1: lit, 2: beyond the outer edge, past the last crossing of an escaping ray, or hidden behind a lower order of
/// an opaque disk), and the lit orders' g and weight. The views are ordered as the crossing's radius is, so an
/// order's image is where its view is 1, between 0 and 2.
struct Vertex {
  ScreenPoint at;
  bool covered = true;
  std::array<signed char, DiskRaySample::kOrders> view{};
  std::array<double, DiskRaySample::kOrders> redshift{}, weight{};
};

/// J = (1 + x^2 + y^2)^-3/2 at the screen point (alpha, beta), x = alpha / r_o, y = beta / r_o: the camera's
/// tangent plane's area to solid angle times r_o^2.
inline double screen_jacobian(double alpha, double beta, double camera_radius) {
  const double x = alpha / camera_radius, y = beta / camera_radius, q = 1.0 + x * x + y * y;
  return 1.0 / (q * std::sqrt(q));
}

/// The area of the triangle (a, b, c) on the screen.
inline double triangle_area(const ScreenPoint& a, const ScreenPoint& b, const ScreenPoint& c) {
  return 0.5 * std::abs((b.alpha - a.alpha) * (c.beta - a.beta) - (c.alpha - a.alpha) * (b.beta - a.beta));
}

/// The views of a ray's orders (Vertex::view; 1: lit); orders from `orders` on are dark (0).
inline std::array<signed char, DiskRaySample::kOrders> views(const DiskRaySample& s, bool transparent,
                                                             int orders = DiskRaySample::kOrders) {
  std::array<signed char, DiskRaySample::kOrders> v{};
  bool seen = false;
  for (std::size_t n = 0; n < static_cast<std::size_t>(std::clamp(orders, 0, DiskRaySample::kOrders)); ++n) {
    switch (s.where[n]) {
      case DiskRaySample::inside_edge:
        v[n] = 0;
        break;
      case DiskRaySample::beyond_edge:
        v[n] = 2;
        break;
      case DiskRaySample::nothing:
        v[n] = s.escaped ? 2 : 0;
        break;
      case DiskRaySample::on_disk:
        v[n] = (seen && !transparent) ? 2 : 1;
        seen = true;
        break;
    }
  }
  return v;
}

/// The Newtonian flux of the disk face-on, 2 pi int eps r dr: the scale of edge_tolerance.
inline double newtonian_flux(const DiskEmissivity& e, double r_in, double r_out) {
  constexpr int kPanels = 400;
  const double l0 = std::log(r_in), l1 = std::log(r_out), dl = (l1 - l0) / kPanels;
  double sum = 0.0;
  for (int i = 0; i < kPanels; ++i) {
    const double r = std::exp(l0 + (i + 0.5) * dl);
    sum += 2.0 * 3.14159265358979323846 * e(r) * r * r * dl;
  }
  return sum;
}

/// Checks an emissivity; std::invalid_argument ("<what>: ...") saying what to change.
inline void check_emissivity(const DiskEmissivity& e, const std::string& what) {
  if (!std::isfinite(e.index_inner) || !std::isfinite(e.index_outer) || !(e.r_break > 0.0))
    throw std::invalid_argument(what + ": the emissivity needs finite indices and a positive break radius");
}

/// Checks a sampling; std::invalid_argument ("<what>: ...") saying what to change.
inline void check_sampling(const DiskSampling& sampling, const std::string& what) {
  auto fail = [&](const std::string& m) { throw std::invalid_argument(what + ": " + m); };
  if (sampling.base_cells < 2 || sampling.base_cells > 4096) fail("base_cells must be in 2 .. 4096");
  if (!(sampling.finest_cell > 0.0) || !(sampling.central_cell >= sampling.finest_cell))
    fail("the cells need 0 < finest_cell <= central_cell");
  if (!(sampling.g_tolerance > 0.0) || !(sampling.weight_tolerance > 0.0) || !(sampling.edge_tolerance >= 0.0))
    fail("the tolerances must be positive");
  if (!(sampling.edge_precision >= 0.0) || !std::isfinite(sampling.edge_precision))
    fail("the edge precision must be >= 0 (0: edges not cut)");
}

struct Counts {
  long rays = 0, triangles = 0, unresolved = 0, uncovered = 0;
  void add(const Counts& o) {
    rays += o.rays, triangles += o.triangles, unresolved += o.unresolved, uncovered += o.uncovered;
  }
};

/// A Sink takes an order's light on one triangle (its corners on the screen, g and the weight there, linear
/// between them) into a Row: the sums of one row of start cells (summed in row order afterwards, so the result
/// does not depend on the threads' schedule).
template <class S>
concept Sink = requires(const S& sink, typename S::Row& row, std::size_t channel, int start_row,
                        const std::array<ScreenPoint, 3>& xy, const std::array<double, 3>& g,
                        const std::array<double, 3>& w) {
  { sink.row(start_row) } -> std::same_as<typename S::Row>;
  sink.deposit(channel, xy, g, w, row);
};

template <DiskMap Map, Sink S>
class Mesher {
 public:
  /// The points on one edge where an order's view passes 1: cached per start cell, since the triangles on either
  /// side of an edge walk it.
  struct EdgeKey {
    std::array<long, 4> ends;
    std::size_t order;
    bool operator==(const EdgeKey&) const = default;
  };
  struct EdgeHash {
    std::size_t operator()(const EdgeKey& k) const {
      std::uint64_t h = k.order;
      for (long e : k.ends) h = h * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(e);
      return static_cast<std::size_t>(h ^ (h >> 29));
    }
  };
  struct EdgeCut {
    int count = 0;
    std::array<Vertex, 2> lit;  ///< lit samples just inside the image's edges, from the edge's first end on
  };

  struct Caches {
    std::unordered_map<std::uint64_t, Vertex> vertices;
    std::unordered_map<EdgeKey, EdgeCut, EdgeHash> edges;
    void clear() {
      vertices.clear();
      edges.clear();
    }
  };

  /// The lattice: corner (i, j) at (origin + h i, origin + h j); g_tolerance absolute (infinity: g is not checked
  /// beyond the weight).
  Mesher(const Map& map, const DiskLight& light, const DiskSampling& sampling, const S& sink, double g_tolerance,
         double flux_scale, double origin, double h)
      : map_(map),
        light_(light),
        sampling_(sampling),
        sink_(sink),
        g_tolerance_(g_tolerance),
        flux_scale_(flux_scale),
        origin_(origin),
        h_(h) {}

  Vertex vertex(double alpha, double beta, Counts& counts) const {
    Vertex v;
    v.at = {alpha, beta};
    const DiskRaySample s = map_.sample(alpha, beta);
    ++counts.rays;
    v.covered = s.covered;
    if (!s.covered) ++counts.uncovered;
    const double jacobian = screen_jacobian(alpha, beta, map_.camera_radius());
    v.view = views(s, light_.transparent, light_.orders);
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      if (v.view[n] != 1) continue;
      v.redshift[n] = s.redshift[n];
      v.weight[n] = light_.intensity(s.redshift[n], s.radius[n]) * jacobian;
    }
    return v;
  }

  /// Refines and integrates one triangle (corners in lattice units of the finest cell, origin at the square's
  /// corner); `cache` holds the vertices met so far in its start cell.
  void triangle(const std::array<std::array<long, 2>, 3>& p, Caches& cache, typename S::Row& row,
                Counts& counts) const {
    std::array<const Vertex*, 3> v{};
    for (std::size_t i = 0; i < 3; ++i) v[i] = &at(p[i], cache, counts);
    const double size = static_cast<double>(std::max(std::abs(p[1][0] - p[0][0]), std::abs(p[2][0] - p[0][0]))) * h_,
                 area = 0.5 * size * size;
    const bool can_split = size > 1.5 * h_;
    const bool mixed = !same_view(*v[0], *v[1]) || !same_view(*v[0], *v[2]);
    const bool any_lit = lit_anywhere(*v[0]) || lit_anywhere(*v[1]) || lit_anywhere(*v[2]);
    if (can_split && size > sampling_.central_cell * map_.mass() && near_centre(p)) return split(p, cache, row, counts);
    if (mixed) {
      // An order's band may lie between corners none of which it lights: split those down to the finest cell,
      // lit edges only while they carry flux worth resolving.
      const double w = std::max({max_weight(*v[0]), max_weight(*v[1]), max_weight(*v[2])});
      if (can_split && (dark_mixed(v) || area * w > sampling_.edge_tolerance * flux_scale_))
        return split(p, cache, row, counts);
      if (can_split) ++counts.unresolved;
      return cut(p, v, cache, row, counts);
    }
    if (!any_lit) return;
    if (!can_split) return integrate(v, row, counts);
    // Uniform and lit: settled when the midpoints agree with the linear interpolation; then the four halves,
    // already sampled, are integrated.
    const std::array<std::array<long, 2>, 3> m = midpoints(p);
    std::array<const Vertex*, 3> mv{};
    for (std::size_t i = 0; i < 3; ++i) mv[i] = &at(m[i], cache, counts);
    bool settled = true;
    for (std::size_t i = 0; i < 3 && settled; ++i) {
      const Vertex &a = *v[i], &b = *v[(i + 1) % 3], &c = *mv[i];
      settled = same_view(a, c) && linear_enough(a, b, c);
    }
    if (!settled) return split(p, cache, row, counts);
    for (const auto& child : children(p, m)) {
      std::array<const Vertex*, 3> cv{};
      for (std::size_t i = 0; i < 3; ++i) cv[i] = &at(child[i], cache, counts);
      integrate(cv, row, counts);
    }
  }

 private:
  const Vertex& at(const std::array<long, 2>& p, Caches& cache, Counts& counts) const {
    const std::uint64_t key = (static_cast<std::uint64_t>(p[0]) << 32) | static_cast<std::uint64_t>(p[1]);
    if (auto it = cache.vertices.find(key); it != cache.vertices.end()) return it->second;
    return cache.vertices
        .emplace(key,
                 vertex(origin_ + h_ * static_cast<double>(p[0]), origin_ + h_ * static_cast<double>(p[1]), counts))
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

  void split(const std::array<std::array<long, 2>, 3>& p, Caches& cache, typename S::Row& row, Counts& counts) const {
    const auto m = midpoints(p);
    for (const auto& child : children(p, m)) triangle(child, cache, row, counts);
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

  static bool same_view(const Vertex& a, const Vertex& b) { return a.covered == b.covered && a.view == b.view; }
  static bool lit_anywhere(const Vertex& v) {
    return std::any_of(v.view.begin(), v.view.end(), [](signed char c) { return c == 1; });
  }
  static double max_weight(const Vertex& v) { return *std::max_element(v.weight.begin(), v.weight.end()); }
  /// Some order's view differs between the corners while it lights none of them (a band may pass between).
  static bool dark_mixed(const std::array<const Vertex*, 3>& v) {
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      const signed char a = v[0]->view[n], b = v[1]->view[n], c = v[2]->view[n];
      if (a != 1 && b != 1 && c != 1 && (a != b || a != c)) return true;
    }
    return false;
  }

  /// c, the midpoint of a and b, agrees with their mean within the tolerances for every lit order.
  bool linear_enough(const Vertex& a, const Vertex& b, const Vertex& c) const {
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      if (c.view[n] != 1) continue;
      if (std::abs(c.redshift[n] - 0.5 * (a.redshift[n] + b.redshift[n])) > g_tolerance_) return false;
      if (std::abs(c.weight[n] - 0.5 * (a.weight[n] + b.weight[n])) > sampling_.weight_tolerance * c.weight[n])
        return false;
    }
    return true;
  }

  /// A settled triangle lit alike at its corners: each lit order's light as it is.
  void integrate(const std::array<const Vertex*, 3>& v, typename S::Row& row, Counts& counts) const {
    ++counts.triangles;
    const std::array<ScreenPoint, 3> xy{v[0]->at, v[1]->at, v[2]->at};
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      if (v[0]->view[n] != 1) continue;
      sink_.deposit(order_channel(n), xy, {v[0]->redshift[n], v[1]->redshift[n], v[2]->redshift[n]},
                    {v[0]->weight[n], v[1]->weight[n], v[2]->weight[n]}, row);
    }
  }

 private:
  /// The points where order n's view passes 1 going from a to b (views differ): lit samples just inside.
  EdgeCut edge_cut(const Vertex& a, const Vertex& b, std::size_t n, Counts& counts) const {
    EdgeCut out;
    const signed char ka = a.view[n], kb = b.view[n];
    // Walking up (inside -> lit -> beyond) or down, the view passes 1 where it leaves `from`'s side of a threshold.
    const bool up = ka < kb;
    const auto past_entry = [up](signed char k) { return up ? k >= 1 : k <= 1; };
    const auto past_exit = [up](signed char k) { return up ? k >= 2 : k <= 0; };
    Vertex start = a;
    if (ka != 1) {
      const Vertex next = bisect(a, b, n, past_entry, counts).second;
      if (next.view[n] != 1) return out;  // straight from inside to beyond: no band wider than the precision
      start = next;
      out.lit[static_cast<std::size_t>(out.count++)] = next;
    }
    if (kb != 1) out.lit[static_cast<std::size_t>(out.count++)] = bisect(start, b, n, past_exit, counts).first;
    return out;
  }

  /// A mixed triangle at its last size: per order, the polygon where the order is lit (its lit corners and the
  /// points on the edges where its view changes, found by bisection), in a fan of triangles. With edge_precision
  /// 0 the corners alone: lit ones with their weight, dark ones with none (first order in the cell's size).
  void cut(const std::array<std::array<long, 2>, 3>& p, const std::array<const Vertex*, 3>& v, Caches& caches,
           typename S::Row& row, Counts& counts) const {
    ++counts.triangles;
    const std::array<ScreenPoint, 3> xy{v[0]->at, v[1]->at, v[2]->at};
    for (std::size_t n = 0; n < DiskRaySample::kOrders; ++n) {
      const signed char k0 = v[0]->view[n], k1 = v[1]->view[n], k2 = v[2]->view[n];
      if (k0 == k1 && k0 == k2) {
        if (k0 == 1)
          sink_.deposit(order_channel(n), xy, {v[0]->redshift[n], v[1]->redshift[n], v[2]->redshift[n]},
                        {v[0]->weight[n], v[1]->weight[n], v[2]->weight[n]}, row);
        continue;
      }
      if (!(sampling_.edge_precision > 0.0)) {
        std::array<double, 3> g{}, w{};
        int lit = 0;
        double g_sum = 0.0;
        for (std::size_t i = 0; i < 3; ++i)
          if (v[i]->view[n] == 1) ++lit, g_sum += v[i]->redshift[n];
        if (lit == 0) continue;
        for (std::size_t i = 0; i < 3; ++i) {
          g[i] = v[i]->view[n] == 1 ? v[i]->redshift[n] : g_sum / lit;
          w[i] = v[i]->view[n] == 1 ? v[i]->weight[n] : 0.0;
        }
        sink_.deposit(order_channel(n), xy, g, w, row);
        continue;
      }
      // Walk the triangle's boundary: a lit corner, then the points where the view passes 1 along the next edge.
      std::array<const Vertex*, 9> polygon{};
      int count = 0;
      for (std::size_t i = 0; i < 3; ++i) {
        const std::size_t j = (i + 1) % 3;
        if (v[i]->view[n] == 1) polygon[static_cast<std::size_t>(count++)] = v[i];
        if (v[i]->view[n] == v[j]->view[n]) continue;
        const bool forward = p[i] < p[j];
        const EdgeKey key{forward ? std::array<long, 4>{p[i][0], p[i][1], p[j][0], p[j][1]}
                                  : std::array<long, 4>{p[j][0], p[j][1], p[i][0], p[i][1]},
                          n};
        auto it = caches.edges.find(key);
        if (it == caches.edges.end())
          it =
              caches.edges.emplace(key, forward ? edge_cut(*v[i], *v[j], n, counts) : edge_cut(*v[j], *v[i], n, counts))
                  .first;
        const EdgeCut& e = it->second;
        for (int c = 0; c < e.count; ++c)
          polygon[static_cast<std::size_t>(count++)] = &e.lit[static_cast<std::size_t>(forward ? c : e.count - 1 - c)];
      }
      for (int i = 1; i + 1 < count; ++i) {
        const Vertex &p0 = *polygon[0], &p1 = *polygon[static_cast<std::size_t>(i)],
                     &p2 = *polygon[static_cast<std::size_t>(i + 1)];
        sink_.deposit(order_channel(n), {p0.at, p1.at, p2.at}, {p0.redshift[n], p1.redshift[n], p2.redshift[n]},
                      {p0.weight[n], p1.weight[n], p2.weight[n]}, row);
      }
    }
  }

  /// From a (where `reached` is false for order n) towards b (where it is true): the last sample where it is false
  /// and the first where it is true, edge_precision apart.
  template <class Reached>
  std::pair<Vertex, Vertex> bisect(const Vertex& a, const Vertex& b, std::size_t n, Reached reached,
                                   Counts& counts) const {
    Vertex lo = a, hi = b;
    const double precision = sampling_.edge_precision * map_.mass();
    for (int it = 0; it < 60; ++it) {
      const double da = hi.at.alpha - lo.at.alpha, db = hi.at.beta - lo.at.beta;
      if (da * da + db * db <= precision * precision) break;
      Vertex mid = vertex(lo.at.alpha + 0.5 * da, lo.at.beta + 0.5 * db, counts);
      (reached(mid.view[n]) ? hi : lo) = mid;
    }
    return {lo, hi};
  }

  const Map& map_;
  const DiskLight& light_;
  const DiskSampling& sampling_;
  const S& sink_;
  double g_tolerance_, flux_scale_;
  double origin_, h_;
};

/// Meshes the square [-half, half]^2 (the map's lengths) in base x base start cells, rows of them in parallel
/// (OpenMP); returns the sink's rows (in row order) and the counts. g_tolerance: absolute, as for the Mesher.
template <DiskMap Map, Sink S>
std::vector<typename S::Row> mesh_square(const Map& map, const DiskLight& light, const DiskSampling& sampling,
                                         const S& sink, double half, double g_tolerance, Counts& counts) {
  const double flux_scale = newtonian_flux(light.emissivity, map.r_in(), map.r_out());
  // The lattice: the finest cell is 2^-depth of a start cell, every corner an integer point of it.
  const int base = sampling.base_cells;
  const double cell = 2.0 * half / base;
  int depth = 0;
  while (cell / std::ldexp(1.0, depth) > sampling.finest_cell * map.mass() && depth < 24) ++depth;
  const long step = 1L << depth;
  const Mesher<Map, S> mesher(map, light, sampling, sink, g_tolerance, flux_scale, -half,
                              cell / static_cast<double>(step));
  std::vector<typename S::Row> rows;
  rows.reserve(static_cast<std::size_t>(base));
  for (int j = 0; j < base; ++j) rows.push_back(sink.row(j));
  std::vector<Counts> row_counts(static_cast<std::size_t>(base));
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
  for (int j = 0; j < base; ++j) {
    typename S::Row& row = rows[static_cast<std::size_t>(j)];
    Counts& c = row_counts[static_cast<std::size_t>(j)];
    typename Mesher<Map, S>::Caches cache;
    for (int i = 0; i < base; ++i) {
      cache.clear();
      const long x0 = i * step, y0 = j * step, x1 = x0 + step, y1 = y0 + step;
      mesher.triangle({{{x0, y0}, {x1, y0}, {x1, y1}}}, cache, row, c);
      mesher.triangle({{{x0, y0}, {x1, y1}, {x0, y1}}}, cache, row, c);
    }
  }
  for (const Counts& c : row_counts) counts.add(c);
  return rows;
}

/// The square that holds the disk's image: grown from 1.1 r_out + 8 M until no ray on its rim sees the disk.
/// Throws std::runtime_error (`what` names the caller) when it has not fitted after 8 growths.
template <DiskMap Map>
double disk_image_half_width(const Map& map, const std::string& what) {
  double half = 1.1 * map.r_out() + 8.0 * map.mass();
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
    if (!rim_lit) return half;
    if (tries == 8)
      throw std::runtime_error(what + ": the disk's image did not fit in a square 2 x " + std::to_string(half) +
                               " M wide");
    half *= 1.25;
  }
}

}  // namespace disk_mesh
}  // namespace grtrace
