// The scene as VTK XML files for ParaView (see grtrace/viz/vtk_export.hpp).
#include "grtrace/viz/vtk_export.hpp"

#include "grtrace/core/ray_status.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/viz/surfaces.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLPolyDataWriter.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <system_error>

namespace grtrace::viz {

namespace {

template <class Array>
vtkSmartPointer<Array> named(const char* name, int components, vtkIdType tuples) {
  auto a = vtkSmartPointer<Array>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->Allocate(static_cast<vtkIdType>(components) * tuples);
  return a;
}

}  // namespace

vtkSmartPointer<vtkPolyData> paths_to_export_polydata(std::span<const TracedPath> paths) {
  vtkIdType total = 0;
  for (const auto& p : paths) total += static_cast<vtkIdType>(p.samples.size());
  const auto n_paths = static_cast<vtkIdType>(paths.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->Allocate(total);
  const auto lambda = named<vtkDoubleArray>("affine_parameter", 1, total);
  const auto h = named<vtkDoubleArray>("step_size", 1, total);
  const auto redshift = named<vtkDoubleArray>("redshift", 1, total);
  const auto status = named<vtkIntArray>("status", 1, total);
  const auto pixel = named<vtkIntArray>("pixel", 2, total);
  const auto step = named<vtkIntArray>("step", 1, total);
  const auto coords = named<vtkDoubleArray>("coordinates", 4, total);
  const auto momentum = named<vtkDoubleArray>("momentum", 4, total);
  const auto color = named<vtkUnsignedCharArray>("pixel_color", 3, total);
  const auto cell_ray = named<vtkIntArray>("ray", 1, n_paths);
  const auto cell_status = named<vtkIntArray>("status", 1, n_paths);
  const auto cell_pixel = named<vtkIntArray>("pixel", 2, n_paths);

  // VTK numbers vertex cells before line cells: fill the cell arrays in that order (two passes).
  vtkNew<vtkCellArray> lines, verts;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t index = 0; index < paths.size(); ++index) {
      const TracedPath& p = paths[index];
      if (p.samples.empty() || (p.samples.size() < 2) != (pass == 0)) continue;
      const int st = static_cast<int>(p.status);
      const int px[2] = {p.pixel_x, p.pixel_y};
      const Rgb8 c = p.color.value_or(Rgb8{128, 128, 128});
      vtkNew<vtkIdList> ids;
      for (const auto& s : p.samples) {
        ids->InsertNextId(points->InsertNextPoint(s.position[0], s.position[1], s.position[2]));
        lambda->InsertNextValue(s.lambda);
        h->InsertNextValue(s.h);
        redshift->InsertNextValue(s.redshift);
        status->InsertNextValue(st);
        pixel->InsertNextTypedTuple(px);
        step->InsertNextValue(s.step);
        const double x[4] = {s.state[0], s.state[1], s.state[2], s.state[3]};
        const double k[4] = {s.state[4], s.state[5], s.state[6], s.state[7]};
        coords->InsertNextTypedTuple(x);
        momentum->InsertNextTypedTuple(k);
        color->InsertNextTypedTuple(c.data());
      }
      (pass == 0 ? verts : lines)->InsertNextCell(ids);
      cell_ray->InsertNextValue(static_cast<int>(index));
      cell_status->InsertNextValue(st);
      cell_pixel->InsertNextTypedTuple(px);
    }
  }

  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetVerts(verts);
  poly->SetLines(lines);
  vtkPointData* pd = poly->GetPointData();
  for (vtkDataArray* a : std::initializer_list<vtkDataArray*>{lambda, h, redshift, status, pixel, step, coords,
                                                              momentum, color})
    pd->AddArray(a);
  pd->SetActiveScalars("affine_parameter");
  vtkCellData* cd = poly->GetCellData();
  cd->AddArray(cell_ray);
  cd->AddArray(cell_status);
  cd->AddArray(cell_pixel);
  vtkNew<vtkStringArray> names;
  names->SetName("status_names");
  for (const auto name : kRayStatusNames) names->InsertNextValue(std::string(name));
  poly->GetFieldData()->AddArray(names);
  return poly;
}

void add_camera_record(vtkPolyData* data, const CameraRecord& camera) {
  const auto pos = named<vtkDoubleArray>("camera_position", 4, 1);
  const double x[4] = {camera.position[0], camera.position[1], camera.position[2], camera.position[3]};
  pos->InsertNextTypedTuple(x);
  const auto tetrad = named<vtkDoubleArray>("camera_tetrad", 16, 1);
  double e[16];
  for (int a = 0; a < 4; ++a)
    for (int mu = 0; mu < 4; ++mu) e[4 * a + mu] = camera.tetrad[static_cast<std::size_t>(a)][mu];
  tetrad->InsertNextTypedTuple(e);
  const auto fov = named<vtkDoubleArray>("camera_fov_degrees", 1, 1);
  fov->InsertNextValue(camera.fov_degrees);
  const auto size = named<vtkIntArray>("frame_size", 2, 1);
  const int wh[2] = {camera.width, camera.height};
  size->InsertNextTypedTuple(wh);
  vtkFieldData* fd = data->GetFieldData();
  for (vtkAbstractArray* a : std::initializer_list<vtkAbstractArray*>{pos, tetrad, fov, size}) fd->AddArray(a);
}

vtkSmartPointer<vtkPolyData> flight_to_export_polydata(const TracedPath& flight, const std::string& kind, int frame,
                                                       const std::optional<CameraRecord>& camera) {
  if (frame < 0 || static_cast<std::size_t>(frame) >= flight.samples.size())
    throw std::invalid_argument("flight_to_export_polydata: frame " + std::to_string(frame) + " is not on the path");
  auto poly = paths_to_export_polydata(std::span(&flight, 1));
  const auto n = static_cast<vtkIdType>(flight.samples.size());
  const auto tau = named<vtkDoubleArray>("tau", 1, n);
  const auto index = named<vtkIntArray>("frame", 1, n);
  for (const PathSample& s : flight.samples) {
    tau->InsertNextValue(s.lambda);
    index->InsertNextValue(s.step);
  }
  poly->GetPointData()->AddArray(tau);
  poly->GetPointData()->AddArray(index);
  poly->GetPointData()->SetActiveScalars("tau");
  vtkNew<vtkStringArray> name;
  name->SetName("flight");
  name->InsertNextValue(kind);
  const auto in_use = named<vtkIntArray>("flight_frame", 1, 1);
  in_use->InsertNextValue(frame);
  const auto in_use_tau = named<vtkDoubleArray>("flight_frame_tau", 1, 1);
  in_use_tau->InsertNextValue(flight.samples[static_cast<std::size_t>(frame)].lambda);
  vtkFieldData* fd = poly->GetFieldData();
  for (vtkAbstractArray* a : std::initializer_list<vtkAbstractArray*>{name, in_use, in_use_tau}) fd->AddArray(a);
  if (camera) add_camera_record(poly, *camera);
  return poly;
}

vtkSmartPointer<vtkImageData> frame_to_imagedata(const Rgb8Image& rgb, const Image* channels) {
  if (rgb.empty()) throw std::invalid_argument("frame_to_imagedata: the frame is empty");
  if (channels && (channels->width() != rgb.width || channels->height() != rgb.height))
    throw std::invalid_argument("frame_to_imagedata: the image's channels and its colours differ in size");
  const int W = rgb.width, H = rgb.height;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(W, H, 1);
  image->SetOrigin(0.0, 0.0, 0.0);
  image->SetSpacing(1.0, 1.0, 1.0);
  const vtkIdType n = static_cast<vtkIdType>(W) * H;
  // VTK point (i, j) has id i + W j and sits at height j: pixel row H - 1 - j (frames are stored from the top).
  auto row_of = [&](vtkIdType id) { return H - 1 - static_cast<int>(id / W); };
  auto col_of = [&](vtkIdType id) { return static_cast<int>(id % W); };
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("rgb");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(n);
  for (vtkIdType id = 0; id < n; ++id) {
    const Rgb8 c = rgb.at(col_of(id), row_of(id));
    colors->SetTypedTuple(id, c.data());
  }
  image->GetPointData()->SetScalars(colors);
  if (channels) {
    for (const std::string& name : channels->channel_names()) {
      const std::vector<float>& values = channels->channel(name);
      vtkNew<vtkFloatArray> a;
      a->SetName(name.c_str());
      a->SetNumberOfTuples(n);
      for (vtkIdType id = 0; id < n; ++id) a->SetValue(id, values[channels->index(col_of(id), row_of(id))]);
      image->GetPointData()->AddArray(a);
    }
    if (!channels->metadata.empty()) {
      vtkNew<vtkStringArray> header;  // the render's recorded options and camera, "key=value"
      header->SetName("header");
      for (const auto& [key, value] : channels->metadata) header->InsertNextValue(key + "=" + value);
      image->GetFieldData()->AddArray(header);
    }
  }
  return image;
}

std::vector<SceneSurface> scene_surfaces(const SceneLayout& layout) {
  const double M = layout.mass;
  if (!(M > 0.0) || !std::isfinite(M)) throw std::invalid_argument("scene_surfaces: mass must be > 0");
  if (!std::isfinite(layout.spin) || !(std::abs(layout.spin) < M))
    throw std::invalid_argument("scene_surfaces: the spin must satisfy |a| < M");
  const double r_horizon = M + std::sqrt(M * M - layout.spin * layout.spin);
  // The surfaces in the rays' chart, as scene_view.cpp draws them.
  auto chart = [&](vtkSmartPointer<vtkPolyData> p) {
    return layout.kerr_schild ? to_kerr_schild(p, layout.spin, *layout.kerr_schild) : p;
  };
  std::vector<SceneSurface> out;
  out.push_back({Layer::horizon, "horizon",
                 chart(layout.horizon_checkerboard
                           ? make_checkered_sphere(r_horizon, layout.checker_theta, layout.checker_phi,
                                                   layout.checker_a, layout.checker_b)
                           : make_sphere(r_horizon))});
  if (layout.spin != 0.0) out.push_back({Layer::ergosphere, "ergosphere", chart(make_ergosphere(M, layout.spin))});
  else out.push_back({Layer::photon_sphere, "photon_sphere", chart(make_sphere(3.0 * M))});
  out.push_back({Layer::isco, "isco", chart(make_ring(layout.isco_radius > 0.0 ? layout.isco_radius : 6.0 * M))});
  if (layout.disk) out.push_back({Layer::disk, "disk", chart(make_annulus((*layout.disk)[0], (*layout.disk)[1]))});
  if (layout.sky_radius > 0.0) out.push_back({Layer::sky, "sky", chart(make_lat_long_sphere(layout.sky_radius))});
  if (layout.camera) {
    const CameraGlyph& cam = *layout.camera;
    const double len = layout.camera_glyph_length > 0.0 ? layout.camera_glyph_length
                                                         : std::max(M, 0.25 * cam.position.norm());
    out.push_back({Layer::camera, "camera_frustum", make_camera_frustum(cam, len)});
    out.push_back({Layer::camera, "camera_axes", make_camera_axes(cam, 0.6 * len)});
  }
  return out;
}

std::string to_vtk_xml(vtkDataObject* data) {
  if (data == nullptr) throw std::invalid_argument("to_vtk_xml: no data");
  auto encode = [&](auto& writer) {
    writer->SetInputData(data);
    writer->SetDataModeToAppended();
    writer->EncodeAppendedDataOff();
    writer->SetCompressorTypeToZLib();
    writer->WriteToOutputStringOn();
    if (writer->Write() != 1 || writer->GetErrorCode() != 0)
      throw std::runtime_error("VTK's XML writer failed to encode the data");
    return writer->GetOutputString();
  };
  if (vtkPolyData::SafeDownCast(data)) {
    vtkNew<vtkXMLPolyDataWriter> w;
    return encode(w);
  }
  if (vtkImageData::SafeDownCast(data)) {
    vtkNew<vtkXMLImageDataWriter> w;
    return encode(w);
  }
  throw std::invalid_argument(std::string("to_vtk_xml: cannot write a ") + data->GetClassName());
}

void write_vtk_xml(OutputSet& set, vtkDataObject* data, const std::filesystem::path& target) {
  const std::string bytes = to_vtk_xml(data);
  TemporaryOutput& out = set.add(target);
  out.write(bytes.data(), bytes.size());
  out.finish();
}

void write_vtk_xml(vtkDataObject* data, const std::filesystem::path& target) {
  const std::string bytes = to_vtk_xml(data);
  TemporaryOutput out(target);
  out.write(bytes.data(), bytes.size());
  out.commit();
}

void prepare_export_directory(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  if (dir.empty()) throw ExportPathError("the export directory name is empty");
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st) && !fs::is_directory(st))
    throw ExportPathError("'" + dir.string() + "' exists and is not a directory");
  if (!fs::exists(st)) {
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
      throw ExportPathError("cannot create the directory '" + dir.string() + "': " +
                            (ec ? ec.message() : std::string("not a directory")));
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw ExportPathError("the directory '" + dir.string() + "' is not writable");
  // Every name the export may write (<piece>.vtp, frame.vti, scene.vtm) is checked now, not after the rays: an
  // entry with such a name that is not a regular file (a directory, a device, a FIFO) would fail the export at
  // its end. Bounded: a directory of more entries than any export writes is only scanned that far.
  std::size_t seen = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end && seen < 100000; it.increment(ec), ++seen) {
    const fs::path& entry = it->path();
    const std::string ext = entry.extension().string();
    if (ext != ".vtp" && ext != ".vti" && ext != ".vtm") continue;
    try {
      check_output_path(entry);
    } catch (const std::runtime_error& e) {
      throw ExportPathError(std::string(e.what()) + " (the export writes its " + ext +
                            " files there: move it away or choose another directory)");
    }
  }
}

namespace {

std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace

std::string multiblock_xml(const std::filesystem::path& collection, std::span<const ExportedFile> blocks) {
  const std::filesystem::path base = collection.has_parent_path() ? collection.parent_path() : ".";
  std::ostringstream x;
  x << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" byte_order=\"LittleEndian\" "
       "header_type=\"UInt64\">\n"
    << "  <vtkMultiBlockDataSet>\n";
  int index = 0;
  for (const ExportedFile& b : blocks) {
    const std::filesystem::path rel = b.path.lexically_proximate(base);
    x << "    <DataSet index=\"" << index++ << "\" name=\"" << xml_escape(b.name) << "\" file=\""
      << xml_escape(rel.generic_string()) << "\"/>\n";
  }
  x << "  </vtkMultiBlockDataSet>\n</VTKFile>\n";
  return x.str();
}

std::vector<ExportedFile> export_scene(const std::filesystem::path& dir, const SceneExport& scene) {
  auto shown = [&](Layer l) { return std::find(scene.hidden.begin(), scene.hidden.end(), l) == scene.hidden.end(); };
  struct Piece {
    std::string name;
    vtkSmartPointer<vtkDataObject> data;
    const char* extension;
  };
  std::vector<Piece> pieces;
  if (!scene.rays.empty() && shown(Layer::rays)) {
    auto rays = paths_to_export_polydata(scene.rays);
    if (scene.camera) add_camera_record(rays, *scene.camera);
    if (!scene.light.empty()) add_light_array(rays, scene.rays, scene.light);
    pieces.push_back({"rays", rays, ".vtp"});
  }
  if (scene.orbit && shown(Layer::orbit))
    pieces.push_back({"orbit", paths_to_export_polydata(std::span(scene.orbit, 1)), ".vtp"});
  if (scene.flight && shown(Layer::orbit)) {
    const FlightExport& f = *scene.flight;
    pieces.push_back({"flight", flight_to_export_polydata(*f.path, f.kind, f.frame, f.camera), ".vtp"});
  }
  for (SceneSurface& s : scene_surfaces(scene.layout))
    if (shown(s.layer)) pieces.push_back({s.name, s.data, ".vtp"});
  if (scene.frame) pieces.push_back({"frame", frame_to_imagedata(*scene.frame, scene.frame_channels), ".vti"});
  if (scene.medium && shown(Layer::medium)) pieces.push_back({"medium", medium_to_imagedata(*scene.medium), ".vti"});

  std::vector<ExportedFile> files;
  OutputSet set;
  for (const Piece& p : pieces) {
    files.push_back({p.name, dir / (p.name + p.extension)});
    write_vtk_xml(set, p.data, files.back().path);
  }
  const std::filesystem::path collection = dir / "scene.vtm";
  const std::string xml = multiblock_xml(collection, files);
  TemporaryOutput& out = set.add(collection);
  out.write(xml.data(), xml.size());
  out.finish();
  set.commit();
  files.push_back({"scene", collection});
  return files;
}

}  // namespace grtrace::viz
