// The tools' application layer (examples/app, grtrace/app/frame_tracer.hpp): a frame it draws through a FrameTracer
// is the frame the core draws with the concrete tracer, bit for bit, for each kind of tracer it hands over (planar,
// kerr-mino, general with rays four at a time, straight line) and for a flight; and it refuses, before any work,
// what its tracers cannot draw, saying what to use instead.
#include "grtrace/app/frame_tracer.hpp"
#include "grtrace/app/tool_methods.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/trace/auto_tracer.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace grtrace;

/// Every standard channel of a and b holds the same bits, and the header names the same tracer.
void expect_same_frame(const Frame& a, const Frame& b) {
  ASSERT_EQ(a.image.width(), b.image.width());
  ASSERT_EQ(a.image.height(), b.image.height());
  for (const char* c : Image::kStandardChannels) {
    const auto& x = a.image.channel(c);
    const auto& y = b.image.channel(c);
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "channel " << c;
  }
  EXPECT_EQ(a.image.metadata.at("tracer"), b.image.metadata.at("tracer"));
  EXPECT_EQ(a.image.metadata.at("mirrors"), b.image.metadata.at("mirrors"));
  EXPECT_EQ(a.stats.traced_rays, b.stats.traced_rays);
}

template <class M>
Camera small_camera(const M& metric, double r, double theta_degrees) {
  CameraSpec cs;
  cs.position = Vec4(0.0, r, theta_degrees * std::numbers::pi / 180.0, 0.0);
  cs.spherical_position = true;
  cs.width = 33;
  cs.height = 21;
  cs.fov_degrees = 60.0;
  return make_camera(metric, cs);
}

app::FrameRequest request(const std::string& metric, const std::string& scene, const std::string& tableau,
                          const std::string& control, const std::string& tracer) {
  app::FrameRequest q;
  q.metric.name = metric;
  q.metric.spin = metric == "kerr" ? 0.9 : 0.0;
  q.scene.name = scene;
  q.tableau = tableau;
  q.control = control;
  q.tracer = tracer;
  q.settings.integrator.tolerance = {1e-8, 1e-10};
  q.settings.escape_radius = 400.0;
  return q;
}

TEST(AppLayer, SchwarzschildFramesAreTheCoresBitForBit) {
  const SchwarzschildMetric metric{1.0};
  const Camera camera = small_camera(metric, 30.0, 80.0);
  app::FrameRequest q = request("schwarzschild", "disk", "rkf78", "i", "auto");
  const Frame erased = app::render_frame(q, camera);
  const PlanarSceneTracer<SchwarzschildMetric, Fehlberg78, IController, DiskScene> planar(
      metric, q.settings, camera, q.correction, disk_scene(q.scene), q.table_rays);
  expect_same_frame(erased, render_frame(camera, planar));
  EXPECT_EQ(erased.image.metadata.at("tracer"), "planar");

  q = request("schwarzschild", "checker", "tsit5", "i", "general");
  TracerReport report;
  const Frame general = app::render_frame(q, camera, {}, nullptr, &report);
  expect_same_frame(general, render_frame(camera, make_general_tracer<Tsitouras54, IController>(
                                                      metric, q.settings, q.correction, background_scene(q.scene))));
  EXPECT_EQ(report.name, "general");
}

TEST(AppLayer, KerrAndFlatFramesAreTheCoresBitForBit) {
  const KerrMetric metric{1.0, 0.9};
  const Camera camera = small_camera(metric, 50.0, 80.0);
  const app::FrameRequest q = request("kerr", "disk", "rkf78", "i", "auto");
  const Frame erased = app::render_frame(q, camera);
  expect_same_frame(erased, render_frame(camera, make_kerr_mino_tracer<Fehlberg78, IController>(
                                                     metric, q.settings, q.correction, disk_scene(q.scene))));
  EXPECT_EQ(erased.image.metadata.at("tracer"), "kerr-mino");

  const MinkowskiSpherical flat{};
  const Camera flat_camera = small_camera(flat, 30.0, 90.0);
  const app::FrameRequest f = request("minkowski", "checker", "rkf78", "i", "auto");
  expect_same_frame(app::render_frame(f, flat_camera),
                    render_frame(flat_camera, StraightLineTracer(flat, f.settings.escape_radius, f.correction,
                                                                 background_scene(f.scene))));
}

TEST(AppLayer, FlightFramesAreItsSingleFrames) {
  const SchwarzschildMetric metric{1.0};
  const std::vector<Camera> cameras = {small_camera(metric, 30.0, 80.0), small_camera(metric, 20.0, 60.0)};
  const app::FrameRequest q = request("schwarzschild", "disk", "tsit5", "i", "auto");
  std::vector<std::optional<Frame>> frames(cameras.size());
  const FlightStats stats = app::render_flight(
      q, cameras, [](int) { return false; },
      [&](int i, Frame&& frame, const TracerReport& report) {
        EXPECT_EQ(report.name, "planar");
        frames[static_cast<std::size_t>(i)].emplace(std::move(frame));
      });
  EXPECT_EQ(stats.rendered, 2);
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    ASSERT_TRUE(frames[i].has_value());
    expect_same_frame(*frames[i], app::render_frame(q, cameras[i]));
  }
}

/// A request and what its refusal must say.
struct Refused {
  app::FrameRequest q;
  std::string says;
};

TEST(AppLayer, RefusesWhatItsTracersCannotDrawBeforeAnyWork) {
  const std::vector<Refused> cases = {
      {request("schwarzschild", "checker", "dopri5", "i", "auto"), "rkf78 + i, tsit5 + i"},
      {request("schwarzschild", "checker", "rk4", "pi", "auto"), "embedded error estimate"},
      {request("kerr", "checker", "rkf78", "i", "planar"), "--tracer planar needs"},
      {request("schwarzschild", "checker", "rk4", "fixed", "planar"), "fixed --step"},
      {request("schwarzschild", "checker", "rkf78", "i", "symmetric"), "use --tracer planar"},
      {request("schwarzschild", "checker", "rkf78", "i", "teapot"), "choose auto, general or planar"},
  };
  for (const Refused& c : cases) {
    SCOPED_TRACE(c.says);
    try {
      app::check_frame_request(c.q);
      ADD_FAILURE() << "not refused";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(c.says), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(app::check_frame_request(request("rn", "disk", "vern6", "i", "planar")));
  for (const app::ToolMethod& m : app::kToolMethods) EXPECT_TRUE(app::is_tool_method(m.tableau, m.control));
  EXPECT_FALSE(app::is_tool_method("rkf45", "i"));
}

TEST(AppLayer, ChoosesTheDeviceAndSaysWhyTheGpuCannotDrawARequest) {
  const app::FrameRequest q = request("kerr", "disk", "rkf78", "i", "auto");
  EXPECT_EQ(app::choose_device("cpu", q), "cpu");
  EXPECT_THROW(app::choose_device("teapot", q), std::invalid_argument);
  // What the GPU does not run is refused whatever the machine has, naming what to use instead.
  const std::vector<Refused> cases = {
      {request("kerr", "disk", "tsit5", "i", "auto"), "--tableau rkf78 --control i only"},
      {request("schwarzschild", "disk", "rkf78", "i", "planar"), "use --tracer general or auto"},
      {request("minkowski", "checker", "rkf78", "i", "auto"), "straight lines, on the CPU"},
  };
  for (const Refused& c : cases) {
    SCOPED_TRACE(c.says);
    const auto refusal = app::gpu_refusal(c.q);
    ASSERT_TRUE(refusal.has_value());
    EXPECT_NE(refusal->find(c.says), std::string::npos) << *refusal;
    EXPECT_EQ(app::choose_device("auto", c.q), "cpu");
    app::FrameRequest on_gpu = c.q;
    on_gpu.device = "cuda";
    EXPECT_THROW(app::check_frame_request(on_gpu), std::invalid_argument);
  }
  // The request itself is the GPU's: whether it runs there is the machine's answer.
  const app::GpuStatus& gpu = app::gpu_status();
  if (gpu.present) {
    EXPECT_FALSE(app::gpu_refusal(q).has_value());
    EXPECT_EQ(app::choose_device("auto", q), app::kAutoPicksGpu ? "cuda" : "cpu");
    EXPECT_EQ(app::choose_device("cuda", q), "cuda");
  } else {
    ASSERT_TRUE(app::gpu_refusal(q).has_value());
    EXPECT_NE(app::gpu_refusal(q)->find("use --device cpu"), std::string::npos);
    EXPECT_FALSE(gpu.why_not.empty());
    EXPECT_EQ(app::choose_device("auto", q), "cpu");
    EXPECT_THROW(app::choose_device("cuda", q), std::invalid_argument);
  }
  // auto leaves to the CPU what its table tracer draws (one table for the frame beats integrating every pixel),
  // whatever the machine has; the same request with every pixel integrated is the GPU's where there is one.
  const app::FrameRequest main_frame = request("schwarzschild", "checker", "rkf78", "i", "auto");
  EXPECT_TRUE(app::cpu_table_tracer_draws(main_frame));
  EXPECT_EQ(app::choose_device("auto", main_frame), "cpu");
  EXPECT_TRUE(app::cpu_table_tracer_draws(request("rn", "disk", "rkf78", "i", "auto")));
  EXPECT_FALSE(app::cpu_table_tracer_draws(q));
  const app::FrameRequest general = request("schwarzschild", "checker", "rkf78", "i", "general");
  EXPECT_FALSE(app::cpu_table_tracer_draws(general));
  EXPECT_EQ(app::choose_device("auto", general), gpu.present && app::kAutoPicksGpu ? "cuda" : "cpu");
  // A frame drawn on the CPU says so in its header.
  const Camera camera = small_camera(KerrMetric{1.0, 0.9}, 50.0, 80.0);
  EXPECT_EQ(app::render_frame(q, camera).image.metadata.at("device"), "cpu");
}

}  // namespace
