// grtrace/viz/scene_view.hpp
// The 3D half of grtrace-view: a vtkRenderer holding the reference surfaces, the camera glyph, the traced rays
// and orbits, and a colour bar, each a layer that can be shown or hidden.
//
// Takes:   a SceneLayout (mass, disk, sky radius, camera glyph, horizon checkerboard), then ray and orbit polydata
//          from paths_to_polydata (geodesic_data.hpp) and the field that colours them.
// Gives:   renderer() to place in a render window; set_visible/toggle per layer; set_view for the 3D camera.
// Radii are those of Schwarzschild with mass M: horizon 2M, photon sphere 3M, ISCO 6M; with a spin a != 0 (Kerr),
// the outer horizon r_+, the ergosphere (static limit r_E(theta), translucent magenta) and the ISCO of the layout
// (isco_radius; there is no single photon sphere, so that layer is absent). Boyer-Lindquist embedding (r, theta,
// phi drawn as spherical polar coordinates, as KerrMetric::to_cartesian draws BL rays), or with kerr_schild the
// Cartesian Kerr-Schild coordinates of KerrSchildMetric::to_cartesian (surfaces.hpp to_kerr_schild: each r = const
// surface an oblate spheroid), so that rays traced in either chart and the surfaces share one picture.
// Background mid grey (black horizon rays and white disk rays both show). Colours: horizon black (or the
// checkerboard), photon sphere translucent cyan, ISCO ring orange tube, disk
// translucent amber, sky sphere grey wireframe, camera frustum white, tetrad axes forward red / up green /
// right blue / velocity yellow. Rays coloured by a scalar use a perceptual (viridis-like) map, step size on a
// log scale, status as named categories; "pixel" colours each ray with its frame pixel's colour.
#pragma once

#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/viz/camera_glyph.hpp"
#include "grtrace/viz/geodesic_data.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <vtkSmartPointer.h>

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

class vtkRenderer;
class vtkPolyData;

namespace grtrace::viz {

enum class Layer { horizon, photon_sphere, isco, disk, sky, camera, rays, orbit, colorbar, ergosphere, picks };
inline constexpr std::array<Layer, 11> kAllLayers = {Layer::horizon, Layer::photon_sphere, Layer::isco,
                                                     Layer::disk,    Layer::sky,           Layer::camera,
                                                     Layer::rays,    Layer::orbit,         Layer::colorbar,
                                                     Layer::ergosphere, Layer::picks};
/// "horizon", "photon-sphere", "isco", "disk", "sky", "camera", "rays", "orbit", "colorbar", "ergosphere", "picks".
std::string_view to_string(Layer layer);
std::optional<Layer> layer_from_string(std::string_view name);

struct SceneLayout {
  double mass = 1.0;
  double spin = 0.0;           ///< Kerr a, |a| < M; 0: Schwarzschild (no ergosphere layer)
  double isco_radius = 0.0;    ///< radius of the ISCO ring; <= 0: 6M (Schwarzschild)
  /// Kerr-Schild slicing whose Cartesian coordinates the surfaces are drawn in (the rays' chart); none: BL embedding.
  std::optional<KerrSchildSlicing> kerr_schild;
  bool horizon_checkerboard = false;
  int checker_theta = 8, checker_phi = 16;  ///< squares in theta in [0, pi] and phi in [0, 2 pi]
  Rgb8 checker_a{200, 30, 30}, checker_b{20, 20, 20};
  std::optional<std::array<double, 2>> disk;  ///< inner, outer radius (equatorial plane); none: no disk layer
  double sky_radius = 0.0;                    ///< <= 0: no sky layer
  std::optional<CameraGlyph> camera;
  double camera_glyph_length = 0.0;           ///< <= 0: a quarter of the camera's distance from the centre
};

/// Where the 3D view looks from (embedding coordinates, units of M).
struct ViewPose {
  Vec3 from = Vec3(60.0, -60.0, 30.0);
  Vec3 at = Vec3::Zero();
  Vec3 up = Vec3::UnitZ();
  double view_angle_degrees = 30.0;  ///< vertical
};

class SceneView {
 public:
  explicit SceneView(const SceneLayout& layout);
  ~SceneView();
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  vtkRenderer* renderer() const;
  const SceneLayout& layout() const;

  /// Replaces the ray layer (polylines, drawn as lines) and colours it.
  void set_rays(vtkPolyData* rays, ScalarField color_by = ScalarField::pixel_color);
  /// Replaces the orbit layer (drawn as tubes of the given radius; <= 0: 0.5% of its extent, at least 0.3 M)
  /// and colours it. `marks` (a camera flight's frame positions, embedding coordinates) are drawn on it as white
  /// beads 2.5 times the tube's radius, in the same layer.
  void set_orbit(vtkPolyData* orbit, ScalarField color_by = ScalarField::lambda, double tube_radius = 0.0,
                 std::span<const Vec3> marks = {});
  /// Replaces the picked rays (pick.hpp; polylines from paths_to_polydata, drawn thick in magenta) and the text
  /// that lists their outcomes (top left, under the caption). Null or no points: no picks layer and no text.
  void set_picks(vtkPolyData* picks, const std::string& text);
  /// The picked rays as drawn (null when there are none).
  vtkPolyData* picks() const;
  /// Recolours the rays or the orbit (layer must be Layer::rays or Layer::orbit). Throws if the data lacks the array.
  void set_color_by(Layer layer, ScalarField field);
  ScalarField color_by(Layer layer) const;
  /// Cycles the ray colouring through the fields their data has (pixel, redshift, h, lambda, status).
  ScalarField cycle_ray_coloring();

  bool has(Layer layer) const;  ///< the layer exists (e.g. no disk layer without a disk)
  bool visible(Layer layer) const;
  void set_visible(Layer layer, bool on);
  void toggle(Layer layer);

  void set_view(const ViewPose& pose);
  /// A view that frames the hole, the disk and the camera glyph from above the equatorial plane.
  ViewPose default_view() const;
  ViewPose view() const;
  /// Colour of the background (the test checks the horizon silhouette against it).
  static constexpr Rgb8 kBackground{78, 82, 92};

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace grtrace::viz
