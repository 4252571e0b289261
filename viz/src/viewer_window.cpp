// The two-viewport window (see grtrace/viz/viewer_window.hpp).
#include "grtrace/viz/viewer_window.hpp"

#include "grtrace/render/output_file.hpp"
#include "grtrace/viz/frame_view.hpp"
#include "grtrace/viz/geodesic_data.hpp"
#include "grtrace/viz/scene_view.hpp"

#include <X11/Xlib.h>
#include <unistd.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkImageData.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPolyData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkUnsignedCharArray.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace grtrace::viz {

namespace {

/// Takes nothing; returns a new connection to the X server at DISPLAY, or null when none answers. Assumes DISPLAY
/// is set. A busy server (Xvfb under load) refuses some connections for a moment: its listen queue is full
/// (EAGAIN), or it resets or drops a pending one (ECONNRESET, or no errno at all). Those attempts are repeated
/// (up to about two seconds); a missing server (ENOENT, ECONNREFUSED) is answered at once.
Display* open_display() {
  for (int attempt = 0; attempt < 100; ++attempt) {
    errno = 0;
    if (Display* display = XOpenDisplay(nullptr)) return display;
    if (errno == ENOENT || errno == ECONNREFUSED) return nullptr;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return nullptr;
}

}  // namespace

void* x_display() {
  // Opened once and kept for the life of the process (the OS closes it at exit), so every window shares it.
  static Display* const display = [] {
    const char* d = std::getenv("DISPLAY");
    return d == nullptr || *d == '\0' ? nullptr : open_display();
  }();
  return display;
}

bool display_available() { return x_display() != nullptr; }

void prepare_window(vtkRenderWindow* window) {
  if (void* display = x_display()) window->SetDisplayId(display);
  if (window->GetOffScreenRendering()) window->SetInteractor(nullptr);
}

void require_display(const std::string& program, const std::string& alternative) {
  if (display_available()) return;
  const char* d = std::getenv("DISPLAY");
  const std::string why = d == nullptr || *d == '\0' ? std::string("no X display (DISPLAY is not set)")
                                                     : "no X server answers at DISPLAY='" + std::string(d) + "'";
  throw NoDisplayError(why + "; VTK here renders only through X. Run headless as\n  xvfb-run -a -s \"-screen 0 " +
                       "1280x1024x24\" " + program + " ..." + (alternative.empty() ? "" : "\nor " + alternative));
}

namespace {

vtkSmartPointer<vtkTextActor> caption(const std::string& text, int font_size) {
  auto t = vtkSmartPointer<vtkTextActor>::New();
  t->SetInput(text.c_str());
  t->GetTextProperty()->SetFontSize(font_size);
  t->GetTextProperty()->SetColor(0.85, 0.87, 0.9);
  t->GetTextProperty()->SetVerticalJustificationToTop();
  t->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
  t->GetPositionCoordinate()->SetValue(0.015, 0.985);
  return t;
}

Rgb8Image from_vtk_image(vtkImageData* data) {
  int dims[3];
  data->GetDimensions(dims);
  const int comps = data->GetNumberOfScalarComponents();
  if (data->GetScalarType() != VTK_UNSIGNED_CHAR || comps < 3)
    throw std::runtime_error("expected an 8-bit RGB(A) image");
  Rgb8Image out(dims[0], dims[1]);
  const auto* src = static_cast<const unsigned char*>(data->GetScalarPointer());
  const auto ncomp = static_cast<std::size_t>(comps);
  for (int y = 0; y < dims[1]; ++y)
    for (int x = 0; x < dims[0]; ++x) {
      const std::size_t o = (static_cast<std::size_t>(dims[1] - 1 - y) * static_cast<std::size_t>(dims[0]) +
                             static_cast<std::size_t>(x)) * ncomp;
      out.set(x, y, {src[o], src[o + 1], src[o + 2]});
    }
  return out;
}

/// The PNG file (bytes) of an RGB8 image, encoded by VTK in memory.
std::vector<unsigned char> encode_png(const Rgb8Image& image, const std::string& path) {
  if (image.empty()) throw std::runtime_error("cannot write an empty image to '" + path + "'");
  vtkNew<vtkImageData> data;
  data->SetDimensions(image.width, image.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* dst = static_cast<unsigned char*>(data->GetScalarPointer());
  const auto row = static_cast<std::size_t>(image.width) * 3;
  for (int y = 0; y < image.height; ++y)
    std::memcpy(dst + static_cast<std::size_t>(image.height - 1 - y) * row, image.rgb.data() + image.offset(0, y), row);
  vtkNew<vtkPNGWriter> writer;
  writer->WriteToMemoryOn();
  writer->SetInputData(data);
  writer->Write();
  vtkUnsignedCharArray* result = writer->GetResult();
  if (writer->GetErrorCode() != 0 || result == nullptr || result->GetNumberOfValues() <= 0)
    throw std::runtime_error("cannot encode the PNG for '" + path + "'");
  const auto* bytes = result->GetPointer(0);
  return std::vector<unsigned char>(bytes, bytes + result->GetNumberOfValues());
}

}  // namespace

void write_png(const Rgb8Image& image, const std::string& path) {
  const std::vector<unsigned char> bytes = encode_png(image, path);
  TemporaryOutput out(path);
  out.write(bytes.data(), bytes.size());
  out.commit();
}

void write_png(OutputSet& set, const Rgb8Image& image, const std::string& path) {
  const std::vector<unsigned char> bytes = encode_png(image, path);
  TemporaryOutput& out = set.add(path);
  out.write(bytes.data(), bytes.size());
  out.finish();
}

Rgb8Image read_png(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error("no such file: '" + path + "'");
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str())) throw std::runtime_error("'" + path + "' is not a PNG file");
  reader->SetFileName(path.c_str());
  reader->Update();
  return from_vtk_image(reader->GetOutput());
}

struct ViewerWindow::Impl {
  SceneView* scene;
  FrameView* frame;
  WindowOptions options;
  vtkNew<vtkRenderWindow> window;
  vtkSmartPointer<vtkTextActor> scene_caption, frame_caption;
  vtkSmartPointer<vtkRenderWindowInteractor> interactor;
  std::string prefix = "grtrace-view";
  PickHandler pick_handler;
  std::vector<RayPick> picks;

  /// Redraws the picks layer, the pick text (the last kShownPicks lines) and the frame's pick markers.
  void show_picks() {
    constexpr std::size_t kShownPicks = 8;
    std::vector<TracedPath> paths;
    std::vector<std::array<int, 2>> pixels;
    std::string text;
    if (picks.size() > kShownPicks) text = std::to_string(picks.size() - kShownPicks) + " earlier picks\n";
    for (std::size_t i = 0; i < picks.size(); ++i) {
      paths.push_back(picks[i].path);
      pixels.push_back(picks[i].pixel);
      if (i + kShownPicks >= picks.size()) text += describe(picks[i]) + "\n";
    }
    if (!text.empty()) text.pop_back();
    vtkSmartPointer<vtkPolyData> data = paths.empty() ? nullptr : paths_to_polydata(paths);
    // A medium's picks: coloured by the light each collects.
    if (data && std::any_of(picks.begin(), picks.end(), [](const RayPick& p) { return !p.light.empty(); })) {
      std::vector<std::vector<double>> light;
      for (const RayPick& p : picks) light.push_back(p.light);
      add_light_array(data, paths, light);
    }
    scene->set_picks(data.Get(), text);
    if (frame) frame->set_pick_markers(pixels);
  }

  std::array<int, 4> viewport_pixels(vtkRenderer* r) const {
    const int* size = window->GetSize();
    double vp[4];
    r->GetViewport(vp);
    const int x0 = static_cast<int>(vp[0] * size[0] + 0.5), y0 = static_cast<int>(vp[1] * size[1] + 0.5);
    const int x1 = static_cast<int>(vp[2] * size[0] + 0.5), y1 = static_cast<int>(vp[3] * size[1] + 0.5);
    return {x0, y0, x1 - x0, y1 - y0};
  }

  std::string next_screenshot() const {
    for (int i = 1; i < 1000; ++i) {
      char name[64];
      std::snprintf(name, sizeof name, "-%03d.png", i);
      const std::string candidate = prefix + name;
      if (!std::filesystem::exists(candidate)) return candidate;
    }
    return prefix + "-999.png";
  }

  static void on_char(vtkObject* caller, unsigned long, void* client, void*);
};

namespace {

/// Left button on the frame viewport: picks the pixel under the pointer and keeps the event from the trackball
/// style (which would start turning the 3D view). Elsewhere the event goes on to the style.
class FrameClick : public vtkCommand {
 public:
  static FrameClick* New() { return new FrameClick; }
  ViewerWindow* window = nullptr;

  void Execute(vtkObject* caller, unsigned long, void*) override {
    auto* iren = static_cast<vtkRenderWindowInteractor*>(caller);
    const int* at = iren->GetEventPosition();
    if (!window->frame_pixel_at(at[0], at[1])) return;
    SetAbortFlag(1);
    std::string said;
    try {
      said = window->pick_at(at[0], at[1]);
    } catch (const std::exception& e) {
      said = std::string("pick failed: ") + e.what();
    }
    if (!said.empty()) std::cout << said << std::endl;
    window->render();
  }
};

}  // namespace

ViewerWindow::ViewerWindow(SceneView& scene, FrameView* frame, const WindowOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  if (options.width <= 0 || options.height <= 0) throw std::invalid_argument("window size must be positive");
  m.scene = &scene;
  m.frame = frame;
  m.options = options;
  m.window->SetSize(options.width, options.height);
  m.window->SetWindowName(options.title.c_str());
  m.window->SetMultiSamples(0);  // exact pixels (the frame must show its colours unchanged)
  if (options.offscreen) m.window->SetOffScreenRendering(1);
  prepare_window(m.window);
  const double split = frame ? options.split : 1.0;
  scene.renderer()->SetViewport(0.0, 0.0, split, 1.0);
  m.window->AddRenderer(scene.renderer());
  const int font = std::max(11, std::min(options.height / 45, static_cast<int>(options.width * split) / 50));
  if (!options.scene_caption.empty()) {
    m.scene_caption = caption(options.scene_caption, font);
    scene.renderer()->AddViewProp(m.scene_caption);
  }
  if (frame) {
    frame->renderer()->SetViewport(split, 0.0, 1.0, 1.0);
    m.window->AddRenderer(frame->renderer());
    if (!options.frame_caption.empty()) {
      m.frame_caption = caption(options.frame_caption, font);
      frame->renderer()->AddViewProp(m.frame_caption);
    }
  }
}

ViewerWindow::~ViewerWindow() {
  Impl& m = *impl_;
  if (m.scene_caption) m.scene->renderer()->RemoveViewProp(m.scene_caption);
  if (m.frame && m.frame_caption) m.frame->renderer()->RemoveViewProp(m.frame_caption);
  m.window->RemoveRenderer(m.scene->renderer());
  if (m.frame) m.window->RemoveRenderer(m.frame->renderer());
  m.window->Finalize();
}

vtkRenderWindow* ViewerWindow::window() const { return impl_->window; }

void ViewerWindow::render() {
  impl_->scene->renderer()->ResetCameraClippingRange();
  impl_->window->Render();
}

Rgb8Image capture_window(vtkRenderWindow* window) {
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  return from_vtk_image(grab->GetOutput());
}

void save_window_png(vtkRenderWindow* window, const std::string& path) { write_png(capture_window(window), path); }

void save_window_png(OutputSet& set, vtkRenderWindow* window, const std::string& path) {
  write_png(set, capture_window(window), path);
}

Rgb8Image ViewerWindow::capture() {
  render();
  return capture_window(impl_->window);
}

void ViewerWindow::save_png(const std::string& path) { write_png(capture(), path); }

std::array<int, 4> ViewerWindow::frame_viewport_pixels() const {
  if (!impl_->frame) return {0, 0, 0, 0};
  return impl_->viewport_pixels(impl_->frame->renderer());
}

std::array<int, 4> ViewerWindow::scene_viewport_pixels() const {
  return impl_->viewport_pixels(impl_->scene->renderer());
}

std::string ViewerWindow::key_help() {
  return "keys: 1 horizon, 2 photon sphere, 3 ISCO, 4 disk, 5 sky, 6 camera, 7 rays, 8 orbit, 9 colour bar, "
         "0 ergosphere, g glowing medium, m frame markers, c ray colouring, x clear picks, r reset view, s screenshot, "
         "h help, q quit; "
         "left click on the frame: pick that pixel's ray";
}

std::string ViewerWindow::handle_key(const std::string& key) {
  Impl& m = *impl_;
  auto toggle = [&](Layer l) -> std::string {
    if (!m.scene->has(l)) return std::string("no ") + std::string(to_string(l)) + " layer";
    m.scene->toggle(l);
    return std::string(to_string(l)) + (m.scene->visible(l) ? " on" : " off");
  };
  if (key == "Escape" || key == "q") return "quit";
  if (key.size() != 1) return "";
  switch (key[0]) {
    case '1': return toggle(Layer::horizon);
    case '2': return toggle(Layer::photon_sphere);
    case '3': return toggle(Layer::isco);
    case '4': return toggle(Layer::disk);
    case '5': return toggle(Layer::sky);
    case '6': return toggle(Layer::camera);
    case '7': return toggle(Layer::rays);
    case '8': return toggle(Layer::orbit);
    case '9': return toggle(Layer::colorbar);
    case '0': return toggle(Layer::ergosphere);
    case 'g':
      return toggle(Layer::medium);
    case 'm':
      if (!m.frame) return "no frame";
      m.frame->set_markers_visible(!m.frame->markers_visible());
      return m.frame->markers_visible() ? "markers on" : "markers off";
    case 'c': return "rays coloured by " + std::string(to_string(m.scene->cycle_ray_coloring()));
    case 'x': return clear_picks();
    case 'r': m.scene->set_view(m.scene->default_view()); return "view reset";
    case 's': {
      const std::string file = m.next_screenshot();
      save_png(file);
      return "saved " + file;
    }
    case 'h': return key_help();
    default: return "";
  }
}

void ViewerWindow::Impl::on_char(vtkObject* caller, unsigned long, void* client, void*) {
  auto* self = static_cast<ViewerWindow*>(client);
  auto* iren = static_cast<vtkRenderWindowInteractor*>(caller);
  const std::string sym = iren->GetKeySym() ? iren->GetKeySym() : "";
  const char code = iren->GetKeyCode();
  const std::string key = sym == "Escape" ? sym : std::string(1, code);
  std::string said;
  try {
    said = self->handle_key(key);
  } catch (const std::exception& e) {
    said = std::string("failed: ") + e.what();
  }
  if (said == "quit") {
    iren->TerminateApp();
    return;
  }
  if (!said.empty()) std::cout << said << std::endl;
  self->render();
}

void ViewerWindow::set_screenshot_prefix(const std::string& prefix) {
  impl_->prefix = prefix.empty() ? "grtrace-view" : prefix;
}

vtkRenderWindowInteractor* ViewerWindow::interactor() {
  Impl& m = *impl_;
  if (!m.interactor) {
    m.interactor = vtkSmartPointer<vtkRenderWindowInteractor>::New();
    m.interactor->SetRenderWindow(m.window);
    vtkNew<vtkInteractorStyleTrackballCamera> style;
    m.interactor->SetInteractorStyle(style);
    vtkNew<vtkCallbackCommand> keys;
    keys->SetCallback(&Impl::on_char);
    keys->SetClientData(this);
    keys->SetAbortFlagOnExecute(1);  // the style's own key bindings (w, s, e, 3, f, p ...) never see our keys
    m.interactor->AddObserver(vtkCommand::CharEvent, keys, 10.0f);
    vtkNew<FrameClick> click;
    click->window = this;
    m.interactor->AddObserver(vtkCommand::LeftButtonPressEvent, click, 10.0f);
  }
  return m.interactor;
}

void ViewerWindow::set_pick_handler(PickHandler handler) { impl_->pick_handler = std::move(handler); }

std::optional<std::array<int, 2>> ViewerWindow::frame_pixel_at(int display_x, int display_y) {
  Impl& m = *impl_;
  if (!m.frame || m.frame->frame().empty()) return std::nullopt;
  const auto [x0, y0, w, h] = frame_viewport_pixels();
  if (display_x < x0 || display_y < y0 || display_x >= x0 + w || display_y >= y0 + h) return std::nullopt;
  m.frame->fit(w, h);
  // The centre of the display pixel, in the viewport's continuous coordinates.
  return m.frame->placement().pixel_at(display_x - x0 + 0.5, display_y - y0 + 0.5);
}

std::string ViewerWindow::pick_at(int display_x, int display_y) {
  const auto pixel = frame_pixel_at(display_x, display_y);
  return pixel ? pick_pixel(*pixel) : std::string();
}

std::string ViewerWindow::pick_pixel(std::array<int, 2> pixel) {
  Impl& m = *impl_;
  if (!m.pick_handler) throw std::logic_error("no pick handler: nothing to trace a picked pixel with");
  const Rgb8Image* shown = m.frame ? &m.frame->frame() : nullptr;
  if (shown && (pixel[0] < 0 || pixel[1] < 0 || pixel[0] >= shown->width || pixel[1] >= shown->height))
    throw std::out_of_range("pixel (" + std::to_string(pixel[0]) + ", " + std::to_string(pixel[1]) +
                            ") is outside the frame");
  return add_pick(m.pick_handler(pixel));
}

std::string ViewerWindow::add_pick(RayPick pick) {
  Impl& m = *impl_;
  m.picks.push_back(std::move(pick));
  m.show_picks();
  return describe(m.picks.back());
}

std::string ViewerWindow::clear_picks() {
  Impl& m = *impl_;
  const std::size_t n = m.picks.size();
  m.picks.clear();
  m.show_picks();
  return "picks cleared (" + std::to_string(n) + ")";
}

const std::vector<RayPick>& ViewerWindow::picks() const { return impl_->picks; }

void ViewerWindow::interact(const std::string& screenshot_prefix) {
  set_screenshot_prefix(screenshot_prefix);
  vtkRenderWindowInteractor* iren = interactor();
  iren->Initialize();
  render();
  iren->Start();
}

}  // namespace grtrace::viz
