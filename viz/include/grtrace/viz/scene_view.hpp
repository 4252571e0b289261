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
#include <vector>

class vtkRenderer;
class vtkPolyData;
class vtkImageData;

namespace grtrace::viz {

enum class Layer { horizon, photon_sphere, isco, disk, sky, camera, rays, orbit, colorbar, ergosphere, picks, medium };
inline constexpr std::array<Layer, 12> kAllLayers = {
    Layer::horizon, Layer::photon_sphere, Layer::isco,     Layer::disk,       Layer::sky,   Layer::camera,
    Layer::rays,    Layer::orbit,         Layer::colorbar, Layer::ergosphere, Layer::picks, Layer::medium};
/// "horizon", "photon-sphere", "isco", "disk", "sky", "camera", "rays", "orbit", "colorbar", "ergosphere", "picks",
/// "medium".
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

/// An emitting medium's emission on a cube of points (app::MediumVolume's: x fastest), drawn as iso-surfaces.
struct MediumField {
  int n = 0;                  ///< points a side (>= 2)
  double half_width = 0.0;    ///< the cube is [-half_width, half_width]^3 in the embedding's coordinates
  std::vector<float> values;  ///< n^3 values, x fastest, z slowest
  double peak = 0.0;          ///< the largest value (the levels are fractions of it)
};

/// The field as VTK image data (the point array "emission"; spacing and origin in the embedding's coordinates): what
/// the medium layer draws and what an export writes as medium.vti. Throws std::invalid_argument unless n >= 2, n^3
/// values and a positive half width.
vtkSmartPointer<vtkImageData> medium_to_imagedata(const MediumField& field);

/// The medium layer's iso-surfaces: these fractions of the peak, drawn translucent, brighter and more opaque
/// inwards (a medium's emission falls over decades: one surface a decade).
inline constexpr std::array<double, 3> kMediumLevels = {0.3, 0.03, 0.003};

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
  /// The picked rays as drawn (null when there are none). Picks whose polydata carry a point array "light" (the
  /// intensity a ray collected from a medium between the camera and each point, over the ray's whole: 0 to 1) are
  /// coloured by it, black through red and yellow to white, instead of magenta.
  vtkPolyData* picks() const;
  /// Replaces the medium layer: the iso-surfaces of `field` at kMediumLevels (translucent, nested). A field without
  /// a positive peak removes the layer.
  void set_medium(const MediumField& field);
  /// The medium layer's surfaces as drawn, all levels in one polydata with a point array "level" (its fraction of
  /// the peak); null without a medium.
  vtkPolyData* medium_surfaces() const;
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
