// The 3D scene renderer with toggleable layers (see grtrace/viz/scene_view.hpp).
#include "grtrace/viz/scene_view.hpp"

#include "grtrace/viz/surfaces.hpp"
#include "lookup_tables.hpp"

#include <Eigen/Geometry>
#include <vtkActor.h>
#include <vtkAppendPolyData.h>
#include <vtkCamera.h>
#include <vtkContourFilter.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkGlyph3D.h>
#include <vtkImageData.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPropAssembly.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSphereSource.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTubeFilter.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

namespace grtrace::viz {

std::string_view to_string(Layer layer) {
  switch (layer) {
    case Layer::horizon: return "horizon";
    case Layer::photon_sphere: return "photon-sphere";
    case Layer::isco: return "isco";
    case Layer::disk: return "disk";
    case Layer::sky: return "sky";
    case Layer::camera: return "camera";
    case Layer::rays: return "rays";
    case Layer::orbit: return "orbit";
    case Layer::colorbar: return "colorbar";
    case Layer::ergosphere: return "ergosphere";
    case Layer::picks: return "picks";
    case Layer::medium:
      return "medium";
  }
  return "";
}

std::optional<Layer> layer_from_string(std::string_view name) {
  for (Layer l : kAllLayers)
    if (to_string(l) == name) return l;
  return std::nullopt;
}

namespace {

vtkSmartPointer<vtkActor> make_actor(vtkPolyData* data, std::array<double, 3> color, double opacity = 1.0) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(color.data());
  actor->GetProperty()->SetOpacity(opacity);
  return actor;
}

/// An actor whose cells carry their own uint8 colours (checkerboard, camera axes).
vtkSmartPointer<vtkActor> make_direct_color_actor(vtkPolyData* data) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  mapper->SetScalarModeToUseCellData();
  mapper->SetColorModeToDirectScalars();
  mapper->ScalarVisibilityOn();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  return actor;
}

vtkSmartPointer<vtkPolyData> tube(vtkPolyData* lines, double radius, int sides = 12) {
  vtkNew<vtkTubeFilter> t;
  t->SetInputData(lines);
  t->SetRadius(radius);
  t->SetNumberOfSides(sides);
  t->CappingOn();
  t->Update();
  return t->GetOutput();
}

}  // namespace

struct SceneView::Impl {
  SceneLayout layout;
  vtkNew<vtkRenderer> renderer;
  std::map<Layer, vtkSmartPointer<vtkProp>> props;
  std::map<Layer, bool> wanted;  // user visibility (the colour bar also depends on what is coloured)
  vtkSmartPointer<vtkPolyData> ray_data, orbit_data;
  vtkSmartPointer<vtkPolyDataMapper> ray_mapper, orbit_mapper;
  vtkSmartPointer<vtkActor> orbit_actor;  // the tube (the layer's prop is an assembly when marks are drawn)
  bool orbit_marked = false;               // the orbit is a camera flight with its frames marked
  ScalarField ray_field = ScalarField::none, orbit_field = ScalarField::none;
  vtkNew<vtkScalarBarActor> bar;
  vtkNew<vtkTextActor> legend;  // what the visible layers are, bottom left
  vtkSmartPointer<vtkPolyData> pick_data;
  vtkNew<vtkTextActor> pick_text;  // the picks' outcomes, top left under the caption
  vtkSmartPointer<vtkPolyData> medium_data;

  void update_legend() {
    std::string text;
    auto line = [&](Layer l, const std::string& what) {
      if (props.count(l) && wanted[l]) text += what + "\n";
    };
    const std::string rh = layout.spin != 0.0 ? "r_+" : "2M";
    line(Layer::horizon, layout.horizon_checkerboard ? "horizon r = " + rh + " (renderer's checkerboard)"
                                                     : "horizon r = " + rh + " (black)");
    line(Layer::photon_sphere, "photon sphere r = 3M (translucent)");
    line(Layer::ergosphere, "ergosphere: static limit r_E(theta) (translucent magenta)");
    line(Layer::isco, layout.isco_radius > 0.0 ? "ISCO (orange ring)" : "ISCO r = 6M (orange ring)");
    line(Layer::disk, "disk (amber)");
    line(Layer::sky, "sky sphere (grey wireframe)");
    line(Layer::camera, "camera: frustum; axes forward red, up green, right blue");
    if (props.count(Layer::rays) && wanted[Layer::rays])
      text += ray_field == ScalarField::pixel_color ? "rays: colour of their frame pixel\n"
                                                    : "rays: " + std::string(scalar_title(ray_field)) + "\n";
    line(Layer::orbit, orbit_marked ? "camera flight path (tube; frames: white beads)" : "timelike orbit (tube)");
    const bool lit_picks = pick_data && pick_data->GetPointData()->GetArray("light");
    line(Layer::picks, lit_picks ? "picked rays: the light they collect, from the camera (black) to all of it (white)"
                                 : "picked rays (magenta; outcomes top left)");
    line(Layer::medium, "medium: emission at 30 %, 3 % and 0.3 % of its peak (translucent)");
    if (!text.empty()) text.pop_back();
    legend->SetInput(text.c_str());
  }

  void remove(Layer l) {
    if (auto it = props.find(l); it != props.end()) {
      renderer->RemoveViewProp(it->second);
      props.erase(it);
    }
  }

  void add(Layer l, vtkProp* p) {
    if (auto it = props.find(l); it != props.end()) renderer->RemoveViewProp(it->second);
    props[l] = p;
    renderer->AddViewProp(p);
    if (!wanted.count(l)) wanted[l] = true;
    p->SetVisibility(wanted[l]);
  }

  void color(vtkPolyDataMapper* mapper, vtkPolyData* data, ScalarField field, std::array<double, 3> solid,
             vtkActor* actor) {
    if (field == ScalarField::none) {
      mapper->ScalarVisibilityOff();
      actor->GetProperty()->SetColor(solid.data());
      return;
    }
    const std::string name(array_name(field));
    vtkDataArray* array = data->GetPointData()->GetArray(name.c_str());
    if (!array)
      throw std::invalid_argument("cannot colour by '" + std::string(to_string(field)) + "': the paths carry no '" +
                                  name + "' data");
    mapper->ScalarVisibilityOn();
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray(name.c_str());
    if (field == ScalarField::pixel_color) {
      mapper->SetColorModeToDirectScalars();
      return;
    }
    mapper->SetColorModeToMapScalars();
    const auto lut = make_lookup_table(field, array);
    mapper->SetLookupTable(lut);
    mapper->SetScalarRange(lut->GetRange());
    mapper->UseLookupTableScalarRangeOn();
  }

  void update_bar() {
    update_legend();
    // The bar describes the rays when they are shown and coloured by a scalar, else the orbit.
    vtkPolyDataMapper* source = nullptr;
    ScalarField field = ScalarField::none;
    auto mapped = [](ScalarField f) { return f != ScalarField::none && f != ScalarField::pixel_color; };
    if (props.count(Layer::rays) && wanted[Layer::rays] && mapped(ray_field)) {
      source = ray_mapper;
      field = ray_field;
    } else if (props.count(Layer::orbit) && wanted[Layer::orbit] && mapped(orbit_field)) {
      source = orbit_mapper;
      field = orbit_field;
    }
    const bool show = source && wanted[Layer::colorbar];
    bar->SetVisibility(show);
    if (!source) return;
    bar->SetLookupTable(source->GetLookupTable());
    const bool categories = field == ScalarField::status;
    bar->SetHeight(categories ? 0.5 : 0.75);
    bar->SetPosition(categories ? 0.8 : 0.85, categories ? 0.3 : 0.12);
    std::string title(scalar_title(field));
    if (source == orbit_mapper.Get()) title = "orbit: " + std::string(field == ScalarField::lambda ? "proper time" : title);
    bar->SetTitle(title.c_str());
  }
};

SceneView::SceneView(const SceneLayout& layout) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.layout = layout;
  if (!(layout.mass > 0.0) || !std::isfinite(layout.mass)) throw std::invalid_argument("SceneView: mass must be > 0");
  const double M = layout.mass;
  if (!std::isfinite(layout.spin) || !(std::abs(layout.spin) < M))
    throw std::invalid_argument("SceneView: the spin must satisfy |a| < M");
  const bool kerr = layout.spin != 0.0;
  // Boyer-Lindquist outer horizon r_+ = M + sqrt(M^2 - a^2) (2M without spin).
  const double r_horizon = M + std::sqrt(M * M - layout.spin * layout.spin);
  m.renderer->SetBackground(kBackground[0] / 255.0, kBackground[1] / 255.0, kBackground[2] / 255.0);
  // The surfaces in the rays' chart: the BL embedding, or Cartesian Kerr-Schild (vtk_export.cpp does the same).
  auto chart = [&](vtkSmartPointer<vtkPolyData> p) {
    return layout.kerr_schild ? to_kerr_schild(p, layout.spin, *layout.kerr_schild) : p;
  };

  if (layout.horizon_checkerboard) {
    m.add(Layer::horizon, make_direct_color_actor(chart(make_checkered_sphere(r_horizon, layout.checker_theta,
                                                                              layout.checker_phi, layout.checker_a,
                                                                              layout.checker_b))));
  } else {
    auto horizon = make_actor(chart(make_sphere(r_horizon)), {0.0, 0.0, 0.0});
    horizon->GetProperty()->SetSpecular(0.0);
    m.add(Layer::horizon, horizon);
  }
  if (kerr) {  // no single photon sphere in Kerr; the static limit instead
    auto ergo = make_actor(chart(make_ergosphere(M, layout.spin)), {0.85, 0.3, 0.85}, 0.18);
    ergo->GetProperty()->SetSpecular(0.0);
    m.add(Layer::ergosphere, ergo);
  } else {
    auto photon = make_actor(chart(make_sphere(3.0 * M)), {0.35, 0.8, 0.95}, 0.12);
    photon->GetProperty()->SetSpecular(0.0);
    m.add(Layer::photon_sphere, photon);
  }
  const double isco = layout.isco_radius > 0.0 ? layout.isco_radius : 6.0 * M;
  m.add(Layer::isco, make_actor(tube(chart(make_ring(isco)), 0.06 * M, 10), {1.0, 0.55, 0.1}));
  if (layout.disk) {
    auto disk = make_actor(chart(make_annulus((*layout.disk)[0], (*layout.disk)[1])), {0.95, 0.7, 0.3}, 0.35);
    disk->GetProperty()->SetSpecular(0.0);
    m.add(Layer::disk, disk);
  }
  if (layout.sky_radius > 0.0) {
    auto sky = make_actor(chart(make_lat_long_sphere(layout.sky_radius)), {0.45, 0.47, 0.55}, 0.6);
    sky->GetProperty()->LightingOff();
    m.add(Layer::sky, sky);
  }
  if (layout.camera) {
    const CameraGlyph& cam = *layout.camera;
    const double len = layout.camera_glyph_length > 0.0 ? layout.camera_glyph_length
                                                         : std::max(M, 0.25 * cam.position.norm());
    vtkNew<vtkPropAssembly> glyph;
    auto frustum = make_actor(make_camera_frustum(cam, len), {0.92, 0.92, 0.92});
    frustum->GetProperty()->LightingOff();
    frustum->GetProperty()->SetLineWidth(1.5f);
    auto axes = make_direct_color_actor(make_camera_axes(cam, 0.6 * len));
    axes->GetProperty()->LightingOff();
    axes->GetProperty()->SetLineWidth(3.0f);
    glyph->AddPart(frustum);
    glyph->AddPart(axes);
    m.add(Layer::camera, glyph);
  }

  m.bar->SetNumberOfLabels(5);
  m.bar->SetMaximumWidthInPixels(90);
  m.bar->SetWidth(0.11);
  m.bar->GetTitleTextProperty()->SetFontSize(14);
  m.bar->GetTitleTextProperty()->ItalicOff();
  m.bar->GetTitleTextProperty()->BoldOff();
  m.bar->GetLabelTextProperty()->ItalicOff();
  m.bar->GetLabelTextProperty()->BoldOff();
  m.bar->SetTextPositionToSucceedScalarBar();
  m.bar->SetLabelFormat("%.3g");
  m.bar->UnconstrainedFontSizeOn();
  m.bar->GetTitleTextProperty()->SetFontSize(13);
  m.bar->GetLabelTextProperty()->SetFontSize(12);
  m.bar->GetAnnotationTextProperty()->ItalicOff();
  m.bar->GetAnnotationTextProperty()->BoldOff();
  m.bar->GetAnnotationTextProperty()->SetFontSize(12);
  m.bar->SetBarRatio(0.25);
  m.bar->SetVerticalTitleSeparation(8);
  m.bar->SetVisibility(false);
  m.renderer->AddViewProp(m.bar);
  m.legend->GetTextProperty()->SetFontSize(13);
  m.legend->GetTextProperty()->SetColor(0.9, 0.9, 0.92);
  m.legend->GetTextProperty()->SetLineSpacing(1.15);
  m.legend->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  m.legend->GetPositionCoordinate()->SetValue(0.015, 0.015);
  m.renderer->AddViewProp(m.legend);
  m.pick_text->GetTextProperty()->SetFontSize(13);
  m.pick_text->GetTextProperty()->SetColor(1.0, 0.75, 0.95);
  m.pick_text->GetTextProperty()->SetVerticalJustificationToTop();
  m.pick_text->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  m.pick_text->GetPositionCoordinate()->SetValue(0.015, 0.935);  // under the window's caption
  m.renderer->AddViewProp(m.pick_text);
  m.wanted[Layer::colorbar] = true;
  m.update_legend();
  set_view(default_view());
}

SceneView::~SceneView() = default;

vtkRenderer* SceneView::renderer() const { return impl_->renderer; }
const SceneLayout& SceneView::layout() const { return impl_->layout; }

void SceneView::set_rays(vtkPolyData* rays, ScalarField color_by) {
  Impl& m = *impl_;
  m.ray_data = rays;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(rays);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetLineWidth(2.0f);
  m.ray_mapper = mapper.Get();
  m.add(Layer::rays, actor);
  set_color_by(Layer::rays, color_by);
}

void SceneView::set_picks(vtkPolyData* picks, const std::string& text) {
  Impl& m = *impl_;
  if (picks == nullptr || picks->GetNumberOfPoints() == 0) {
    m.pick_data = nullptr;
    m.remove(Layer::picks);
    m.pick_text->SetInput("");
    m.update_legend();
    return;
  }
  m.pick_data = picks;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(picks);
  mapper->ScalarVisibilityOff();
  if (picks->GetPointData()->GetArray("light")) {  // the light collected, black through red and yellow to white
    vtkNew<vtkLookupTable> lut;
    lut->SetNumberOfTableValues(256);
    lut->SetRange(0.0, 1.0);
    for (int i = 0; i < 256; ++i) {
      const double v = i / 255.0;
      lut->SetTableValue(i, std::clamp(3.0 * v, 0.0, 1.0), std::clamp(3.0 * v - 1.0, 0.0, 1.0),
                         std::clamp(3.0 * v - 2.0, 0.0, 1.0), 1.0);
    }
    lut->Build();
    mapper->ScalarVisibilityOn();
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray("light");
    mapper->SetColorModeToMapScalars();
    mapper->SetLookupTable(lut);
    mapper->SetScalarRange(0.0, 1.0);
    mapper->UseLookupTableScalarRangeOn();
  }
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(1.0, 0.25, 0.85);
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetLineWidth(4.0f);
  m.add(Layer::picks, actor);
  m.pick_text->SetInput(text.c_str());
  m.pick_text->SetVisibility(m.wanted[Layer::picks]);
  m.update_legend();
}

vtkPolyData* SceneView::picks() const { return impl_->pick_data; }

vtkSmartPointer<vtkImageData> medium_to_imagedata(const MediumField& field) {
  const auto n = static_cast<std::size_t>(std::max(field.n, 0));
  if (field.n < 2 || field.values.size() != n * n * n || !(field.half_width > 0.0))
    throw std::invalid_argument("medium field: need n >= 2, n^3 values and a positive half width");
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(field.n, field.n, field.n);
  const double h = 2.0 * field.half_width / (field.n - 1);
  image->SetSpacing(h, h, h);
  image->SetOrigin(-field.half_width, -field.half_width, -field.half_width);
  vtkNew<vtkFloatArray> values;
  values->SetName("emission");
  values->SetNumberOfTuples(static_cast<vtkIdType>(field.values.size()));
  for (std::size_t i = 0; i < field.values.size(); ++i) values->SetValue(static_cast<vtkIdType>(i), field.values[i]);
  image->GetPointData()->SetScalars(values);
  return image;
}

void SceneView::set_medium(const MediumField& field) {
  Impl& m = *impl_;
  const vtkSmartPointer<vtkImageData> image = medium_to_imagedata(field);
  if (!(field.peak > 0.0)) {
    m.medium_data = nullptr;
    m.remove(Layer::medium);
    m.update_legend();
    return;
  }
  vtkNew<vtkAppendPolyData> all;
  vtkNew<vtkPropAssembly> surfaces;
  for (std::size_t l = 0; l < kMediumLevels.size(); ++l) {
    vtkNew<vtkContourFilter> contour;
    contour->SetInputData(image);
    contour->SetValue(0, kMediumLevels[l] * field.peak);
    contour->ComputeNormalsOn();
    contour->Update();
    vtkSmartPointer<vtkPolyData> surface = contour->GetOutput();
    vtkNew<vtkFloatArray> level;
    level->SetName("level");
    level->SetNumberOfTuples(surface->GetNumberOfPoints());
    level->Fill(kMediumLevels[l]);
    surface->GetPointData()->AddArray(level);
    all->AddInputData(surface);
    // The inner (brighter) surfaces hot and more opaque, the outer ones red and faint, so all three show.
    const std::array<std::array<double, 3>, 3> colours = {{{1.0, 0.95, 0.6}, {1.0, 0.6, 0.15}, {0.8, 0.2, 0.1}}};
    auto actor = make_actor(surface, colours[l], std::array<double, 3>{0.45, 0.25, 0.12}[l]);
    actor->GetProperty()->SetSpecular(0.0);
    surfaces->AddPart(actor);
  }
  all->Update();
  m.medium_data = all->GetOutput();
  m.add(Layer::medium, surfaces);
  m.update_legend();
}

vtkPolyData* SceneView::medium_surfaces() const { return impl_->medium_data; }

void SceneView::set_orbit(vtkPolyData* orbit, ScalarField color_by, double tube_radius, std::span<const Vec3> marks) {
  Impl& m = *impl_;
  double b[6];
  orbit->GetBounds(b);
  double extent = 0.0;
  for (double v : b) extent = std::max(extent, std::abs(v));
  const double radius = tube_radius > 0.0 ? tube_radius : std::max(0.3 * m.layout.mass, 0.005 * extent);
  m.orbit_data = tube(orbit, radius, 10);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(m.orbit_data);
  m.orbit_actor = vtkSmartPointer<vtkActor>::New();
  m.orbit_actor->SetMapper(mapper);
  m.orbit_mapper = mapper.Get();
  m.orbit_marked = !marks.empty();
  if (marks.empty()) {
    m.add(Layer::orbit, m.orbit_actor);
  } else {
    vtkNew<vtkPoints> centres;
    for (const Vec3& p : marks) centres->InsertNextPoint(p.data());
    vtkNew<vtkPolyData> at;
    at->SetPoints(centres);
    vtkNew<vtkSphereSource> bead;
    bead->SetRadius(2.5 * radius);
    bead->SetThetaResolution(12);
    bead->SetPhiResolution(8);
    vtkNew<vtkGlyph3D> beads;
    beads->SetInputData(at);
    beads->SetSourceConnection(bead->GetOutputPort());
    beads->ScalingOff();
    beads->Update();
    vtkNew<vtkPropAssembly> path;
    path->AddPart(m.orbit_actor);
    path->AddPart(make_actor(beads->GetOutput(), {0.95, 0.95, 0.95}));
    m.add(Layer::orbit, path);
  }
  set_color_by(Layer::orbit, color_by);
}

void SceneView::set_color_by(Layer layer, ScalarField field) {
  Impl& m = *impl_;
  if (layer != Layer::rays && layer != Layer::orbit) throw std::invalid_argument("only rays and orbits are coloured");
  if (!m.props.count(layer)) throw std::invalid_argument("no " + std::string(to_string(layer)) + " layer yet");
  auto* actor = layer == Layer::orbit ? m.orbit_actor.Get() : vtkActor::SafeDownCast(m.props[layer]);
  if (layer == Layer::rays) {
    m.color(m.ray_mapper, m.ray_data, field, {0.9, 0.9, 0.6}, actor);
    m.ray_field = field;
  } else {
    m.color(m.orbit_mapper, m.orbit_data, field, {0.85, 0.85, 0.9}, actor);
    m.orbit_field = field;
  }
  m.update_bar();
}

ScalarField SceneView::color_by(Layer layer) const {
  return layer == Layer::rays ? impl_->ray_field : layer == Layer::orbit ? impl_->orbit_field : ScalarField::none;
}

ScalarField SceneView::cycle_ray_coloring() {
  Impl& m = *impl_;
  if (!m.ray_data) return ScalarField::none;
  constexpr std::array<ScalarField, 5> order = {ScalarField::pixel_color, ScalarField::redshift, ScalarField::step_size,
                                                ScalarField::lambda, ScalarField::status};
  std::size_t i = 0;
  while (i < order.size() && order[i] != m.ray_field) ++i;
  for (std::size_t n = 1; n <= order.size(); ++n) {
    const ScalarField f = order[(i + n) % order.size()];
    if (m.ray_data->GetPointData()->GetArray(std::string(array_name(f)).c_str())) {
      set_color_by(Layer::rays, f);
      return f;
    }
  }
  return m.ray_field;
}

bool SceneView::has(Layer layer) const { return layer == Layer::colorbar || impl_->props.count(layer) > 0; }

bool SceneView::visible(Layer layer) const {
  if (!has(layer)) return false;
  return impl_->wanted.at(layer);
}

void SceneView::set_visible(Layer layer, bool on) {
  Impl& m = *impl_;
  m.wanted[layer] = on;
  if (auto it = m.props.find(layer); it != m.props.end()) it->second->SetVisibility(on);
  if (layer == Layer::picks) m.pick_text->SetVisibility(on);
  m.update_bar();
}

void SceneView::toggle(Layer layer) { set_visible(layer, !visible(layer)); }

void SceneView::set_view(const ViewPose& pose) {
  if (!((pose.from - pose.at).norm() > 0.0)) throw std::invalid_argument("3D view: eye and focal point coincide");
  vtkCamera* cam = impl_->renderer->GetActiveCamera();
  cam->SetPosition(pose.from.data());
  cam->SetFocalPoint(pose.at.data());
  // An up vector along the line of sight is no up: fall back to +y (then +x).
  const Vec3 dir = (pose.at - pose.from).normalized();
  Vec3 up = pose.up;
  for (const Vec3& alt : {Vec3(Vec3::UnitY()), Vec3(Vec3::UnitX())})
    if (!(dir.cross(up).norm() > 1e-6 * up.norm())) up = alt;
  cam->SetViewUp(up.data());
  cam->SetViewAngle(pose.view_angle_degrees);
  cam->OrthogonalizeViewUp();
  impl_->renderer->ResetCameraClippingRange();
}

ViewPose SceneView::view() const {
  vtkCamera* cam = impl_->renderer->GetActiveCamera();
  ViewPose p;
  cam->GetPosition(p.from.data());
  cam->GetFocalPoint(p.at.data());
  cam->GetViewUp(p.up.data());
  p.view_angle_degrees = cam->GetViewAngle();
  return p;
}

ViewPose SceneView::default_view() const {
  const SceneLayout& l = impl_->layout;
  double extent = 8.0 * l.mass;
  if (l.disk) extent = std::max(extent, (*l.disk)[1]);
  Vec3 centre = Vec3::Zero();
  double azimuth = -std::numbers::pi / 2.0;  // look along +y by default
  if (l.camera) {
    // Frame the hole and the camera: centre between them, looking from 80 degrees around, so the camera's rays
    // run across the view.
    const Vec3& c = l.camera->position;
    centre = 0.35 * c;
    extent = std::max(extent, 0.75 * c.norm());
    azimuth = std::atan2(c[1], c[0]) - 80.0 * std::numbers::pi / 180.0;
  }
  // An orbit on show is framed too.
  if (impl_->orbit_data && visible(Layer::orbit)) {
    double b[6];
    impl_->orbit_data->GetBounds(b);
    for (double v : b) extent = std::max(extent, std::abs(v));
    centre = Vec3::Zero();
  }
  const double elevation = 35.0 * std::numbers::pi / 180.0;
  ViewPose p;
  p.view_angle_degrees = 30.0;
  const double distance = 1.15 * extent / std::tan(p.view_angle_degrees * std::numbers::pi / 360.0);
  p.from = centre + distance * Vec3(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                                    std::sin(elevation));
  p.at = centre;
  p.up = Vec3::UnitZ();
  return p;
}

}  // namespace grtrace::viz
