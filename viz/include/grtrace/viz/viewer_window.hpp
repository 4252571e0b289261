// grtrace/viz/viewer_window.hpp
// The grtrace-view window: the 3D scene on the left, the frame on the right (or the scene alone), captions,
// offscreen capture to PNG, and the interactive loop with key bindings.
//
// Keys (interactive): 1 horizon, 2 photon sphere, 3 ISCO, 4 disk, 5 sky, 6 camera, 7 rays, 8 orbit, 9 colour bar,
// 0 ergosphere, m frame markers, c cycle the ray colouring, x clear the picks, r reset the 3D view, s save a
// screenshot (<prefix>-NNN.png in the working directory), h print the key list, q / Escape quit.
// Mouse: trackball camera in the 3D view (left rotate, middle pan, right / wheel zoom); a left click on the frame
// picks that pixel: its ray is traced (the pick handler, pick.hpp) and drawn in the 3D view, its outcome listed.
//
// Rendering needs an X display (Debian's VTK has no EGL/OSMesa): run headless under
//   xvfb-run -a -s "-screen 0 1280x1024x24" ...
#pragma once

#include "grtrace/viz/frame_image.hpp"
#include "grtrace/viz/pick.hpp"

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

class vtkRenderWindow;
class vtkRenderWindowInteractor;

namespace grtrace {
class OutputSet;
}

namespace grtrace::viz {

class SceneView;
class FrameView;

/// Takes nothing; returns the process's one X connection (an Xlib Display*), opened on first use and kept until
/// exit, or null when no X server answers at DISPLAY. A server that is only busy (Xvfb under load refuses or drops
/// some connections for a moment) is asked again for up to about two seconds. Every window the viz library makes
/// draws through this connection (prepare_window): VTK 9.1 opens one of its own per window and per interactor and
/// does not check it (a refused XOpenDisplay in vtkXRenderWindowInteractor::Initialize is a null Display and a
/// segfault in XSync), and one connection per process is also one chance of refusal instead of several.
void* x_display();

/// True when an X server answers at DISPLAY (x_display() is not null). Without one, VTK here (Debian: X only, no
/// EGL/OSMesa) crashes on the first render, offscreen or not.
bool display_available();

/// Takes a render window before its first render (offscreen rendering already set or not); gives it the process's
/// X connection (x_display()) and, when it renders offscreen, removes its interactor (vtkContextView makes one, and
/// the first Render() would initialise it: an offscreen picture takes no input). Every tool that makes a VTK window
/// calls this. Assumes the window is an X window (Debian's VTK) or ignores SetDisplayId.
void prepare_window(vtkRenderWindow* window);

/// Thrown by require_display(); tools report it as bad input (exit 2).
struct NoDisplayError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The one display check of every tool that draws (charts, screenshots, the window): call it before any work.
/// Throws NoDisplayError with a message that says to run under xvfb-run (`program` is the tool's name) and,
/// if `alternative` is not empty, "or <alternative>" (e.g. "pass --no-png").
void require_display(const std::string& program, const std::string& alternative = "");

struct WindowOptions {
  int width = 1600, height = 800;
  bool offscreen = false;
  double split = 0.5;              ///< fraction of the width given to the 3D view when a frame is shown
  std::string scene_caption;       ///< top-left text of the 3D view ("" = none)
  std::string frame_caption;       ///< top-left text of the frame view
  std::string title = "grtrace-view";
};

class ViewerWindow {
 public:
  /// `frame` may be null: the scene then fills the window. Both views must outlive the window.
  ViewerWindow(SceneView& scene, FrameView* frame, const WindowOptions& options);
  ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  vtkRenderWindow* window() const;
  void render();
  /// The window's pixels (RGB, row 0 at the top), after a render.
  Rgb8Image capture();
  /// Renders and writes the window to a PNG, whole or not at all (temporary file, then rename).
  void save_png(const std::string& path);
  /// Pixel origin (x, y from the bottom) and size of the frame viewport in window pixels.
  std::array<int, 4> frame_viewport_pixels() const;
  std::array<int, 4> scene_viewport_pixels() const;
  /// Opens the window and runs the event loop until the user quits. Screenshots go to <prefix>-NNN.png.
  void interact(const std::string& screenshot_prefix = "grtrace-view");
  /// The window's interactor with the trackball style and the key bindings (created on first use; interact()
  /// starts its event loop). Key presses sent to it (CharEvent) go through handle_key().
  vtkRenderWindowInteractor* interactor();
  /// Screenshots taken with the 's' key go to <prefix>-NNN.png (the first free NNN).
  void set_screenshot_prefix(const std::string& prefix);
  /// What a key press does in interact() (key: the character, or a key symbol such as "Escape"). Returns a line
  /// describing the effect ("horizon off", "saved grtrace-view-001.png", ...); "quit" for q / Escape; "" if unbound.
  std::string handle_key(const std::string& key);
  /// The key list printed by 'h'.
  static std::string key_help();

  /// Traces a frame pixel (column, row from the top) for a pick: the tool binds its tracer here (pick_ray).
  using PickHandler = std::function<RayPick(std::array<int, 2>)>;
  void set_pick_handler(PickHandler handler);
  /// Takes a display position (window pixel, x from the left, y from the bottom, as VTK reports mouse events);
  /// returns the frame pixel under it, or nothing outside the frame (another viewport, the letterbox margin, no
  /// frame). Fits the frame to the window's current size first, so it holds before the first render too.
  std::optional<std::array<int, 2>> frame_pixel_at(int display_x, int display_y);
  /// What a left click at a display position does: picks the frame pixel under it (pick_pixel) and returns the
  /// pick's line (describe); "" outside the frame. Throws std::logic_error without a pick handler.
  std::string pick_at(int display_x, int display_y);
  /// Traces the pixel with the pick handler and adds the pick. Throws std::logic_error without a handler and
  /// std::out_of_range for a pixel outside the frame.
  std::string pick_pixel(std::array<int, 2> pixel);
  /// Adds a pick traced elsewhere (e.g. before an export): its path joins the picks layer, its pixel is marked on
  /// the frame, its line is listed. Returns the line.
  std::string add_pick(RayPick pick);
  /// Removes every pick (the 'x' key). Returns what it did ("picks cleared (N)").
  std::string clear_picks();
  const std::vector<RayPick>& picks() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Writes an RGB8 image as PNG, whole or not at all (grtrace/render/output_file.hpp: an exclusively created
/// temporary, then rename). Throws std::runtime_error on failure.
void write_png(const Rgb8Image& image, const std::string& path);
/// The same as part of a set of outputs, renamed into place by set.commit().
void write_png(OutputSet& set, const Rgb8Image& image, const std::string& path);
/// What a rendered window shows (RGB: an RGBA grab would make the background transparent), row 0 at the top.
/// Assumes the window has been rendered (offscreen or on screen).
Rgb8Image capture_window(vtkRenderWindow* window);
/// capture_window + write_png: every tool's "--screenshot" / chart PNG goes through here.
void save_window_png(vtkRenderWindow* window, const std::string& path);
void save_window_png(OutputSet& set, vtkRenderWindow* window, const std::string& path);
/// Reads an 8-bit PNG (RGB or RGBA; alpha dropped). Throws std::runtime_error on failure.
Rgb8Image read_png(const std::string& path);

}  // namespace grtrace::viz
