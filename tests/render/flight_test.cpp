// Camera flights: the camera path against exact timelike geodesics (circular orbit, radial
// infall from rest: Misner, Thorne & Wheeler 25.4 cycloid), conserved E and L on the seed orbit, the moving
// camera's tetrad against the static observer boosted to the same 4-velocity, a flight's frames bit for bit equal
// to single renders at the same camera states, and the flight's files (names, resume test, CSV paths).
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/flight_path.hpp"
#include "grtrace/observer/timelike_start.hpp"
#include "grtrace/observer/worldline.hpp"
#include "grtrace/render/flight.hpp"
#include "grtrace/render/flight_files.hpp"
#include "grtrace/render/frame_files.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/tsitouras54.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <unistd.h>

// In a namespace of its own: the render tests compile together in unity batches (tests/render/CMakeLists.txt).
namespace flight_test {

namespace {

using namespace grtrace;
constexpr double pi = std::numbers::pi;

// Circular geodesic of Schwarzschild: r constant, u^t = 1/sqrt(1 - 3M/r), phi = Omega t with Omega = sqrt(M/r^3).
TEST(Worldline, CircularOrbitStaysOnTheExactOrbit) {
  const double M = 1.0, r = 10.0;
  const SchwarzschildMetric metric{M};
  const TimelikeStart start = circular_orbit_start(metric, r);
  const double ut = 1.0 / std::sqrt(1.0 - 3.0 * M / r), omega = std::sqrt(M / (r * r * r));
  EXPECT_NEAR(start.u[0], ut, 1e-14);
  EXPECT_NEAR(start.u[3], ut * omega, 1e-15);
  const double period_tau = 2.0 * pi / (ut * omega);
  const Worldline w = sample_worldline(metric, start, period_tau / 40.0, 81);  // two revolutions
  ASSERT_TRUE(w.complete());
  ASSERT_EQ(w.samples.size(), 81u);
  for (const WorldlineSample& s : w.samples) {
    EXPECT_NEAR(s.x[1], r, 1e-10 * r) << "tau " << s.tau;
    EXPECT_NEAR(s.x[0], ut * s.tau, 1e-10 * (1.0 + ut * s.tau)) << "tau " << s.tau;
    EXPECT_NEAR(s.x[3], ut * omega * s.tau, 1e-10) << "tau " << s.tau;
    // double(pi / 2) lies 6.1e-17 off the equator, so theta'' = sin cos (u^phi)^2 ~ 9e-20 pulls it, below theta's
    // resolution (ulp 2.2e-16) for the restoring force to show: ~1/2 theta'' tau^2 = 5e-15 after two revolutions,
    // plus round-off of the same size (1.1e-14 measured with fused multiply-adds, 4.7e-15 without).
    EXPECT_NEAR(s.x[2], pi / 2.0, 1e-13);
    EXPECT_NEAR(inner_product(metric, s.x, s.u, s.u), 1.0, 1e-11);
  }
  // The proper time of one revolution, found by the event the tool's automatic frame step uses.
  const auto turn = proper_time_until(metric, start, revolution_event(start));
  ASSERT_TRUE(turn);
  EXPECT_NEAR(*turn, period_tau, 1e-8 * period_tau);
}

// Radial fall from rest at r0: r = r0 (1 + cos eta) / 2, tau = sqrt(r0^3 / 8M) (eta + sin eta).
TEST(Worldline, RadialInfallFollowsTheCycloid) {
  const double M = 1.0, r0 = 20.0;
  const SchwarzschildMetric metric{M};
  const TimelikeStart start = radial_infall_start(metric, r0);
  const double scale = std::sqrt(r0 * r0 * r0 / (8.0 * M));
  // Proper time to r = 2.2 M from the cycloid, and the path sampled up to just before it.
  auto eta_at_r = [&](double r) { return std::acos(2.0 * r / r0 - 1.0); };
  const double eta_end = eta_at_r(2.2 * M);
  const double tau_end = scale * (eta_end + std::sin(eta_end));
  const auto fall = proper_time_until(metric, start, radius_event(metric, 2.2 * M));
  ASSERT_TRUE(fall);
  EXPECT_NEAR(*fall, tau_end, 1e-8 * tau_end);
  const int n = 30;
  const Worldline w = sample_worldline(metric, start, tau_end / (n - 1), n);
  ASSERT_TRUE(w.complete());
  for (const WorldlineSample& s : w.samples) {
    double eta = 0.0;  // Newton on tau(eta) = s.tau
    for (int it = 0; it < 60; ++it) eta -= (scale * (eta + std::sin(eta)) - s.tau) / (scale * (1.0 + std::cos(eta)));
    EXPECT_NEAR(s.x[1], 0.5 * r0 * (1.0 + std::cos(eta)), 1e-9 * r0) << "tau " << s.tau;
    EXPECT_EQ(s.x[3], 0.0);
  }
  // Asked beyond the stop radius (just outside the horizon guard): fewer samples, stopped as captured.
  const Worldline past = sample_worldline(metric, start, 2.0 * tau_end / (n - 1), n);
  EXPECT_FALSE(past.complete());
  EXPECT_EQ(*past.stopped, RayStatus::captured);
  EXPECT_LT(past.samples.size(), static_cast<std::size_t>(n));
  for (const WorldlineSample& s : past.samples) EXPECT_GT(s.x[1], 2.0 * M);
}

// The seed report's orbit: E = (1 - 2M/r) u^t and L = r^2 u^phi conserved, g(u, u) = 1, a precessing ellipse
// between its periapsis (~39 M) and r = 100 M.
TEST(Worldline, SeedOrbitConservesEnergyAndAngularMomentum) {
  const SchwarzschildMetric metric{1.0};
  const TimelikeStart start = seed_orbit_start(metric);
  EXPECT_EQ(start.x[1], 100.0);
  EXPECT_EQ(start.u[3], 0.00075);
  const auto turn = proper_time_until(metric, start, revolution_event(start));
  ASSERT_TRUE(turn);
  const Worldline w = sample_worldline(metric, start, *turn / 300.0, 300);
  ASSERT_TRUE(w.complete());
  const double E0 = (1.0 - 2.0 / 100.0) * start.u[0], L0 = 100.0 * 100.0 * start.u[3];
  double r_min = 1e300;
  for (const WorldlineSample& s : w.samples) {
    const double r = s.x[1];
    r_min = std::min(r_min, r);
    EXPECT_NEAR((1.0 - 2.0 / r) * s.u[0] / E0 - 1.0, 0.0, 1e-11);
    EXPECT_NEAR(r * r * s.u[3] / L0 - 1.0, 0.0, 1e-11);
    EXPECT_NEAR(inner_product(metric, s.x, s.u, s.u), 1.0, 1e-11);
  }
  EXPECT_GT(r_min, 35.0);
  EXPECT_LT(r_min, 45.0);
  EXPECT_LT(w.samples.back().x[3], 2.0 * pi);
  EXPECT_GT(w.samples.back().x[3], 2.0 * pi * 0.95);
}

// flight_path: the automatic frame step (one revolution over the frames; the fall to 1.1 r_h over frames - 1)
// and its refusals, each before any rendering.
TEST(FlightPath, AutomaticStepsAndRefusals) {
  const SchwarzschildMetric metric{1.0};
  FlightPathSpec spec;
  spec.frames = 30;
  const Worldline seed = flight_path(metric, spec);
  ASSERT_EQ(seed.samples.size(), 30u);
  const auto turn = proper_time_until(metric, seed_orbit_start(metric), revolution_event(seed_orbit_start(metric)));
  ASSERT_TRUE(turn);
  EXPECT_DOUBLE_EQ(frame_step(seed), *turn / 30.0);
  spec.kind = "infall";
  spec.r = 20.0;
  spec.frames = 11;
  const Worldline fall = flight_path(metric, spec);
  ASSERT_EQ(fall.samples.size(), 11u);
  EXPECT_NEAR(fall.samples.back().x[1], 2.2, 1e-8);  // the last frame at 1.1 r_h
  auto refused = [&](FlightPathSpec bad, const std::string& says) {
    try {
      (void)flight_path(metric, bad);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  FlightPathSpec bad;
  bad.kind = "spiral";
  refused(bad, "unknown flight 'spiral'");
  bad = {};
  bad.frames = 0;
  refused(bad, "--frames must be in 1 .. 100000");
  bad = {};
  bad.dtau = -1.0;
  refused(bad, "--frame-dtau must be >= 0");
  bad = {};
  bad.kind = "circular";
  bad.r = 2.5;
  refused(bad, "no timelike circular orbit at r = 2.5");
  bad = {};
  bad.sky_radius = 90.0;
  refused(bad, "frame 0 is at r = 100, outside the sky sphere");
  bad = {};
  bad.kind = "orbit";
  bad.r = 20.0;
  bad.dphi_dtau = 0.0;  // radial fall: no revolution to spread the frames over
  refused(bad, "does not complete a revolution");
  bad = {};
  bad.kind = "infall";
  bad.r = 20.0;
  bad.frames = 5;
  bad.dtau = 40.0;
  refused(bad, "the camera's path ends (captured");
}

// make_moving_camera's look rule: look and up are components along the moving observer's own axes. With no
// component along the motion this is make_camera's static observer boosted to the same 4-velocity (on a circular
// orbit the local speed is v = sqrt(M / (r - 2M)) along +phi); a component along the motion is read in the moving
// frame (make_camera reads it in the static frame, where it is shorter by the Lorentz factor).
TEST(MovingCamera, LooksAlongItsOwnAxesAndEqualsTheBoostedStaticCamera) {
  const SchwarzschildMetric metric{1.0};
  const double r = 12.0;
  const TimelikeStart s = circular_orbit_start(metric, r, +1, 0.4);
  CameraView view;
  view.look = Vec3(-1.0, 0.2, 0.0);
  view.width = 64;
  view.height = 48;
  view.fov_degrees = 70.0;
  const Camera moving = make_moving_camera(metric, s.x, s.u, view);
  CameraSpec spec;
  spec.position = s.x;
  spec.velocity = Vec3(0.0, 0.0, std::sqrt(1.0 / (r - 2.0)));
  spec.look = view.look;
  spec.up = view.up;
  spec.width = view.width;
  spec.height = view.height;
  spec.fov_degrees = view.fov_degrees;
  const Camera boosted = make_camera(metric, spec);
  for (int a = 0; a < 4; ++a)
    EXPECT_LT((moving.tetrad().e[static_cast<std::size_t>(a)] - boosted.tetrad().e[static_cast<std::size_t>(a)]).norm(),
              1e-12)
        << "e" << a;
  EXPECT_LT((moving.tetrad().e[0] - s.u).norm(), 1e-15);
  // A look with a component along the motion: the forward vector has exactly those components on the moving axes.
  view.look = Vec3(-1.0, 0.2, 0.3);
  const Camera oblique = make_moving_camera(metric, s.x, s.u, view);
  const Mat4 g = metric.metric(s.x);
  const ObserverFrame axes(g, s.u);
  const Vec3 want = view.look.normalized();
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(-oblique.tetrad().e[1].dot(g * axes.e[static_cast<std::size_t>(i + 1)]), want[i], 1e-14) << i;
}

TraceSettings flight_settings() {
  TraceSettings s;
  s.integrator.tolerance = {1e-9, 1e-11};
  s.escape_radius = 400.0;
  return s;
}

// A flight adds nothing between frames: every frame equals render_frame of its camera with the tracer auto picks
// (the planar tracer here: Schwarzschild, disk scene, adaptive control), every channel bit for bit.
TEST(Flight, FramesEqualSingleRendersBitForBit) {
  const SchwarzschildMetric metric{1.0};
  StandardSceneSpec spec;
  spec.name = "disk";
  const DiskScene scene = disk_scene(spec);
  const TimelikeStart start = seed_orbit_start(metric);
  const Worldline path = sample_worldline(metric, start, 900.0, 3);
  ASSERT_TRUE(path.complete());
  CameraView view;
  view.look = Vec3(-1.0, 0.1, 0.0);
  view.width = 40;
  view.height = 28;
  view.fov_degrees = 40.0;
  const auto cameras = flight_cameras(metric, path, view);
  const TraceSettings settings = flight_settings();
  RenderOptions options;
  options.progress = ProgressMode::never;
  std::vector<Frame> flown;
  std::vector<std::string> tracers;
  const FlightStats stats = render_flight(
      cameras, auto_tracer_per_camera<Tsitouras54, IController>(metric, settings, AngleCorrection::exact, scene, 512),
      [](int) { return false; },
      [&](int i, Frame&& f, const TracerReport& report) {
        EXPECT_EQ(i, static_cast<int>(flown.size()));
        tracers.push_back(report.name);
        EXPECT_GT(report.table_rays, 0);
        flown.push_back(std::move(f));
      },
      options);
  ASSERT_EQ(flown.size(), 3u);
  EXPECT_EQ(stats.rendered, 3);
  EXPECT_EQ(stats.skipped, 0);
  EXPECT_EQ(stats.rays, 3L * 40 * 28);
  EXPECT_EQ(stats.count(RayStatus::max_steps) + stats.count(RayStatus::step_underflow) +
                stats.count(RayStatus::non_finite),
            0);
  long hits = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(tracers[i], "planar");
    with_auto_tracer<Tsitouras54, IController>(metric, settings, cameras[i], AngleCorrection::exact, scene, 512,
                                               [&](const auto& tracer) {
                                                 const Frame single = render_frame(cameras[i], tracer, options);
                                                 for (const std::string& name : single.image.channel_names()) {
                                                   const auto& a = single.image.channel(name);
                                                   const auto& b = flown[i].image.channel(name);
                                                   ASSERT_EQ(a.size(), b.size());
                                                   EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0)
                                                       << "frame " << i << " channel " << name;
                                                 }
                                               });
    hits += flown[i].stats.count(RayStatus::hit);
  }
  EXPECT_GT(hits, 0);  // the disk is in view: the frames are not trivially equal backgrounds
  // Each frame records its own camera (the camera moves along the orbit).
  EXPECT_NE(flown[0].image.metadata.at("camera_position"), flown[2].image.metadata.at("camera_position"));
}

// skip(i) leaves frames out: the sink never sees them, the counts say so.
TEST(Flight, SkippedFramesAreNotRendered) {
  const SchwarzschildMetric metric{1.0};
  StandardSceneSpec spec;
  const BackgroundScene scene = background_scene(spec);
  const Worldline path = sample_worldline(metric, circular_orbit_start(metric, 30.0), 50.0, 4);
  CameraView view;
  view.width = view.height = 8;
  const auto cameras = flight_cameras(metric, path, view);
  RenderOptions options;
  options.progress = ProgressMode::never;
  std::vector<int> seen;
  const FlightStats stats = render_flight(
      cameras, auto_tracer_per_camera<Tsitouras54, IController>(metric, flight_settings(), AngleCorrection::exact, scene, 64),
      [](int i) { return i % 2 == 0; }, [&](int i, Frame&&, const TracerReport&) { seen.push_back(i); }, options);
  EXPECT_EQ(seen, (std::vector<int>{1, 3}));
  EXPECT_EQ(stats.skipped, 2);
  EXPECT_EQ(stats.rendered, 2);
  // A sink that fails (a full disk) stops the flight: the error reaches the caller, no later frame is written.
  seen.clear();
  EXPECT_THROW(render_flight(
                   cameras,
                   auto_tracer_per_camera<Tsitouras54, IController>(metric, flight_settings(), AngleCorrection::exact,
                                                                    scene, 64),
                   [](int) { return false; },
                   [&](int i, Frame&&, const TracerReport&) {
                     seen.push_back(i);
                     if (i == 1) throw std::runtime_error("disk full");
                   },
                   options),
               std::runtime_error);
  EXPECT_EQ(seen, (std::vector<int>{0, 1}));
}

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    char tmpl[] = "/tmp/grtrace-flight-XXXXXX";
    path = ::mkdtemp(tmpl);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
};

TEST(FlightFiles, NumberedNamesAndPattern) {
  EXPECT_EQ(flight_frame_path("out/orbit.exr", 7, 300).string(), "out/orbit-0007.exr");
  EXPECT_EQ(flight_frame_path("orbit.exr", 12345, 20000).string(), "orbit-12345.exr");
  EXPECT_EQ(flight_frame_path("a.b/x.exr", 3, 5).string(), "a.b/x-0003.exr");
  EXPECT_EQ(flight_png_pattern("dir%/o%k.png", 300), "dir%%/o%%k-%04d.png");
  EXPECT_EQ(flight_png_pattern("o.png", 300), "o-%04d.png");
}

// A frame counts as done only when its EXR reads back whole with the same signature and its PNG is whole, of the
// same size.
TEST(FlightFiles, DoneOnlyWhenWholeWithTheSameSignature) {
  TempDir dir;
  const auto exr = dir.path / "f-0000.exr", png = dir.path / "f-0000.png";
  const std::string sig = flight_signature({{"scene", "disk"}, {"width", "8"}});
  EXPECT_NE(sig, flight_signature({{"scene", "disk"}, {"width", "9"}}));
  EXPECT_FALSE(flight_frame_done(exr, png, sig));
  Image image(8, 4);
  image.metadata["flight_signature"] = sig;
  OutputSet set;
  write_exr_and_preview(set, exr, png, image);
  set.commit();
  EXPECT_TRUE(flight_frame_done(exr, png, sig));
  EXPECT_FALSE(flight_frame_done(exr, png, flight_signature({{"scene", "sky"}})));
  std::string whole_png(static_cast<std::size_t>(std::filesystem::file_size(png)), '\0');
  std::ifstream(png, std::ios::binary).read(whole_png.data(), static_cast<std::streamsize>(whole_png.size()));
  ASSERT_EQ(grtrace::whole_png_size(png), (std::array<int, 2>{8, 4}));
  std::filesystem::remove(png);
  EXPECT_FALSE(flight_frame_done(exr, png, sig));
  std::ofstream(png) << "x";
  EXPECT_FALSE(flight_frame_done(exr, png, sig)) << "not a PNG";
  for (const std::size_t cut : {std::size_t{20}, whole_png.size() / 2, whole_png.size() - 1}) {
    std::ofstream(png, std::ios::binary | std::ios::trunc) << whole_png.substr(0, cut);
    EXPECT_FALSE(flight_frame_done(exr, png, sig)) << "a PNG cut at byte " << cut;
  }
  std::ofstream(png, std::ios::binary | std::ios::trunc) << whole_png << "trailing";
  EXPECT_FALSE(flight_frame_done(exr, png, sig)) << "bytes after IEND";
  write_png_preview(png, Image(8, 5));
  EXPECT_FALSE(flight_frame_done(exr, png, sig)) << "another frame's size";
  std::ofstream(png, std::ios::binary | std::ios::trunc) << whole_png;
  EXPECT_TRUE(flight_frame_done(exr, png, sig));
  std::filesystem::resize_file(exr, std::filesystem::file_size(exr) / 2);  // a damaged EXR is not done
  EXPECT_FALSE(flight_frame_done(exr, png, sig));
}

TEST(FlightFiles, CameraPathCsvRoundTripsAndRefusesBadRows) {
  TempDir dir;
  const SchwarzschildMetric metric{1.0};
  const Worldline w = sample_worldline(metric, seed_orbit_start(metric), 100.0, 5);
  const auto csv = dir.path / "path.csv";
  std::ofstream(csv) << worldline_csv(w);
  const Worldline back = read_worldline_csv(csv);
  ASSERT_EQ(back.samples.size(), w.samples.size());
  for (std::size_t i = 0; i < w.samples.size(); ++i) {
    EXPECT_EQ(back.samples[i].tau, w.samples[i].tau);
    EXPECT_EQ(back.samples[i].x, w.samples[i].x);
    EXPECT_EQ(back.samples[i].u, w.samples[i].u);
  }
  EXPECT_NO_THROW(check_worldline(metric, back));
  auto refused = [&](const std::string& text, const std::string& says) {
    std::ofstream(csv) << text;
    try {
      WorldlineSource source;
      const Worldline read = read_worldline_csv(csv, &source);
      check_worldline(metric, read, &source);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  const std::string header = "tau,t,r,theta,phi,ut,ur,utheta,uphi\n";
  refused(header, "no camera states");
  refused(header + "0,0,100,1.5707963267948966,0,1.0,0,0\n", "line 2: need 9 numbers");
  refused(header + "0,0,100,1.57,0,x,0,0,0\n", "line 2: 'x' is not a number");
  // Errors found after reading name the file's line too (comments and blank lines counted).
  const std::string at_line_4 = csv.string() + " line 4: ";
  const std::string first = "0,0,100,1.57,0,1.0101525445522108,0,0,0\n";
  refused(header + "# comment\n" + "0,0,100,1.57,0,1.2,0,0,0\n", csv.string() + " line 3: g(u, u)");  // not unit
  refused(header + first + "\n" + "1,0,1.5,1.57,0,1,0,0,0\n", at_line_4 + "r = 1.5");        // inside the horizon
  refused(header + first + "\n" + "1,0,100,0,0,1.0101525445522108,0,0,0\n", at_line_4 + "theta = 0");  // the axis
  refused(header + first + "\n" + "1,0,100,3.1415926535897931,0,1.0101525445522108,0,0,0\n",
          at_line_4 + "theta = 3.14");
  // The numbers the command line takes (blanks around, hexadecimal, a subnormal), and its refusals' wording.
  refused(header + first + "1,0,100,1.57,0,1.0101525445522108,0,0,1e400\n", "line 3: '1e400' is not finite");
  refused(header + first + "1,0,100,1.57,0,1.0101525445522108,0,0,nan\n", "line 3: 'nan' is not finite");
  std::ofstream(csv) << header << " 0x0p0 , 0,100, 1.57,0,1.0101525445522108,0,0,1e-320\n";
  EXPECT_EQ(read_worldline_csv(csv).samples.at(0).u[3], 1e-320);
  refused(header + "1,0,100,1.57,0,1.0101525445522108,0,0,0\n0,0,100,1.57,0,1.0101525445522108,0,0,0\n",
          "line 3: proper time tau must increase");
  refused("", "no camera states");
  EXPECT_THROW(read_worldline_csv(dir.path / "missing.csv"), std::invalid_argument);
  // Bounded readers: a line, the rows (one per frame), the file, and no device (/dev/zero never ends).
  refused(header + std::string(5000, '1') + "\n", "line 2: longer than 4096 bytes");
  {
    std::ofstream out(csv);
    out << header;
    for (std::size_t i = 0; i <= kMaxWorldlineRows; ++i) out << i << ",0,100,1.57,0,1.0101525445522108,0,0,0\n";
  }
  try {
    (void)read_worldline_csv(csv);
    ADD_FAILURE() << "100 001 rows accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("line 100002: more than 100000 camera states"), std::string::npos)
        << e.what();
  }
  std::filesystem::resize_file(csv, kMaxWorldlineFileBytes + 1);
  EXPECT_THROW(read_worldline_csv(csv), std::invalid_argument);
  try {
    (void)read_worldline_csv("/dev/zero");
    ADD_FAILURE() << "/dev/zero accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("is not a regular file"), std::string::npos) << e.what();
  }
}

}  // namespace

}  // namespace flight_test
