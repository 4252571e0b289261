// examples/view/view_request.hpp
// What grtrace-view was asked to do (parsed and checked in grtrace_view.cpp), and the tracing work, split over
// translation units so the many (tableau x controller) instantiations compile in parallel:
//   view_orbit.cpp  trace_orbit   the timelike orbit (charts, orbit layer)
//   view_rays.cpp   trace_bundle  the bundle's rays through the scene (camera pixels or a parallel beam)
//   view_frame.cpp  render_frame  the frame rendered in-process, as grtrace-render does
//   view_pick.cpp   pick_ray      one picked pixel's ray (--pick, clicks on the frame)
#pragma once

#include "grtrace/app/tool_methods.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/ray_outcome.hpp"
#include "grtrace/viz/frame_image.hpp"
#include "grtrace/viz/geodesic_data.hpp"
#include "grtrace/viz/orbits.hpp"
#include "grtrace/viz/pick.hpp"
#include "grtrace/viz/scene_view.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace grtrace::view {

using MethodChoice = app::MethodChoice;  ///< grtrace/app/tool_methods.hpp

/// --flight: the camera's path and the frame the viewer looks through (its camera is Request::camera).
struct FlightView {
  std::string kind;     ///< --flight: seed, circular, orbit, infall or csv
  int frame = 0;        ///< --flight-frame: index of the frame in use
  int frames = 0;       ///< frames on the path
  double tau = 0.0;     ///< the proper time of the frame in use
  viz::TracedPath path; ///< the whole path, one sample per frame (viz::worldline_path)
};

struct Request {
  std::string screenshot;
  std::string export_dir;  ///< --export: write the scene as VTK XML files here (viz/vtk_export.hpp)
  std::array<int, 2> size{};
  std::string plot;  ///< --plot (or its older spelling --chart): orbit, norm or step; empty: the 3D view
  std::string scene = "disk";  ///< a preset of scene/standard_scenes.hpp
  double mass = 1.0;
  bool kerr = false;   ///< --metric kerr: Kerr with spin `spin` in the coordinates of `chart`
  double spin = 0.0;
  std::string chart = "bl";  ///< kerr: "bl" (Boyer-Lindquist) or "ks" (Cartesian Kerr-Schild), as grtrace-render's
  /// kerr ks: outgoing (single frames: camera rays cross the past horizon) or ingoing (--flight: the camera falls
  /// through the future horizon), as grtrace-render's MetricSpec::slicing.
  KerrSchildSlicing ks_slicing = KerrSchildSlicing::outgoing;
  int disk_sense = +1;  ///< +1: the disk turns towards +phi (scene/thin_disk.hpp)
  std::optional<Camera> camera;
  double fov = 55.0;
  int width = 0, height = 0;
  double sky_radius = 1000.0;
  std::array<double, 2> disk{6.0, 20.0};
  AngleCorrection correction = AngleCorrection::exact;
  MethodChoice rays;
  int threads = 0;
  std::string frame_file;
  std::optional<Image> frame;  ///< read from --frame
  float exposure = 1.0f;
  std::string bundle;
  std::array<int, 2> bundle_size{};
  double beam_width = 0.0;
  int samples_per_step = 8;
  viz::ScalarField color_by = viz::ScalarField::pixel_color;
  bool show_orbit = false;
  viz::OrbitSpec orbit;
  std::optional<FlightView> flight;  ///< --flight: drawn in the orbit layer, its frame's camera is `camera`
  MethodChoice orbit_method;
  std::vector<viz::Layer> hidden;
  bool checkerboard = false;
  std::optional<Vec3> view_from;
  Vec3 view_at = Vec3::Zero();
  double view_angle = 30.0;
  std::vector<std::array<int, 2>> picks;  ///< --pick: frame pixels (column, row from the top) picked at start-up
};

/// The preset scene of the request (scene/standard_scenes.hpp), as grtrace-render builds it.
inline StandardSceneSpec make_scene_spec(const Request& q) {
  StandardSceneSpec s;
  s.name = q.scene;
  s.disk.r_in = q.disk[0];
  s.disk.r_out = q.disk[1];
  s.disk.sense = q.disk_sense;
  return s;
}

/// Takes the request and a generic callable; calls f(metric) with the metric the rays are traced in: Schwarzschild,
/// Kerr in Boyer-Lindquist coordinates, or Kerr in Cartesian Kerr-Schild coordinates of q.ks_slicing (outgoing, the
/// one camera rays cross the horizon in; ingoing for a flight, as grtrace-render's --chart ks). Only these three
/// types are instantiated.
template <class F>
void with_metric(const Request& q, F&& f) {
  if (!q.kerr) f(SchwarzschildMetric{q.mass});
  else if (q.chart == "ks")
    f(q.ks_slicing == KerrSchildSlicing::ingoing ? kerr_schild_for_flights(q.mass, q.spin)
                                                 : kerr_schild_for_camera_rays(q.mass, q.spin));
  else f(KerrMetric{q.mass, q.spin});
}

/// Where the parallel beam starts: far enough out for its rays to be nearly straight.
inline double beam_start_radius(const Request& q) { return std::max(4.0 * q.beam_width, 30.0 * q.mass); }

/// The timelike orbit of q.orbit with q.orbit_method (view_orbit.cpp).
viz::TracedPath trace_orbit(const Request& q);

/// The bundle: rays through `pixels` of q.camera (colours from `frame`), or the parallel beam for q.bundle == "beam",
/// traced with q.rays through the scene's objects (the disk for the disk scene) (view_rays.cpp).
std::vector<viz::TracedPath> trace_bundle(const Request& q, std::span<const std::array<int, 2>> pixels,
                                          const viz::Rgb8Image& frame);

/// The frame as grtrace-render renders it (--tracer auto) (view_frame.cpp).
Image render_frame(const Request& q);

/// One frame pixel (column, row from the top) of q.camera picked: its ray traced with q.rays through the scene by
/// the general scene tracer (path drawn and outcome listed), coloured from `frame` (view_pick.cpp). Assumes the
/// pixel lies in the frame.
viz::RayPick pick_ray(const Request& q, std::array<int, 2> pixel, const viz::Rgb8Image& frame);

}  // namespace grtrace::view
