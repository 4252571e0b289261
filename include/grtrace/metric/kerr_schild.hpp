// grtrace/metric/kerr_schild.hpp
// Kerr spacetime in Cartesian Kerr-Schild coordinates x = (t, x, y, z): regular across the horizon that the
// chosen slicing penetrates, no polar axis. G = c = 1, signature (+,-,-,-).
//
// Takes:   mass M > 0, spin a with |a| < M (KerrSchildMetric::checked refuses anything else), and the slicing:
//          ingoing (regular on the future horizon) or outgoing (regular on the past horizon). Events off the
//          ring singularity (x^2 + y^2 = a^2, z = 0) and off the disk z = 0, x^2 + y^2 < a^2 it bounds.
// Returns: g_{mu nu} = eta_{mu nu} - f l_mu l_nu, its exact inverse g^{mu nu} = eta^{mu nu} + f L^mu L^nu
//          (L^mu = eta^{mu nu} l_nu; l is null), Gamma, the acceleration -Gamma^mu_ab k^a k^b in closed form,
//          the Boyer-Lindquist-like radius r, E, L_z, Q, the Kretschmann scalar, and (free functions below)
//          the maps of events and tangent vectors between this chart and KerrMetric's Boyer-Lindquist chart.
// Source: Kerr, PRL 11, 237 (1963); Kerr & Schild (1965); Visser, arXiv:0706.0622, sec. 3; shared/reference/kerr.md.
// In the usual (-,+,+,+) form g = eta + f l l; flipping the overall sign gives the (+,-,-,-) form used here:
//   f = 2 M r^3 / (r^4 + a^2 z^2),   r^4 - (R^2 - a^2) r^2 - a^2 z^2 = 0,   R^2 = x^2 + y^2 + z^2,
//   l_mu = (1, (e r x + a y)/(r^2 + a^2), (e r y - a x)/(r^2 + a^2), e z / r),   e = +1 ingoing, -1 outgoing.
// (The outgoing chart is the time reverse t -> -t of the ingoing chart of spin -a.) Relation to Boyer-Lindquist:
//   x + i y = (r + i e a) sin(th) e^{i phi_KS},  z = r cos(th),
//   dt_KS = dt_BL + e (2 M r / Delta) dr,  dphi_KS = dphi_BL + e (a / Delta) dr.
// The tests check these signs by pulling g back to the BL metric and by tracing the same ray in both charts.
//
// Which slicing to use. A ray crosses r_+ in this chart only towards the horizon the slicing is regular on:
// future-directed rays (k^t > 0) fall through the future horizon of the ingoing chart; past-directed rays
// (k^t < 0, rays traced backwards from a camera) fall through the past horizon of the outgoing chart. The other
// combination behaves like Boyer-Lindquist (the ray creeps towards r_+ while k^t grows without bound), and is
// captured as there, at the guard (1 + eps) r_+ outside (capture_radius): pick the slicing by the time direction of
// k (slicing_crossed_by(k^t)) to see rays cross. The default is ingoing, the form of shared/reference/kerr.md.
// The ingoing chart also carries a camera that falls into the hole (kerr_schild_for_flights); its rays, traced
// into the past from inside r_+, come out through the future horizon or are captured at once (leaves_interior).
//
// Capture. radius(x) is the BL-like r of the quadric above (constant on oblate spheroids; it is the BL r of the
// event), and horizon_radius() returns the capture radius r_c = r_+ - (r_+ - r_-)/4 of the rays the slicing carries
// across r_+ (capture_radius(y0) gives each ray its own: r_c for those, r_+ for the others), inside the outer horizon:
// the tracer's guard (1 + eps) r_c stays below r_+ for eps < (r_+ - r_c)/r_c (1/3 for a = 0, 2% for a = 0.999 M),
// so a ray is only called captured once it is inside r_+, from where no ray returns: the decision is exact, not a
// tolerance. r_c stays above r_- so rays never reach the region near the ring. outer_horizon() gives r_+ itself.
//
// Acceleration (closed form from the Kerr-Schild structure, no 4x4 tables): with s = l_a k^a, J_ij = d_i l_j,
// Df = k^i d_i f, Dl_j = k^i J_ij, Ds = k^i J_ij k^j, the Euler-Lagrange form of the geodesic equation gives
//   F_nu = -1/2 s^2 d_nu f - f s (J k)_nu + s (Df l_nu + f Dl_nu) + f Ds l_nu,
//   -Gamma^mu_ab k^a k^b = g^{mu nu} F_nu = eta^{mu nu} F_nu + f L^mu (L . F).
// The derivatives of r follow from the quadric: d_x r = x r^3 / W, d_y r = y r^3 / W, d_z r = z r (r^2 + a^2) / W,
// W = r^4 + a^2 z^2.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/mul_add.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace grtrace {

enum class KerrSchildSlicing { ingoing, outgoing };

/// The slicing whose horizon a ray with this k^t crosses: ingoing for future-directed rays (k^t > 0), outgoing
/// for past-directed ones (k^t < 0, camera rays traced backwards). The Kerr-Schild t = const slices are spacelike
/// everywhere (g^tt = 1 + f > 0), so the sign of k^t is the ray's time orientation at any event, even inside r_+.
inline constexpr GRTRACE_HD KerrSchildSlicing slicing_crossed_by(double k_t) {
  return k_t < 0.0 ? KerrSchildSlicing::outgoing : KerrSchildSlicing::ingoing;
}

/// The quantities of the Kerr-Schild form at a spatial point: r, f, l, and their first derivatives.
struct KerrSchildTerms {
  double r;
  double f;
  Vec4 l;              ///< l_mu (lower index), l_t = 1
  Eigen::Vector3d dr;  ///< d_i r
  Eigen::Vector3d df;  ///< d_i f
  Eigen::Matrix3d dl;  ///< dl(i, j) = d_i l_j (spatial; l_t is constant)

  /// r^2 alone: the positive root of r^4 - b r^2 - c = 0 (b = R^2 - a^2, c = a^2 z^2), in the form without
  /// cancellation for either sign of b. radius() needs only this (the events test it every step).
  static GRTRACE_HD double radius_squared(double a, double x, double y, double z) {
    const double a2 = a * a, b = mul_add(z, z, mul_add(y, y, x * x)) - a2, c = a2 * z * z;
    const double root = std::sqrt(mul_add(b, b, 4.0 * c));
    return b >= 0.0 ? 0.5 * (b + root) : 2.0 * c / (root - b);
  }

  GRTRACE_HD KerrSchildTerms(double mass, double a, double e, double x, double y, double z) {
    const double a2 = a * a, c = a2 * z * z;
    const double r2 = radius_squared(a, x, y, z);
    r = std::sqrt(r2);
    // One division for 1/P, 1/W and 1/r (P W r ~ r^7 stays finite for any r below ~1e40 M).
    const double p = r2 + a2, w = r2 * r2 + c, inv_pwr = 1.0 / (p * w * r);
    const double inv_p = w * r * inv_pwr, inv_w = p * r * inv_pwr, inv_r = p * w * inv_pwr;
    f = 2.0 * mass * r2 * r * inv_w;
    l = Vec4(1.0, (e * r * x + a * y) * inv_p, (e * r * y - a * x) * inv_p, e * z * inv_r);
    dr = Eigen::Vector3d(x * r2 * r * inv_w, y * r2 * r * inv_w, z * r * p * inv_w);
    // d_i f = f (3 d_i r / r - (4 r^3 d_i r + 2 a^2 z delta_iz) / W)
    const double kf = 3.0 * inv_r - 4.0 * r2 * r * inv_w;
    df = f * kf * dr;
    df[2] -= f * 2.0 * a2 * z * inv_w;
    // d_i l_x = (e x d_i r + e r delta_ix + a delta_iy - 2 r l_x d_i r) / P, and likewise for l_y; l_z = e z / r.
    const double cx = (e * x - 2.0 * r * l[1]) * inv_p, cy = (e * y - 2.0 * r * l[2]) * inv_p;
    const double cz = -e * z * inv_r * inv_r;
    for (int i = 0; i < 3; ++i) {
      dl(i, 0) = cx * dr[i];
      dl(i, 1) = cy * dr[i];
      dl(i, 2) = cz * dr[i];
    }
    dl(0, 0) += e * r * inv_p;
    dl(1, 0) += a * inv_p;
    dl(1, 1) += e * r * inv_p;
    dl(0, 1) -= a * inv_p;
    dl(2, 2) += e * inv_r;
  }
};

struct KerrSchildMetric {
  static constexpr std::string_view name = "kerr-schild";
  static constexpr Chart chart = Chart::cartesian;
  double mass = 1.0;
  double spin = 0.0;  ///< a = J/M, |a| < M; the sign gives the sense of rotation about +z
  KerrSchildSlicing slicing = KerrSchildSlicing::ingoing;

  /// A KerrSchildMetric after checking M > 0 finite and |a| < M; throws std::invalid_argument otherwise.
  static GRTRACE_HD KerrSchildMetric checked(double mass, double spin,
                                             KerrSchildSlicing slicing = KerrSchildSlicing::ingoing) {
    const KerrMetric bl = KerrMetric::checked(mass, spin);  // same rules, same messages
    return KerrSchildMetric{bl.mass, bl.spin, slicing};
  }

  /// e = +1 for the ingoing chart, -1 for the outgoing one.
  GRTRACE_HD double orientation() const { return slicing == KerrSchildSlicing::ingoing ? 1.0 : -1.0; }
  GRTRACE_HD KerrSchildTerms terms(const Vec4& x) const {
    return KerrSchildTerms(mass, spin, orientation(), x[1], x[2], x[3]);
  }
  /// The Boyer-Lindquist metric of the same hole (for the conversions and the BL quantities).
  GRTRACE_HD KerrMetric boyer_lindquist() const { return KerrMetric{mass, spin}; }
  /// Optional trait (metric/metric_traits.hpp): the spherical chart of this spacetime (Boyer-Lindquist) and the BL
  /// coordinates of an event outside r_+ (ks_to_bl_position, defined below).
  GRTRACE_HD KerrMetric spherical_chart() const { return boyer_lindquist(); }
  GRTRACE_HD Vec4 spherical_event(const Vec4& x) const;

  static GRTRACE_HD Mat4 eta() { return minkowski_eta(); }

  GRTRACE_HD Mat4 metric(const Vec4& x) const {
    const KerrSchildTerms q = terms(x);
    return eta() - q.f * q.l * q.l.transpose();
  }

  /// g^{mu nu} = eta^{mu nu} + f L^mu L^nu, exact.
  GRTRACE_HD Mat4 inverse_metric(const Vec4& x) const {
    const KerrSchildTerms q = terms(x);
    const Vec4 up = eta() * q.l;
    return eta() + q.f * up * up.transpose();
  }

  /// d_c g_{mu nu} = -(d_c f) l_mu l_nu - f (d_c l_mu l_nu + l_mu d_c l_nu); zero for c = t.
  GRTRACE_HD std::array<Mat4, 4> metric_derivatives(const Vec4& x) const {
    const KerrSchildTerms q = terms(x);
    std::array<Mat4, 4> dg;
    dg[0].setZero();
    for (int i = 0; i < 3; ++i) {
      Vec4 dl = Vec4::Zero();
      dl.tail<3>() = q.dl.row(i).transpose();
      const Mat4 outer = dl * q.l.transpose();
      dg[static_cast<std::size_t>(i + 1)] = -q.df[i] * q.l * q.l.transpose() - q.f * (outer + outer.transpose());
    }
    return dg;
  }

  GRTRACE_HD Christoffel christoffel(const Vec4& x) const {
    return christoffel_from_derivatives(inverse_metric(x), metric_derivatives(x));
  }

  /// -Gamma^mu_ab k^a k^b in closed form (see the header comment), in scalars. The terms of KerrSchildTerms are
  /// formed inline, without the 3x3 matrix J = d_i l_j: J = dr c^T + D with c_j = (e x - 2 r l_x, e y - 2 r l_y,
  /// -e z / r) / (P, P, r) and D = [[e r, -a, 0], [a, e r, 0], [0, 0, e P / r]] / P, so that
  /// J k = dr (c.k) + D k, J^T k = c (dr.k) + D^T k and k.J.k = (dr.k)(c.k) + e r (k_x^2 + k_y^2) / P + e k_z^2 / r
  /// (a's part of D is antisymmetric). The same quantities as the Eigen form (acceleration_reference) up to
  /// round-off, at about half the cost.
  GRTRACE_HD Vec4 acceleration(const Vec4& x4, const Vec4& k) const {
    const double a = spin, e = orientation(), x = x4[1], y = x4[2], z = x4[3];
    const double a2 = a * a, c = a2 * z * z;
    const double r2 = KerrSchildTerms::radius_squared(a, x, y, z), r = std::sqrt(r2), r3 = r2 * r;
    const double p = r2 + a2, w = mul_add(r2, r2, c), inv_pwr = 1.0 / (p * w * r);
    const double inv_p = w * r * inv_pwr, inv_w = p * r * inv_pwr, inv_r = p * w * inv_pwr;
    const double f = 2.0 * mass * r3 * inv_w;
    const double lx = mul_add(e * r, x, a * y) * inv_p, ly = mul_add(e * r, y, -a * x) * inv_p, lz = e * z * inv_r;
    const double drx = x * r3 * inv_w, dry = y * r3 * inv_w, drz = z * r * p * inv_w;
    const double fkf = f * mul_add(-4.0 * r3, inv_w, 3.0 * inv_r);
    const double dfx = fkf * drx, dfy = fkf * dry, dfz = mul_add(fkf, drz, -f * 2.0 * a2 * z * inv_w);
    const double cx = mul_add(-2.0 * r, lx, e * x) * inv_p, cy = mul_add(-2.0 * r, ly, e * y) * inv_p;
    const double cz = -e * z * inv_r * inv_r;
    const double erp = e * r * inv_p, ap = a * inv_p, er = e * inv_r;
    const double kt = k[0], kx = k[1], ky = k[2], kz = k[3];
    // Sums of products are chains of mul_add (core/mul_add.hpp): one rounding each where the processor fuses them.
    const auto dot3 = [](double u0, double v0, double u1, double v1, double u2, double v2) {
      return mul_add(u2, v2, mul_add(u1, v1, u0 * v0));
    };
    const double s = mul_add(lz, kz, mul_add(ly, ky, mul_add(lx, kx, kt)));  // l_t = 1
    const double dr_k = dot3(drx, kx, dry, ky, drz, kz), c_k = dot3(cx, kx, cy, ky, cz, kz);
    const double jkx = mul_add(drx, c_k, mul_add(erp, kx, -ap * ky)), jky = mul_add(dry, c_k, mul_add(ap, kx, erp * ky)),
                 jkz = mul_add(drz, c_k, er * kz);  // J k
    const double dlkx = mul_add(cx, dr_k, mul_add(erp, kx, ap * ky)), dlky = mul_add(cy, dr_k, mul_add(erp, ky, -ap * kx)),
                 dlkz = mul_add(cz, dr_k, er * kz);  // J^T k
    const double df_k = dot3(dfx, kx, dfy, ky, dfz, kz), ds = dot3(kx, jkx, ky, jky, kz, jkz);
    // F = (s Df + f Ds) l + (-1/2 s^2 df - f s J k + f s J^T k) on the spatial components: F_i = fl l_i +
    // (-1/2 s^2) df_i + f s (J^T k - J k)_i.
    const double fl = mul_add(f, ds, s * df_k), hs2 = 0.5 * s * s, fs = f * s;
    const double f0 = fl;
    const double f1 = mul_add(fl, lx, mul_add(fs, dlkx - jkx, -hs2 * dfx));
    const double f2 = mul_add(fl, ly, mul_add(fs, dlky - jky, -hs2 * dfy));
    const double f3 = mul_add(fl, lz, mul_add(fs, dlkz - jkz, -hs2 * dfz));
    // g^{-1} F = eta F + f L (L . F), L = eta l = (1, -l_x, -l_y, -l_z).
    const double f_lf = f * mul_add(-lz, f3, mul_add(-ly, f2, mul_add(-lx, f1, f0)));
    return Vec4(f0 + f_lf, mul_add(-f_lf, lx, -f1), mul_add(-f_lf, ly, -f2), mul_add(-f_lf, lz, -f3));
  }

  /// The same acceleration from KerrSchildTerms with Eigen's 3-vectors and 3x3 J (the form acceleration() was
  /// derived from; tests compare the two).
  GRTRACE_HD Vec4 acceleration_reference(const Vec4& x, const Vec4& k) const {
    const KerrSchildTerms q = terms(x);
    const Eigen::Vector3d ks = k.tail<3>();
    const double s = q.l.dot(k);
    const Eigen::Vector3d jk = q.dl * ks;               // (d_i l_j) k^j
    const Eigen::Vector3d dlk = q.dl.transpose() * ks;  // k^i d_i l_j
    const double df_k = q.df.dot(ks), ds = ks.dot(jk);
    Vec4 force = (s * df_k + q.f * ds) * q.l;
    force.tail<3>() += -0.5 * s * s * q.df - q.f * s * jk + q.f * s * dlk;
    // g^{-1} F = eta F + f L (L . F), L = eta l.
    const Vec4 up(q.l[0], -q.l[1], -q.l[2], -q.l[3]);
    const Vec4 eta_f(force[0], -force[1], -force[2], -force[3]);
    return eta_f + q.f * up.dot(force) * up;
  }

  /// The Boyer-Lindquist-like r of the event (the quadric's root), not the Euclidean distance.
  GRTRACE_HD double radius(const Vec4& x) const {
    return std::sqrt(KerrSchildTerms::radius_squared(spin, x[1], x[2], x[3]));
  }
  /// The capture radius r_c = r_+ - (r_+ - r_-)/4 (see the header comment: inside r_+, so capture is exact).
  GRTRACE_HD double horizon_radius() const { return outer_horizon() - 0.25 * (outer_horizon() - inner_horizon()); }
  /// The chart's own coordinates: the Kerr-Schild x, y, z (r = const surfaces are oblate spheroids).
  GRTRACE_HD Vec3 to_cartesian(const Vec4& x) const { return x.tail<3>(); }

  GRTRACE_HD double outer_horizon() const { return mass + std::sqrt(mass * mass - spin * spin); }
  GRTRACE_HD double inner_horizon() const { return mass - std::sqrt(mass * mass - spin * spin); }
  /// Omega_H = a / (r_+^2 + a^2): the horizon's generator is chi = d_t + Omega_H d_phi (KerrMetric's).
  GRTRACE_HD double horizon_angular_velocity() const { return boyer_lindquist().horizon_angular_velocity(); }

  /// Optional trait (metric/metric_traits.hpp): the capture radius for the ray starting at y0. A ray whose time
  /// direction crosses the horizon this slicing is regular on (slicing_crossed_by(k^t) == slicing) is captured
  /// at r_c inside r_+ (exact, see the header comment); any other ray cannot cross r_+ in this chart (it creeps
  /// towards it as in Boyer-Lindquist) and is captured at the guard (1 + eps) r_+ outside, where a ray moving
  /// inwards inside the photon orbits has no turning point left: the Boyer-Lindquist decision.
  GRTRACE_HD double capture_radius(const GeodesicState& y0) const {
    return slicing_crossed_by(y0[4]) == slicing ? horizon_radius() : outer_horizon();
  }

  /// Optional trait: for a ray starting inside its guard, whether it comes out of the hole and may reach the sky.
  /// Only rays of the other time direction can (a camera inside the black hole of the ingoing chart, its rays
  /// traced into the past; or the white hole of the outgoing chart, its rays traced into the future).
  /// Method:  between r_- and r_+ r is a time coordinate: every such ray runs to r_+ monotonically and leaves
  /// through one of the two horizons bounding the region (Hawking & Ellis 1973, sec. 5.6). At ours, chi =
  /// d_t + Omega_H d_phi is a null generator, future-directed, so a future-directed momentum p crossing it has
  /// g(chi, p) = E - Omega_H L_z > 0; a ray with the opposite sign leaves through the other universe's horizon
  /// (it never reaches ours: captured, the picture's black). With s = sign(k^t) the ray's time direction, p = s k:
  /// it comes out when s (E(k) - Omega_H L_z(k)) > 0. One that comes out but has a radial turning point above r_+
  /// (KerrMetric::radial_turning_point_outside, from E, L_z and Carter's Q) falls back into the horizon the chart
  /// is singular on: captured at once too, where it would end anyway. That is also the only way to decide the rays
  /// with E - Omega_H L_z -> 0+ (all of them turn back): they leave near the bifurcation sphere, where this chart's
  /// k^t grows without bound before they are out. Between r_+ and the guard: when it moves outwards.
  GRTRACE_HD bool leaves_interior(const GeodesicState& y0) const {
    if (slicing_crossed_by(y0[4]) == slicing) return false;  // it falls in: captured
    const KerrSchildTerms q = terms(y0.head<4>());
    if (q.r >= outer_horizon()) return q.dr.dot(y0.tail<3>()) > 0.0;
    if (!(q.r > inner_horizon())) return false;
    const double s = y0[4] > 0.0 ? 1.0 : -1.0, e = energy(y0), lz = angular_momentum(y0);
    if (!(s * (e - horizon_angular_velocity() * lz) > 0.0)) return false;
    return !boyer_lindquist().radial_turning_point_outside(e, lz, carter_constant(y0));
  }

  // ---- constants of geodesic motion (same values as KerrMetric's at the corresponding BL state) -------------
  /// E = p_t = g_{t nu} k^nu (d_t is the same Killing field in both charts).
  GRTRACE_HD double energy(const GeodesicState& y) const { return metric(y.head<4>()).row(0).dot(y.tail<4>()); }
  /// L_z = -p_phi with d_phi = -y d_x + x d_y: L_z = -(x p_y - y p_x).
  GRTRACE_HD double angular_momentum(const GeodesicState& y) const {
    const Vec4 p = metric(y.head<4>()) * y.tail<4>();
    return -(y[1] * p[2] - y[2] * p[1]);
  }
  /// Carter's constant, evaluated at the corresponding Boyer-Lindquist state (valid for r > r_+).
  GRTRACE_HD double carter_constant(const GeodesicState& y) const;

  /// Optional trait (metric/metric_traits.hpp): cameras and tools state events in Boyer-Lindquist (t, r, theta,
  /// phi); these map an event and the BL coordinate basis into this chart (defined below the free functions).
  GRTRACE_HD Vec4 event_from_spherical(const Vec4& x_bl) const;
  GRTRACE_HD Mat4 jacobian_from_spherical(const Vec4& x_bl) const;

  /// Kretschmann scalar, the BL formula at r and cos(theta) = z / r.
  GRTRACE_HD double kretschmann(const Vec4& x) const {
    const double r = radius(x);
    return boyer_lindquist().kretschmann_at(r, x[3] / r);
  }
};

static_assert(MetricPolicy<KerrSchildMetric>);

// ---- Boyer-Lindquist <-> Kerr-Schild (valid outside the outer horizon, r > r_+) -------------------------------

namespace kerr_schild_detail {
/// t_KS - t_BL = e int 2 M r / Delta dr and phi_KS - phi_BL = e a int dr / Delta (constants chosen to vanish
/// nowhere special; only differences matter): partial fractions over r_+ and r_-.
inline GRTRACE_HD double time_shift(const KerrSchildMetric& m, double r) {
  const double rp = m.outer_horizon(), rm = m.inner_horizon(), d = rp - rm;
  double v = 2.0 * m.mass * rp / d * std::log(std::abs(r - rp) / m.mass);
  if (rm > 0.0) v -= 2.0 * m.mass * rm / d * std::log(std::abs(r - rm) / m.mass);
  return m.orientation() * v;
}
inline GRTRACE_HD double phi_shift(const KerrSchildMetric& m, double r) {
  const double rp = m.outer_horizon(), rm = m.inner_horizon();
  return m.orientation() * m.spin / (rp - rm) * std::log(std::abs((r - rp) / (r - rm)));
}
}  // namespace kerr_schild_detail

/// The Kerr-Schild event of a Boyer-Lindquist event (t, r, theta, phi).
inline GRTRACE_HD Vec4 bl_to_ks_position(const KerrSchildMetric& m, const Vec4& x_bl) {
  const double r = x_bl[1], st = std::sin(x_bl[2]), ct = std::cos(x_bl[2]);
  const double ea = m.orientation() * m.spin;
  const double ph = x_bl[3] + kerr_schild_detail::phi_shift(m, r), cp = std::cos(ph), sp = std::sin(ph);
  return Vec4(x_bl[0] + kerr_schild_detail::time_shift(m, r), st * (r * cp - ea * sp), st * (r * sp + ea * cp), r * ct);
}

/// d x_KS / d x_BL at a Boyer-Lindquist event: maps BL tangent vectors to KS ones.
inline GRTRACE_HD Mat4 bl_to_ks_jacobian(const KerrSchildMetric& m, const Vec4& x_bl) {
  const double r = x_bl[1], st = std::sin(x_bl[2]), ct = std::cos(x_bl[2]);
  const double e = m.orientation(), ea = e * m.spin;
  const double delta = r * r - 2.0 * m.mass * r + m.spin * m.spin;
  const double ph = x_bl[3] + kerr_schild_detail::phi_shift(m, r), cp = std::cos(ph), sp = std::sin(ph);
  const double dph_dr = e * m.spin / delta;  // d phi_KS / dr at fixed phi_BL
  const double x = st * (r * cp - ea * sp), y = st * (r * sp + ea * cp);
  Mat4 jac = Mat4::Zero();
  jac(0, 0) = 1.0;
  jac(0, 1) = e * 2.0 * m.mass * r / delta;
  // x(r, theta, phi_KS): d/dr = st cp, d/dtheta = ct (r cp - ea sp), d/dphi_KS = -y; phi_KS depends on r and phi_BL.
  jac(1, 1) = st * cp - y * dph_dr;
  jac(1, 2) = ct * (r * cp - ea * sp);
  jac(1, 3) = -y;
  jac(2, 1) = st * sp + x * dph_dr;
  jac(2, 2) = ct * (r * sp + ea * cp);
  jac(2, 3) = x;
  jac(3, 1) = ct;
  jac(3, 2) = -r * st;
  return jac;
}

inline GRTRACE_HD GeodesicState bl_to_ks(const KerrSchildMetric& m, const GeodesicState& y_bl) {
  const Vec4 x = y_bl.head<4>();
  return make_state(bl_to_ks_position(m, x), bl_to_ks_jacobian(m, x) * y_bl.tail<4>());
}

/// The Boyer-Lindquist event of a Kerr-Schild event outside r_+ (phi in (-pi, pi] plus the BL shift).
inline GRTRACE_HD Vec4 ks_to_bl_position(const KerrSchildMetric& m, const Vec4& x_ks) {
  const double r = m.radius(x_ks);
  const double theta = std::acos(std::clamp(x_ks[3] / r, -1.0, 1.0));
  const double phi_ks = std::atan2(x_ks[2], x_ks[1]) - std::atan2(m.orientation() * m.spin, r);
  return Vec4(x_ks[0] - kerr_schild_detail::time_shift(m, r), r, theta, phi_ks - kerr_schild_detail::phi_shift(m, r));
}

/// A Kerr-Schild state (event and tangent) in Boyer-Lindquist coordinates, outside r_+ and off the axis.
inline GRTRACE_HD GeodesicState ks_to_bl(const KerrSchildMetric& m, const GeodesicState& y_ks) {
  const Vec4 x = y_ks.head<4>(), k = y_ks.tail<4>();
  const KerrSchildTerms q = m.terms(x);
  const double r = q.r, e = m.orientation(), a = m.spin;
  const double delta = r * r - 2.0 * m.mass * r + a * a;
  const double kr = q.dr.dot(k.tail<3>());
  const double ct = x[3] / r, st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
  const double kth = (ct * kr - k[3]) / (r * st);
  const double rho2 = x[1] * x[1] + x[2] * x[2];
  const double kph_ks = (x[1] * k[2] - x[2] * k[1]) / rho2 + e * a * kr / (r * r + a * a);
  const Vec4 k_bl(k[0] - e * 2.0 * m.mass * r / delta * kr, kr, kth, kph_ks - e * a / delta * kr);
  return make_state(ks_to_bl_position(m, x), k_bl);
}

/// The Kerr-Schild chart the tools trace camera rays in (checked as KerrSchildMetric::checked): the outgoing
/// slicing, because camera rays are traced backwards (k^t < 0) and cross the past horizon (slicing_crossed_by).
inline GRTRACE_HD KerrSchildMetric kerr_schild_for_camera_rays(double mass, double spin) {
  return KerrSchildMetric::checked(mass, spin, KerrSchildSlicing::outgoing);
}

/// The Kerr-Schild chart a camera flight is flown in: the ingoing slicing, regular on the future horizon a falling
/// camera crosses (a flight's infall continues into the black hole). Its camera rays are past-directed: from
/// outside they are captured at r_+ as in Boyer-Lindquist, from inside they come out of the hole or are captured at
/// once (capture_radius, leaves_interior).
inline GRTRACE_HD KerrSchildMetric kerr_schild_for_flights(double mass, double spin) {
  return KerrSchildMetric::checked(mass, spin, KerrSchildSlicing::ingoing);
}

inline GRTRACE_HD Vec4 KerrSchildMetric::spherical_event(const Vec4& x) const { return ks_to_bl_position(*this, x); }
inline GRTRACE_HD Vec4 KerrSchildMetric::event_from_spherical(const Vec4& x_bl) const { return bl_to_ks_position(*this, x_bl); }
inline GRTRACE_HD Mat4 KerrSchildMetric::jacobian_from_spherical(const Vec4& x_bl) const { return bl_to_ks_jacobian(*this, x_bl); }

inline GRTRACE_HD double KerrSchildMetric::carter_constant(const GeodesicState& y) const {
  return boyer_lindquist().carter_constant(ks_to_bl(*this, y));
}

}  // namespace grtrace
