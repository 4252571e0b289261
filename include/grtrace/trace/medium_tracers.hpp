// grtrace/trace/medium_tracers.hpp
// A frame's light from an emitting medium (medium/emitting_medium.hpp), pixel by pixel: the general tracer, which
// integrates every pixel's ray with its light (trace/emission_system.hpp); the same on Kerr's separated equations in
// Mino time for a stationary medium around a Kerr hole, the empty space around it crossed in closed form
// (KerrMinoMediumTracer); and, for a spherically symmetric
// medium around a static spherically symmetric hole, one table of rays for the whole frame.
//
// Takes:   the metric, the medium, trace settings (tolerances, sky radius, horizon guard), the camera (its
//          4-velocity: the photon's energy E_cam it measures) and the observed frequency nu_obs.
// Returns: per pixel a MediumSample: the ray's status, the intensity I_nu(nu_obs) at the camera, the optical depth
//          along the ray, the accepted steps; from the general tracer also the intensity by image order and the
//          ray's order (trace/emission_system.hpp); the general and Mino-time tracers at several frequencies in one
//          pass, a SpectralMediumSample (the same, one value a band). The table's rays lie in the equatorial plane, so
//          they cannot say where a pixel's ray, in a plane of its own, crosses it or turns: the table tracer does not
//          split by order (a spherically symmetric scene has no plane of its own either; the general tracer splits it
//          by the chart's).
//
// Why one table serves a spherical medium (SphericalMediumTracer): the ray, the fluid along it and so the light it
// collects depend only on the ray's angle delta to the outward radial in the static frame at the camera
// (trace/planar_geometry.hpp); a static observer there would see I_static(delta) at nu_obs. A camera that moves
// sees the same photon at E_cam = rho E_static, and I_nu / nu^3 is invariant, so it sees
//   I_cam(nu_obs) = rho^3 I_static(delta, nu_obs / rho),
// which is rho^3 times the table's value when the medium is frequency-independent (the trait of that name) or the
// camera is static (rho = 1). A moving camera and a medium with a spectrum: every pixel is traced by the general
// tracer (exact, slower; fallback_rays() counts them). The table's rays are the general tracer's, equatorial, at
// delta spaced as trace/critical_angle_grid.hpp says (logarithmically near the critical angle, where a ray winds
// around the photon sphere and the intensity diverges like -ln |delta - delta_c|), read by quintic interpolation.
// Assumes: a medium whose light is a smooth function of delta, but at the ray that grazes its edge (a medium with a
// boundary: the sphere r = outer_radius()), where the light has a kink: the pixels whose stencil of table rays
// straddles that ray are integrated by the general tracer (interpolated across it, SphericalAccretion cut at 8 M
// seen from 1000 M was 12 % of the frame's peak off at the pixels beyond the edge).
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/medium/emitting_medium.hpp"
#include "grtrace/metric/static_spherical.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/trace/critical_angle_grid.hpp"
#include "grtrace/trace/emission_system.hpp"
#include "grtrace/trace/kerr_mino_system.hpp"
#include "grtrace/trace/planar_geometry.hpp"
#include "grtrace/trace/planar_scene_tracer.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace grtrace {

/// Table rays on each side of the critical angle where the caller names no number. The light is smoother in delta
/// than the sweep the planar table reads (critical_angle_grid.hpp): 512 rays a side read it within 2e-11 of the
/// table's own ray at every pixel of the accreting hole's frame (256: 1.3e-9, 128: 9e-8), below the integration's
/// error at any tolerance the tools offer, in half the time of 1024.
inline constexpr int default_medium_table_rays = 512;

/// What a medium tracer gives a pixel (see the top of this file).
struct MediumSample {
  RayStatus status = RayStatus::max_steps;
  double intensity = 0.0;      ///< I_nu at the camera, at nu_obs
  double optical_depth = 0.0;  ///< tau along the ray, from the camera to its end
  int steps = 0;               ///< accepted steps (the table tracer: the nearest table ray's)
  double redshift = std::numeric_limits<double>::quiet_NaN();  ///< emission-weighted g = nu_obs / nu_fluid
  /// The intensity by image order n = 0, 1, 2, >= 3 (EmissionResult's), where the tracer splits it (its
  /// `splits_by_order`); zero otherwise.
  std::array<double, 4> intensity_by_order{};
  int order = -1;  ///< the ray's crossings of the equatorial plane (RayOutcome::order); -1: not counted
};

/// Whether a medium tracer's samples carry the intensity by order (a `static constexpr bool splits_by_order`).
template <class Tracer>
constexpr bool splits_by_order() {
  if constexpr (requires { Tracer::splits_by_order; }) return Tracer::splits_by_order;
  else return false;
}

/// What a tracer at several observing frequencies gives a pixel: MediumSample's light in each band, from one ray.
template <std::size_t Bands>
struct SpectralMediumSample {
  RayStatus status = RayStatus::max_steps;
  std::array<double, Bands> intensity{};                          ///< I_nu at the camera, at each nu_obs
  std::array<double, Bands> optical_depth{};                      ///< tau along the ray in each band
  std::array<double, Bands> redshift{};                           ///< emission-weighted g in each band (NaN: no light)
  std::array<std::array<double, 4>, Bands> intensity_by_order{};  ///< each band's by image order
  int steps = 0;                                                  ///< accepted steps
  int order = -1;                                                 ///< the ray's crossings of the equatorial plane
};

/// Every pixel's ray integrated with its light on the ray's system Ray (trace_emission_along), seen by the camera's
/// 4-velocity: GeneralMediumTracer (the geodesic equation of any metric) and KerrMinoMediumTracer (below), at one
/// observing frequency (Bands = 1: MediumSample) or at Bands of them in one pass (SpectralMediumSample<Bands>: each
/// pixel's ray traced once, the medium asked for every band at each stage, the steps set by every band's error).
template <class Ray, ExplicitTableau T, StepController C, class Medium, std::size_t Bands = 1>
class RayMediumTracer {
 public:
  using Metric = detail::RayMetric<Ray>;
  using Frequencies = std::conditional_t<Bands == 1, double, std::array<double, Bands>>;
  using Sample = std::conditional_t<Bands == 1, MediumSample, SpectralMediumSample<Bands>>;
  static constexpr const char* name = std::is_same_v<Ray, KerrMinoSystem> ? "kerr-mino" : "general";
  static constexpr bool splits_by_order = true;

  RayMediumTracer(Metric metric, Medium medium, const TraceSettings& settings, const Vec4& camera_velocity,
                  const Frequencies& frequency, C controller = {})
      : metric_(metric),
        medium_(medium),
        settings_(settings),
        controller_(controller),
        velocity_(camera_velocity),
        frequency_(frequency) {
    static_assert(check_emitting_medium<Medium, Metric>());
  }

  Sample trace(const GeodesicState& y0) const {
    const double e_cam = camera_photon_energy(metric_, y0, velocity_);
    const auto r = [&] {
      // Kerr: the empty space outside the medium's outer radius crossed in closed form (trace_kerr_medium_ray).
      if constexpr (std::is_same_v<Ray, KerrMinoSystem>)
        return trace_kerr_medium_ray<T>(metric_, medium_, settings_, y0, e_cam, frequency_, controller_);
      else return trace_emission_along<Ray, T>(metric_, medium_, settings_, y0, e_cam, frequency_, controller_);
    }();
    if constexpr (Bands == 1) {
      return {r.trace.status, r.intensity,          r.optical_depth,  r.trace.accepted,
              r.redshift,     r.intensity_by_order, r.trace.crossings};
    } else {
      return {r.trace.status,       r.intensity,      r.optical_depth,  r.redshift,
              r.intensity_by_order, r.trace.accepted, r.trace.crossings};
    }
  }

  const Metric& metric() const { return metric_; }
  const Medium& medium() const { return medium_; }
  const Frequencies& frequencies() const { return frequency_; }

 private:
  Metric metric_;
  Medium medium_;
  TraceSettings settings_;
  C controller_;
  Vec4 velocity_;
  Frequencies frequency_;
};

/// Every pixel's ray integrated with its light (trace_emission) through the geodesic equation of any metric.
template <MetricPolicy Metric, ExplicitTableau T, StepController C, class Medium, std::size_t Bands = 1>
using GeneralMediumTracer = RayMediumTracer<MetricGeodesicSystem<Metric>, T, C, Medium, Bands>;

/// Every pixel's ray integrated with its light on Kerr's separated equations in Mino time (trace_kerr_medium_ray):
/// a stationary medium around a Kerr hole in Boyer-Lindquist coordinates, the same light as GeneralMediumTracer's
/// within the tolerance (tests/medium_torus_test.cpp), each stage's ray a few polynomials in place of the metric's
/// Christoffel symbols; the empty space outside the medium's outer radius (and inside its inner radius, for a ray
/// that falls in) crossed in closed form, a ray that never reaches the medium answered without a step (its sample's
/// steps 0).
template <ExplicitTableau T, StepController C, class Medium, std::size_t Bands = 1>
using KerrMinoMediumTracer = RayMediumTracer<KerrMinoSystem, T, C, Medium, Bands>;

/// The light a static observer at the camera's radius sees along the ray at angle delta (see the top of this file),
/// interpolated from table rays on each side of the critical angle.
template <StaticSphericalMetric Metric, ExplicitTableau T, StepController C, class Medium>
class SphericalMediumTable {
  static_assert(medium_is_spherically_symmetric<Medium>(),
                "SphericalMediumTable: the medium must be spherically symmetric (declare `static constexpr bool "
                "spherically_symmetric = true;` if it is: j, alpha a function of r alone, the fluid moving radially)");

 public:
  /// Takes the metric, the medium, the camera's radius, the settings of the table rays (their sky radius too), the
  /// range of delta the frame needs, the frequency a static observer at the camera measures, the rays per side.
  /// Assumes (checked) a horizon, guard < camera_r < sky radius.
  SphericalMediumTable(Metric metric, Medium medium, double camera_r, const TraceSettings& settings, double delta_min,
                       double delta_max, double frequency, int nodes_per_side = default_medium_table_rays,
                       C controller = {})
      : metric_(metric),
        medium_(medium),
        settings_(settings),
        controller_(controller),
        camera_r_(camera_r),
        frequency_(frequency) {
    const double rh = metric.horizon_radius();
    if (!(rh > 0.0))
      throw std::invalid_argument("SphericalMediumTable: the metric has no horizon (use the general tracer)");
    if (!(camera_r > (1.0 + settings.horizon_epsilon) * rh && camera_r < settings.escape_radius))
      throw std::invalid_argument("SphericalMediumTable: need horizon guard < camera radius < sky radius");
    const double a = std::asin(
        std::min(1.0, critical_impact_parameter(metric) / camera_r * std::sqrt(metric.lapse_squared(camera_r))));
    delta_c_ = camera_r >= photon_sphere_radius(metric) ? std::numbers::pi - a : a;
    delta_min = std::clamp(delta_min, 0.0, std::numbers::pi);
    delta_max = std::clamp(delta_max, 0.0, std::numbers::pi);
    constexpr double min_gap = 1e-14;  // as the planar table: closer rays are read from the last node
    if (delta_min < delta_c_)
      escaped_ =
          build(+1, std::max(delta_c_ - std::min(delta_max, delta_c_), min_gap), delta_c_ - delta_min, nodes_per_side);
    if (delta_max > delta_c_)
      captured_ =
          build(-1, std::max(std::max(delta_min, delta_c_) - delta_c_, min_gap), delta_max - delta_c_, nodes_per_side);
    // A medium with an edge (a boundary: the sphere r_e = outer_radius() of a spherically symmetric medium) puts a
    // kink in the light at the ray whose periapsis grazes it, b_e = r_e / sqrt(A(r_e)) (an escaping ray, seen
    // from a camera outside r_e): its place on the escaped side's grid, for at() to refuse the stencils across it.
    if constexpr (detail::MediumWithBoundary<Medium, Metric>) {
      const double r_e = medium.outer_radius();
      if (r_e > photon_sphere_radius(metric) && r_e < camera_r && !escaped_.values.empty()) {
        const double b_e = r_e / std::sqrt(metric.lapse_squared(r_e));
        const double s_e = b_e * std::sqrt(metric.lapse_squared(camera_r)) / camera_r;
        if (s_e < 1.0) {
          const double gap = delta_c_ - (std::numbers::pi - std::asin(s_e));
          if (gap > 0.0) escaped_.edge = (escaped_.grid.coordinate(gap) - escaped_.grid.s0) * escaped_.grid.inverse_ds;
        }
      }
    }
  }

  double critical_angle() const { return delta_c_; }
  double camera_radius() const { return camera_r_; }
  long table_steps() const { return total_steps_; }
  int table_rays() const { return static_cast<int>(escaped_.values.size() + captured_.values.size()); }

  /// The interpolated sample at delta (status escaped or captured, or a table ray's failure nearby).
  MediumSample at(double delta) const {
    const bool escaped = delta < delta_c_;
    const Side& side = escaped ? escaped_ : captured_;
    if (side.values.empty()) throw std::out_of_range("SphericalMediumTable: delta outside the tabulated range");
    const CriticalAngleGrid::Stencil st = side.grid.stencil(std::abs(delta - delta_c_));
    const RayStatus expected = escaped ? RayStatus::escaped : RayStatus::captured;
    MediumSample s{expected, 0.0, 0.0, 0};
    double weight = 0.0;  // I g, interpolated as I is (a product of smooth functions), then divided by I
    // Near the medium's edge: no interpolation there (max_steps: not a value). The light grows as the square root
    // of the chord inside the edge, sqrt(b_e - b), which a polynomial through nodes within a few spacings of it
    // misreads (SphericalAccretion cut at 8 M: 17 % at a pixel whose stencil lay just inside the edge).
    if (side.edge >= 0.0 && std::abs(st.nearest - side.edge) <= kEdgeNodes) {
      s.status = RayStatus::max_steps;
      return s;
    }
    for (int j = 0; j < st.count; ++j) {
      const MediumSample& v = side.values[static_cast<std::size_t>(st.first + j)];
      const double w = st.weight[static_cast<std::size_t>(j)];
      if (v.status != expected) s.status = v.status;  // a failed table ray poisons its neighbourhood
      s.intensity += w * v.intensity;
      s.optical_depth += w * v.optical_depth;
      if (v.intensity > 0.0) weight += w * v.intensity * v.redshift;
    }
    if (s.intensity > 0.0) s.redshift = weight / s.intensity;
    s.steps = side.values[static_cast<std::size_t>(st.nearest)].steps;
    return s;
  }

  /// One table ray: the equatorial ray from the camera's radius at angle delta, photon energy 1 in the static frame.
  MediumSample trace_node(double delta) const {
    const double r = camera_r_;
    const Vec4 x(0.0, r, std::numbers::pi / 2.0, 0.0);
    // Past-directed (traced from the camera backwards), as a camera's pixel: k^t = -1 / sqrt(A); its spatial part
    // has unit length in the static frame, at angle delta from the outward radial towards +phi.
    const Vec4 k(-1.0 / std::sqrt(metric_.lapse_squared(r)),
                 std::cos(delta) / std::sqrt(radial_scale_squared(metric_, r)), 0.0, std::sin(delta) / r);
    const EmissionResult e =
        trace_emission<T>(metric_, medium_, settings_, make_state(x, k), 1.0, frequency_, controller_);
    return {e.trace.status, e.intensity, e.optical_depth, e.trace.accepted, e.redshift};
  }

 private:
  /// Table rays on each side of the medium's edge within which pixels are integrated instead (see at()).
  static constexpr double kEdgeNodes = 12.0;

  struct Side {
    CriticalAngleGrid grid;
    std::vector<MediumSample> values;
    double edge = -1.0;  ///< the grid position of the medium's edge (negative: none on this side)
  };

  // sign +1: escaped side, delta = delta_c - gap; sign -1: captured side, delta = delta_c + gap.
  Side build(int sign, double gap_min, double gap_max, int nodes) {
    Side side{CriticalAngleGrid(gap_min, gap_max, nodes), {}};
    const int n = side.grid.nodes;
    side.values.resize(static_cast<std::size_t>(n));
    long steps = 0;
#ifdef _OPENMP
#pragma omp parallel for schedule(dynamic, 8) reduction(+ : steps)
#endif
    for (int i = 0; i < n; ++i) {
      const MediumSample s = trace_node(delta_c_ - sign * side.grid.gap_of_node(i));
      side.values[static_cast<std::size_t>(i)] = s;
      steps += s.steps;
    }
    total_steps_ += steps;
    return side;
  }

  Metric metric_;
  Medium medium_;
  TraceSettings settings_;
  C controller_;
  double camera_r_, frequency_;
  double delta_c_ = 0.0;
  Side escaped_, captured_;
  long total_steps_ = 0;
};

/// A camera's frame of a spherically symmetric medium from one SphericalMediumTable (see the top of this file),
/// the general tracer for the pixels the table cannot give.
template <StaticSphericalMetric Metric, ExplicitTableau T, StepController C, class Medium>
class SphericalMediumTracer {
  static_assert(C::estimate != ErrorEstimate::none,
                "the medium's table needs an adaptive controller (i, pi, doubling): a fixed step would skip thin "
                "bright layers unnoticed");

 public:
  static constexpr const char* name = "planar";
  static constexpr bool splits_by_order = false;  ///< its table's rays do not know a pixel's plane (see the top)

  /// Builds the table for the camera's pixels at nu_obs. Assumes (checked by the table) horizon guard < camera
  /// radius < sky radius, and the camera's chart is the metric's spherical one.
  SphericalMediumTracer(Metric metric, Medium medium, const TraceSettings& settings, const Camera& camera,
                        double frequency, int nodes_per_side = default_medium_table_rays, C controller = {})
      : metric_(metric), fallback_(metric, medium, settings, camera.tetrad().e[0], frequency, controller) {
    const Vec4 x = camera.position();
    const Vec4 u = camera.tetrad().e[0];
    camera_r_ = x[1];
    camera_theta_ = x[2];
    camera_phi_ = x[3];
    camera_basis_ = spherical_basis(camera_theta_, camera_phi_);
    camera_frame_ = static_radial_frame(metric, camera_r_);
    camera_covelocity_ = metric.metric(x) * u;
    static_camera_ = u[1] == 0.0 && u[2] == 0.0 && u[3] == 0.0;
    if (static_camera_ || medium_is_frequency_independent<Medium>()) {
      const auto [lo, hi] = planar_angle_range(metric, camera);
      // A static observer at the camera measures nu_obs / rho; for a static camera rho = 1, and a
      // frequency-independent medium does not care which frequency the table holds.
      table_.emplace(metric, medium, camera_r_, settings, lo, hi, frequency, nodes_per_side, controller);
    }
  }

  MediumSample trace(const GeodesicState& y0) const {
    const bool at_camera = y0[1] == camera_r_ && y0[2] == camera_theta_ && y0[3] == camera_phi_;
    if (!table_ || !at_camera) return fall_back(y0);
    const PlanarGeometry g = planar_geometry(y0, camera_basis_, camera_frame_);
    MediumSample s = table_->at(g.delta);
    // A failed table ray nearby, or the medium's edge within the stencil: integrated instead.
    if (s.status != RayStatus::escaped && s.status != RayStatus::captured) return fall_back(y0);
    if (!static_camera_) {
      // rho = E_cam / E_static, E_static = sqrt(A) |k^t| (the static observer's u = e_t / sqrt(A)).
      const Vec4 k = y0.template tail<4>();
      const double rho =
          std::abs(k.dot(camera_covelocity_)) / (std::sqrt(camera_frame_.lapse_squared) * std::abs(k[0]));
      s.intensity *= rho * rho * rho;
      s.redshift *= rho;  // every g along the ray scales by rho, and every weight by rho^3
    }
    return s;
  }

  const Metric& metric() const { return metric_; }
  /// The table (nothing when a moving camera and a medium with a spectrum left every pixel to the general tracer).
  const SphericalMediumTable<Metric, T, C, Medium>* table() const { return table_ ? &*table_ : nullptr; }
  long table_rays() const { return table_ ? table_->table_rays() : 0; }
  long table_steps() const { return table_ ? table_->table_steps() : 0; }
  /// Pixels traced by the general tracer instead, since construction.
  long fallback_rays() const { return fallbacks_.load(std::memory_order_relaxed); }

 private:
  MediumSample fall_back(const GeodesicState& y0) const {
    fallbacks_.fetch_add(1, std::memory_order_relaxed);
    return fallback_.trace(y0);
  }

  Metric metric_;
  GeneralMediumTracer<Metric, T, C, Medium> fallback_;
  std::optional<SphericalMediumTable<Metric, T, C, Medium>> table_;
  double camera_r_ = 0.0, camera_theta_ = 0.0, camera_phi_ = 0.0;
  SphericalBasis camera_basis_{};
  StaticRadialFrame camera_frame_{};
  Vec4 camera_covelocity_ = Vec4::Zero();  ///< g(u_cam, .) at the camera: E_cam = |k . it|
  bool static_camera_ = false;
  mutable std::atomic<long> fallbacks_{0};
};

}  // namespace grtrace
