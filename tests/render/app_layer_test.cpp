// The application library's front door (app/, grtrace/app/front_door.hpp): a frame an owned FrameRenderer draws is
// the frame the core draws with the concrete tracer, bit for bit, for each kind of tracer it builds (planar,
// kerr-mino, general with rays four at a time, straight line) and for a flight; its report is typed and agrees with
// the frame; a request read by option names is the typed request; RayTracer's paths end where the scene tracer's
// rays end; a render can be cancelled and counts its progress; and it refuses, before any work, what its tracers
// cannot draw, saying what to use instead.
#include "grtrace/app/front_door.hpp"
#include "grtrace/app/medium_view.hpp"
#include "grtrace/app/tool_methods.hpp"
#include "grtrace/core/physical_units.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/medium/polish_doughnut.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/flight_path.hpp"
#include "grtrace/render/disk_light_frame.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/spectra/kerr_disk_map.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/auto_tracer.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"
#include "grtrace/trace/medium_tracers.hpp"
#include "grtrace/trace/scene_tracer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace grtrace;

/// Every standard channel of a and b holds the same bits.
void expect_same_channels(const Image& a, const Image& b) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  for (const char* c : Image::kStandardChannels) {
    const auto& x = a.channel(c);
    const auto& y = b.channel(c);
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "channel " << c;
  }
}

/// A small frame's request: 33 x 21 pixels, fov 60, rtol 1e-8.
app::RenderRequest request(const std::string& metric, const std::string& scene, const std::string& tableau,
                           const std::string& control, const std::string& tracer, double r = 30.0,
                           double theta = 80.0) {
  app::RenderRequest q;
  q.metric.name = metric;
  q.metric.spin = metric == "kerr" ? 0.9 : 0.0;
  q.scene = scene;
  q.method.tableau = tableau;
  q.method.control = control;
  q.method.rtol = 1e-8;
  q.method.atol = 1e-10;
  q.tracer = tracer;
  q.camera.r = r;
  q.camera.theta_degrees = theta;
  q.camera.width = 33;
  q.camera.height = 21;
  q.camera.fov_degrees = 60.0;
  q.device = "cpu";
  return q;
}

TEST(AppLayer, SchwarzschildFramesAreTheCoresBitForBit) {
  const SchwarzschildMetric metric{1.0};
  const app::CheckedRequest c = app::check_request(request("schwarzschild", "disk", "rkf78", "i", "auto"));
  const app::RenderResult erased = app::FrameRenderer::create(c)->render();
  const PlanarSceneTracer<SchwarzschildMetric, Fehlberg78, IController, DiskScene> planar(
      metric, c.settings, c.camera, c.correction, disk_scene(c.scene), c.request.table_rays);
  const Frame core = render_frame(c.camera, planar);
  expect_same_channels(erased.image, core.image);
  EXPECT_EQ(erased.report.tracer, "planar");
  EXPECT_EQ(erased.report.stats.traced_rays, core.stats.traced_rays);
  EXPECT_EQ(erased.report.mirrors, core.image.metadata.at("mirrors"));
  // The planar tracer's mean steps are its table's, spread over the frame; its setup is the table.
  EXPECT_GT(erased.report.table_rays, 0);
  EXPECT_DOUBLE_EQ(erased.report.mean_steps,
                   static_cast<double>(erased.report.table_steps) / static_cast<double>(erased.report.stats.rays));
  EXPECT_GT(erased.report.setup_seconds, 0.0);
  EXPECT_GE(erased.report.seconds, erased.report.setup_seconds);

  const app::CheckedRequest g = app::check_request(request("schwarzschild", "checker", "tsit5", "i", "general"));
  const app::RenderResult general = app::FrameRenderer::create(g)->render();
  expect_same_channels(general.image,
                       render_frame(g.camera, make_general_tracer<Tsitouras54, IController>(
                                                  metric, g.settings, g.correction, background_scene(g.scene)))
                           .image);
  EXPECT_EQ(general.report.tracer, "general");
  long counted = 0;
  for (long n : general.report.stats.status_counts) counted += n;
  EXPECT_EQ(counted, 33L * 21L);
}

TEST(AppLayer, KerrAndFlatFramesAreTheCoresBitForBit) {
  const KerrMetric metric{1.0, 0.9};
  const app::CheckedRequest k = app::check_request(request("kerr", "disk", "rkf78", "i", "auto", 50.0));
  const app::RenderResult erased = app::FrameRenderer::create(k)->render();
  expect_same_channels(erased.image, render_frame(k.camera, make_kerr_closed_form_tracer<Fehlberg78, IController>(
                                                                metric, k.settings, k.correction, disk_scene(k.scene)))
                                         .image);
  EXPECT_EQ(erased.report.tracer, "kerr-closed-form");
  EXPECT_EQ(erased.report.device, "cpu");
  EXPECT_EQ(erased.image.metadata.at("device"), "cpu");
  // The ZAMO carries a Kerr camera unless another observer is named; the disk's edge is the prograde ISCO.
  EXPECT_EQ(k.request.camera.observer, "zamo");
  ASSERT_TRUE(k.request.disk_inner.has_value());
  EXPECT_NEAR(*k.request.disk_inner, 2.3209, 1e-4);

  const MinkowskiSpherical flat{};
  const app::CheckedRequest f = app::check_request(request("minkowski", "checker", "rkf78", "i", "auto", 30.0, 90.0));
  expect_same_channels(app::FrameRenderer::create(f)->render().image,
                       render_frame(f.camera, StraightLineTracer(flat, f.settings.escape_radius, f.correction,
                                                                 background_scene(f.scene)))
                           .image);
}

TEST(AppLayer, FlightFramesAreItsSingleFrames) {
  const app::CheckedRequest c = app::check_request(request("schwarzschild", "disk", "tsit5", "i", "auto"));
  const app::CheckedRequest other =
      app::check_request(request("schwarzschild", "disk", "tsit5", "i", "auto", 20.0, 60.0));
  const std::vector<Camera> cameras = {c.camera, other.camera};
  std::vector<std::optional<app::RenderResult>> frames(cameras.size());
  const FlightStats stats = app::render_flight(
      c, cameras, [](int) { return false; },
      [&](int i, app::RenderResult&& result) {
        EXPECT_EQ(result.report.tracer, "planar");
        frames[static_cast<std::size_t>(i)].emplace(std::move(result));
      });
  EXPECT_EQ(stats.rendered, 2);
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    ASSERT_TRUE(frames[i].has_value());
    expect_same_channels(frames[i]->image, app::FrameRenderer::create(app::with_camera(c, cameras[i]))->render().image);
  }
}

/// Option texts by name, as a command line or Python keywords give them.
/// f() must throw a RequestError whose message contains `says`.
template <class F>
void expect_refused(const std::string& says, F&& f) {
  SCOPED_TRACE(says);
  try {
    f();
    ADD_FAILURE() << "not refused";
  } catch (const app::RequestError& e) {
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

class Texts : public app::OptionSource {
 public:
  explicit Texts(std::map<std::string, std::string> given) : given_(std::move(given)) {}
  bool given(const std::string& name) const override { return given_.count(name) > 0; }
  std::optional<std::string> text(const std::string& name) const override {
    if (auto it = given_.find(name); it != given_.end()) return it->second;
    return std::nullopt;
  }

 private:
  std::map<std::string, std::string> given_;
};

TEST(AppLayer, ReadsTheRequestByOptionNamesAsTheToolsSpellThem) {
  const app::RenderRequest q = app::read_render_request(Texts({{"metric", "kerr"},
                                                               {"spin", "0.7"},
                                                               {"scene", "disk"},
                                                               {"disk-retrograde", "1"},
                                                               {"camera-theta", "60"},
                                                               {"look", "-1,0.1,0"},
                                                               {"width", "64"},
                                                               {"rtol", "1e-7"},
                                                               {"tracer", "general"}}));
  EXPECT_EQ(q.metric.name, "kerr");
  EXPECT_EQ(q.metric.spin, 0.7);
  EXPECT_EQ(q.scene, "disk");
  EXPECT_TRUE(q.disk_retrograde);
  EXPECT_FALSE(q.disk_inner.has_value());  // not given: the ISCO, chosen by check_request
  EXPECT_EQ(q.camera.theta_degrees, 60.0);
  EXPECT_EQ(q.camera.look, Vec3(-1.0, 0.1, 0.0));
  EXPECT_EQ(q.camera.width, 64);
  EXPECT_EQ(q.camera.height, 1024);  // the table's default
  EXPECT_EQ(q.method.rtol, 1e-7);
  EXPECT_EQ(q.tracer, "general");
  // Names see what values cannot: a parameter of another metric, a disk's option without the disk.
  const std::vector<std::pair<std::map<std::string, std::string>, std::string>> refused = {
      {{{"spin", "0.5"}}, "--spin applies only with --metric kerr"},
      {{{"disk-outer", "30"}}, "--disk-outer applies only with --scene disk"},
      {{{"fov", "abc"}}, "--fov expects a number, got 'abc'"},
      {{{"look", "1,2"}}, "--look expects 3 comma-separated numbers"},
      {{{"metric", "teapot"}},
       "--metric must be schwarzschild, minkowski, kerr, rn, sds, wormhole or "
       "schwarzschild-ef, got 'teapot'"},
  };
  for (const auto& [given, says] : refused)
    expect_refused(says, [&] { (void)app::read_render_request(Texts(given)); });
}

TEST(AppLayer, RayPathsEndWhereTheSceneTracersRaysEnd) {
  const KerrMetric metric{1.0, 0.9};
  const app::CheckedRequest c = app::check_request(request("kerr", "disk", "dopri5", "pi", "auto", 40.0, 75.0));
  const auto rays = app::RayTracer::create(c);
  EXPECT_EQ(rays->object_names(), (std::vector<std::string>{"sky", "horizon", "disk"}));
  const auto general =
      make_general_tracer<DormandPrince54, PIController>(metric, c.settings, c.correction, disk_scene(c.scene));
  int hits = 0;
  for (const auto& [col, row] : std::vector<std::array<int, 2>>{{16, 10}, {16, 2}, {0, 0}, {20, 12}}) {
    const GeodesicState y0 = c.camera.pixel_state(col, row);
    app::PathOptions options;
    options.observer_velocity = c.camera.tetrad().e[0];
    const app::TracedRay ray = rays->trace(y0, options);
    // The outcome is the general scene tracer's, bit for bit; the path ends where the ray ends.
    const RayOutcome o = general.trace(y0);
    EXPECT_EQ(ray.outcome.status, o.status) << col << "," << row;
    EXPECT_EQ(ray.outcome.object, o.object);
    EXPECT_EQ(ray.outcome.steps, o.steps);
    EXPECT_EQ(ray.outcome.order, o.order);
    EXPECT_EQ(ray.outcome.state, o.state);
    EXPECT_EQ(ray.path.status, o.status);
    ASSERT_FALSE(ray.path.steps.empty());
    EXPECT_EQ(ray.path.samples.front().state, y0);
    if (o.status == RayStatus::hit) {
      ++hits;
      EXPECT_EQ(ray.object, "disk");
      // The path's last point is the crossing the tracer located (not the interpolant's point there).
      EXPECT_TRUE(ray.path.steps.back().located);
      EXPECT_EQ(ray.path.steps.back().state, o.state);
      EXPECT_EQ(ray.path.samples.back().state, o.state);
    }
  }
  EXPECT_GT(hits, 0);
  // Without the scene's objects the disk does not end a ray.
  app::PathOptions through;
  through.scene_objects = false;
  EXPECT_NE(rays->trace(c.camera.pixel_state(16, 10), through).outcome.status, RayStatus::hit);
}

TEST(AppLayer, RendersCanBeCancelledAndCountTheirPixels) {
  const auto renderer = app::FrameRenderer::create(request("schwarzschild", "checker", "tsit5", "i", "general"));
  std::atomic<long> done{0};
  app::RenderControl control;
  control.pixels_done = &done;
  const app::RenderResult result = renderer->render(control);
  EXPECT_EQ(done.load(), result.report.stats.rays);  // every pixel, the mirrored ones included
  const std::atomic<bool> cancel{true};
  control.cancel = &cancel;
  EXPECT_THROW(renderer->render(control), RenderCancelled);
}

TEST(AppLayer, ReportEntriesAreTheToolsJsonKeys) {
  const app::CheckedRequest c = app::check_request(request("schwarzschild", "checker", "rkf78", "i", "auto"));
  const app::RenderResult result = app::FrameRenderer::create(c)->render();
  std::vector<std::string> keys;
  for (const app::ReportEntry& e : app::report_entries(result.report, c)) keys.push_back(e.key);
  for (const char* key : {"width", "height", "seconds", "rays_per_second", "mean_steps", "status_counts", "tracer",
                          "tableau", "rtol", "atol", "device", "traced_rays", "table_rays", "fallback_rays"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key;
}

/// A request and what its refusal must say.
struct Refused {
  app::RenderRequest q;
  std::string says;
};

TEST(AppLayer, RefusesWhatItsTracersCannotDrawBeforeAnyWork) {
  app::RenderRequest inside = request("schwarzschild", "checker", "rkf78", "i", "auto", 2.0);
  app::RenderRequest fixed_without_step = request("schwarzschild", "checker", "rk4", "fixed", "general");
  const std::vector<Refused> cases = {
      {request("schwarzschild", "checker", "dopri5", "i", "auto"), "rkf78 + i, tsit5 + i"},
      {request("schwarzschild", "checker", "rk4", "pi", "auto"), "embedded error estimate"},
      {request("kerr", "checker", "rkf78", "i", "planar"), "--tracer planar needs"},
      {request("schwarzschild", "checker", "rkf78", "i", "symmetric"), "use --tracer planar"},
      {request("schwarzschild", "checker", "rkf78", "i", "teapot"),
       "choose auto, general, planar, kerr-mino, kerr-closed-form or straight-line"},
      {request("schwarzschild", "checker", "rkf78", "i", "kerr-mino"), "--tracer kerr-mino needs --metric kerr"},
      {request("kerr", "checker", "rkf78", "i", "straight-line"), "--tracer straight-line draws flat space only"},
      {request("minkowski", "disk", "rkf78", "i", "auto"), "--scene disk needs a metric with a mass"},
      {inside, "--camera-r 2 is at or inside the horizon"},
      {fixed_without_step, "--control fixed needs a step"},
  };
  for (const Refused& c : cases) expect_refused(c.says, [&] { (void)app::check_request(c.q); });
  EXPECT_NO_THROW((void)app::check_request(request("rn", "disk", "vern6", "i", "planar")));
  EXPECT_NO_THROW((void)app::check_request(request("kerr", "disk", "rkf78", "i", "kerr-mino")));
  EXPECT_NO_THROW((void)app::check_request(request("minkowski", "checker", "rkf78", "i", "straight-line")));
  for (const app::ToolMethod& m : app::kToolMethods) EXPECT_TRUE(app::is_tool_method(m.tableau, m.control));
  EXPECT_FALSE(app::is_tool_method("rkf45", "i"));
}

TEST(AppLayer, ASkyTextureIsHeldOnceHoweverOftenTheRequestIsCopied) {
  // A texture can be most of a process's memory: the request, its copies (a flight's cameras, the tracer's scene)
  // and the sky share its texels instead of holding a copy each.
  const std::string file = ::testing::TempDir() + "grtrace_app_texture.exr";
  grtrace::write_exr(file, Image::with_channels(16, 8, {"R", "G", "B", "A"}, 0.25f));
  app::RenderRequest q = request("schwarzschild", "sky", "rkf78", "i", "auto");
  q.sky_texture = file;
  const app::CheckedRequest checked = app::check_request(q);
  ASSERT_TRUE(checked.scene.texture.has_value());
  const app::CheckedRequest copy = app::with_camera(checked, checked.camera);
  EXPECT_EQ(copy.scene.texture->r.get(), checked.scene.texture->r.get());
  EXPECT_EQ(checked.scene.texture->r.use_count(), 2);
  EXPECT_EQ(checked.scene.texture->r->size(), 16u * 8u);
  std::remove(file.c_str());
}

TEST(AppLayer, TheKerrFlightsRaysPastThePoleDoNotFail) {
  // The README's 300-frame Kerr flight (a = 0.9, circular at r = 50, fov 60, 1024 x 1024): in frame 5, pixels
  // (657, 49) and (657, 974) pass 1.8e-3 rad from the poles and ended non_finite (a step across the axis). They
  // escape now, where the general tracer in Kerr-Schild's chart (no axis; rtol 1e-13) says.
  app::RenderRequest q = request("kerr", "disk", "rkf78", "i", "auto", 50.0, 80.0);
  q.method.rtol = 1e-9;
  q.method.atol = 1e-11;
  q.camera.width = q.camera.height = 1024;
  const app::CheckedRequest checked = app::check_request(q);
  FlightPathSpec spec;
  spec.kind = "circular";
  spec.r = 50.0;
  spec.frames = 300;
  const Worldline path = app::flight_worldline(checked.request.metric, spec);
  const CameraView view{checked.request.camera.look, checked.request.camera.up, 1024, 1024, 60.0};
  const Camera camera = app::flight_cameras(checked.request.metric, path, view).at(5);
  const KerrMetric metric{1.0, 0.9};
  const auto mino = make_kerr_mino_tracer<Fehlberg78, IController>(metric, checked.settings, checked.correction,
                                                                    disk_scene(checked.scene));
  TraceSettings reference = checked.settings;
  reference.integrator.tolerance = {1e-13, 1e-15};
  const KerrSchildMetric ks = kerr_schild_for_camera_rays(1.0, 0.9);
  const auto general = make_general_tracer<Fehlberg78, IController>(ks, reference, checked.correction,
                                                                    disk_scene(checked.scene));
  for (const int row : {49, 974}) {
    SCOPED_TRACE(row);
    const GeodesicState y0 = camera.pixel_state(657, row);
    const RayOutcome a = mino.trace(y0), b = general.trace(bl_to_ks(ks, y0));
    ASSERT_EQ(a.status, RayStatus::escaped);
    ASSERT_EQ(b.status, RayStatus::escaped);
    EXPECT_LT(angular_distance(a.where, b.where), 1e-6);
    EXPECT_NEAR(a.redshift, b.redshift, 2e-6);  // the charts' sky redshifts differ by 7e-7 on every ray of this frame
  }
}

TEST(AppLayer, ChoosesTheDeviceAndSaysWhyTheGpuCannotDrawARequest) {
  const app::RenderRequest q = request("kerr", "disk", "rkf78", "i", "auto", 50.0);
  EXPECT_EQ(app::choose_device("cpu", q), "cpu");
  EXPECT_THROW(app::choose_device("teapot", q), std::invalid_argument);
  // What the GPU does not run is refused whatever the machine has, naming what to use instead.
  const std::vector<Refused> cases = {
      {request("kerr", "disk", "tsit5", "i", "auto", 50.0), "--tableau rkf78 --control i only"},
      {request("schwarzschild", "disk", "rkf78", "i", "planar"), "use --tracer general or auto"},
      {request("minkowski", "checker", "rkf78", "i", "auto"), "straight lines, on the CPU"},
  };
  for (const Refused& c : cases) {
    SCOPED_TRACE(c.says);
    const auto refusal = app::gpu_refusal(c.q);
    ASSERT_TRUE(refusal.has_value());
    EXPECT_NE(refusal->find(c.says), std::string::npos) << *refusal;
    EXPECT_EQ(app::choose_device("auto", c.q), "cpu");
    app::RenderRequest on_gpu = c.q;
    on_gpu.device = "cuda";
    EXPECT_THROW((void)app::check_request(on_gpu), std::invalid_argument);
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
    // A machine with no NVIDIA driver is told so, not that its driver's version is too old (CUDA's own words for
    // both cases).
    if (gpu.built && !std::filesystem::exists("/dev/nvidiactl")) {
      EXPECT_NE(gpu.why_not.find("no NVIDIA driver is loaded on this machine"), std::string::npos) << gpu.why_not;
    }
    EXPECT_EQ(gpu.why_not.find("driver version is insufficient"), std::string::npos) << gpu.why_not;
    EXPECT_EQ(app::choose_device("auto", q), "cpu");
    EXPECT_THROW(app::choose_device("cuda", q), std::invalid_argument);
  }
  // auto leaves to the CPU what its table tracer draws (one table for the frame beats integrating every pixel),
  // whatever the machine has; the same request with every pixel integrated is the GPU's where there is one.
  const app::RenderRequest main_frame = request("schwarzschild", "checker", "rkf78", "i", "auto");
  EXPECT_TRUE(app::cpu_table_tracer_draws(main_frame));
  EXPECT_EQ(app::choose_device("auto", main_frame), "cpu");
  EXPECT_TRUE(app::cpu_table_tracer_draws(request("rn", "disk", "rkf78", "i", "auto")));
  EXPECT_FALSE(app::cpu_table_tracer_draws(q));
  const app::RenderRequest general = request("schwarzschild", "checker", "rkf78", "i", "general");
  EXPECT_FALSE(app::cpu_table_tracer_draws(general));
  EXPECT_EQ(app::choose_device("auto", general), gpu.present && app::kAutoPicksGpu ? "cuda" : "cpu");
}

}  // namespace

namespace {

/// The accreting hole seen from r = 100 M (the shadow, radius 5.2 M, about half the frame), 33 x 33 pixels.
app::RenderRequest accretion_request(const std::string& metric, const std::string& tracer, double rtol) {
  app::RenderRequest q;
  q.metric.name = metric;
  q.metric.charge = metric == "rn" ? 0.5 : 0.0;
  q.scene = "accretion";
  q.tracer = tracer;
  q.method.rtol = rtol;
  q.method.atol = rtol * 1e-2;
  q.camera.r = 100.0;
  q.camera.fov_degrees = 8.0;
  q.camera.width = q.camera.height = 33;
  return q;
}

}  // namespace

TEST(AppLayer, AnAccretionFrameFromOneTableIsTheGeneralTracersFrame) {
  // The table (auto picks it) against every pixel integrated, at a tolerance where the integration's own error
  // (1.8e-7 at rtol 1e-10 for rays grazing the photon sphere) does not hide the table's.
  for (const std::string metric : {"schwarzschild"}) {
    for (const std::string gas : {"free-fall", "rest"}) {
      SCOPED_TRACE(metric + " " + gas);
      app::RenderRequest q = accretion_request(metric, "auto", 1e-12);
      q.accretion_gas = gas;
      const app::RenderResult table = app::render(q);
      q.tracer = "general";
      const app::RenderResult general = app::render(q);
      EXPECT_EQ(table.report.tracer, "planar");
      EXPECT_EQ(table.report.table_rays, 2 * default_medium_table_rays);
      EXPECT_EQ(table.report.fallback_rays, 0);
      EXPECT_EQ(general.report.tracer, "general");
      EXPECT_EQ(table.report.device, "cpu");
      const auto& a = table.image.channel("intensity");
      const auto& b = general.image.channel("intensity");
      double worst = 0.0;
      for (std::size_t i = 0; i < a.size(); ++i)
        worst = std::max(worst, std::abs(static_cast<double>(a[i]) - static_cast<double>(b[i])) /
                                    static_cast<double>(b[i]));
      EXPECT_LT(worst, 1e-6);  // float channels: 6e-8 is their rounding
      EXPECT_EQ(table.image.channel("status"), general.image.channel("status"));
      EXPECT_EQ(table.report.stats.failures(), 0);
      EXPECT_NEAR(*table.report.flux, *general.report.flux, 1e-7 * *general.report.flux);
      EXPECT_EQ(table.image.metadata.at("accretion_gas"), gas);
      EXPECT_EQ(table.image.metadata.at("scene"), "accretion");
    }
  }
}

TEST(AppLayer, AnAccretionFramesFluxConvergesWithItsPixels) {
  // The flux sums intensity times each pixel's solid angle: finer frames of the same view converge to one flux.
  // The midpoint rule's error falls as the pixel's side (first order, not second: the intensity has a logarithmic
  // peak on the photon ring), measured 2.4e-4 then 1.1e-4 of a flux of 6.4e-3 (33 -> 65 -> 129 pixels a side).
  std::vector<double> flux;
  for (const int n : {33, 65, 129}) {
    app::RenderRequest q = accretion_request("schwarzschild", "auto", 1e-10);
    q.camera.width = q.camera.height = n;
    flux.push_back(*app::render(q).report.flux);
  }
  const double coarse = std::abs(flux[1] - flux[0]), fine = std::abs(flux[2] - flux[1]);
  EXPECT_LT(fine, 0.03 * flux[2]) << flux[0] << " " << flux[1] << " " << flux[2];
  EXPECT_LT(fine, 0.6 * coarse) << flux[0] << " " << flux[1] << " " << flux[2];
}

TEST(AppLayer, AnAccretionRequestItsTracersCannotDrawIsRefused) {
  app::RenderRequest kerr = accretion_request("kerr", "auto", 1e-9);
  kerr.metric.spin = 0.5;
  app::RenderRequest tsit5 = accretion_request("schwarzschild", "auto", 1e-9);
  tsit5.method.tableau = "tsit5";
  app::RenderRequest on_gpu = accretion_request("schwarzschild", "auto", 1e-9);
  on_gpu.device = "cuda";
  app::RenderRequest error_map = accretion_request("schwarzschild", "auto", 1e-9);
  error_map.error_map = true;
  app::RenderRequest gas = accretion_request("schwarzschild", "auto", 1e-9);
  gas.accretion_gas = "plasma";
  app::RenderRequest power = accretion_request("schwarzschild", "auto", 1e-9);
  power.accretion_power = -1.0;
  const std::vector<Refused> cases = {
      {kerr, "--scene accretion falls onto a Schwarzschild hole in the tools: use --metric schwarzschild"},
      {accretion_request("wormhole", "auto", 1e-9), "--scene accretion falls onto a Schwarzschild hole"},
      {accretion_request("rn", "auto", 1e-9), "--scene accretion falls onto a Schwarzschild hole"},
      {tsit5, "--scene accretion is drawn with --tableau vern6 --control i"},
      {accretion_request("schwarzschild", "kerr-mino", 1e-9), "--tracer kerr-mino cannot draw --scene accretion"},
      {on_gpu, "--device cuda: --scene accretion is drawn on the CPU"},
      {error_map, "leave --error-map out"},
      {gas, "unknown --accretion-gas 'plasma'; choose free-fall or rest"},
      {power, "--accretion-power must lie in [0, 10]"},
  };
  for (const Refused& c : cases) expect_refused(c.says, [&] { (void)app::check_request(c.q); });
  // By option names: the accretion's options without it, and what means nothing with it.
  const std::vector<std::pair<std::map<std::string, std::string>, std::string>> refused = {
      {{{"accretion-gas", "rest"}}, "--accretion-gas applies only with --scene accretion"},
      {{{"scene", "sky"}, {"accretion-power", "3"}}, "--accretion-power applies only with --scene accretion"},
      {{{"scene", "accretion"}, {"angle-correction", "flat"}}, "--angle-correction applies only with a scene that"},
      {{{"scene", "accretion"}, {"tracer", "general"}, {"table-rays", "64"}}, "--table-rays applies only with"},
      {{{"scene", "teapot"}}, "choose checker, sky, redshift, disk, accretion, riaf or torus"},
  };
  for (const auto& [given, says] : refused)
    expect_refused(says, [&] { (void)app::read_render_request(Texts(given)); });
  const app::RenderRequest read = app::read_render_request(
      Texts({{"scene", "accretion"}, {"accretion-gas", "rest"}, {"accretion-power", "3"}, {"table-rays", "64"}}));
  EXPECT_EQ(read.accretion_gas, "rest");
  EXPECT_EQ(read.accretion_power, 3.0);
  EXPECT_EQ(read.table_rays, 64);
}

namespace {

/// Sgr A* seen from 1000 M at 17 degrees to the spin axis, a frame 40 M wide, 16 x 16 pixels.
app::RenderRequest riaf_request() {
  app::RenderRequest q;
  q.metric.name = "kerr";
  q.metric.spin = 0.9;
  q.scene = "riaf";
  q.source = "sgr-a";
  q.method.rtol = 1e-8;
  q.method.atol = 1e-10;
  q.sky_radius = 2000.0;
  q.camera.r = 1000.0;
  q.camera.theta_degrees = 17.0;
  q.camera.fov_degrees = 2.0 * std::atan(20.0 / 1000.0) * 180.0 / std::numbers::pi;
  q.camera.width = q.camera.height = 16;
  return q;
}

TEST(AppLayer, ADiskDrawnByItsLightIsTheLibrarysDiskLightFrame) {
  // The tools' transparent disk (Kerr a = 0.9, its ISCO to 20 M, r^-2.5, g^4) against the library's frame of the
  // same camera and disk, channel for channel, bit for bit; its report's flux by order is the library's.
  app::RenderRequest q;
  q.metric.name = "kerr";
  q.metric.spin = 0.9;
  q.scene = "disk";
  q.disk_light = app::DiskLightRequest{};
  q.disk_light->transparent = true;
  q.disk_light->emissivity_index = 2.5;
  q.redshift_power = 4.0;
  q.camera.r = 50.0;
  q.camera.theta_degrees = 80.0;
  q.camera.fov_degrees = 40.0;
  q.camera.width = 36;
  q.camera.height = 24;
  const app::RenderResult r = app::render(q);
  EXPECT_EQ(r.report.tracer, "kerr-closed-form");
  const app::CheckedRequest checked = app::check_request(q);
  const ThinDisk& disk = checked.scene.disk;
  EXPECT_NEAR(disk.r_in, exact::isco_radius(0.9, exact::Orbit::prograde), 1e-12);
  const KerrDiskRays rays(KerrMetric{1.0, 0.9}, disk.r_in, disk.r_out, disk.sense, checked.settings.escape_radius);
  DiskLight light;
  light.emissivity.index_inner = light.emissivity.index_outer = 2.5;
  light.redshift_power = 4.0;
  light.transparent = true;
  const DiskLightFrame library = render_disk_light_frame(checked.camera, rays, light);
  for (const char* c : {"intensity", "intensity_n0", "intensity_n1", "intensity_n2", "intensity_n3_up", "order",
                        "object", "status", "R", "G", "B"}) {
    const std::vector<float>&a = r.image.channel(c), &b = library.frame.image.channel(c);
    ASSERT_EQ(a.size(), b.size()) << c;
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << c << " " << i;
  }
  const std::array<double, 4> flux = flux_by_order(checked.camera, library.frame.image);
  ASSERT_TRUE(r.report.flux_by_order);
  for (std::size_t n = 0; n < 4; ++n) EXPECT_EQ((*r.report.flux_by_order)[n], flux[n]) << n;
  EXPECT_GT(flux[1], 0.0);
  EXPECT_EQ(r.image.metadata.at("disk_transparent"), "true");
  EXPECT_EQ(r.image.metadata.count("angle_correction"), 0u);  // no sky in the picture

  // Refused before any work: another hole, another tracer, the GPU, an error map, a disk light without the disk.
  app::RenderRequest rn = q;
  rn.metric.name = "rn";
  expect_refused("--disk-light follows the disk's rays in closed form", [&] { (void)app::check_request(rn); });
  app::RenderRequest general = q;
  general.tracer = "general";
  expect_refused("use auto or kerr-closed-form", [&] { (void)app::check_request(general); });
  app::RenderRequest gpu = q;
  gpu.device = "cuda";
  expect_refused("is drawn on the CPU", [&] { (void)app::check_request(gpu); });
  app::RenderRequest error = q;
  error.error_map = true;
  expect_refused("shows no sky", [&] { (void)app::check_request(error); });
  app::RenderRequest sky = q;
  sky.scene = "sky";
  expect_refused("--disk-light draws the disk scene", [&] { (void)app::check_request(sky); });
}

}  // namespace

TEST(AppLayer, ARiafFrameIsInPhysicalUnits) {
  const app::RenderRequest q = riaf_request();
  const app::RenderResult r = app::render(q);
  EXPECT_EQ(r.report.tracer, "kerr-mino");
  EXPECT_EQ(r.image.metadata.at("tableau"), "vern6");  // the media's method: rkf78's estimate cannot see the light
  EXPECT_EQ(r.report.stats.failures(), 0);
  // The flux at the telescope is the camera's times (r_cam / D)^2, in janskys: Sgr A*'s order (2.4 Jy measured).
  const SourceScale s = SourceScale::sgr_a();
  const double d = s.distance_pc * cgs::parsec / s.gravitational_radius_cm();
  ASSERT_TRUE(r.report.flux_jy && r.report.flux);
  EXPECT_NEAR(*r.report.flux_jy, *r.report.flux * (1000.0 / d) * (1000.0 / d) / 1e-23, 1e-12 * *r.report.flux_jy);
  EXPECT_GT(*r.report.flux_jy, 1.2);
  EXPECT_LT(*r.report.flux_jy, 4.8);
  // A pixel: 40 M over 15 pitches at the camera, 4.84 microarcseconds an M at Sgr A*'s distance.
  EXPECT_NEAR(*r.report.microarcseconds_per_pixel, 40.0 / 15.0 * s.microarcseconds_per_m(), 1e-9);
  EXPECT_EQ(r.image.metadata.at("medium"), "riaf");
  EXPECT_EQ(r.image.metadata.at("source"), "sgr-a");
  EXPECT_EQ(std::stod(r.image.metadata.at("accretion_rate")), 1e-8);
  EXPECT_EQ(std::stod(r.image.metadata.at("frequency_ghz")), 230.0);
  EXPECT_EQ(std::stod(r.image.metadata.at("flux_jy")), *r.report.flux_jy);
  // Ten times the accretion rate: denser, hotter in field, brighter.
  app::RenderRequest more = q;
  more.accretion_rate = 1e-7;
  EXPECT_GT(*app::render(more).report.flux_jy, 3.0 * *r.report.flux_jy);
}

TEST(AppLayer, ARiafFrameAtSeveralFrequenciesIsEachFrequencysFrameInOnePass) {
  // Three frequencies in one pass: a channel and a flux each, the first one's also the picture; each band's light
  // is the single-frequency frame's within the integration's error (both at rtol 1e-8).
  app::RenderRequest q = riaf_request();
  q.frequencies_ghz =
      app::read_render_request(Texts({{"scene", "riaf"}, {"frequency", "86,230,345.5"}})).frequencies_ghz;
  ASSERT_EQ(q.frequencies_ghz, (std::vector<double>{86.0, 230.0, 345.5}));
  const app::RenderResult all = app::render(q);
  EXPECT_EQ(all.report.stats.failures(), 0);
  EXPECT_EQ(all.image.metadata.at("frequencies_ghz"), "86,230,345.5");
  ASSERT_EQ(all.report.band_fluxes.size(), 3u);
  EXPECT_EQ(all.image.channel("intensity"), all.image.channel("intensity_86GHz"));
  EXPECT_EQ(*all.report.flux_jy, *all.report.band_fluxes[0].flux_jy);
  bool reported = false;
  for (const app::ReportEntry& e : app::report_entries(all.report, app::check_request(q)))
    reported = reported || e.key == "flux_jy_345p5GHz";
  EXPECT_TRUE(reported);
  for (std::size_t b = 0; b < 3; ++b) {
    app::RenderRequest one = riaf_request();
    one.frequencies_ghz = {q.frequencies_ghz[b]};
    const app::RenderResult single = app::render(one);
    const std::string band = app::frequency_band_name(q.frequencies_ghz[b]);
    EXPECT_EQ(all.report.band_fluxes[b].band, band);
    const std::vector<float>& many = all.image.channel("intensity_" + band);
    const std::vector<float>& alone = single.image.channel("intensity");
    const float peak = *std::max_element(alone.begin(), alone.end());
    for (std::size_t i = 0; i < alone.size(); ++i) EXPECT_NEAR(many[i], alone[i], 1e-5f * peak) << band << " " << i;
    EXPECT_NEAR(*all.report.band_fluxes[b].flux_jy, *single.report.flux_jy, 1e-5 * *single.report.flux_jy) << band;
    EXPECT_EQ(std::stod(all.image.metadata.at("flux_jy_" + band)), *all.report.band_fluxes[b].flux_jy);
  }
  // The spectrum of the thin flow rises to its peak and falls: 86 GHz below 230 (self-absorbed), 345.5 too.
  EXPECT_LT(*all.report.band_fluxes[0].flux_jy, *all.report.band_fluxes[1].flux_jy);
  EXPECT_LT(*all.report.band_fluxes[2].flux_jy, *all.report.band_fluxes[1].flux_jy);
}

TEST(AppLayer, ARiafRequestItCannotDrawIsRefused) {
  app::RenderRequest schwarzschild = riaf_request();
  schwarzschild.metric.name = "schwarzschild";
  app::RenderRequest ks = riaf_request();
  ks.metric.chart = "ks";
  app::RenderRequest mass = riaf_request();
  mass.metric.mass = 2.0;
  app::RenderRequest near = riaf_request();
  near.camera.r = 50.0;
  app::RenderRequest source = riaf_request();
  source.source = "cyg-x1";
  app::RenderRequest rate = riaf_request();
  rate.accretion_rate = 0.0;
  app::RenderRequest frequency = riaf_request();
  frequency.frequencies_ghz = {-230.0};
  app::RenderRequest nine = riaf_request();
  nine.frequencies_ghz = {43, 86, 140, 230, 345, 490, 690, 1000, 1500};
  app::RenderRequest twice = riaf_request();
  twice.frequencies_ghz = {230, 345, 230};
  app::RenderRequest general = riaf_request();
  general.tracer = "general";
  app::RenderRequest tsit5 = riaf_request();
  tsit5.method.tableau = "tsit5";
  const std::vector<Refused> cases = {
      {schwarzschild, "--scene riaf flows around a Kerr hole in Boyer-Lindquist coordinates"},
      {ks, "--scene riaf flows around a Kerr hole in Boyer-Lindquist coordinates"},
      {mass, "--scene riaf takes the hole's mass from --source"},
      {near, "use --camera-r 100 or more (got 50)"},
      {source, "unknown --source 'cyg-x1'; choose m87 or sgr-a"},
      {rate, "--accretion-rate must lie in (0, 1e3]"},
      {frequency, "--frequency must lie in (0, 1e7] GHz"},
      {nine, "--frequency takes 1 to 8 frequencies, got 9"},
      {twice, "--frequency names 230 GHz twice: list each band once"},
      {general, "--tracer general cannot draw --scene riaf; use auto or kerr-mino"},
      {tsit5, "--scene riaf is drawn with --tableau vern6 --control i"},
  };
  for (const Refused& c : cases) expect_refused(c.says, [&] { (void)app::check_request(c.q); });
  const std::vector<std::pair<std::map<std::string, std::string>, std::string>> refused = {
      {{{"source", "m87"}}, "--source applies only with --scene riaf"},
      {{{"scene", "accretion"}, {"frequency", "86"}}, "--frequency applies only with --scene riaf"},
  };
  for (const auto& [given, says] : refused) expect_refused(says, [&] { (void)app::read_render_request(Texts(given)); });
}

app::RenderRequest small_torus_request() {
  app::RenderRequest q;
  q.metric.name = "kerr";
  q.metric.spin = 0.9;
  q.scene = "torus";
  q.torus_opacity = 0.5;
  q.camera.r = 100.0;
  q.camera.theta_degrees = 70.0;
  q.camera.fov_degrees = 36.0;
  q.camera.width = q.camera.height = 12;
  return q;
}

TEST(AppLayer, AMediumsVolumeIsItsEmissionWithItsPeakAtThePressureMaximum) {
  // What grtrace-view draws of the torus: at every point of the cube its emission (j = rho: no direction), 0 inside
  // the horizon; the largest on the equator within a spacing of the pressure maximum (r_c = 10).
  const app::CheckedRequest checked = app::check_request(small_torus_request());
  const app::MediumVolume v = app::medium_volume(checked, 41, 20.0);
  ASSERT_EQ(v.emission.size(), 41u * 41u * 41u);
  EXPECT_EQ(v.kind, "polish-doughnut");
  const KerrMetric metric{1.0, 0.9};
  const PolishDoughnut<KerrMetric> torus(metric, 6.0, 10.0, 3.0, 1.0, 0.5);
  const double h = v.spacing();
  EXPECT_DOUBLE_EQ(h, 1.0);
  std::size_t best = 0, lit = 0, inside = 0;
  for (std::size_t at = 0; at < v.emission.size(); ++at) {
    const int i = static_cast<int>(at % 41), j = static_cast<int>(at / 41 % 41), k = static_cast<int>(at / 1681);
    const double px = -20.0 + i * h, py = -20.0 + j * h, pz = -20.0 + k * h;
    const double r = std::sqrt(px * px + py * py + pz * pz);
    if (v.emission[at] > v.emission[best]) best = at;
    lit += v.emission[at] > 0.0f;
    if (r <= metric.outer_horizon()) {
      EXPECT_EQ(v.emission[at], 0.0f);
      continue;
    }
    if (at % 97 != 0) continue;  // a sample of the points against the torus itself: its gas inside its surface
    const Vec4 x(0.0, r, std::acos(pz / r), std::atan2(py, px));
    const bool gas = torus.boundary(metric, x) <= 0.0;
    EXPECT_EQ(v.emission[at], gas ? static_cast<float>(torus.coefficients(metric, x, 1.0).emission) : 0.0f) << at;
    inside += gas;
  }
  EXPECT_EQ(v.peak, static_cast<double>(v.emission[best]));
  const double bx = -20.0 + static_cast<double>(best % 41), by = -20.0 + static_cast<double>(best / 41 % 41),
               bz = -20.0 + static_cast<double>(best / 1681);
  EXPECT_NEAR(std::hypot(bx, by), 10.0, h);
  EXPECT_EQ(bz, 0.0);
  EXPECT_GT(lit, 1000u);
  EXPECT_GT(inside, 10u);
  app::RenderRequest sky = small_torus_request();
  sky.scene = "sky";
  sky.torus_opacity = 0.0;
  expect_refused("--scene sky has no emitting medium", [&] { (void)app::medium_volume(app::check_request(sky), 8); });
  expect_refused("2 to 256 points a side, got 1", [&] { (void)app::medium_volume(checked, 1); });
}

TEST(AppLayer, TheLightAlongAPickedRayIsItsPixelsIntensity) {
  // The light a picked ray collects (grtrace-view colours it by this), summed by the trapezoid rule over its
  // path's samples, ends at its pixel's intensity in the frame to the samples' resolution; it only grows.
  const app::RenderRequest q = small_torus_request();
  const app::RenderResult frame = app::render(q);
  const app::CheckedRequest checked = app::check_request(q);
  const auto tracer = app::RayTracer::create(checked);
  app::PathOptions options;
  options.samples_per_step = 64;
  options.observer_velocity = checked.camera.tetrad().e[0];
  const std::vector<float>& intensity = frame.image.channel("intensity");
  int compared = 0;
  double worst = 0.0;
  for (int y = 1; y < 12; y += 3)
    for (int x = 1; x < 12; x += 3) {
      const double pixel = intensity[frame.image.index(x, y)];
      if (!(pixel > 0.0)) continue;
      const app::TracedRay ray = tracer->trace(checked.camera.pixel_state(x, y), options);
      const std::vector<double> light = app::medium_light_along(checked, ray.path, *options.observer_velocity);
      ASSERT_EQ(light.size(), ray.path.samples.size());
      EXPECT_EQ(light.front(), 0.0);
      EXPECT_TRUE(std::is_sorted(light.begin(), light.end()));
      EXPECT_NEAR(light.back(), pixel, 5e-4 * pixel) << x << " " << y;  // measured 4.6e-5
      worst = std::max(worst, std::abs(light.back() / pixel - 1.0));
      ++compared;
    }
  EXPECT_GT(compared, 4);
  std::printf("light along picked rays against their pixels: worst %.2e (%d rays, 64 samples a step)\n", worst,
              compared);
}

TEST(AppLayer, ATorusFrameIsTheLibrarysMinoTimeTracersFrame) {
  // The tools' torus (Kerr a = 0.9, r_in 6, peak 10, grey) against the library's tracer on the same camera.
  const app::RenderRequest q = small_torus_request();
  const app::RenderResult r = app::render(q);
  EXPECT_EQ(r.report.tracer, "kerr-mino");
  EXPECT_EQ(r.report.stats.failures(), 0);
  const app::CheckedRequest checked = app::check_request(q);
  const KerrMetric metric{1.0, 0.9};
  const PolishDoughnut<KerrMetric> torus(metric, 6.0, 10.0, 3.0, 1.0, 0.5);
  const KerrMinoMediumTracer<Verner65, IController, PolishDoughnut<KerrMetric>> tracer(
      metric, torus, checked.settings, checked.camera.tetrad().e[0], 1.0);
  // Its light split by image order (trace/emission_system.hpp): each order's channel the tracer's piece, the
  // intensity their sum (the same float additions) and the tracer's intensity up to that rounding, the order
  // channel the ray's crossings; the report's flux by order sums to its flux.
  const auto& intensity = r.image.channel("intensity");
  const auto& order = r.image.channel("order");
  double lit = 0.0;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) {
      const MediumSample s = tracer.trace(checked.camera.pixel_state(x, y));
      const std::size_t i = r.image.index(x, y);
      float sum = 0.0f;
      for (std::size_t n = 0; n < kOrderIntensityChannels.size(); ++n) {
        const float piece = r.image.channel(kOrderIntensityChannels[n])[i];
        EXPECT_EQ(piece, static_cast<float>(s.intensity_by_order[n]));
        sum += piece;
      }
      EXPECT_EQ(intensity[i], sum);
      EXPECT_NEAR(intensity[i], s.intensity, 1e-6 * s.intensity);
      EXPECT_EQ(order[i], static_cast<float>(s.order));
      lit += s.intensity > 0.0 ? 1.0 : 0.0;
    }
  EXPECT_GT(lit, 10.0);  // the torus is in the frame
  ASSERT_TRUE(r.report.flux_by_order.has_value());
  const std::array<double, 4>& by_order = *r.report.flux_by_order;
  EXPECT_NEAR(by_order[0] + by_order[1] + by_order[2] + by_order[3], *r.report.flux, 1e-6 * *r.report.flux);
  std::printf("torus flux by order: %.4g %.4g %.4g %.4g\n", by_order[0], by_order[1], by_order[2], by_order[3]);
  EXPECT_GT(by_order[0], by_order[1]);  // the photon ring is fainter than the direct image, and lit
  EXPECT_GT(by_order[1], 0.0);
  EXPECT_EQ(r.image.metadata.at("medium"), "polish-doughnut");
  EXPECT_NEAR(std::stod(r.image.metadata.at("torus_outer")), torus.outer_radius(), 1e-9);
  EXPECT_GT(*r.report.flux, 0.0);
  // A torus that cannot exist, refused before any work, naming the radii.
  app::RenderRequest open = q;
  open.torus_inner = 12.0;
  expect_refused("--torus-inner 12 --torus-peak 10: need 0 < r_in < r_c", [&] { (void)app::check_request(open); });
  app::RenderRequest ks = q;
  ks.metric.chart = "ks";
  expect_refused("--scene torus flows around a Kerr hole in Boyer-Lindquist coordinates",
                 [&] { (void)app::check_request(ks); });
  expect_refused("--torus-opacity applies only with --scene torus", [&] {
    (void)app::read_render_request(Texts(std::map<std::string, std::string>{{"torus-opacity", "2"}}));
  });
}
