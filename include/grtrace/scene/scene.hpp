// grtrace/scene/scene.hpp
// A scene: what the sky looks like, what the horizon looks like, and any number of objects (scene_object.hpp),
// each with its own colour function. Tracers take the scene as a template parameter and report outcomes by
// position in it (scene/object_ids.hpp); Scene::shade turns an outcome into a pixel.
//
//   auto scene = make_scene(StarFieldSky{}, HorizonPaint{}, ThinDisk{}, MyStar{...});
//
// Sky and horizon painters are any `Rgb operator()(double theta, double phi) const`: the sky is painted at the
// escaped ray's asymptotic direction, the horizon at the direction of the point where the ray met it. A painter
// that needs more than the direction (which side of a wormhole the ray ended on: RayOutcome::state) instead
// provides `Rgb operator()(const RayOutcome&) const` (OutcomePainter); when it has both, the outcome form is used.
// A failed ray (max_steps, step_underflow, non_finite) gets the flat `failure` colour and NaN data, never NaN
// colour. With colour_by_redshift every pixel is painted by f_obs / f_src (seed Fig. 5) instead.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/scene/colour_maps.hpp"
#include "grtrace/scene/object_ids.hpp"
#include "grtrace/scene/pixel_sample.hpp"
#include "grtrace/scene/scene_object.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <concepts>
#include <cstddef>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace grtrace {

/// What paints the sky or the horizon: a colour for a direction (theta, phi).
template <class P>
concept DirectionPainter = std::copy_constructible<P> && requires(const P p, double theta, double phi) {
  { p(theta, phi) } -> std::convertible_to<Rgb>;
};

/// What paints from the whole outcome of the ray (its end state, not only its direction): e.g. a sky that differs
/// on the two sides of a wormhole (scene/sky.hpp AnySky::far_side). Called only for rays that did not fail.
template <class P>
concept OutcomePainter = std::copy_constructible<P> && requires(const P p, const RayOutcome& o) {
  { p(o) } -> std::convertible_to<Rgb>;
};

/// Either kind of painter: what a Scene takes as its sky and its horizon.
template <class P>
concept ScenePainter = DirectionPainter<P> || OutcomePainter<P>;

/// The colour `painter` gives the outcome `o`: the outcome form when the painter has one (it sees the end state),
/// else the direction form at o.where. Assumes o did not fail (o.where is finite).
template <ScenePainter P>
Rgb paint(const P& painter, const RayOutcome& o) {
  if constexpr (OutcomePainter<P>) return painter(o);
  else return painter(o.where.theta, o.where.phi);
}

/// The horizon's paint: black, or a theta-phi checkerboard (seed Fig. 4) when squares > 0.
struct HorizonPaint {
  int squares = 0;  ///< 0: black; else squares along theta (twice as many along phi)
  Rgb light{0.55f, 0.05f, 0.05f}, dark{0.05f, 0.0f, 0.0f};
  Rgb operator()(double theta, double phi) const {
    if (squares <= 0) return {0.0f, 0.0f, 0.0f};
    return checker_parity(theta, phi, squares) ? light : dark;
  }
};

template <ScenePainter Sky, ScenePainter Horizon, SceneObject... Objects>
struct Scene {
  Sky sky;
  Horizon horizon;
  std::tuple<Objects...> objects;
  bool colour_by_redshift = false;
  Rgb failure{1.0f, 0.0f, 1.0f};

  static constexpr int object_count = static_cast<int>(sizeof...(Objects));

  /// Names by scene position: "sky", "horizon", then each object's label (scene_object.hpp); kinds that occur
  /// more than once without labels are numbered ("star-1", "star-2") so every position has its own name.
  std::vector<std::string> object_names() const {
    std::vector<std::string> names{"sky", "horizon"};
    // (Without objects there is nothing to number; GCC 12 also warns, wrongly, on the loops' dead bodies then.)
    if constexpr (sizeof...(Objects) > 0) {
      std::apply([&](const auto&... o) { (names.push_back(object_label(o)), ...); }, objects);
      std::map<std::string, int> total, seen;
      for (std::size_t i = 2; i < names.size(); ++i) ++total[names[i]];
      for (std::size_t i = 2; i < names.size(); ++i)
        if (total[names[i]] > 1) names[i] += "-" + std::to_string(++seen[names[i]]);
    }
    return names;
  }

  /// Calls f(object) for the object at scene position `position` (>= kFirstSceneObject); nothing otherwise.
  template <class F>
  GRTRACE_HD void visit_object(int position, F&& f) const {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      ((static_cast<int>(I) + kFirstSceneObject == position ? f(std::get<I>(objects)) : void()), ...);
    }(std::index_sequence_for<Objects...>{});
  }

  // Forced inline: called once per pixel, and out of line (GCC's inliner gives up in a translation unit with many
  // instantiations, such as grtrace-render's) the caller reads the returned sample back with wide loads that stall
  // on the callee's narrow stores (perf: a quarter of the main frame's pixel loop).
  [[gnu::always_inline]] PixelSample shade(const RayOutcome& o) const {
    PixelSample p;
    p.status = o.status;
    p.object = o.object;
    p.steps = o.steps;
    p.order = o.order;
    if (is_failure(o.status)) {
      p.rgb = failure;
      return p;
    }
    p.redshift = static_cast<float>(o.redshift);
    if (o.status == RayStatus::escaped) {
      p.sky_theta = static_cast<float>(o.where.theta);
      p.sky_phi = static_cast<float>(o.where.phi);
    }
    if (colour_by_redshift) {
      p.rgb = redshift_colour(o.redshift);
    } else if (o.object == kSkyObject) {
      p.rgb = paint(sky, o);
    } else if (o.object == kHorizonObject) {
      p.rgb = paint(horizon, o);
    } else {
      p.rgb = failure;  // a position outside the scene: cannot happen for the library's tracers
      visit_object(o.object, [&](const auto& object) { p.rgb = object.colour(SurfaceHit{o.state, o.redshift, o.radius}); });
    }
    return p;
  }
};

/// f(objects...) for a scene's tuple of objects: std::apply, callable on a GPU (core/host_device.hpp).
template <class F, class... Objects>
GRTRACE_HD decltype(auto) apply_to_objects(const F& f, const std::tuple<Objects...>& objects) {
  return [&]<std::size_t... I>(std::index_sequence<I...>)->decltype(auto) { return f(std::get<I>(objects)...); }
  (std::index_sequence_for<Objects...>{});
}

namespace detail {
template <class Tuple>
struct EveryObject;
template <class... Objects>
struct EveryObject<std::tuple<Objects...>> {
  template <class Predicate>
  static constexpr bool holds(const Predicate& p) {
    return (p.template operator()<Objects>() && ...);
  }
};
}  // namespace detail

/// True when `predicate.template operator()<O>()` holds for the type O of every object of the scene type SceneT
/// (true for a scene without objects): what a tracer asks of a whole scene, e.g.
///   every_object_of<SceneT>([]<class O>() { return object_is_stationary<O>(); })
template <class SceneT, class Predicate>
constexpr bool every_object_of(const Predicate& predicate) {
  return detail::EveryObject<decltype(SceneT::objects)>::holds(predicate);
}

template <ScenePainter Sky, ScenePainter Horizon, SceneObject... Objects>
Scene<Sky, Horizon, Objects...> make_scene(Sky sky, Horizon horizon, Objects... objects) {
  return {std::move(sky), std::move(horizon), std::tuple<Objects...>(std::move(objects)...)};
}

}  // namespace grtrace
