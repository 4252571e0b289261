// The frame viewport (see grtrace/viz/frame_view.hpp).
#include "grtrace/viz/frame_view.hpp"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkImageMapper3D.h>
#include <vtkImageProperty.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include <algorithm>
#include <cstring>

namespace grtrace::viz {

struct FrameView::Impl {
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkImageActor> image_actor;
  vtkNew<vtkImageData> image;
  vtkNew<vtkActor> markers, marker_shadow;  // a white outline over a wider black one: visible on any picture
  vtkNew<vtkPolyData> marker_data, shadow_data;
  vtkNew<vtkActor> pick_markers, pick_shadow;  // picked pixels: magenta over black
  vtkNew<vtkPolyData> pick_data, pick_shadow_data;
  vtkNew<vtkCallbackCommand> on_start;
  Rgb8Image frame;
  double scale = 1.0;
  int vw = 1, vh = 1;

  double marker_half() const { return std::max(1.5, std::max(frame.width, frame.height) / 200.0); }
  FrameFit placement() const { return {frame.width, frame.height, vw, vh}; }

  static void before_render(vtkObject*, unsigned long, void* client, void*) {
    auto* self = static_cast<FrameView*>(client);
    const int* size = self->impl_->renderer->GetSize();
    if (size[0] > 0 && size[1] > 0) self->fit(size[0], size[1]);
  }
};

namespace {

/// Takes the frame's renderer, an actor, the polydata of its squares, a colour and a line width; draws the squares
/// with that actor (unlit lines) in the renderer. Assumes the actor has no mapper yet.
void add_marker_layer(vtkRenderer* renderer, vtkActor* actor, vtkPolyData* squares, std::array<double, 3> color,
                      float line_width) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(squares);
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(color.data());
  actor->GetProperty()->LightingOff();
  actor->GetProperty()->SetLineWidth(line_width);
  renderer->AddViewProp(actor);
}

}  // namespace

FrameView::FrameView() : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.renderer->SetBackground(kBackground.data());
  m.renderer->InteractiveOff();  // the trackball acts on the 3D view only
  m.image_actor->InterpolateOff();
  m.image_actor->GetProperty()->SetInterpolationTypeToNearest();
  m.image_actor->GetProperty()->SetColorWindow(255.0);
  m.image_actor->GetProperty()->SetColorLevel(127.5);
  m.image_actor->GetMapper()->SetInputData(m.image);
  m.image_actor->GetMapper()->BorderOn();  // edge pixels shown whole, not cut at their centres
  m.image_actor->SetVisibility(false);
  m.renderer->AddViewProp(m.image_actor);

  add_marker_layer(m.renderer, m.marker_shadow, m.shadow_data, {0.0, 0.0, 0.0}, 3.0f);
  add_marker_layer(m.renderer, m.markers, m.marker_data, {1.0, 1.0, 1.0}, 1.0f);
  add_marker_layer(m.renderer, m.pick_shadow, m.pick_shadow_data, {0.0, 0.0, 0.0}, 4.0f);
  add_marker_layer(m.renderer, m.pick_markers, m.pick_data, {1.0, 0.25, 0.85}, 2.0f);

  vtkCamera* cam = m.renderer->GetActiveCamera();
  cam->ParallelProjectionOn();
  m.on_start->SetCallback(&Impl::before_render);
  m.on_start->SetClientData(this);
  m.renderer->AddObserver(vtkCommand::StartEvent, m.on_start);
}

FrameView::~FrameView() { impl_->renderer->RemoveObserver(impl_->on_start); }

vtkRenderer* FrameView::renderer() const { return impl_->renderer; }
const Rgb8Image& FrameView::frame() const { return impl_->frame; }

void FrameView::set_frame(const Rgb8Image& frame) {
  Impl& m = *impl_;
  m.frame = frame;
  m.image->SetDimensions(frame.width, frame.height, 1);
  m.image->SetOrigin(0.0, 0.0, 0.0);
  m.image->SetSpacing(1.0, 1.0, 1.0);
  m.image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* dst = static_cast<unsigned char*>(m.image->GetScalarPointer());
  const auto row_bytes = static_cast<std::size_t>(frame.width) * 3;
  for (int y = 0; y < frame.height; ++y)  // VTK row 0 is the bottom
    std::memcpy(dst + static_cast<std::size_t>(frame.height - 1 - y) * row_bytes, frame.rgb.data() + frame.offset(0, y),
                row_bytes);
  m.image->Modified();
  m.image_actor->SetVisibility(!frame.empty());
}

namespace {

/// Takes a marker polydata, frame pixels (x, y from the top), the frame's height, the half side of a square in
/// frame pixels and a depth z; fills the polydata with one closed square around each pixel's centre.
void draw_squares(vtkPolyData* data, std::span<const std::array<int, 2>> pixels, int frame_height, double half,
                  double z) {
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> lines;
  for (const auto& p : pixels) {
    const double cx = p[0], cy = frame_height - 1 - p[1];
    vtkIdType ids[5];
    const double corner[4][2] = {{-half, -half}, {half, -half}, {half, half}, {-half, half}};
    for (int i = 0; i < 4; ++i) ids[i] = pts->InsertNextPoint(cx + corner[i][0], cy + corner[i][1], z);
    ids[4] = ids[0];
    lines->InsertNextCell(5, ids);
  }
  data->SetPoints(pts);
  data->SetLines(lines);
  data->Modified();
}

}  // namespace

void FrameView::set_markers(std::span<const std::array<int, 2>> pixels) {
  Impl& m = *impl_;
  // A square of side 2 * half frame pixels around each marked pixel's centre (at least 3 pixels across).
  const double half = m.marker_half();
  draw_squares(m.shadow_data, pixels, m.frame.height, half, 1.0);
  draw_squares(m.marker_data, pixels, m.frame.height, half, 2.0);
}

void FrameView::set_pick_markers(std::span<const std::array<int, 2>> pixels) {
  Impl& m = *impl_;
  // A little larger than the bundle's squares, so a picked bundle pixel shows both.
  const double half = 1.6 * m.marker_half();
  draw_squares(m.pick_shadow_data, pixels, m.frame.height, half, 3.0);
  draw_squares(m.pick_data, pixels, m.frame.height, half, 4.0);
}

void FrameView::set_markers_visible(bool on) {
  impl_->markers->SetVisibility(on);
  impl_->marker_shadow->SetVisibility(on);
}
bool FrameView::markers_visible() const { return impl_->markers->GetVisibility() != 0; }

void FrameView::fit(int viewport_width, int viewport_height) {
  Impl& m = *impl_;
  m.vw = viewport_width;
  m.vh = viewport_height;
  if (m.frame.empty()) return;
  m.scale = m.placement().scale();
  vtkCamera* cam = m.renderer->GetActiveCamera();
  const double cx = 0.5 * (m.frame.width - 1.0), cy = 0.5 * (m.frame.height - 1.0);
  cam->SetFocalPoint(cx, cy, 0.0);
  cam->SetPosition(cx, cy, 100.0);
  cam->SetViewUp(0.0, 1.0, 0.0);
  cam->SetParallelScale(0.5 * viewport_height / m.scale);
  cam->SetClippingRange(50.0, 150.0);
}

double FrameView::scale() const { return impl_->scale; }

FrameFit FrameView::placement() const { return impl_->placement(); }

std::array<double, 2> FrameView::frame_to_viewport(double x, double y) const {
  return impl_->placement().to_viewport(x, y);
}

}  // namespace grtrace::viz
