// grtrace/scene/scene_object.hpp
// What a scene object is: the one place that lists what an object must and may provide.
//
// An object is a small value type (no base class, no virtual functions); the scene tracers take objects as
// template parameters, so a tracer instantiated for a scene contains exactly that scene's objects.
//
// Must provide (checked by the SceneObject / SceneObjectIn concepts, with messages that name the mistake):
//   static constexpr std::string_view kind        what it is ("disk", "star"): the default name in image headers
//   double operator()(const GeodesicState& y) const
//       a function of the state, positive outside the object and <= 0 on or inside it; the tracer locates where
//       it first reaches 0 along the ray (integrate/event_locator.hpp)
//   Vec4 emitter_velocity(const Metric& metric, const Vec4& x) const   (a template on the metric, or one overload)
//       the 4-velocity of the emitting matter at the hit event x: the redshift is g(e_0, k_cam) / g(u, k_hit)
//       (seed eq. 9), so this is all the physics of its redshift
//   Rgb colour(const SurfaceHit& hit) const
//       its linear RGB colour given the hit: the state (x, k) where the ray met it and the redshift
//
// May provide (detected at compile time; the defaults are what an object without them gets):
//   static constexpr bool two_sided = true;         any sign change counts (a surface with no inside, e.g. a thin
//                                                   disk: g = cos theta); default false
//   static constexpr int interior_samples = n;      samples inside each step to catch a surface entered and left
//                                                   within one step (small objects); default 0. The straight-line
//                                                   tracer samples the whole line at least this often
//   bool accepts(const GeodesicState& y) const;     filters located crossings (the disk's plane outside its radii);
//                                                   a refused crossing does not end the ray; default: accept all
//   static constexpr bool equatorial = true;        the object lies in the equatorial plane theta = pi / 2 of a
//                                                   spherical chart (its event vanishes there and only there,
//                                                   accepts() says where in the plane); the planar tracer
//                                                   (trace/planar_scene_tracer.hpp) draws only such objects;
//                                                   default false
//   static constexpr bool axisymmetric = true;      where the object is and what accepts() takes do not depend on
//                                                   phi (its matter may orbit, its colour may vary); a tracer for
//                                                   which phi costs (trace/kerr_closed_form_tracer.hpp) then tests
//                                                   crossings with phi NaN and computes it at the hit alone;
//                                                   default false
//   static constexpr bool stationary = true;        the object and its matter's motion do not depend on t (its
//                                                   event never reads y[0]); tracers that do not follow t (the
//                                                   reduced Kerr tracer, trace/kerr_mino_tracer.hpp) draw only
//                                                   such objects; default: false, or true for an equatorial one
//   static constexpr bool equator_mirror_symmetric = true;   the object (where it is, what accepts() takes, how
//                                                   its matter moves) is unchanged by the reflection
//                                                   theta -> pi - theta; its colour need not be (each pixel is
//                                                   coloured at its own hit). A frame whose metric and camera are
//                                                   symmetric too traces only half its rows (render/mirror_symmetry.hpp);
//                                                   default false
//   static constexpr bool meridian_mirror_symmetric = true;  the same for phi -> 2 phi0 - phi, every phi0 (an
//                                                   axisymmetric object whose matter does not orbit; not a
//                                                   Keplerian disk); half the columns; default false
//   std::string label() const;                      this instance's name in image headers (two stars in one scene);
//                                                   default: kind, numbered when the scene has several of a kind
//   double surface(const Metric& m, const GeodesicState& y) const;   bool accepts(const Metric& m, y) const;
//                                                   the event and the filter written with the metric at hand (e.g.
//                                                   the thin disk's plane in a Cartesian chart, where its radius is
//                                                   the metric's radius(x), not a coordinate); when present they are
//                                                   used instead of operator()(y) and accepts(y) (the general scene
//                                                   tracer binds its objects to the metric: bind_to_metric)
// The event traits (two_sided, interior_samples, accepts) are read by GeodesicTracer for any event, scene object
// or not: trace/geodesic_tracer.hpp defines their detectors (event_is_two_sided, event_interior_samples,
// event_accepts).
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/scene/colour_maps.hpp"

#include <concepts>
#include <limits>
#include <string>
#include <string_view>

namespace grtrace {

/// Where a ray met an object, as the object's colour function receives it.
struct SurfaceHit {
  GeodesicState state;  ///< (x^mu, k^mu) at the hit, in the metric's chart; k is the traced (past-directed) tangent
  double redshift;      ///< f_obs / f_src
  double radius = std::numeric_limits<double>::quiet_NaN();  ///< the metric's radius(x) at the hit
  GRTRACE_HD Vec4 position() const { return state.head<4>(); }
  GRTRACE_HD Vec4 momentum() const { return state.tail<4>(); }
};

/// What every scene object provides, whatever the metric (see the top of this file).
template <class O>
concept SceneObject = std::copy_constructible<O> && requires(const O o, const GeodesicState y, const SurfaceHit h) {
  { O::kind } -> std::convertible_to<std::string_view>;
  { o(y) } -> std::convertible_to<double>;
  { o.colour(h) } -> std::convertible_to<Rgb>;
};

/// A scene object that can also say how its matter moves in the metric M.
template <class O, class M>
concept SceneObjectIn = SceneObject<O> && MetricPolicy<M> && requires(const O o, const M m, const Vec4 x) {
  { o.emitter_velocity(m, x) } -> std::convertible_to<Vec4>;
};

/// Compile-time check with messages that name what is missing; used by the scene tracers.
template <class O, class M>
constexpr bool check_scene_object() {
  static_assert(requires { { O::kind } -> std::convertible_to<std::string_view>; },
                "scene object: add `static constexpr std::string_view kind = \"...\";` (its name in image headers)");
  static_assert(requires(const O o, const GeodesicState y) { { o(y) } -> std::convertible_to<double>; },
                "scene object: add `double operator()(const GeodesicState&) const`, positive outside the object");
  static_assert(requires(const O o, const SurfaceHit h) { { o.colour(h) } -> std::convertible_to<Rgb>; },
                "scene object: add `Rgb colour(const SurfaceHit&) const` (its colour at a hit)");
  static_assert(requires(const O o, const M m, const Vec4 x) { { o.emitter_velocity(m, x) } -> std::convertible_to<Vec4>; },
                "scene object: add `Vec4 emitter_velocity(const Metric&, const Vec4& x) const` for this metric (the "
                "4-velocity of its matter at x; a template on the metric serves every metric)");
  return true;
}

/// True when the object declares itself equatorial (see the top of this file).
template <class O>
constexpr GRTRACE_HD bool object_is_equatorial() {
  if constexpr (requires { O::equatorial; }) return O::equatorial;
  else return false;
}

/// True when the object declares itself stationary, or equatorial (which implies it: see the top of this file).
template <class O>
constexpr GRTRACE_HD bool object_is_stationary() {
  if constexpr (requires { O::stationary; }) return O::stationary;
  else return object_is_equatorial<O>();
}

/// True when the object declares that where it is and what it accepts do not depend on phi (see the top of this
/// file).
template <class O>
constexpr GRTRACE_HD bool object_is_axisymmetric() {
  if constexpr (requires { O::axisymmetric; }) return O::axisymmetric;
  else return false;
}

/// True when the object declares itself unchanged by the reflection theta -> pi - theta (see the top of this file).
template <class O>
constexpr GRTRACE_HD bool object_is_equator_mirror_symmetric() {
  if constexpr (requires { O::equator_mirror_symmetric; }) return O::equator_mirror_symmetric;
  else return false;
}

/// True when the object declares itself unchanged by every reflection phi -> 2 phi0 - phi (see the top of this file).
template <class O>
constexpr GRTRACE_HD bool object_is_meridian_mirror_symmetric() {
  if constexpr (requires { O::meridian_mirror_symmetric; }) return O::meridian_mirror_symmetric;
  else return false;
}

/// The name of one object in image headers: its label() if it has one, else its kind.
template <SceneObject O>
std::string object_label(const O& o) {
  if constexpr (requires { { o.label() } -> std::convertible_to<std::string>; }) return std::string(o.label());
  else return std::string(O::kind);
}

}  // namespace grtrace
