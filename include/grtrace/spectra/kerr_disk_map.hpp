// grtrace/spectra/kerr_disk_map.hpp
// The disk map of a Kerr (or Schwarzschild: spin 0) hole: a ray in closed form (exact/kerr_null_geodesic.hpp) -> its
// crossings of the equatorial plane, each with its radius and the redshift of gas on a Keplerian circular orbit
// there; for any ray from its state (KerrDiskRays: a camera's disk-light frame, render/disk_light_frame.hpp), and
// for a distant screen's points (KerrDiskMap: what the line profile, spectra/line_profile.hpp, and the ring image,
// spectra/ring_image.hpp, mesh).
#pragma once

#include "grtrace/core/types.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/exact/kerr_null_geodesic.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/spectra/disk_mesh.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace grtrace {

/// A thin disk's crossings along any ray of a Kerr hole (Boyer-Lindquist; spin 0: Schwarzschild): from the ray's
/// state (a camera's pixel, any camera outside the disk's photon orbit), each crossing's radius by one Jacobi function
/// (exact/kerr_null_geodesic.hpp) and the redshift against gas on Keplerian circular orbits there
/// (exact/kerr_exact.hpp's u^t and Omega: Bardeen, Press & Teukolsky 1972; sense +1 towards +phi) from the ray's
/// conserved k_t and k_phi: g = -1 / (u^t (k_t + Omega k_phi)), in the scale of the state's k (a camera's pixel
/// momentum has unit energy in the camera's frame: g = f_obs / f_src). What KerrDiskMap samples on its screen and a
/// camera's disk-light frame (render/disk_light_frame.hpp) at its pixels.
class KerrDiskRays {
 public:
  /// Throws std::invalid_argument (what to change) for a disk not outside the photon orbit of its sense (no
  /// circular orbit inside it), r_out <= r_in, or a sky sphere (where rays end) not beyond the disk.
  KerrDiskRays(KerrMetric metric, double r_in, double r_out, int sense, double sky_radius)
      : metric_(metric),
        r_in_(r_in),
        r_out_(r_out),
        orbit_((sense >= 0) == (metric.spin >= 0.0) ? exact::Orbit::prograde : exact::Orbit::retrograde),
        sky_(sky_radius),
        guard_((1.0 + 1e-6) * metric.horizon_radius()) {
    const double photon_orbit = exact::photon_orbit_radius(metric.spin, orbit_, metric.mass);
    if (!(r_in > photon_orbit) || !(r_out > r_in) || !std::isfinite(r_out))
      throw std::invalid_argument("disk map: the disk needs photon orbit (" + std::to_string(photon_orbit) +
                                  " M for its sense) < r_in < r_out (finite), got r_in = " + std::to_string(r_in) +
                                  ", r_out = " + std::to_string(r_out));
    if (!(sky_radius > r_out) || !std::isfinite(sky_radius))
      throw std::invalid_argument("disk map: the sky sphere (" + std::to_string(sky_radius) +
                                  " M) must lie beyond the disk's outer radius; raise it");
  }

  double r_in() const { return r_in_; }
  double r_out() const { return r_out_; }
  double sky_radius() const { return sky_; }
  const KerrMetric& metric() const { return metric_; }

  /// The crossings of the ray y0 (Boyer-Lindquist, outside the horizon, inside the sky sphere). covered = false
  /// where the closed form does not follow the ray: vortical rays (eta <= 0, which never reach the plane), and a
  /// camera inside the ray's potential barrier or on the axis (exact/kerr_null_geodesic.hpp).
  DiskRaySample sample(const GeodesicState& y0) const {
    DiskRaySample s;
    const KerrNullGeodesic geodesic(metric_, y0, sky_, guard_);
    if (!geodesic.supported()) {
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
      } else {
        s.where[static_cast<std::size_t>(n)] = DiskRaySample::beyond_edge;
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
  double sky_, guard_;
};

/// The disk map of a Kerr hole (Boyer-Lindquist; spin 0: Schwarzschild) seen by a static camera at (r_o, theta_o):
/// each screen point's ray (alpha, beta at the camera's distance) followed by KerrDiskRays, the sky sphere at 10 r_o.
class KerrDiskMap {
 public:
  /// Throws std::invalid_argument (what to change) for a disk not outside the photon orbit of its sense (no
  /// circular orbit inside it), r_out <= r_in, a camera not outside the disk or on the axis (theta_o within 1e-4
  /// rad of it).
  KerrDiskMap(KerrMetric metric, double camera_r, double camera_theta, double r_in, double r_out, int sense = +1)
      : rays_(metric, r_in, r_out, sense, 10.0 * camera_r) {
    if (!(camera_r > 10.0 * r_out) || !std::isfinite(camera_r))
      throw std::invalid_argument("disk map: the camera must be far from the disk (r_o > 10 r_out); got r_o = " +
                                  std::to_string(camera_r));
    if (!(std::sin(camera_theta) > 1e-4))
      throw std::invalid_argument("disk map: the inclination must be off the axis (more than 1e-4 rad from it)");
    CameraSpec spec;
    spec.position = Vec4(0.0, camera_r, camera_theta, 0.0);
    spec.width = spec.height = 1;
    const Camera camera = make_camera(metric, spec);
    x0_ = camera.position();
    tetrad_ = camera.tetrad();
    r_o_ = camera_r;
  }

  double r_in() const { return rays_.r_in(); }
  double r_out() const { return rays_.r_out(); }
  double camera_radius() const { return r_o_; }
  double mass() const { return rays_.metric().mass; }

  /// The ray of the screen point (alpha, beta) (M; beta towards the hole's north pole, alpha to the right).
  GeodesicState ray(double alpha, double beta) const {
    const double x = alpha / r_o_, y = beta / r_o_, n = std::sqrt(1.0 + x * x + y * y);
    const Vec4 k = (1.0 / n) * tetrad_.e[1] + (y / n) * tetrad_.e[2] + (x / n) * tetrad_.e[3] - tetrad_.e[0];
    return make_state(x0_, k);
  }

  /// The crossings of the screen point's ray. The camera is off the axis and far outside every ray's barrier: the
  /// only rays the closed form leaves are vortical (eta <= 0), which never reach the plane.
  DiskRaySample sample(double alpha, double beta) const { return rays_.sample(ray(alpha, beta)); }

 private:
  KerrDiskRays rays_;
  Vec4 x0_;
  Tetrad tetrad_;
  double r_o_ = 0.0;
};

}  // namespace grtrace
