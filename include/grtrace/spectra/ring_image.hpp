// grtrace/spectra/ring_image.hpp
// The photon ring by order: a thin disk's image split into its orders n = 0, 1, 2, >= 3, each sampled as finely as
// its band needs and taken into the output's pixels with its flux conserved, and the rings' diameters, widths and
// fluxes measured along radial cuts.
//
// ring_image(map, RingImageSpec, DiskSampling = RingImageSampling{}) -> RingImage
//   Takes:   a disk map (spectra/disk_mesh.hpp's DiskMap; spectra/kerr_disk_map.hpp for Kerr), the image's pixels
//            and field (square pixels of side 2 half_width / width M, centred on the screen's origin), the disk's
//            light (eps(r), the power p of g in the observed intensity, opaque or transparent).
//   Returns: per order, the mean over each pixel of the observed intensity g^p eps(r) J (J: the screen's area to
//            solid angle times r_o^2, 1 - O(r_o^-2)), the top row first; each order's flux in the field
//            (int I dalpha dbeta, M^2 times the emissivity's unit); the rings (RingGeometry, below).
//   Method:  orders 0 and 1 (bands >= ~0.3 M wide) on the mesh of spectra/disk_mesh.hpp, each triangle (its weight
//            linear) clipped against the pixels it overlaps (Sutherland-Hodgman) and the integral of the weight
//            over each piece (its area times the weight at its corners' mean) added to that pixel. The thinner
//            rings (n = 2: ~0.02-0.07 M, n = 3: ~1e-3 M, each e^-gamma of the one before) along radial cuts from
//            the shadow's centre, one pixel apart at 6 M: on each cut every order's lit intervals (a scan of
//            offsets from the critical radius spaced logarithmically from 1e-12 M to 12 M, each change of view
//            refined by bisection, a band narrower than the scan found between a point inside it and one beyond),
//            each interval split where the cut crosses the pixels' edges and int I rho drho over each piece by
//            adaptive Simpson (1e-5 of the interval's), then spread evenly over the piece's wedge (half the angle
//            to either neighbouring cut) and clipped against the pixels. So the rings are integrated across their
//            width however thin (a uniform grid samples the n = 2 ring with one pixel in ten and misses n = 3), and
//            the pixels of each order sum to its flux. This is AART's sampling by lensing band (Cardenas-Avendano,
//            Lupsasca & Zhu 2023) with the bands found on the rays rather than from their closed-form boundaries.
//   Assumes: a far camera (as the line profile); the shadow's centre within 12 M of the screen's; intensity
//            constant across a cut's wedge (the cuts are a pixel apart or closer where the rings are).
//
// measure_rings(map, light, cuts) -> RingGeometry
//   The cuts alone (no pixels), every order n >= 1 integrated along them. On cut k, at the angle
//   phi_k = 2 pi (k + 1/2) / cuts about the shadow's centre (the midpoint of its extent on the alpha axis, found by
//   bisection on capture): the critical radius, and per order its width (the summed length of its lit intervals)
//   and radius (their length-weighted mean midpoint). The ring's diameter is twice the mean radius over the cuts
//   that see the order, its width the mean width, its flux sum_k (2 pi / cuts) int I rho drho (the trapezoidal rule
//   in angle: spectrally accurate for a smooth periodic integrand). Near the critical curve the (n+1)-th image is
//   e^-gamma times as wide as the n-th, more closely as n grows (gamma: the Lyapunov exponent of the photon orbit
//   whose point of the curve the cut crosses, exact::photon_orbit_lyapunov; Johnson et al. 2020; tested in
//   tests/ring_image_test.cpp).
#pragma once

#include "grtrace/spectra/disk_mesh.hpp"
#include "grtrace/spectra/kerr_disk_map.hpp"
#include "grtrace/spectra/ring_image_result.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace grtrace {

struct RingImageSpec {
  int width = 512, height = 512;  ///< pixels
  double half_width = 8.0;        ///< the field's half width (M): pixels of 2 half_width / width M, square
  DiskEmissivity emissivity;
  /// The observed intensity is g^redshift_power eps(r): 3 for the specific intensity at a fixed frequency of a
  /// source flat in frequency (I_nu / nu^3 is invariant), 4 for the energy flux of a line (spectra/line_profile).
  double redshift_power = 3.0;
  bool transparent = true;  ///< every crossing inside the disk's radii emits (AART's model); false: the first only
  /// radial cuts that take the rings (n >= 1) into the image and measure them; 0: one pixel apart at 6 M from the
  /// centre (the rings lie within ~4.5-6 M of it)
  int ring_cuts = 0;
};

/// The mesh's sampling for ring images: cut edges (the n = 2, 3 bands are narrower than any cell), finer cells.
struct RingImageSampling : DiskSampling {
  RingImageSampling() {
    central_cell = 0.5;
    finest_cell = 1.0 / 128.0;
    edge_precision = 1e-7;
    edge_tolerance = 1e-10;
    g_tolerance = std::numeric_limits<double>::infinity();  // g enters only through the weight
  }
};

static_assert(RingImage::kOrderChannels == disk_mesh::kOrderChannels, "a ring image's channels are the mesh's");

namespace ring_detail {

using disk_mesh::ScreenPoint;

/// A convex polygon clipped by the half-plane s * (coordinate d) <= s * bound (Sutherland-Hodgman, one edge).
inline int clip(const std::array<ScreenPoint, 8>& in, int n, std::array<ScreenPoint, 8>& out, int d, double bound,
                double s) {
  auto coord = [d](const ScreenPoint& p) { return d == 0 ? p.alpha : p.beta; };
  auto inside = [&](const ScreenPoint& p) { return s * coord(p) <= s * bound; };
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const ScreenPoint& a = in[static_cast<std::size_t>(i)];
    const ScreenPoint& b = in[static_cast<std::size_t>((i + 1) % n)];
    const bool ia = inside(a), ib = inside(b);
    if (ia) out[static_cast<std::size_t>(m++)] = a;
    if (ia != ib) {
      const double t = (bound - coord(a)) / (coord(b) - coord(a));
      out[static_cast<std::size_t>(m++)] = {a.alpha + t * (b.alpha - a.alpha), a.beta + t * (b.beta - a.beta)};
    }
  }
  return m;
}

/// The ring image's Sink: an order's light on a triangle into the pixels it overlaps, per row of start cells
/// the rows of pixels that row's cells can reach.
struct PixelSink {
  struct Row {
    int first = 0, rows = 0;  ///< the pixel rows held
    std::array<std::vector<double>, RingImage::kOrderChannels> sum;
    std::array<double, RingImage::kOrderChannels> flux{};
  };
  int width, height;
  double half_x, half_y, pixel;  ///< the field: alpha in [-half_x, half_x], beta in [-half_y, half_y]
  double mesh_half, cell;        ///< the mesh's square and its start cells

  int pixel_row(double beta) const { return static_cast<int>(std::floor((half_y - beta) / pixel)); }
  int pixel_column(double alpha) const { return static_cast<int>(std::floor((alpha + half_x) / pixel)); }

  Row row(int j) const {
    Row r;
    const double b0 = -mesh_half + cell * j, b1 = b0 + cell;
    r.first = std::clamp(pixel_row(b1) - 1, 0, height);
    const int last = std::clamp(pixel_row(b0) + 1, 0, height - 1);
    r.rows = std::max(0, last - r.first + 1);
    for (auto& s : r.sum) s.assign(static_cast<std::size_t>(r.rows) * static_cast<std::size_t>(width), 0.0);
    return r;
  }

  void deposit(std::size_t channel, const std::array<ScreenPoint, 3>& xy, const std::array<double, 3>& g,
               const std::array<double, 3>& w, Row& row) const {
    (void)g;
    const double e1a = xy[1].alpha - xy[0].alpha, e1b = xy[1].beta - xy[0].beta;
    const double e2a = xy[2].alpha - xy[0].alpha, e2b = xy[2].beta - xy[0].beta;
    const double det = e1a * e2b - e2a * e1b;
    if (det == 0.0) return;
    // The linear weight: w0 + (x - x0) . grad
    const double ga = ((w[1] - w[0]) * e2b - (w[2] - w[0]) * e1b) / det;
    const double gb = ((w[2] - w[0]) * e1a - (w[1] - w[0]) * e2a) / det;
    auto weight_at = [&](const ScreenPoint& p) {
      return w[0] + (p.alpha - xy[0].alpha) * ga + (p.beta - xy[0].beta) * gb;
    };
    const double lo_a = std::min({xy[0].alpha, xy[1].alpha, xy[2].alpha});
    const double hi_a = std::max({xy[0].alpha, xy[1].alpha, xy[2].alpha});
    const double lo_b = std::min({xy[0].beta, xy[1].beta, xy[2].beta});
    const double hi_b = std::max({xy[0].beta, xy[1].beta, xy[2].beta});
    const int c0 = std::max(0, pixel_column(lo_a)), c1 = std::min(width - 1, pixel_column(hi_a));
    const int r0 = std::max(row.first, pixel_row(hi_b)), r1 = std::min(row.first + row.rows - 1, pixel_row(lo_b));
    auto add = [&](int r, int c, double v) {
      row.sum[channel][static_cast<std::size_t>(r - row.first) * static_cast<std::size_t>(width) +
                       static_cast<std::size_t>(c)] += v;
      row.flux[channel] += v;
    };
    if (pixel_column(lo_a) == pixel_column(hi_a) && pixel_row(hi_b) == pixel_row(lo_b) && c0 == c1 && r0 == r1) {
      // wholly inside one pixel of the image
      add(r0, c0, 0.5 * std::abs(det) * (w[0] + w[1] + w[2]) / 3.0);
      return;
    }
    for (int r = r0; r <= r1; ++r) {
      const double top = half_y - pixel * r, bottom = top - pixel;
      for (int c = c0; c <= c1; ++c) {
        const double left = -half_x + pixel * c, right = left + pixel;
        std::array<ScreenPoint, 8> a{xy[0], xy[1], xy[2]}, b{};
        int n = 3;
        n = clip(a, n, b, 0, left, -1.0);
        n = clip(b, n, a, 0, right, 1.0);
        n = clip(a, n, b, 1, bottom, -1.0);
        n = clip(b, n, a, 1, top, 1.0);
        if (n < 3) continue;
        // int of a linear function over the convex polygon: fan triangles, area times the mean of the corners
        double integral = 0.0;
        const double w0 = weight_at(a[0]);
        for (int i = 1; i + 1 < n; ++i) {
          const ScreenPoint &p = a[static_cast<std::size_t>(i)], &q = a[static_cast<std::size_t>(i + 1)];
          integral += disk_mesh::triangle_area(a[0], p, q) * (w0 + weight_at(p) + weight_at(q)) / 3.0;
        }
        if (integral != 0.0) add(r, c, integral);
      }
    }
  }
};

/// One piece of an order's image on a cut: rho in [from, to] (M from the cuts' centre), int I rho drho over it.
struct Segment {
  std::size_t order;
  double from, to, integral;
};

/// int_a^b f by adaptive Simpson, to `tolerance` (absolute), at most 2^depth panels.
template <class F>
double adaptive_simpson(const F& f, double a, double fa, double b, double fb, double m, double fm, double whole,
                        double tolerance, int depth) {
  const double lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm), right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  if (depth <= 0 || std::abs(left + right - whole) <= 15.0 * tolerance)
    return left + right + (left + right - whole) / 15.0;
  return adaptive_simpson(f, a, fa, m, fm, lm, flm, left, 0.5 * tolerance, depth - 1) +
         adaptive_simpson(f, m, fm, b, fb, rm, frm, right, 0.5 * tolerance, depth - 1);
}

/// The radial cuts (see the top of this file): per cut its angle, critical radius and the segments of every order
/// n >= 1, split where the cut crosses the pixels' edges when a grid is given; the rays taken.
struct Cuts {
  double centre_alpha = 0.0;
  std::vector<double> angle, critical_radius;
  std::vector<std::vector<Segment>> segments;
  long rays = 0;
};

template <DiskMap Map>
Cuts trace_cuts(const Map& map, const DiskLight& light, int cuts, const PixelSink* grid, std::size_t first_integrated) {
  Cuts out;
  const double mass = map.mass();
  // The shadow's edge along a line from (a0, b0) in direction (ca, cb): captured at 0, escaped at 12 M.
  auto edge = [&](double a0, double b0, double ca, double cb, long& count) {
    double lo = 0.0, hi = 12.0 * mass;
    for (int it = 0; it < 100 && hi - lo > 1e-14 * mass; ++it) {
      const double mid = 0.5 * (lo + hi);
      ++count;
      (map.sample(a0 + mid * ca, b0 + mid * cb).escaped ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
  };
  ++out.rays;
  if (map.sample(0.0, 0.0).escaped)
    throw std::invalid_argument("ring geometry: the screen's centre is not inside the shadow (no hole in view?)");
  const double right = edge(0.0, 0.0, 1.0, 0.0, out.rays), left = edge(0.0, 0.0, -1.0, 0.0, out.rays);
  out.centre_alpha = 0.5 * (right - left);
  const double centre = out.centre_alpha;

  const auto k = static_cast<std::size_t>(cuts);
  out.angle.resize(k);
  out.critical_radius.resize(k);
  out.segments.assign(k, {});
  std::vector<long> cut_rays(k, 0);
  constexpr int kScan = 120;  // offsets outside, 1e-12 M .. 12 M, 1.26 apart; half as many inside
  constexpr std::size_t kOrders = DiskRaySample::kOrders;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 1)
#endif
  for (int c = 0; c < cuts; ++c) {
    const auto ci = static_cast<std::size_t>(c);
    long& count = cut_rays[ci];
    const double phi = 2.0 * std::numbers::pi * (c + 0.5) / cuts, ca = std::cos(phi), cb = std::sin(phi);
    const double rc = edge(centre, 0.0, ca, cb, count);
    out.angle[ci] = phi;
    out.critical_radius[ci] = rc;
    auto sample = [&](double rho) {
      ++count;
      return map.sample(centre + rho * ca, rho * cb);
    };
    auto view_at = [&](double rho) { return disk_mesh::views(sample(rho), light.transparent); };
    // From lo (reached false) to hi (reached true): the last rho where it is false and the first where it is true,
    // 1e-7 of their distance from the critical radius apart (the bands close in on it geometrically).
    auto bisect = [&](double lo, double hi, std::size_t n, auto reached) {
      const double precision = 1e-7 * std::max(std::abs(lo - rc), 1e-12 * mass);
      while (hi - lo > precision) {
        const double mid = 0.5 * (lo + hi);
        if (!(mid > lo && mid < hi)) break;
        (reached(view_at(mid)[n]) ? hi : lo) = mid;
      }
      return std::pair{lo, hi};
    };
    std::vector<double> rho;
    for (int i = kScan / 2; i >= 0; --i)
      if (const double d = mass * 1e-12 * std::pow(12e12, 2.0 * i / kScan); d < rc) rho.push_back(rc - d);
    for (int i = 0; i <= kScan; ++i) rho.push_back(rc + mass * 1e-12 * std::pow(12e12, static_cast<double>(i) / kScan));

    // The lit intervals of each order: between scan points whose views differ, the view's passes through 1 (a
    // band narrower than the scan's spacing is found between a point inside it and one beyond).
    std::array<std::vector<std::array<double, 2>>, kOrders> lit;
    std::array<double, kOrders> open{};
    auto prev = view_at(rho.front());
    for (std::size_t n = 1; n < kOrders; ++n)
      if (prev[n] == 1) open[n] = rho.front();
    for (std::size_t i = 1; i < rho.size(); ++i) {
      const auto now = view_at(rho[i]);
      for (std::size_t n = 1; n < kOrders; ++n) {
        const signed char a = prev[n], b = now[n];
        if (a == b) continue;
        double lo = rho[i - 1];
        if (a != 1) {  // entering: the first point at or past 1 from a's side
          const double next = bisect(lo, rho[i], n, [a](signed char v) { return a < 1 ? v >= 1 : v <= 1; }).second;
          if (view_at(next)[n] != 1) continue;  // straight past 1: no band wider than the precision
          open[n] = next;
          lo = next;
        }
        if (b != 1) {  // leaving: the last point at 1 before b's side
          const double inside = bisect(lo, rho[i], n, [b](signed char v) { return b > 1 ? v >= 2 : v <= 0; }).first;
          lit[n].push_back({open[n], inside});
        }
      }
      prev = now;
    }
    for (std::size_t n = 1; n < kOrders; ++n)
      if (prev[n] == 1) lit[n].push_back({open[n], rho.back()});

    // Each interval, split where the cut crosses the pixels' edges, integrated: int I rho drho.
    auto weight = [&](double r, std::size_t n) {
      const DiskRaySample s = sample(r);
      const auto v = disk_mesh::views(s, light.transparent);
      if (v[n] != 1) return 0.0;
      return light.intensity(s.redshift[n], s.radius[n]) *
             disk_mesh::screen_jacobian(centre + r * ca, r * cb, map.camera_radius()) * r;
    };
    for (std::size_t n = 1; n < kOrders; ++n)
      for (const auto& [from, to] : lit[n]) {
        if (n < first_integrated) {
          out.segments[ci].push_back({n, from, to, std::numeric_limits<double>::quiet_NaN()});
          continue;
        }
        std::vector<double> cuts_at{from, to};
        if (grid) {
          for (int i = 0; i <= grid->width; ++i)
            if (const double t = (-grid->half_x + grid->pixel * i - centre) / ca; ca != 0.0 && t > from && t < to)
              cuts_at.push_back(t);
          for (int j = 0; j <= grid->height; ++j)
            if (const double t = (grid->half_y - grid->pixel * j) / cb; cb != 0.0 && t > from && t < to)
              cuts_at.push_back(t);
          std::sort(cuts_at.begin(), cuts_at.end());
        }
        // the interval's scale for the tolerance: its Simpson estimate
        const double fa = weight(from, n), fb = weight(to, n), fm = weight(0.5 * (from + to), n);
        const double scale = std::abs((to - from) / 6.0 * (fa + 4.0 * fm + fb)) + 1e-300;
        for (std::size_t i = 0; i + 1 < cuts_at.size(); ++i) {
          const double a = cuts_at[i], b = cuts_at[i + 1];
          if (!(b > a)) continue;
          const double wa = weight(a, n), wb = weight(b, n), m = 0.5 * (a + b), wm = weight(m, n);
          const double whole = (b - a) / 6.0 * (wa + 4.0 * wm + wb);
          const double part = adaptive_simpson([&](double r) { return weight(r, n); }, a, wa, b, wb, m, wm, whole,
                                               1e-5 * scale * (b - a) / (to - from), 18);
          out.segments[ci].push_back({n, a, b, part});
        }
      }
  }
  for (long r : cut_rays) out.rays += r;
  return out;
}

/// The rings' shape from the cuts.
inline RingGeometry geometry(const Cuts& cuts) {
  RingGeometry out;
  out.centre_alpha = cuts.centre_alpha;
  out.cut_angle = cuts.angle;
  out.critical_radius = cuts.critical_radius;
  const std::size_t k = cuts.angle.size();
  out.cut_width.assign(k, {});
  out.cut_radius.assign(k, {});
  out.cut_flux.assign(k, {});
  for (std::size_t c = 0; c < k; ++c) {
    std::array<double, RingGeometry::kOrders> moment{};
    for (const Segment& s : cuts.segments[c]) {
      const std::size_t o = disk_mesh::order_channel(s.order);
      if (std::isfinite(s.integral)) out.cut_flux[c][o] += s.integral;
      if (s.order >= RingGeometry::kOrders) continue;
      out.cut_width[c][s.order] += s.to - s.from;
      moment[s.order] += (s.to - s.from) * 0.5 * (s.to + s.from);
    }
    for (std::size_t n = 1; n < RingGeometry::kOrders; ++n)
      out.cut_radius[c][n] = out.cut_width[c][n] > 0.0 ? moment[n] / out.cut_width[c][n] : 0.0;
  }
  out.diameter[0] = out.width[0] = std::numeric_limits<double>::quiet_NaN();
  const double dphi = 2.0 * std::numbers::pi / static_cast<double>(k);
  for (std::size_t n = 1; n < RingGeometry::kOrders; ++n) {
    double d = 0.0, w = 0.0;
    int seen = 0;
    for (std::size_t c = 0; c < k; ++c) {
      out.flux[n] += out.cut_flux[c][n] * dphi;
      if (out.cut_width[c][n] > 0.0) ++seen, d += 2.0 * out.cut_radius[c][n], w += out.cut_width[c][n];
    }
    out.cuts_seen[n] = seen;
    out.diameter[n] = seen ? d / seen : std::numeric_limits<double>::quiet_NaN();
    out.width[n] = seen ? w / seen : std::numeric_limits<double>::quiet_NaN();
  }
  out.rays = cuts.rays;
  return out;
}

}  // namespace ring_detail

/// The rings' diameters, widths and fluxes along radial cuts (see the top of this file). Parallel over cuts
/// (OpenMP). Throws std::invalid_argument for cuts outside 2 .. 100000 or a screen centre outside the shadow.
template <DiskMap Map>
RingGeometry measure_rings(const Map& map, const DiskLight& light, int cuts = 180) {
  if (cuts < 2 || cuts > 100000) throw std::invalid_argument("ring geometry: cuts must be in 2 .. 100000");
  return ring_detail::geometry(ring_detail::trace_cuts(map, light, cuts, nullptr, 1));
}

/// Checks a ring image's spec and sampling; std::invalid_argument saying what to change.
inline void check_ring_image(const RingImageSpec& spec, const DiskSampling& sampling) {
  auto fail = [](const std::string& m) { throw std::invalid_argument("ring image: " + m); };
  if (spec.width < 1 || spec.height < 1 || spec.width > 16384 || spec.height > 16384)
    fail("width and height must be in 1 .. 16384 pixels");
  if (!(spec.half_width > 0.0) || !std::isfinite(spec.half_width)) fail("the field's half width must be positive");
  disk_mesh::check_emissivity(spec.emissivity, "ring image");
  if (!std::isfinite(spec.redshift_power)) fail("the redshift power must be finite");
  if (spec.ring_cuts != 0 && (spec.ring_cuts < 2 || spec.ring_cuts > 100000))
    fail("ring_cuts must be 0 (automatic) or in 2 .. 100000");
  disk_mesh::check_sampling(sampling, "ring image");
}

/// The ring image of the map's disk (see the top of this file). Parallel over rows of start cells and over cuts
/// (OpenMP); the sums do not depend on the threads' schedule.
template <DiskMap Map>
RingImage ring_image(const Map& map, const RingImageSpec& spec, const DiskSampling& sampling = RingImageSampling{}) {
  check_ring_image(spec, sampling);
  RingImage out;
  out.width = spec.width;
  out.height = spec.height;
  out.half_width = spec.half_width;
  out.pixel = 2.0 * spec.half_width / spec.width;
  const double half_y = 0.5 * out.pixel * spec.height;
  const double mesh_half = std::max(spec.half_width, half_y);
  const ring_detail::PixelSink sink{
      spec.width, spec.height, spec.half_width, half_y, out.pixel, mesh_half, 2.0 * mesh_half / sampling.base_cells};
  // Orders 0 and 1 (bands >= ~0.3 M wide) on the mesh, the thinner rings along the cuts.
  constexpr int kMeshed = 2;
  const DiskLight light{spec.emissivity, spec.redshift_power, spec.transparent};
  DiskLight direct = light;
  direct.orders = kMeshed;
  disk_mesh::Counts counts;
  const auto rows = disk_mesh::mesh_square(map, direct, sampling, sink, mesh_half, sampling.g_tolerance, counts);
  const std::size_t pixels = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
  for (auto& image : out.intensity) image.assign(pixels, 0.0);
  for (const auto& r : rows)
    for (std::size_t o = 0; o < kMeshed; ++o) {
      for (int i = 0; i < r.rows; ++i)
        for (int c = 0; c < spec.width; ++c) {
          const std::size_t from =
              static_cast<std::size_t>(i) * static_cast<std::size_t>(spec.width) + static_cast<std::size_t>(c);
          out.intensity[o][static_cast<std::size_t>(r.first + i) * static_cast<std::size_t>(spec.width) +
                           static_cast<std::size_t>(c)] += r.sum[o][from];
        }
      out.flux[o] += r.flux[o];
    }
  const int cuts =
      spec.ring_cuts > 0
          ? spec.ring_cuts
          : std::clamp(static_cast<int>(std::ceil(2.0 * std::numbers::pi * 6.0 * map.mass() / out.pixel)), 64, 100000);
  const ring_detail::Cuts traced = ring_detail::trace_cuts(map, light, cuts, &sink, kMeshed);
  // Each segment as the wedge of its cut (half the angle to either neighbour), its flux spread evenly over the
  // wedge's chord quadrilateral and clipped against the pixels.
  ring_detail::PixelSink::Row whole;
  whole.first = 0;
  whole.rows = spec.height;
  for (auto& v : whole.sum) v.assign(pixels, 0.0);
  const double dphi = 2.0 * std::numbers::pi / cuts;
  for (std::size_t c = 0; c < traced.angle.size(); ++c) {
    const double p0 = traced.angle[c] - 0.5 * dphi, p1 = traced.angle[c] + 0.5 * dphi;
    const double c0 = std::cos(p0), s0 = std::sin(p0), c1 = std::cos(p1), s1 = std::sin(p1);
    for (const ring_detail::Segment& g : traced.segments[c]) {
      if (!std::isfinite(g.integral)) continue;  // a meshed order's
      const double quad = 0.5 * (g.to * g.to - g.from * g.from) * std::sin(dphi);
      if (!(quad > 0.0)) continue;
      const double w = g.integral * dphi / quad;
      const disk_mesh::ScreenPoint a{traced.centre_alpha + g.from * c0, g.from * s0},
          b{traced.centre_alpha + g.to * c0, g.to * s0}, d{traced.centre_alpha + g.to * c1, g.to * s1},
          e{traced.centre_alpha + g.from * c1, g.from * s1};
      const std::size_t channel = disk_mesh::order_channel(g.order);
      sink.deposit(channel, {a, b, d}, {0.0, 0.0, 0.0}, {w, w, w}, whole);
      sink.deposit(channel, {a, d, e}, {0.0, 0.0, 0.0}, {w, w, w}, whole);
    }
  }
  for (std::size_t o = kMeshed; o < RingImage::kOrderChannels; ++o) {
    for (std::size_t i = 0; i < pixels; ++i) out.intensity[o][i] += whole.sum[o][i];
    out.flux[o] = whole.flux[o];
  }
  const double pixel_area = out.pixel * out.pixel;
  for (auto& image : out.intensity)
    for (double& v : image) v /= pixel_area;
  out.rays = counts.rays + traced.rays;
  out.triangles = counts.triangles;
  out.unresolved = counts.unresolved;
  out.uncovered = counts.uncovered;
  out.rings = ring_detail::geometry(traced);
  return out;
}

}  // namespace grtrace
