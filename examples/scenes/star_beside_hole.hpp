// examples/scenes/star_beside_hole.hpp
// The view of star_beside_hole.cpp and star_beside_hole_gpu.cu, written once: a static camera at r = 30 M a little
// above the plane of a Schwarzschild hole, looking at it, and the glowing star (glowing_star.hpp) behind the hole,
// off to one side, traced with the tableau T and an I controller at rtol 1e-9 against a sky sphere at 400 M.
#pragma once

#include "glowing_star.hpp"

#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/scene/scene.hpp"
#include "grtrace/scene/sky.hpp"
#include "grtrace/trace/scene_tracer.hpp"

/// The camera (size x size pixels) and the scene tracer of the view.
template <grtrace::ExplicitTableau T>
auto star_beside_hole_view(int size) {
  using namespace grtrace;
  const SchwarzschildMetric metric{1.0};
  CameraSpec spec;
  spec.position = Vec4(0.0, 30.0, 1.48, 0.0);
  spec.width = spec.height = size;
  spec.fov_degrees = 60.0;
  const GlowingStar star;  // at (-12, 6, 0)
  check_star(metric, star, spec.position);
  TraceSettings settings;
  settings.integrator.tolerance = {1e-9, 1e-11};
  settings.escape_radius = 400.0;
  return std::pair(make_camera(metric, spec),
                   make_general_tracer<T, IController>(metric, settings, AngleCorrection::exact,
                                                       make_scene(StarFieldSky{}, HorizonPaint{}, star)));
}
