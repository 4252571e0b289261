// examples/view/view_request.hpp
// What grtrace-view was asked to do (parsed and checked in grtrace_view.cpp), and its tracing, all of it through
// the application library's front door (grtrace/app/front_door.hpp; view_tracing.cpp): the frame as grtrace-render
// draws it, the bundle's rays and the picked rays (app::RayTracer), the seed orbit. The viewer instantiates no
// tracer of its own.
#pragma once

#include "grtrace/app/front_door.hpp"
#include "grtrace/metric/named_metrics.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/viz/frame_image.hpp"
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

/// --flight: the camera's path and the frame the viewer looks through (its camera is Request::checked's).
struct FlightView {
  std::string kind;      ///< --flight: seed, circular, orbit, infall or csv
  int frame = 0;         ///< --flight-frame: index of the frame in use
  int frames = 0;        ///< frames on the path
  double tau = 0.0;      ///< the proper time of the frame in use
  viz::TracedPath path;  ///< the whole path, one sample per frame
};

struct Request {
  std::string screenshot;
  std::string export_dir;  ///< --export: write the scene as VTK XML files here (viz/vtk_export.hpp)
  std::array<int, 2> size{};
  std::string plot;            ///< --plot (or its older spelling --chart): orbit, norm or step; empty: the 3D view
  std::string scene = "disk";  ///< a preset of scene/standard_scenes.hpp
  /// The metric (schwarzschild, or kerr in the coordinates of metric.chart; a Kerr-Schild flight flies in the
  /// ingoing slicing), and these of it for the pictures: mass, whether it is Kerr, the spin.
  MetricSpec metric;
  double mass = 1.0;
  bool kerr = false;
  double spin = 0.0;
  /// The frame's, the bundle's and the picks' request as the library checked it: metric, scene, camera (the frame
  /// header's with --frame, the flight frame's with --flight), method, sky radius, angle correction, threads.
  std::optional<app::CheckedRequest> checked;
  int disk_sense = +1;  ///< +1: the disk turns towards +phi (scene/thin_disk.hpp)
  double fov = 55.0;
  int width = 0, height = 0;
  double sky_radius = 1000.0;
  std::array<double, 2> disk{6.0, 20.0};
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
  std::optional<FlightView> flight;  ///< --flight: drawn in the orbit layer, its frame's camera is the camera
  /// The orbit's request (the seed orbit in Schwarzschild with --orbit-tableau ..., its sky far beyond the orbit).
  std::optional<app::CheckedRequest> orbit_checked;
  std::vector<viz::Layer> hidden;
  bool checkerboard = false;
  std::optional<Vec3> view_from;
  Vec3 view_at = Vec3::Zero();
  double view_angle = 30.0;
  std::vector<std::array<int, 2>> picks;  ///< --pick: frame pixels (column, row from the top) picked at start-up

  const Camera& camera() const { return checked->camera; }
};

/// Where the parallel beam starts: far enough out for its rays to be nearly straight.
inline double beam_start_radius(const Request& q) { return std::max(4.0 * q.beam_width, 30.0 * q.mass); }

/// The timelike orbit of q.orbit with its method (view_tracing.cpp).
viz::TracedPath trace_orbit(const Request& q);

/// The bundle: rays through `pixels` of the camera (colours from `frame`), or the parallel beam for q.bundle ==
/// "beam", traced with the request's method through the scene's objects (the disk for the disk scene).
std::vector<viz::TracedPath> trace_bundle(const Request& q, std::span<const std::array<int, 2>> pixels,
                                          const viz::Rgb8Image& frame);

/// The frame as grtrace-render renders it (--tracer auto, --device auto), with its report.
app::RenderResult render_frame(const Request& q);

/// One frame pixel (column, row from the top) picked: its ray traced with the request's method through the scene by
/// the general scene tracer (path drawn and outcome listed), coloured from `frame`. Assumes the pixel lies in the
/// frame.
viz::RayPick pick_ray(const Request& q, std::array<int, 2> pixel, const viz::Rgb8Image& frame);

}  // namespace grtrace::view
