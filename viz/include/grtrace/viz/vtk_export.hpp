// grtrace/viz/vtk_export.hpp
// The 3D scene as VTK XML files for ParaView: rays and orbits as polylines with their point data, the reference
// surfaces as .vtp, the frame as a .vti image, and one multiblock collection (scene.vtm) that opens them all.
// The pieces are encoded with VTK's own writers (vtkXMLPolyDataWriter, vtkXMLImageDataWriter; binary, appended,
// zlib-compressed, doubles kept exactly); every file goes through grtrace::OutputSet (an unpredictable temporary,
// renamed into place with the others), so a scene directory holds a whole old export or a whole new one.
//
// Rays (paths_to_export_polydata): one polyline cell per path (a vertex cell for a one-sample path; empty paths
// give no cell), points = the samples' Cartesian embedding (traced_path.hpp), and
//   point data  "affine_parameter"  lambda of the sample (double)
//               "step_size"         size h of the accepted step the sample lies on (double)
//               "redshift"          f_obs / f_static(x) (double; NaN where not recorded or no static observer)
//               "status"            how the path ended, RayStatus as a number (int, the same on every point)
//               "pixel"             the path's frame pixel (x, y from the top) (int x 2; -1,-1 when it has none)
//               "step"              accepted-step index of the sample (int; 0 = the start point)
//               "coordinates"       chart coordinates x^mu = (t, r, theta, phi) (double x 4)
//               "momentum"          chart components k^mu (double x 4)
//               "pixel_color"       the pixel's preview colour (uint8 x 3; mid grey without a pixel)
//   cell data   "ray" (index of the path in the input), "status", "pixel" (per ray: the natural place to select
//               or threshold whole rays in ParaView)
//   field data  "status_names" (string: the RayStatus names, indexed by the status numbers)
// The point "status" and "pixel" repeat the ray's value on every point so that point-based filters and
// colouring work without a Cell Data to Point Data step.
//
// Frame (frame_to_imagedata): W x H x 1 points, spacing 1, origin 0; point (i, j) is pixel (i, H - 1 - j)
// (VTK images grow upwards, frames are stored from the top), with point data "rgb" (uint8 x 3, the viewer's
// preview colours, active scalars) and every channel of the rendered grtrace::Image as a float array of the
// same name (R, G, B linear radiance, object, status, redshift, sky_theta, sky_phi, steps, order). The image lives in
// pixel units: show it in its own (2D) render view in ParaView.
//
// Flight (flight_to_export_polydata): a camera flight's path (observer/worldline.hpp worldline_path: one sample per
// frame) as the rays are written (coordinates = x, momentum = the 4-velocity u, affine_parameter = tau) plus
//   point data  "tau" (the frame's proper time, double), "frame" (the frame's index, int)
//   field data  "flight" (the kind, string), "flight_frame" (the frame whose camera the viewer used, int),
//               "flight_frame_tau" (its proper time) and that camera (add_camera_record), when given
//
// Scene (export_scene): in the directory, whichever the layout and data have (the names are the scene.vtm
// block names):
//   rays.vtp, orbit.vtp, flight.vtp, horizon.vtp (r_+; 2M without spin), photon_sphere.vtp (3M, Schwarzschild),
//   ergosphere.vtp (Kerr), isco.vtp (the ring, a closed polyline), disk.vtp, sky.vtp (wireframe),
//   camera_frustum.vtp, camera_axes.vtp, frame.vti, medium.vti (an emitting medium's emission on its cube of
//   points: point array "emission"; contour it in ParaView), and scene.vtm (written last, refers to the others by
//   relative name). Open scene.vtm in ParaView.
#pragma once

#include "grtrace/render/image.hpp"
#include "grtrace/viz/frame_image.hpp"
#include "grtrace/viz/scene_view.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <vtkSmartPointer.h>

#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

class vtkDataObject;
class vtkImageData;
class vtkPolyData;

namespace grtrace {
class OutputSet;
}

namespace grtrace::viz {

/// The rays (or an orbit) with the point, cell and field data above.
vtkSmartPointer<vtkPolyData> paths_to_export_polydata(std::span<const TracedPath> paths);

/// The camera that shot the rays, added to a polydata's field data as "camera_position" (t, r, theta, phi),
/// "camera_tetrad" (16 values: e_0^mu .. e_3^mu), "camera_fov_degrees" and "frame_size" (W, H).
struct CameraRecord {
  Vec4 position = Vec4::Zero();
  std::array<Vec4, 4> tetrad{};
  double fov_degrees = 0.0;
  int width = 0, height = 0;
};
void add_camera_record(vtkPolyData* data, const CameraRecord& camera);

/// The flight above. Takes the path (one sample per frame), its kind, the frame in use (an index into the path's
/// samples) and that frame's camera (nothing: not recorded). Throws std::invalid_argument for a frame outside
/// the path.
vtkSmartPointer<vtkPolyData> flight_to_export_polydata(const TracedPath& flight, const std::string& kind, int frame,
                                                       const std::optional<CameraRecord>& camera);

/// The frame: preview colours `rgb` and (if given) the float channels of the rendered image, of the same size
/// (throws std::invalid_argument otherwise, or for an empty rgb).
vtkSmartPointer<vtkImageData> frame_to_imagedata(const Rgb8Image& rgb, const Image* channels = nullptr);

/// A reference surface of the layout, as the 3D view draws it (without the tube around the ISCO ring).
struct SceneSurface {
  Layer layer;
  std::string name;  ///< file stem and block name: "horizon", "photon_sphere", "camera_frustum", ...
  vtkSmartPointer<vtkPolyData> data;
};
/// horizon (checkerboard if the layout asks for it), photon sphere (no spin) or ergosphere (spin), ISCO ring,
/// disk, sky sphere, camera frustum and axes: whichever the layout has. Radii as in scene_view.hpp.
std::vector<SceneSurface> scene_surfaces(const SceneLayout& layout);

/// The XML file VTK's writer makes of `data` (vtkPolyData -> .vtp, vtkImageData -> .vti). Throws
/// std::invalid_argument for other types and std::runtime_error if the writer fails.
std::string to_vtk_xml(vtkDataObject* data);
/// to_vtk_xml written to `target` as part of `set` (renamed into place by set.commit()), or alone.
void write_vtk_xml(OutputSet& set, vtkDataObject* data, const std::filesystem::path& target);
void write_vtk_xml(vtkDataObject* data, const std::filesystem::path& target);

/// Thrown when an export directory cannot be used; tools report it as bad input (exit 2).
struct ExportPathError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
/// Makes `dir` usable as an export directory before any work: creates it (and its parents) if missing; throws
/// ExportPathError naming it if it is empty, exists as something other than a directory, cannot be created, or
/// is not writable, or if an entry in it with a name the export may write (*.vtp, *.vti, *.vtm) is not a regular
/// file (check_output_path: a directory, device or FIFO in the way). Creates nothing else.
void prepare_export_directory(const std::filesystem::path& dir);

/// A camera flight for export_scene: the arguments of flight_to_export_polydata.
struct FlightExport {
  const TracedPath* path = nullptr;        ///< one sample per frame (observer/worldline.hpp worldline_path); must not be null
  std::string kind;                        ///< --flight
  int frame = 0;                           ///< the frame in use
  std::optional<CameraRecord> camera;      ///< its camera
};

struct SceneExport {
  SceneLayout layout;
  std::vector<Layer> hidden;               ///< layers not to write (the viewer's --hide)
  std::span<const TracedPath> rays;        ///< empty: no rays.vtp
  /// Per ray of `rays` (may be shorter): a medium's light collected to each sample (RayPick::light), written as the
  /// point array "light" (add_light_array); empty: no such array.
  std::span<const std::vector<double>> light;
  const TracedPath* orbit = nullptr;       ///< null: no orbit.vtp
  std::optional<CameraRecord> camera;      ///< recorded in rays.vtp's field data
  std::optional<FlightExport> flight;      ///< flight.vtp (in the orbit layer); nothing: no flight
  const Rgb8Image* frame = nullptr;        ///< null: no frame.vti
  const Image* frame_channels = nullptr;   ///< the rendered image's float channels (optional)
  const MediumField* medium = nullptr;     ///< an emitting medium's emission: medium.vti (null: none)
};

struct ExportedFile {
  std::string name;                        ///< block name in scene.vtm
  std::filesystem::path path;
};

/// Writes the scene into `dir` (which must exist: prepare_export_directory) as one OutputSet: every piece,
/// then scene.vtm; all are renamed into place together. Returns the files written, scene.vtm last.
std::vector<ExportedFile> export_scene(const std::filesystem::path& dir, const SceneExport& scene);

/// The collection file: a vtkMultiBlockDataSet whose blocks are the given files, named, by paths relative to
/// `collection`'s directory.
std::string multiblock_xml(const std::filesystem::path& collection, std::span<const ExportedFile> blocks);

}  // namespace grtrace::viz
