// The CUDA backend (include/grtrace/gpu/gpu_frame.cuh, app/src/gpu_tracers.hpp), compiled by nvcc; the kernels
// are the application library's (app::trace_on_gpu), not instantiated again here.
//   - On any machine: the host pass of this nvcc build runs the same source a GPU thread runs (trace_quietly) and
//     draws the CPU build's frame (the application layer, compiled by the C++ compiler) bit for bit: one source, the
//     same arithmetic (no contraction, fused where core/mul_add.hpp says).
//   - With a CUDA device (else skipped, saying why): the GPU's frames against the CPU's: statuses identical, the
//     object channel identical but for silhouette pixels (counted: a ray grazing an edge may end on either side
//     when the last bits of its path differ), redshift, sky direction, hit point and hit radius within 1e-9 (not a
//     captured ray's end on a Kerr horizon: see outcome_comparison.hpp); the Kerr disk frame's hit radius at
//     rtol 1e-12 within 1e-6 of the CPU's rkf78 + I at rtol 1e-12; one frame with tsit5 + PI, whose own interpolant
//     brackets the disk's crossing.
//   - GpuProbe (first, with a device): one ray integrated by one GPU thread and by the host from the same bytes,
//     step by step (lambda, step, state), for the general tracer's system and the Kerr Mino system (gpu_probe.cuh);
//     a departure is printed at the first step where it happens, so a GPU that draws wrong frames says where in one
//     run. Then one corner pixel of each frame through the application layer's kernels.
// The frame tests cap each ray at kGpuTestMaxSteps (on both sides alike): a GPU that loses its rays fails in
// seconds instead of integrating every ray to the default 100000 steps.
#include "../common/quiet_trace.hpp"
#include "gpu_probe.cuh"
#include "outcome_comparison.hpp"
#include "gpu_tracers.hpp"  // app/src: the application library's kernels (trace_on_gpu), instantiated there only

#include "grtrace/app/front_door.hpp"
#include "grtrace/gpu/gpu_frame.cuh"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace grtrace;
using gpu_probe::probe_camera;

/// Every ray of these tests ends within this many steps on the CPU (they take 15-25 on average).
constexpr int kGpuTestMaxSteps = 20000;

/// The application library's checked request for a frame of `camera` (the tools' default method, on the CPU).
app::CheckedRequest request(const std::string& metric, const std::string& scene, const std::string& tracer,
                            const Camera& camera) {
  app::RenderRequest q;
  q.metric.name = metric;
  q.metric.spin = metric == "kerr" ? 0.9 : 0.0;
  q.scene = scene;
  q.tracer = tracer;
  q.sky_radius = 400.0;
  q.method.max_steps = kGpuTestMaxSteps;
  q.camera.r = 30.0;
  q.camera.width = q.camera.height = 1;
  q.device = "cpu";
  return app::with_camera(app::check_request(q), camera);
}

/// The frame the application library draws for a checked request.
Frame app_frame(const app::CheckedRequest& c) {
  app::RenderResult r = app::FrameRenderer::create(c)->render();
  return Frame{std::move(r.image), r.report.stats};
}

TEST(GpuNvccHostPass, DrawsTheCpuBuildsFrameBitForBit) {
  const KerrMetric kerr{1.0, 0.9};
  const Camera camera = probe_camera(kerr, 50.0, 80.0, 60.0, 24);
  const app::CheckedRequest q = request("kerr", "disk", "kerr-mino", camera);
  const auto tracer = make_kerr_mino_tracer<Fehlberg78, IController>(kerr, q.settings, q.correction, disk_scene(q.scene));
  const Frame here = render_frame_traced_by(camera, tracer, [&](int width, int height) {
    return testing_support::trace_quietly_here(camera, tracer, width, height);
  });
  const Frame cpu = app_frame(q);
  for (const char* c : Image::kStandardChannels) {
    const auto& x = here.image.channel(c);
    const auto& y = cpu.image.channel(c);
    EXPECT_EQ(std::memcmp(x.data(), y.data(), x.size() * sizeof(float)), 0) << "channel " << c;
  }
}

/// The kernel's thread-to-pixel map (gpu/warp_tiles.hpp), on the host: every pixel of the block is traced by exactly
/// one thread, a warp's 32 threads lie in one 4 x 8 tile (lane = column + 4 x row within it), and no warp is launched
/// that holds no pixel; for sides that are and are not multiples of the tile's.
TEST(GpuNvccHostPass, WarpTilesCoverEveryPixelOnceAndKeepEachWarpInOneTile) {
  using gpu::PixelIndex;
  using gpu::WarpTiles;
  const std::pair<int, int> sizes[] = {{1, 1}, {3, 5}, {4, 8}, {7, 9}, {33, 17}, {512, 512}, {1024, 513}};
  for (const auto& [width, height] : sizes) {
    const WarpTiles tiles(width, height);
    std::vector<int> traced(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
    const long threads = tiles.thread_count();
    ASSERT_EQ(threads % WarpTiles::warp_size, 0);
    long padding = 0;
    for (long warp = 0; warp < threads / WarpTiles::warp_size; ++warp) {
      PixelIndex first;
      tiles.pixel_of(warp * WarpTiles::warp_size, first);
      int in_block = 0;
      for (int lane = 0; lane < WarpTiles::warp_size; ++lane) {
        PixelIndex p;
        const bool inside = tiles.pixel_of(warp * WarpTiles::warp_size + lane, p);
        EXPECT_EQ(p.col, first.col + lane % WarpTiles::tile_width) << width << "x" << height << " warp " << warp;
        EXPECT_EQ(p.row, first.row + lane / WarpTiles::tile_width) << width << "x" << height << " warp " << warp;
        EXPECT_EQ(inside, p.col < width && p.row < height);
        if (!inside) {
          ++padding;
          continue;
        }
        ++in_block;
        ++traced[static_cast<std::size_t>(p.row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(p.col)];
      }
      EXPECT_GT(in_block, 0) << width << "x" << height << ": warp " << warp << " traces no pixel";
    }
    EXPECT_EQ(std::count(traced.begin(), traced.end(), 1), static_cast<long>(traced.size()))
        << width << "x" << height << ": a pixel traced twice or never";
    EXPECT_EQ(padding, threads - static_cast<long>(traced.size()));
    for (long t = threads; t < threads + 2 * WarpTiles::warp_size; ++t) {  // a launch's last block runs past the end
      PixelIndex p;
      EXPECT_FALSE(tiles.pixel_of(t, p)) << width << "x" << height << ": thread " << t << " of " << threads;
    }
    EXPECT_EQ(tiles.width(), width);
  }
  PixelIndex p;
  ASSERT_TRUE(WarpTiles(1024, 1024).pixel_of(32 + 5, p));  // the second warp's sixth thread
  EXPECT_EQ(p.col, 5);
  EXPECT_EQ(p.row, 1);
}

/// Skips the test when there is no CUDA device, saying why.
#define GRTRACE_NEED_GPU()                                                                          \
  do {                                                                                              \
    const app::GpuStatus& gpu = app::gpu_status();                                                  \
    if (!gpu.present) GTEST_SKIP() << "no GPU to compare with: " << gpu.why_not;                    \
  } while (false)

using namespace gpu_probe;

/// GpuProbe's check: the device's trail is the host's (gpu_probe.cuh).
template <class Probe>
void expect_same_trail(const char* what, const Probe& probe) {
  RayTrail host;
  probe(host);
  std::string error;
  const RayTrail gpu = trail_on_gpu(probe, &error);
  EXPECT_TRUE(error.empty()) << error;
  for (const std::string& problem : compare_trails(what, host, gpu)) ADD_FAILURE() << problem;
}

/// The corner pixels GpuProbe sends through the application layer's kernels (pixel (0, 0) of a 2x2 camera placed as
/// the probes' frames; its ray escapes), with the tracers the tools would use for them.
Camera main_corner() { return probe_camera(SchwarzschildMetric{1.0}, 200.0, 90.0, 90.0, 2); }
Camera kerr_corner() { return probe_camera(KerrMetric{1.0, 0.9}, 50.0, 80.0, 60.0, 2); }
auto main_corner_tracer() {
  return make_general_tracer<Fehlberg78, IController>(SchwarzschildMetric{1.0}, probe_settings(),
                                                      AngleCorrection::exact, background_scene(StandardSceneSpec{}));
}
auto kerr_corner_tracer() {
  StandardSceneSpec disk;
  disk.name = "disk";
  return make_kerr_mino_tracer<Fehlberg78, IController>(KerrMetric{1.0, 0.9}, probe_settings(), AngleCorrection::exact,
                                                        disk_scene(disk));
}

/// The probes' own bookkeeping, on the host (nvcc's host pass): each records the ray's first steps in order; the
/// main frame's pixel escapes, the Kerr pixel near the middle of the picture falls into the hole.
TEST(GpuNvccHostPass, ProbesRecordTheRaysStepsInOrder) {
  RayTrail general, mino;
  main_frame_probe()(general);
  kerr_frame_probe()(mino);
  for (const RayTrail* t : {&general, &mino}) {
    EXPECT_GT(t->accepted, 3);
    // Every accepted step but the last, which ends on the sky sphere or the horizon guard (theta_end < 1).
    EXPECT_EQ(t->recorded, std::min(t->accepted - 1, kTrailSteps));
    double lambda = 0.0;
    for (int i = 0; i < t->recorded; ++i) {
      EXPECT_GT(t->steps[i].h, 0.0) << i;
      EXPECT_DOUBLE_EQ(t->steps[i].lambda, lambda + t->steps[i].h) << i;
      lambda = t->steps[i].lambda;
    }
    EXPECT_NEAR(t->inverse_roots[0], std::pow(0.37, -1.0 / 8.0), 1e-15);
  }
  EXPECT_EQ(general.status, static_cast<int>(RayStatus::escaped));
  EXPECT_EQ(mino.status, static_cast<int>(RayStatus::captured));
  // The corner pixels GpuProbe sends through the application layer's kernels escape.
  EXPECT_EQ(main_corner_tracer().trace(main_corner().pixel_state(0, 0)).status, RayStatus::escaped);
  EXPECT_EQ(kerr_corner_tracer().trace(kerr_corner().pixel_state(0, 0)).status, RayStatus::escaped);
  EXPECT_EQ(general.start.state[1], 200.0);             // r of the camera
  EXPECT_NEAR(mino.start.state[0], 1.0 / 50.0, 1e-15);  // u = 1/r of the camera
}

TEST(GpuProbe, OneRayStepByStepAsOnTheHost) {
  GRTRACE_NEED_GPU();
  expect_same_trail("Schwarzschild, geodesic equation", main_frame_probe());
  expect_same_trail("Kerr, Mino-time system", kerr_frame_probe());
  // A corner pixel of each frame (its ray escapes) through the application layer's kernels, the tracers built on the
  // host and copied to the device byte for byte: a departure here and none above points at the copy or the scene,
  // not the integration.
  const Camera main_camera = main_corner(), kerr_camera = kerr_corner();
  const auto general = main_corner_tracer();
  const auto mino = kerr_corner_tracer();
  const auto compare = [](const char* what, const RayOutcome& g, const RayOutcome& c) {
    std::printf("[gpu] %s, one pixel: device status %d, %d steps, r %.9g; CPU status %d, %d steps, r %.9g\n", what,
                static_cast<int>(g.status), g.steps, g.radius, static_cast<int>(c.status), c.steps, c.radius);
    EXPECT_EQ(g.status, c.status) << what;
    EXPECT_EQ(g.steps, c.steps) << what;
    EXPECT_EQ(g.order, c.order) << what;
  };
  compare("app layer, Schwarzschild general", app::trace_on_gpu(main_camera, general, 1, 1, nullptr)[0],
          general.trace(main_camera.pixel_state(0, 0)));
  compare("app layer, Kerr disk kerr-mino", app::trace_on_gpu(kerr_camera, mino, 1, 1, nullptr)[0],
          mino.trace(kerr_camera.pixel_state(0, 0)));
}

/// A pixel where the GPU's outcome departs from the CPU's.
struct Departure {
  int col = -1, row = -1;
  double sky = 0.0;
};

inline void print_outcome(const char* side, const RayOutcome& o) {
  std::printf("  %s status %d object %d steps %d where (%.17g, %.17g) r %.17g redshift %.17g\n  %s end state", side,
              static_cast<int>(o.status), o.object, o.steps, o.where.theta, o.where.phi, o.radius, o.redshift, side);
  for (int i = 0; i < 8; ++i) std::printf(" %.17g", o.state[i]);
  std::printf("\n");
}

/// The GPU's outcomes (gpu, the camera's pixels row by row) against the CPU's trace of the same pixels, in double
/// precision (see the top of this file and outcome_comparison.hpp). Returns the pixel whose sky direction departs
/// most (the first few beyond 1e-9 are printed, both sides).
template <class Tracer>
Departure expect_gpu_outcomes_match_cpu(const char* what, const Camera& camera, const Tracer& tracer,
                                        const std::vector<RayOutcome>& gpu) {
  const int width = camera.width(), height = camera.height();
  const std::vector<RayOutcome> cpu = testing_support::trace_quietly_here(camera, tracer, width, height);
  EXPECT_EQ(gpu.size(), cpu.size()) << "the GPU gave outcomes for another number of pixels";
  Departure worst;
  int printed = 0;
  const testing_support::OutcomeComparison r =
      testing_support::compare_outcomes(gpu, cpu, [&](std::size_t i, double where) {
        const int col = static_cast<int>(i % static_cast<std::size_t>(width));
        const int row = static_cast<int>(i / static_cast<std::size_t>(width));
        if (where > worst.sky) worst = {col, row, where};
        if (where > 1e-9 && printed++ < 4) {
          std::printf("[gpu] %s: pixel (%d, %d) departs by %.3g rad\n", what, col, row, where);
          print_outcome("device", gpu[i]);
          print_outcome("CPU   ", cpu[i]);
        }
      });
  std::printf(
      "[gpu] %s: %ld pixels compared, %ld on a silhouette, redshift within %.3g, sky or hit point within %.3g "
      "rad, hit radius within %.3g (relative); captured rays' end on the horizon within %.3g rad\n",
      what, r.compared, r.silhouette, r.redshift, r.direction, r.radius, r.captured);
  EXPECT_EQ(r.status_differs, 0);
  EXPECT_EQ(r.order_differs, 0);
  EXPECT_LE(r.silhouette, width * height / 200) << "more than 0.5 % of the pixels on a silhouette";
  EXPECT_GT(r.compared, width * height / 2);
  EXPECT_LE(r.redshift, 1e-9);
  EXPECT_LE(r.direction, 1e-9);
  EXPECT_LE(r.radius, 1e-9);
  return worst;
}

/// The same, the GPU's outcomes from the application layer's kernels (the tools' GPU tracers).
template <class Tracer>
Departure expect_gpu_outcomes_match_cpu(const char* what, const Camera& camera, const Tracer& tracer) {
  return expect_gpu_outcomes_match_cpu(what, camera, tracer,
                                       app::trace_on_gpu(camera, tracer, camera.width(), camera.height(), nullptr));
}

TEST(GpuDevice, OutcomesMatchTheCpusTrace) {
  GRTRACE_NEED_GPU();
  TraceSettings settings;
  settings.escape_radius = 400.0;
  settings.max_steps = kGpuTestMaxSteps;
  StandardSceneSpec checker, disk;
  disk.name = "disk";
  const SchwarzschildMetric schwarzschild{1.0};
  expect_gpu_outcomes_match_cpu("main frame, general", probe_camera(schwarzschild, 200.0, 90.0, 90.0, 256),
                                make_general_tracer<Fehlberg78, IController>(
                                    schwarzschild, settings, AngleCorrection::exact, background_scene(checker)));
  const KerrMetric kerr{1.0, 0.9};
  const Camera kerr_camera = probe_camera(kerr, 50.0, 80.0, 60.0, 256);
  const Departure mino = expect_gpu_outcomes_match_cpu(
      "Kerr disk, kerr-mino", kerr_camera,
      make_kerr_mino_tracer<Fehlberg78, IController>(kerr, settings, AngleCorrection::exact, disk_scene(disk)));
  if (mino.sky > 1e-9) {
    // Where it departs: the ray's integration (step by step, without the disk) or the continuation to the sky from
    // the same state (the host's last recorded step).
    const KerrMinoSystemProbe probe{kerr_camera, kerr, settings, mino.col, mino.row};
    expect_same_trail("Kerr disk frame's most departing pixel, Mino-time system", probe);
    RayTrail host;
    probe(host);
    if (host.recorded > 0) {
      KerrContinuationProbe continuation{
          kerr, kerr_camera.pixel_state(mino.col, mino.row), {}, settings.integrator.tolerance};
      for (int i = 0; i < KerrMinoSystem::dimension; ++i) continuation.z[i] = host.steps[host.recorded - 1].state[i];
      expect_same_trail("its continuation to the sky from the last recorded step", continuation);
    }
  }
  expect_gpu_outcomes_match_cpu(
      "Kerr disk, general", kerr_camera,
      make_general_tracer<Fehlberg78, IController>(kerr, settings, AngleCorrection::exact, disk_scene(disk)));
  // A tableau with its own interpolant: the disk's crossing is bracketed on it, and on the GPU a trial step's stages
  // live in advance() and are copied back for it (integrate/controlled_integrator.hpp). Not a pair the tools trace
  // on the GPU, so traced as a user's own program does (gpu_frame.cuh).
  const Camera disk_camera = probe_camera(schwarzschild, 30.0, 80.0, 60.0, 128);
  const auto tsit5 = make_general_tracer<Tsitouras54, PIController>(schwarzschild, settings, AngleCorrection::exact,
                                                                    disk_scene(disk));
  expect_gpu_outcomes_match_cpu("Schwarzschild disk, general, tsit5 + pi (its own dense output)", disk_camera, tsit5,
                                gpu::trace_pixels(disk_camera, tsit5, disk_camera.width(), disk_camera.height()));
  AutoReissnerNordstrom rn;
  rn.charge = 0.6;
  expect_gpu_outcomes_match_cpu(
      "Reissner-Nordstrom disk, general", probe_camera(rn, 30.0, 80.0, 60.0, 128),
      make_general_tracer<Fehlberg78, IController>(rn, settings, AngleCorrection::exact, disk_scene(disk)));
}

TEST(GpuDevice, TheApplicationLayersGpuFrameIsTheCpusFrame) {
  GRTRACE_NEED_GPU();
  const std::vector<app::CheckedRequest> cases = {
      request("kerr", "disk", "kerr-mino", probe_camera(KerrMetric{1.0, 0.9}, 50.0, 80.0, 60.0, 128)),
      request("schwarzschild", "disk", "general", probe_camera(SchwarzschildMetric{1.0}, 30.0, 80.0, 60.0, 128))};
  for (app::CheckedRequest q : cases) {
    const Frame cpu = app_frame(q);
    q.request.device = "cuda";
    const Frame gpu = app_frame(q);
    EXPECT_EQ(gpu.image.metadata.at("tracer"), cpu.image.metadata.at("tracer"));
    EXPECT_EQ(gpu.image.metadata.at("device"), app::gpu_status().name);
    EXPECT_EQ(cpu.image.metadata.at("device"), "cpu");
    long differs = 0;
    for (std::size_t i = 0; i < cpu.image.pixel_count(); ++i)
      differs += gpu.image.channel("object")[i] != cpu.image.channel("object")[i] ? 1 : 0;
    EXPECT_LE(differs, static_cast<long>(cpu.image.pixel_count()) / 200) << q.request.metric.name;
  }
}

TEST(GpuDevice, KerrDiskHitRadiusAgreesWithTheCpuAtTightTolerance) {
  GRTRACE_NEED_GPU();
  const KerrMetric kerr{1.0, 0.9};
  const Camera camera = probe_camera(kerr, 50.0, 80.0, 60.0, 256);
  const app::CheckedRequest q = request("kerr", "disk", "auto", camera);
  TraceSettings tight = q.settings;
  tight.integrator.tolerance = {1e-12, 1e-14};
  // The hit radius at rtol 1e-12 on both sides (within 1e-6), and at the tools' rtol 1e-9 on both sides (the same
  // arithmetic: within 1e-9 relative). The GPU at 1e-9 against the CPU at 1e-12 measures the method, not the
  // device: on the CPU alone 26 of this frame's 7554 hits differ by more than 1e-6 between the two tolerances (at
  // most 5.0e-4, pixel (157, 129), r = 13.26), so that is printed, not asserted.
  const auto radii = [&](const TraceSettings& settings, bool on_gpu) {
    const auto tracer =
        make_kerr_mino_tracer<Fehlberg78, IController>(kerr, settings, q.correction, disk_scene(q.scene));
    if (on_gpu) return app::trace_on_gpu(camera, tracer, camera.width(), camera.height(), nullptr);
    return testing_support::trace_quietly_here(camera, tracer, camera.width(), camera.height());
  };
  const std::vector<RayOutcome> gpu_tight = radii(tight, true), cpu_tight = radii(tight, false);
  const std::vector<RayOutcome> gpu = radii(q.settings, true), cpu = radii(q.settings, false);
  double worst_tight = 0.0, worst_same = 0.0, worst_method = 0.0;
  long hits = 0;
  const auto hit_both = [](const RayOutcome& a, const RayOutcome& b) {
    return a.status == RayStatus::hit && b.status == RayStatus::hit && a.object == b.object;
  };
  for (std::size_t i = 0; i < gpu.size(); ++i) {
    if (hit_both(gpu_tight[i], cpu_tight[i])) {
      ++hits;
      worst_tight = std::max(worst_tight, std::abs(gpu_tight[i].radius - cpu_tight[i].radius));
    }
    if (hit_both(gpu[i], cpu[i])) worst_same = std::max(worst_same, std::abs(gpu[i].radius / cpu[i].radius - 1.0));
    if (hit_both(gpu[i], cpu_tight[i]))
      worst_method = std::max(worst_method, std::abs(gpu[i].radius - cpu_tight[i].radius));
  }
  std::printf(
      "[gpu] kerr disk: %ld hits; hit radius at rtol 1e-12 within %.3g of the CPU's; at rtol 1e-9 within %.3g "
      "(relative) of the CPU's; at rtol 1e-9 within %.3g of the CPU's at 1e-12\n",
      hits, worst_tight, worst_same, worst_method);
  EXPECT_GT(hits, 1000);
  EXPECT_LT(worst_tight, 1e-6);
  EXPECT_LE(worst_same, 1e-9);
}

}  // namespace
