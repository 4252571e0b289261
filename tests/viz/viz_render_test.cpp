// grtrace::viz rendering: screenshot sizes, the frame viewport shows the frame's preview colours exactly, the
// horizon silhouette where a sphere of radius 2M projects, charts. Needs an X display: skipped without DISPLAY
// (the project's test command runs everything under xvfb-run, so they run there).
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/png_preview.hpp"
#include "grtrace/viz/charts.hpp"
#include "grtrace/viz/frame_from_image.hpp"
#include "grtrace/viz/frame_view.hpp"
#include "grtrace/viz/geodesic_data.hpp"
#include "grtrace/viz/scene_view.hpp"
#include "grtrace/viz/viewer_window.hpp"

#include <gtest/gtest.h>

#include <vtkCommand.h>
#include <vtkContextView.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <unistd.h>

namespace {

using namespace grtrace;
using namespace grtrace::viz;

#define REQUIRE_DISPLAY()                                                          \
  do {                                                                             \
    if (!display_available()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";   \
  } while (0)

std::filesystem::path scratch_dir() {
  auto dir = std::filesystem::temp_directory_path() / ("grtrace-viz-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

/// Window pixel (x from the left, y from the bottom) in a capture whose row 0 is the top.
Rgb8 at_window(const Rgb8Image& shot, int x, int y_from_bottom) { return shot.at(x, shot.height - 1 - y_from_bottom); }

TEST(VizRender, ScreenshotHasTheRequestedSize) {
  REQUIRE_DISPLAY();
  SceneLayout layout;
  layout.disk = std::array<double, 2>{6.0, 15.0};
  layout.sky_radius = 40.0;
  SceneView scene(layout);
  FrameView frame;
  frame.set_frame(Rgb8Image(32, 18, {200, 100, 50}));
  for (auto [w, h] : {std::array<int, 2>{320, 200}, std::array<int, 2>{417, 233}}) {
    WindowOptions opt;
    opt.width = w;
    opt.height = h;
    opt.offscreen = true;
    opt.scene_caption = "scene";
    ViewerWindow window(scene, &frame, opt);
    const auto file = scratch_dir() / ("shot-" + std::to_string(w) + ".png");
    window.save_png(file.string());
    const Rgb8Image back = read_png(file.string());
    EXPECT_EQ(back.width, w);
    EXPECT_EQ(back.height, h);
    // Written with libpng's reader too (the renderer's), same size.
    const PngRgb8 png = read_png_rgb8(file);
    EXPECT_EQ(png.width, w);
    EXPECT_EQ(png.height, h);
  }
  std::filesystem::remove_all(scratch_dir());
}

TEST(VizRender, FrameViewportShowsThePreviewColours) {
  REQUIRE_DISPLAY();
  // A frame with distinct colours everywhere, written as grtrace-render writes it: EXR + PNG preview.
  const int W = 64, H = 40;
  Image image(W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      PixelSample s;
      s.rgb = {static_cast<float>(x) / W, static_cast<float>(y) / H, ((x / 4 + y / 4) % 2) ? 0.8f : 0.05f};
      s.status = RayStatus::escaped;
      image.set(x, y, s);
    }
  const auto dir = scratch_dir();
  write_exr(dir / "frame.exr", image);
  write_png_preview(dir / "frame.png", image);
  const PngRgb8 preview = read_png_rgb8(dir / "frame.png");
  const Rgb8Image shown = frame_from_exr((dir / "frame.exr").string());
  ASSERT_EQ(shown.rgb, preview.rgb);  // the conversion is the renderer's preview

  SceneView scene(SceneLayout{});
  FrameView frame;
  frame.set_frame(shown);
  const std::array<std::array<int, 2>, 1> marked = {{{3, 3}}};
  frame.set_markers(marked);
  WindowOptions opt;
  opt.width = 700;
  opt.height = 360;
  opt.offscreen = true;
  ViewerWindow window(scene, &frame, opt);
  const Rgb8Image shot = window.capture();
  const auto vp = window.frame_viewport_pixels();
  EXPECT_EQ(vp[0], 350);
  EXPECT_NEAR(frame.scale(), std::min(350.0 / W, 360.0 / H), 1e-12);
  int checked = 0;
  for (int y = 8; y < H; y += 3)
    for (int x = 8; x < W; x += 5) {  // away from the marker at (3, 3)
      const auto p = frame.frame_to_viewport(x, y);
      const int wx = vp[0] + static_cast<int>(std::floor(p[0])), wy = vp[1] + static_cast<int>(std::floor(p[1]));
      const auto o = static_cast<std::size_t>(3 * (y * W + x));
      const Rgb8 want = {preview.rgb[o], preview.rgb[o + 1], preview.rgb[o + 2]};
      EXPECT_EQ(at_window(shot, wx, wy), want) << "frame pixel " << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 100);
  // The marker is drawn around pixel (3, 3): a white outline (over a black one) 1.5 frame pixels from its centre.
  const auto m = frame.frame_to_viewport(3.0, 3.0);
  const double edge_x = m[0] - 1.5 * frame.scale();
  bool white = false, black = false;
  for (int dx = -3; dx <= 3; ++dx) {
    const Rgb8 c = at_window(shot, vp[0] + static_cast<int>(edge_x) + dx, vp[1] + static_cast<int>(m[1]));
    white = white || (c[0] > 240 && c[1] > 240 && c[2] > 240);
    black = black || (c[0] < 15 && c[1] < 15 && c[2] < 15);
  }
  EXPECT_TRUE(white);
  EXPECT_TRUE(black);
  std::filesystem::remove_all(dir);
}

TEST(VizRender, HorizonSilhouetteWhereTheSphereProjects) {
  REQUIRE_DISPLAY();
  const double M = 1.5;  // horizon radius 3
  SceneLayout layout;
  layout.mass = M;
  SceneView scene(layout);
  for (Layer l : kAllLayers) scene.set_visible(l, l == Layer::horizon);
  const double D = 20.0, view_angle = 30.0;
  ViewPose pose;
  pose.from = D * Vec3(0.3, -0.8, 0.52).normalized();
  pose.at = Vec3::Zero();
  pose.up = Vec3::UnitZ();
  pose.view_angle_degrees = view_angle;
  scene.set_view(pose);
  WindowOptions opt;
  opt.width = 480;
  opt.height = 360;
  opt.offscreen = true;
  ViewerWindow window(scene, nullptr, opt);  // the scene fills the window
  const Rgb8Image shot = window.capture();
  const auto vp = window.scene_viewport_pixels();
  ASSERT_EQ(vp[2], 480);
  ASSERT_EQ(vp[3], 360);
  const double R = 2.0 * M;
  const double rho = 0.5 * vp[3] * (R / std::sqrt(D * D - R * R)) / std::tan(view_angle * std::numbers::pi / 360.0);
  const double cx = vp[0] + 0.5 * vp[2], cy = vp[1] + 0.5 * vp[3];
  auto pixel_at = [&](double radius, double angle) {
    const int x = static_cast<int>(std::floor(cx + radius * std::cos(angle)));
    const int y = static_cast<int>(std::floor(cy + radius * std::sin(angle)));
    return at_window(shot, x, y);
  };
  EXPECT_NE(pixel_at(0.0, 0.0), SceneView::kBackground);
  for (int i = 0; i < 12; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 12.0 + 0.1;
    EXPECT_NE(pixel_at(rho - 3.0, a), SceneView::kBackground) << "inside, direction " << i << " (rho " << rho << ")";
    EXPECT_EQ(pixel_at(rho + 3.0, a), SceneView::kBackground) << "outside, direction " << i << " (rho " << rho << ")";
  }
  // The silhouette is sharp: walking outward along +x, the first background pixel is within a pixel of rho.
  int first = 0;
  while (first < vp[2] / 2 && at_window(shot, static_cast<int>(cx) + first, static_cast<int>(cy)) != SceneView::kBackground)
    ++first;
  EXPECT_NEAR(first, rho, 1.5);
}

TEST(VizRender, ChartsHaveTheRequestedSizeAndALine) {
  REQUIRE_DISPLAY();
  ChartSpec spec;
  spec.title = "test";
  spec.x_title = "x";
  spec.y_title = "y";
  ChartSeries s{"sin", {}, {}, {200, 0, 0}, 3.0f, false};
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(i * 0.1);
    s.y.push_back(std::sin(i * 0.1));
  }
  spec.series.push_back(s);
  const Rgb8Image img = render_chart(spec, 400, 300);
  EXPECT_EQ(img.width, 400);
  EXPECT_EQ(img.height, 300);
  int red = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Rgb8 c = img.at(x, y);
      red += c[0] > 150 && c[1] < 80 && c[2] < 80;
    }
  EXPECT_GT(red, 200);
}

TEST(VizRender, RaysAndOrbitLayersDraw) {
  REQUIRE_DISPLAY();
  // A few straight "paths" coloured by pixel colour draw those colours; hiding the layer removes them.
  std::vector<TracedPath> paths(3);
  for (int p = 0; p < 3; ++p) {
    for (int i = 0; i <= 20; ++i) {
      PathSample s;
      s.position = Vec3(-10.0 + i, -2.0 + 2.0 * p, 0.0);
      s.lambda = i;
      s.h = 1.0;
      s.step = i;
      paths[static_cast<std::size_t>(p)].samples.push_back(s);
    }
    paths[static_cast<std::size_t>(p)].color = Rgb8{0, 255, 0};
  }
  SceneView scene(SceneLayout{});
  for (Layer l : kAllLayers) scene.set_visible(l, false);
  scene.set_rays(paths_to_polydata(paths), ScalarField::pixel_color);
  scene.set_visible(Layer::rays, true);
  ViewPose pose;
  pose.from = Vec3(0, 0, 40);
  pose.up = Vec3::UnitY();
  scene.set_view(pose);
  WindowOptions opt;
  opt.width = 300;
  opt.height = 300;
  opt.offscreen = true;
  ViewerWindow window(scene, nullptr, opt);
  auto count_green = [](const Rgb8Image& img) {
    int n = 0;
    for (std::size_t i = 0; i < img.rgb.size(); i += 3) n += img.rgb[i + 1] == 255 && img.rgb[i] == 0;
    return n;
  };
  EXPECT_GT(count_green(window.capture()), 100);
  scene.set_color_by(Layer::rays, ScalarField::lambda);
  EXPECT_LT(count_green(window.capture()), 10);
  scene.set_visible(Layer::rays, false);
  EXPECT_EQ(count_green(window.capture()), 0);
  EXPECT_THROW(scene.set_color_by(Layer::rays, ScalarField::redshift), std::invalid_argument);
}

TEST(VizRender, KeysToggleLayersAndSaveScreenshots) {
  REQUIRE_DISPLAY();
  SceneLayout layout;
  layout.disk = std::array<double, 2>{6.0, 12.0};
  SceneView scene(layout);
  FrameView frame;
  frame.set_frame(Rgb8Image(16, 9, {90, 90, 90}));
  WindowOptions opt;
  opt.width = 320;
  opt.height = 160;
  opt.offscreen = true;
  ViewerWindow window(scene, &frame, opt);
  EXPECT_TRUE(scene.visible(Layer::horizon));
  EXPECT_EQ(window.handle_key("1"), "horizon off");
  EXPECT_FALSE(scene.visible(Layer::horizon));
  EXPECT_EQ(window.handle_key("1"), "horizon on");
  EXPECT_EQ(window.handle_key("4"), "disk off");
  EXPECT_EQ(window.handle_key("5"), "no sky layer");  // no sky radius given
  EXPECT_EQ(window.handle_key("m"), "markers off");
  EXPECT_EQ(window.handle_key("q"), "quit");
  EXPECT_EQ(window.handle_key("Escape"), "quit");
  EXPECT_EQ(window.handle_key("z"), "");  // unbound
  EXPECT_EQ(window.handle_key("x"), "picks cleared (0)");
  const auto prefix = scratch_dir() / "shot";
  window.set_screenshot_prefix(prefix.string());
  EXPECT_EQ(window.handle_key("s"), "saved " + prefix.string() + "-001.png");
  EXPECT_EQ(window.handle_key("s"), "saved " + prefix.string() + "-002.png");
  const Rgb8Image back = read_png(prefix.string() + "-002.png");
  EXPECT_EQ(back.width, 320);
  EXPECT_EQ(back.height, 160);
  // The same through the interactor, as a key press arrives in interact(): '2' toggles the photon sphere and
  // 's' saves (the trackball style's own 's' = surface mode never sees it).
  vtkRenderWindowInteractor* iren = window.interactor();
  auto press = [&](char c) {
    const char sym[2] = {c, 0};
    iren->SetKeyEventInformation(0, 0, c, 1, sym);
    iren->InvokeEvent(vtkCommand::CharEvent, nullptr);
  };
  press('2');
  EXPECT_FALSE(scene.visible(Layer::photon_sphere));
  press('s');
  EXPECT_TRUE(std::filesystem::exists(prefix.string() + "-003.png"));
  std::filesystem::remove_all(scratch_dir());
}

}  // namespace

namespace {

// The flaky chart segfault (viz_tool_test ChartsAreWritten, ~1 run in 100): vtkContextView gives its window an
// interactor; the first Render() initialised it, and VTK 9.1's vtkXRenderWindowInteractor::Initialize opened an X
// connection of its own without checking it: a busy Xvfb refusing that connection meant a null Display and a
// segfault in XSync. prepare_window gives every window the process's one connection and drops the interactor of
// offscreen windows, so no window opens a connection of its own.
TEST(VizRender, WindowsDrawThroughTheSharedDisplay) {
  REQUIRE_DISPLAY();
  ASSERT_NE(x_display(), nullptr);
  EXPECT_EQ(x_display(), x_display());  // one connection per process
  vtkNew<vtkContextView> view;
  vtkRenderWindow* offscreen = view->GetRenderWindow();
  ASSERT_NE(offscreen->GetInteractor(), nullptr);  // what vtkContextView gives it
  offscreen->SetOffScreenRendering(1);
  prepare_window(offscreen);
  EXPECT_EQ(offscreen->GetInteractor(), nullptr);
  EXPECT_EQ(offscreen->GetGenericDisplayId(), x_display());
  offscreen->SetSize(120, 100);
  offscreen->Render();
  EXPECT_EQ(offscreen->GetGenericDisplayId(), x_display());  // rendering kept it (did not open its own)
  offscreen->Finalize();

  // The viewer's window, on screen with an interactor: the interactor uses the window's connection too.
  SceneView scene(SceneLayout{});
  WindowOptions opt;
  opt.width = 160;
  opt.height = 120;
  ViewerWindow window(scene, nullptr, opt);
  EXPECT_EQ(window.window()->GetGenericDisplayId(), x_display());
  vtkRenderWindowInteractor* iren = window.interactor();
  iren->Initialize();
  EXPECT_EQ(window.window()->GetGenericDisplayId(), x_display());
}

}  // namespace
