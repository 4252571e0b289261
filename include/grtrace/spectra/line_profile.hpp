// grtrace/spectra/line_profile.hpp
// The line profile of a thin disk: the flux a distant observer receives per energy bin from a line emitted at one
// energy by gas on circular orbits, integrated over the image plane on an adaptive mesh (not a histogram of a
// frame's pixels), in total and by image order n = 0, 1, 2, >= 3.
//
// Takes:   a disk map (spectra/disk_mesh.hpp's DiskMap: a screen point (alpha, beta) in units of M -> the crossings of
//          its ray with the equatorial plane, each with its radius and redshift g = E_obs / E_emit), a
//          LineProfileSpec (the line's rest energy, the energy bins, the emissivity, opaque or transparent disk)
//          and a LineSampling (how fine the mesh may go). KerrDiskMap gives the map of a Kerr (or Schwarzschild:
//          spin 0) hole (spectra/kerr_disk_map.hpp), for a static camera at any radius.
// Returns: a LineProfile: per bin the energy flux per unit energy, F_E = (1 / dE) int_bin dE int dalpha dbeta
//          I_E, which for a line of rest energy E_0 and emitted intensity eps(r) (gas frame) is
//            F_bin = (1 / dE) int g^4 eps(r) [g E_0 in bin] dalpha dbeta          (I_E / E^3 is invariant),
//          in units of eps times M^2 times the energy unit (a distant observer's flux times D^2 / M^2); the same
//          split by order (the bins of the four orders sum to the total); the flux that fell outside the bins;
//          how many rays and triangles it took.
// Method:  the image plane's mesh of spectra/disk_mesh.hpp (triangles that follow what each order sees, settled
//          when g and the weight g^4 eps J are linear within the tolerances, the images' edges cut by bisection),
//          its triangles taken into the bins: on a triangle with linear g and weight the flux with g in [t1, t2] is
//          exact, the triangle clipped by the lines g = t being a triangle or a quadrilateral, the integral of a
//          linear weight over it its area times the mean of its corners (clipped_weight below). The line profile
//          itself is Laor's (ApJ 376, 90, 1991) observable.
// Assumes: the observer is far enough that the screen coordinates alpha = r_o x, beta = r_o y of the camera's
//          tangent plane (x, y) are the impact parameters (J = (1 + x^2 + y^2)^-3/2 turns them into the solid
//          angle times r_o^2, exact for any r_o); the disk's image lies inside the square (checked: the square grows
//          until no ray on its rim sees the disk).
#pragma once

#include "grtrace/spectra/disk_mesh.hpp"
#include "grtrace/spectra/kerr_disk_map.hpp"
#include "grtrace/spectra/line_profile_result.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace grtrace {

/// The line's intensity in the gas's frame (spectra/disk_mesh.hpp: a power law or a broken one).
using LineEmissivity = DiskEmissivity;
/// How fine the image-plane mesh may go (spectra/disk_mesh.hpp).
using LineSampling = DiskSampling;

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

namespace line_detail {

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

/// The line profile's Sink (spectra/disk_mesh.hpp): an order's light on a triangle into energy bins of width
/// `bin_width` (edges[0] + bin_width i), what falls outside them counted apart.
struct LineBins {
  struct Row {
    std::array<std::vector<double>, LineProfile::kOrderChannels> bins;
    double outside = 0.0;
    double e_min = std::numeric_limits<double>::infinity(), e_max = 0.0;  ///< the energies that carried light
  };
  const std::vector<double>& edges;
  double bin_width, line_energy;

  Row row(int) const {
    Row r;
    for (auto& b : r.bins) b.assign(edges.size() - 1, 0.0);
    return r;
  }

  void deposit(std::size_t channel, const std::array<disk_mesh::ScreenPoint, 3>& xy, std::array<double, 3> g,
               const std::array<double, 3>& w, Row& row) const {
    const double area = disk_mesh::triangle_area(xy[0], xy[1], xy[2]);
    std::vector<double>& bins = row.bins[channel];
    for (double& x : g) x *= line_energy;  // energies from here on
    const double lo = std::min({g[0], g[1], g[2]}), hi = std::max({g[0], g[1], g[2]});
    const double whole = area * (w[0] + w[1] + w[2]) / 3.0;
    if (whole > 0.0) row.e_min = std::min(row.e_min, lo), row.e_max = std::max(row.e_max, hi);
    const auto nb = static_cast<long>(bins.size());
    const long first = bin_of(lo), last = bin_of(hi);
    if (first == last) {
      if (first >= 0 && first < nb) bins[static_cast<std::size_t>(first)] += whole;
      else row.outside += whole;
      return;
    }
    double below = 0.0;  // the weight with energy below the current bin's upper edge
    for (long b = std::max(first, -1L); b <= std::min(last, nb); ++b) {
      const double upper =
          b < nb ? clipped_weight(g, w, area, b >= 0 ? edges[static_cast<std::size_t>(b + 1)] : edges.front()) : whole;
      const double part = upper - below;
      below = upper;
      if (b >= 0 && b < nb) bins[static_cast<std::size_t>(b)] += part;
      else row.outside += part;
    }
  }

  /// The bin of energy e: -1 below the first edge, bins() at or above the last.
  long bin_of(double e) const {
    const auto nb = static_cast<long>(edges.size()) - 1;
    if (e < edges.front()) return -1;
    if (e >= edges.back()) return nb;
    return std::min(nb - 1, static_cast<long>((e - edges.front()) / bin_width));
  }
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
  disk_mesh::check_emissivity(spec.emissivity, "line profile");
  disk_mesh::check_sampling(sampling, "line profile");
}

/// The line profile of the map's disk (see the top of this file). Parallel over rows of start cells (OpenMP);
/// the sums do not depend on the number of threads' schedule.
template <DiskMap Map>
LineProfile line_profile(const Map& map, const LineProfileSpec& spec, const LineSampling& sampling = {}) {
  check_line_profile(spec, sampling);
  LineProfile out;
  const double mass = map.mass();
  const double half = disk_mesh::disk_image_half_width(map, "line profile");
  out.half_width = half;
  const DiskLight light{spec.emissivity, 4.0, spec.transparent};

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
    const int base = sampling.base_cells;
    const double cell = 2.0 * half / base;
    for (int j = 0; j <= base; ++j)
      for (int i = 0; i <= base; ++i) look(-half + cell * i, -half + cell * j);
    constexpr int kCentre = 96;  // 0.25 M apart over the central 24 M
    for (int j = 0; j <= kCentre; ++j)
      for (int i = 0; i <= kCentre; ++i) look(mass * (-12.0 + 24.0 * i / kCentre), mass * (-12.0 + 24.0 * j / kCentre));
    if (!(g_hi > 0.0)) g_lo = 0.5, g_hi = 1.5;  // nothing seen: any range
    e_lo = std::max(0.0, g_lo - 0.1 * (g_hi - g_lo)) * spec.line_energy;
    e_hi = (g_hi + 0.1 * (g_hi - g_lo)) * spec.line_energy;
  }

  std::vector<line_detail::LineBins::Row> rows;
  disk_mesh::Counts counts;
  double bin_width = 0.0;
  auto mesh = [&] {
    bin_width = (e_hi - e_lo) / spec.bins;
    out.edges.resize(static_cast<std::size_t>(spec.bins) + 1);
    for (int i = 0; i <= spec.bins; ++i) out.edges[static_cast<std::size_t>(i)] = e_lo + bin_width * i;
    out.edges.back() = e_hi;
    const line_detail::LineBins sink{out.edges, bin_width, spec.line_energy};
    rows = disk_mesh::mesh_square(map, light, sampling, sink, half, sampling.g_tolerance * bin_width / spec.line_energy,
                                  counts);
  };
  mesh();
  if (automatic) {
    double outside = 0.0, lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const auto& r : rows) outside += r.outside, lo = std::min(lo, r.e_min), hi = std::max(hi, r.e_max);
    if (outside > 0.0) {  // the first mesh's cost stays in the counts
      const double margin = 1e-6 * (hi - lo);
      e_lo = std::max(0.0, lo - margin), e_hi = hi + margin;
      mesh();
    }
  }

  out.flux.assign(static_cast<std::size_t>(spec.bins), 0.0);
  for (auto& b : out.flux_by_order) b.assign(static_cast<std::size_t>(spec.bins), 0.0);
  for (const auto& r : rows) {
    for (std::size_t o = 0; o < LineProfile::kOrderChannels; ++o)
      for (std::size_t b = 0; b < out.flux.size(); ++b) out.flux_by_order[o][b] += r.bins[o][b];
    out.outside += r.outside;
  }
  out.rays = counts.rays;
  out.triangles = counts.triangles;
  out.unresolved = counts.unresolved;
  out.uncovered = counts.uncovered;
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
