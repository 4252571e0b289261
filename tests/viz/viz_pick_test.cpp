// Picking (grtrace/viz/pick.hpp, ViewerWindow's picks): a viewport position maps to the frame pixel under it; a
// picked pixel's drawn ray is the tracer's path for that pixel and its outcome the scene tracer's. The library
// cases need no display; the window cases skip without one (run under xvfb-run).
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/viz/frame_view.hpp"
#include "grtrace/viz/pick.hpp"
#include "grtrace/viz/scene_view.hpp"
#include "grtrace/viz/traced_path.hpp"
#include "grtrace/viz/viewer_window.hpp"

#include <gtest/gtest.h>

#include <vtkCommand.h>
#include <vtkPolyData.h>
#include <vtkRenderWindowInteractor.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <map>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace grtrace;
using namespace grtrace::viz;

TEST(VizPick, ViewportPositionsMapToTheFramePixelUnderThem) {
  // A 40 x 30 frame in a 200 x 200 viewport: scale 5, the frame spans x in [0, 200) and y in [25, 175) (centred).
  const FrameFit fit{40, 30, 200, 200};
  ASSERT_DOUBLE_EQ(fit.scale(), 5.0);
  const double left = 0.0, bottom = 25.0, side = 5.0;
  for (int row = 0; row < 30; ++row)
    for (int column = 0; column < 40; ++column) {
      // Every point of the pixel's square (row 0 at the top) maps to that pixel.
      const double x0 = left + column * side, y0 = bottom + (29 - row) * side;
      for (auto [dx, dy] : {std::array<double, 2>{0.01, 0.01}, {2.5, 2.5}, {4.99, 4.99}, {0.01, 4.99}}) {
        const auto p = fit.pixel_at(x0 + dx, y0 + dy);
        ASSERT_TRUE(p.has_value()) << column << "," << row;
        EXPECT_EQ((*p)[0], column);
        EXPECT_EQ((*p)[1], row);
      }
      // and the pixel's centre is where to_viewport puts it.
      const auto centre = fit.to_viewport(column, row);
      EXPECT_DOUBLE_EQ(centre[0], x0 + 2.5);
      EXPECT_DOUBLE_EQ(centre[1], y0 + 2.5);
    }
  // The letterbox margins and outside the viewport: no pixel.
  for (auto [x, y] : {std::array<double, 2>{100.0, 24.9}, {100.0, 175.1}, {-0.1, 100.0}, {200.1, 100.0}, {NAN, 50.0}})
    EXPECT_FALSE(fit.pixel_at(x, y).has_value()) << x << "," << y;
  // An empty frame has no pixels.
  EXPECT_FALSE((FrameFit{0, 0, 200, 200}.pixel_at(100.0, 100.0).has_value()));
}

/// A camera at r = 30 M a little above a thin disk (6 .. 20 M), looking at the hole.
Camera disk_camera(int width, int height) {
  CameraSpec spec;
  spec.position = Vec4(0.0, 30.0, 80.0 * std::numbers::pi / 180.0, 0.0);
  spec.width = width;
  spec.height = height;
  spec.fov_degrees = 50.0;
  return make_camera(SchwarzschildMetric{1.0}, spec);
}

auto disk_tracer() {
  TraceSettings s;
  s.integrator.tolerance = {1e-9, 1e-11};
  s.escape_radius = 200.0;
  StandardSceneSpec spec;
  spec.name = "disk";
  return make_general_tracer<DormandPrince54, PIController>(SchwarzschildMetric{1.0}, s, AngleCorrection::exact,
                                                            disk_scene(spec));
}

TEST(VizPick, PickedRayIsTheTracersPathAndOutcome) {
  const int W = 48, H = 36;
  const Camera camera = disk_camera(W, H);
  const auto tracer = disk_tracer();
  const auto pixel_state = [&](int x, int y) { return camera.pixel_state(x, y); };
  const std::vector<std::string> names = tracer.scene().object_names();
  // Down the middle column the rays see the sky, the disk and the horizon: pick one of each status found.
  std::map<RayStatus, int> seen;
  for (int row = 0; row < H; row += 2) {
    const std::array<int, 2> pixel{W / 2, row};
    const RayPick pick = pick_ray(tracer, pixel_state, pixel, 5, camera.tetrad().e[0]);
    if (seen[pick.outcome.status]++ > 0) continue;
    SCOPED_TRACE("row " + std::to_string(row) + ": " + describe(pick));
    // The drawn path: the tracer's own path for that pixel, point for point.
    const TracedPath reference = std::apply(
        [&](const auto&... objects) {
          return trace_path(tracer.tracer(), camera.pixel_state(pixel[0], pixel[1]), 5, camera.tetrad().e[0],
                            objects...);
        },
        tracer.scene().objects);
    ASSERT_EQ(pick.path.samples.size(), reference.samples.size());
    for (std::size_t i = 0; i < reference.samples.size(); ++i) {
      EXPECT_LT((pick.path.samples[i].position - reference.samples[i].position).norm(), 1e-12) << i;
      EXPECT_EQ(pick.path.samples[i].step, reference.samples[i].step);
    }
    EXPECT_EQ(pick.path.status, reference.status);
    EXPECT_EQ(pick.path.pixel_x, pixel[0]);
    EXPECT_EQ(pick.path.pixel_y, pixel[1]);
    // The outcome: the scene tracer's for that pixel, and the same integration as the path.
    const RayOutcome expected = tracer.trace(camera.pixel_state(pixel[0], pixel[1]));
    EXPECT_EQ(pick.outcome.status, expected.status);
    EXPECT_EQ(pick.outcome.object, expected.object);
    EXPECT_EQ(pick.outcome.steps, expected.steps);
    EXPECT_EQ(pick.outcome.radius, expected.radius);
    EXPECT_EQ(pick.outcome.redshift, expected.redshift);
    EXPECT_EQ(pick.outcome.status, pick.path.status);
    EXPECT_EQ(static_cast<std::size_t>(pick.outcome.steps) + 1, pick.path.steps.size());
    EXPECT_EQ(pick.object_name, names.at(static_cast<std::size_t>(expected.object)));
    // The line names all of it.
    const std::string line = describe(pick);
    for (const std::string& part : {"pixel (" + std::to_string(pixel[0]) + ", " + std::to_string(pixel[1]) + ")",
                                    std::string(to_string(expected.status)), pick.object_name,
                                    std::to_string(expected.steps) + " steps"})
      EXPECT_NE(line.find(part), std::string::npos) << part;
    if (std::isfinite(expected.redshift)) {
      char z[32];
      std::snprintf(z, sizeof z, "redshift %.6g", expected.redshift);
      EXPECT_NE(line.find(z), std::string::npos) << z;
    }
  }
  EXPECT_EQ(seen.count(RayStatus::escaped) + seen.count(RayStatus::hit) + seen.count(RayStatus::captured), 3u)
      << "the middle column should see sky, disk and horizon";
}

TEST(VizPick, FailedRaysNameNoObject) {
  RayPick pick;
  pick.pixel = {3, 4};
  pick.outcome.status = RayStatus::max_steps;
  pick.outcome.steps = 17;
  const std::string line = describe(pick);
  EXPECT_NE(line.find("pixel (3, 4): max_steps, 17 steps"), std::string::npos) << line;
  EXPECT_EQ(line.find("redshift"), std::string::npos) << line;
}

// ---- the window: a click on the frame picks, 'x' clears ----------------------------------------------------

TEST(VizPickWindow, ClickOnTheFrameDrawsThePixelsRayAndXClears) {
  if (!display_available()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  const int W = 48, H = 36;
  const Camera camera = disk_camera(W, H);
  const auto tracer = disk_tracer();
  const auto pixel_state = [&](int x, int y) { return camera.pixel_state(x, y); };
  SceneView scene(SceneLayout{});
  FrameView frame;
  frame.set_frame(Rgb8Image(W, H, {90, 90, 90}));
  WindowOptions opt;
  opt.width = 400;
  opt.height = 200;
  opt.offscreen = true;
  ViewerWindow window(scene, &frame, opt);
  int traced = 0;
  window.set_pick_handler([&](std::array<int, 2> pixel) {
    ++traced;
    return pick_ray(tracer, pixel_state, pixel, 4, camera.tetrad().e[0], &frame.frame());
  });

  // Where pixel (30, 11) shows: the frame viewport is the right half; its fit puts the pixel's centre there.
  const std::array<int, 2> pixel{30, 11};
  const auto [x0, y0, vw, vh] = window.frame_viewport_pixels();
  const FrameFit fit{W, H, vw, vh};
  const auto centre = fit.to_viewport(pixel[0], pixel[1]);
  const int click_x = x0 + static_cast<int>(centre[0]), click_y = y0 + static_cast<int>(centre[1]);
  EXPECT_EQ(window.frame_pixel_at(click_x, click_y), (std::optional<std::array<int, 2>>(pixel)));
  EXPECT_FALSE(window.frame_pixel_at(10, 100).has_value());  // the 3D view
  EXPECT_EQ(window.pick_at(10, 100), "");
  EXPECT_EQ(traced, 0);

  const std::string line = window.pick_at(click_x, click_y);
  EXPECT_EQ(traced, 1);
  ASSERT_EQ(window.picks().size(), 1u);
  EXPECT_EQ(window.picks()[0].pixel, pixel);
  EXPECT_NE(line.find("pixel (30, 11)"), std::string::npos) << line;
  ASSERT_TRUE(scene.has(Layer::picks));
  // The drawn polyline is the tracer's path for the pixel.
  vtkPolyData* drawn = scene.picks();
  ASSERT_NE(drawn, nullptr);
  const TracedPath reference = std::apply(
      [&](const auto&... objects) {
        return trace_path(tracer.tracer(), camera.pixel_state(pixel[0], pixel[1]), 4, camera.tetrad().e[0], objects...);
      },
      tracer.scene().objects);
  ASSERT_EQ(drawn->GetNumberOfPoints(), static_cast<vtkIdType>(reference.samples.size()));
  for (vtkIdType i = 0; i < drawn->GetNumberOfPoints(); ++i) {
    double p[3];
    drawn->GetPoint(i, p);
    EXPECT_LT((Vec3(p[0], p[1], p[2]) - reference.samples[static_cast<std::size_t>(i)].position).norm(), 1e-12) << i;
  }
  // A second pick adds a polyline; a pixel outside the frame is refused.
  window.pick_pixel({2, 30});
  EXPECT_EQ(window.picks().size(), 2u);
  EXPECT_EQ(scene.picks()->GetNumberOfLines() + scene.picks()->GetNumberOfVerts(), 2);
  EXPECT_THROW(window.pick_pixel({W, 0}), std::out_of_range);
  (void)window.capture();  // draws with the picks layer

  EXPECT_EQ(window.handle_key("x"), "picks cleared (2)");
  EXPECT_TRUE(window.picks().empty());
  EXPECT_FALSE(scene.has(Layer::picks));
  EXPECT_EQ(scene.picks(), nullptr);

  // The same click as a mouse event on the window's interactor picks too; on the 3D view it does not.
  vtkRenderWindowInteractor* iren = window.interactor();
  iren->SetEventPosition(10, 100);
  iren->InvokeEvent(vtkCommand::LeftButtonPressEvent);  // the trackball starts turning the 3D view ...
  iren->InvokeEvent(vtkCommand::LeftButtonReleaseEvent);  // ... and lets go
  EXPECT_TRUE(window.picks().empty());
  iren->SetEventPosition(click_x, click_y);
  iren->InvokeEvent(vtkCommand::LeftButtonPressEvent);
  ASSERT_EQ(window.picks().size(), 1u);
  EXPECT_EQ(window.picks()[0].pixel, pixel);
  iren->SetKeyEventInformation(0, 0, 'x', 0, "x");
  iren->InvokeEvent(vtkCommand::CharEvent);
  EXPECT_TRUE(window.picks().empty());
}

TEST(VizPickWindow, WithoutAHandlerAPickIsRefused) {
  if (!display_available()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run)";
  SceneView scene(SceneLayout{});
  FrameView frame;
  frame.set_frame(Rgb8Image(8, 8));
  WindowOptions opt;
  opt.offscreen = true;
  opt.width = 200;
  opt.height = 100;
  ViewerWindow window(scene, &frame, opt);
  EXPECT_THROW(window.pick_pixel({1, 1}), std::logic_error);
}

}  // namespace
