// grtrace/medium/emitting_medium.hpp
// What an emitting medium is: glowing, partly transparent matter that a ray collects light from all along its path
// (an accretion flow, a torus), where a scene object (scene/scene_object.hpp) is a surface a ray ends on. The one
// place that lists what a medium must and may provide.
//
// A medium is a small value type (no base class, no virtual functions); the tracer that integrates the light along
// a ray (trace/emission_system.hpp) takes it as a template parameter, so it contains exactly that medium's physics.
//
// Must provide (checked by check_emitting_medium, with messages that name the mistake):
//   static constexpr std::string_view kind        what it is ("spherical-accretion"): its name in image headers
//   MediumCoefficients coefficients(const Metric& metric, const Vec4& x, double nu) const
//       (a template on the metric, or one overload) the emission coefficient j_nu (energy per unit time, volume,
//       frequency and solid angle) and the absorption coefficient alpha_nu (per unit length) at the event x, both
//       in the fluid's frame and at the frequency nu measured there
//     or, for light that depends on the direction it leaves in (synchrotron: the angle to the magnetic field),
//   MediumCoefficients coefficients(const Metric& metric, const Vec4& x, const Vec4& k, const Vec4& u, double nu) const
//       the same, given the ray's wave vector k at x (any scale or sign: its direction is what counts) and the
//       fluid's velocity u there (fluid_velocity's, computed once for both)
//   Vec4 fluid_velocity(const Metric& metric, const Vec4& x) const
//       the fluid's 4-velocity at x (future-directed, g(u, u) = 1): the frame of j and alpha, and the redshift
//       g = nu_obs / nu_fluid of the light it sends to the camera
//   double outer_radius() const
//       the metric's radius (radius(x)) beyond which j = alpha = 0: where the tracer stops asking (empty space
//       costs a comparison per stage)
//
// May provide (detected at compile time; default false):
//   static constexpr bool stationary = true;            j, alpha and u do not depend on t
//   static constexpr bool axisymmetric = true;          nor on phi (a spherical chart's)
//   static constexpr bool equator_mirror_symmetric = true;   unchanged by theta -> pi - theta
//   static constexpr bool spherically_symmetric = true;      a function of r alone, u radial (implies the others)
//   double boundary(const Metric& metric, const Vec4& x) const
//       positive outside the gas, <= 0 inside, where j and alpha jump or kink (a hard edge, a torus's surface): the
//       tracer ends a step where a ray crosses it, so that no step is integrated across it
//       (trace/emission_system.hpp); without it, a medium should be smooth
//   double inner_radius() const
//       the metric's radius below which j = alpha = 0 too (a torus's cusp, a ball's near side): a ray that falls
//       into the hole ends there, where the tracer knows it falls in (Kerr's closed form: trace_kerr_medium_ray)
//   template <std::size_t N> std::array<MediumCoefficients, N> coefficients(const Metric& metric, const Vec4& x,
//       const Vec4& k, const Vec4& u, const std::array<double, N>& nu) const
//       the directed form for several frequencies at once (a ray traced at several observing frequencies asks for
//       them together at every stage): for a medium whose work is mostly what does not depend on nu (the RIAF's
//       density, temperature, field and angle); without it the tracer asks once per frequency
//   static constexpr bool frequency_independent = true;      j_nu and alpha_nu do not depend on nu (a flat
//       spectrum): a frame's pixels then differ only by their redshift, which lets a table of rays serve a moving
//       camera (trace/medium_tracers.hpp)
//   Vec4 fluid_velocity(const Metric& metric, const Vec4& x, const Mat4& g) const
//   MediumCoefficients coefficients(const Metric& metric, const Vec4& x, const Mat4& g, double nu) const
//       the same given g_{mu nu} at x, which the tracer computes once a stage for the redshift: for a medium whose
//       own work is mostly the metric (a torus in hydrostatic equilibrium: its velocity and its enthalpy are both
//       functions of g); each is used where the medium has it, the forms above otherwise
//
// Units: geometric (G = c = 1, lengths in the metric's); j and alpha in any units whose product with a length is
// an intensity and an optical depth.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/metric_concept.hpp"

#include <array>
#include <concepts>
#include <cstddef>
#include <string_view>

namespace grtrace {

/// The coefficients of the radiative transfer equation at one event, in the fluid's frame.
struct MediumCoefficients {
  double emission = 0.0;    ///< j_nu
  double absorption = 0.0;  ///< alpha_nu
};

/// What every emitting medium provides in the metric M (see the top of this file).
/// Whether D's coefficients take the ray's direction (the second form at the top of this file).
template <class D, class M>
concept MediumWithDirectedLight = requires(const D d, const M m, const Vec4 x, double nu) {
  { d.coefficients(m, x, x, x, nu) } -> std::convertible_to<MediumCoefficients>;
};

template <class D, class M>
concept EmittingMediumIn =
    std::copy_constructible<D> && MetricPolicy<M> && requires(const D d, const M m, const Vec4 x, double nu) {
      { D::kind } -> std::convertible_to<std::string_view>;
      { d.fluid_velocity(m, x) } -> std::convertible_to<Vec4>;
      { d.outer_radius() } -> std::convertible_to<double>;
    } && (MediumWithDirectedLight<D, M> || requires(const D d, const M m, const Vec4 x, double nu) {
      { d.coefficients(m, x, nu) } -> std::convertible_to<MediumCoefficients>;
    });

/// The coefficients of either form at x, for a ray with wave vector k through fluid moving with u.
template <class D, class M>
GRTRACE_HD MediumCoefficients medium_coefficients(const D& d, const M& m, const Vec4& x, const Vec4& k, const Vec4& u,
                                                  double nu) {
  if constexpr (MediumWithDirectedLight<D, M>) return d.coefficients(m, x, k, u, nu);
  else return d.coefficients(m, x, nu);
}

/// The same given g_{mu nu} at x: the medium's form that takes it where it has one (see the top of this file).
template <class D, class M>
GRTRACE_HD MediumCoefficients medium_coefficients(const D& d, const M& m, const Vec4& x, const Vec4& k, const Vec4& u,
                                                  double nu, const Mat4& g) {
  if constexpr (requires {
                  { d.coefficients(m, x, g, nu) } -> std::convertible_to<MediumCoefficients>;
                })
    return d.coefficients(m, x, g, nu);
  else return medium_coefficients(d, m, x, k, u, nu);
}

/// The fluid's velocity at x given g_{mu nu} there: the medium's form that takes it where it has one.
template <class D, class M>
GRTRACE_HD Vec4 medium_fluid_velocity(const D& d, const M& m, const Vec4& x, const Mat4& g) {
  if constexpr (requires {
                  { d.fluid_velocity(m, x, g) } -> std::convertible_to<Vec4>;
                })
    return d.fluid_velocity(m, x, g);
  else return d.fluid_velocity(m, x);
}

/// Whether D gives the directed coefficients of N frequencies in one call (the form at the top of this file).
template <class D, class M, std::size_t N>
concept MediumWithSpectrum = requires(const D d, const M m, const Vec4 x, const std::array<double, N> nu) {
  { d.coefficients(m, x, x, x, nu) } -> std::convertible_to<std::array<MediumCoefficients, N>>;
};

/// The coefficients at N frequencies, given g_{mu nu} at x: the medium's form for several where it has one, else
/// one call each.
template <class D, class M, std::size_t N>
GRTRACE_HD std::array<MediumCoefficients, N> medium_coefficients(const D& d, const M& m, const Vec4& x, const Vec4& k,
                                                                 const Vec4& u, const std::array<double, N>& nu,
                                                                 const Mat4& g) {
  if constexpr (N > 1 && MediumWithSpectrum<D, M, N>) {
    return d.coefficients(m, x, k, u, nu);
  } else {
    std::array<MediumCoefficients, N> c;
    for (std::size_t i = 0; i < N; ++i) c[i] = medium_coefficients(d, m, x, k, u, nu[i], g);
    return c;
  }
}

namespace detail {
/// A medium that says where its edge is (boundary, at the top of this file).
template <class D, class M>
concept MediumWithBoundary = requires(const D d, const M m, const Vec4 x) {
  { d.boundary(m, x) } -> std::convertible_to<double>;
};
}  // namespace detail

/// The radius below which D has no gas (its optional inner_radius(), at the top of this file), 0 without one.
template <class D>
GRTRACE_HD double medium_inner_radius(const D& d) {
  if constexpr (requires {
                  { d.inner_radius() } -> std::convertible_to<double>;
                })
    return d.inner_radius();
  else return 0.0;
}

/// Whether the event x lies in the gas: within the medium's outer radius and, for a medium with a boundary, on its
/// inner side. Ask it before the coefficients at a lone point: beyond its boundary a medium's coefficients are a
/// smooth continuation for the tracer's steps (a torus's are negative there) and mean nothing.
template <class D, class M>
GRTRACE_HD bool medium_contains(const D& d, const M& m, const Vec4& x) {
  if (!(m.radius(x) < d.outer_radius())) return false;
  if constexpr (detail::MediumWithBoundary<D, M>) return d.boundary(m, x) <= 0.0;
  return true;
}

/// Compile-time check with messages that name what is missing; used by the tracers that take a medium.
template <class D, class M>
constexpr bool check_emitting_medium() {
  static_assert(requires { { D::kind } -> std::convertible_to<std::string_view>; },
                "emitting medium: add `static constexpr std::string_view kind = \"...\";` (its name in image headers)");
  static_assert(MediumWithDirectedLight<D, M> || requires(const D d, const M m, const Vec4 x, double nu) {
                  { d.coefficients(m, x, nu) } -> std::convertible_to<MediumCoefficients>;
                },
                "emitting medium: add `MediumCoefficients coefficients(const Metric&, const Vec4& x, double nu) const` "
                "(j_nu and alpha_nu in the fluid's frame at x, nu measured there; a template on the metric serves "
                "every metric), or its form with the ray's direction, `coefficients(metric, x, k, u, nu)`");
  static_assert(requires(const D d, const M m, const Vec4 x) { { d.fluid_velocity(m, x) } -> std::convertible_to<Vec4>; },
                "emitting medium: add `Vec4 fluid_velocity(const Metric&, const Vec4& x) const` (the fluid's "
                "4-velocity at x, future-directed and unit)");
  static_assert(requires(const D d) { { d.outer_radius() } -> std::convertible_to<double>; },
                "emitting medium: add `double outer_radius() const` (beyond this radius j = alpha = 0)");
  return true;
}

/// The optional traits (see the top of this file); a spherically symmetric medium is all of the others.
template <class D>
constexpr GRTRACE_HD bool medium_is_spherically_symmetric() {
  if constexpr (requires { D::spherically_symmetric; }) return D::spherically_symmetric;
  else return false;
}
template <class D>
constexpr GRTRACE_HD bool medium_is_stationary() {
  if constexpr (requires { D::stationary; }) return D::stationary || medium_is_spherically_symmetric<D>();
  else return medium_is_spherically_symmetric<D>();
}
template <class D>
constexpr GRTRACE_HD bool medium_is_axisymmetric() {
  if constexpr (requires { D::axisymmetric; }) return D::axisymmetric || medium_is_spherically_symmetric<D>();
  else return medium_is_spherically_symmetric<D>();
}
template <class D>
constexpr GRTRACE_HD bool medium_is_equator_mirror_symmetric() {
  if constexpr (requires { D::equator_mirror_symmetric; })
    return D::equator_mirror_symmetric || medium_is_spherically_symmetric<D>();
  else return medium_is_spherically_symmetric<D>();
}

template <class D>
constexpr GRTRACE_HD bool medium_is_frequency_independent() {
  if constexpr (requires { D::frequency_independent; }) return D::frequency_independent;
  else return false;
}

}  // namespace grtrace
