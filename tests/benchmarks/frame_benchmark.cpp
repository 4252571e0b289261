// tests/benchmarks/frame_benchmark.cpp
// Whole frames of the seed's main scene, through grtrace-render's own code path: a static camera at r = 200 M
// looking at the hole (up = north), fov 90, checker sky on a sphere at 400 M with the exact continuation to
// infinity (AngleCorrection::exact), Schwarzschild M = 1, shaded pixel by pixel by the OpenMP image loop on all
// cores (render/parallel_render.hpp):
//   frame/general/<method>/<N>     GeneralSceneTracer: every pixel integrated (trace/scene_tracer.hpp)
//   frame/symmetric/<table>/<N>    SymmetricSceneTracer: one SymmetricSkyTable for the frame, built inside the
//                                  timed region (it is part of the frame's cost), read once per pixel
// N = 256 (quick comparisons; ratios in one run) and 1024 (the seed's main frame; issue-6 target: <= 0.9 s on
// 2 cores with max angular error <= 1e-6 rad over escaped pixels).
// Counters: rays_per_second; ns_per_step = wall time x threads / accepted steps (one core's cost of one
// ray-step; for the symmetric tracer that of the table rays, whose build time is table_ms); ns_per_pixel for
// the symmetric tracer's look-ups; max_error, median_error (radians, escaped pixels, against
// exact::asymptotic_direction at the camera, in double precision, computed after the timed loop); mismatches
// (escaped/captured verdicts that disagree with the exact one); failures.
//
// The general tracer per metric (the cost of one accepted step in a frame):
//   frame/metric/<metric>/<method>/<N>   a ZAMO camera at r = 50 M, theta = 80 deg looking at the hole, fov 60,
//                                        sky sphere at 400 M (flat continuation), N x N, 2 threads; <metric> is
//                                        schwarzschild, kerr_bl (a = 0.9 M, Boyer-Lindquist), kerr_ks (a = 0.9 M,
//                                        Kerr-Schild, outgoing slicing: the rays are past-directed) and
//                                        schwarzschild_disk (the thin disk scene, 6-30 M). Counters: ns_per_step
//                                        (one core), cpu_ns_per_step (the process's processor time per accepted
//                                        step: what to read on a shared machine, where wall time inflates),
//                                        steps_per_ray, rays_per_second, max_error / median_error / p99_error /
//                                        p999_error
//                                        (radians, escaped and hit pixels, against the same frame traced with
//                                        rkf78/i at rtol 1e-12 after the timed loop), mismatches (end object
//                                        differs from the reference's), failures.
//   frame/metric/kerr_bl_disk_mino/...   the Kerr disk frame through the reduced Kerr tracer (Mino time)
//   frame/metric/kerr_bl_disk_closed_form/...   the same through the closed-form tracer (nothing integrated but its
//                                        fallback rays: counter fallback_rays); at 1024 both, for their ratio in one
//                                        run (us_per_ray_core: processor time per ray; no reference above 256).
#include "../../examples/work_precision/work_precision.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/observer/static_frame.hpp"
#include "grtrace/observer/tetrad.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/scene/standard_scenes.hpp"
#include "grtrace/tableau/all_tableaux.hpp"
#include "grtrace/trace/kerr_closed_form_tracer.hpp"
#include "grtrace/trace/kerr_mino_tracer.hpp"
#include "grtrace/trace/scene_tracer.hpp"
#include "grtrace/trace/symmetric_scene_tracer.hpp"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <initializer_list>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace grtrace;
using work_precision::ExitPoint;

constexpr double kCameraR = 200.0, kSkyR = 400.0, kFov = 90.0;
const SchwarzschildMetric kMetric{1.0};

/// grtrace-render's default camera: static at (r, pi/2, 0), looking at the hole, up = north.
Camera seed_camera(int n) {
  const Vec4 x(0.0, kCameraR, std::numbers::pi / 2.0, 0.0);
  const Mat4 g = kMetric.metric(x);
  const StaticFrame frame(g);
  const Tetrad tetrad = make_tetrad(g, frame.velocity(Vec3::Zero()), frame.spatial(Vec3(-1.0, 0.0, 0.0)),
                                    frame.spatial(Vec3(0.0, -1.0, 0.0)));
  return Camera(x, tetrad, n, n, kFov);
}

TraceSettings settings_for(double rtol) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-2 * rtol};
  s.escape_radius = kSkyR;
  return s;
}

RenderOptions quiet_options() {
  RenderOptions o;
  o.progress = ProgressMode::never;
  return o;
}

/// Each pixel's answer in double precision (the image channels are float), for judging after the timed loop.
struct FrameAnswers {
  std::vector<exact::SkyDirection> direction;
  std::vector<unsigned char> escaped;
  explicit FrameAnswers(const Camera& cam)
      : direction(static_cast<std::size_t>(cam.width()) * static_cast<std::size_t>(cam.height())),
        escaped(direction.size(), 0) {}
  void store(std::size_t i, const RayOutcome& o) {
    escaped[i] = o.status == RayStatus::escaped ? 1 : 0;
    direction[i] = o.where;
  }
};

struct Timing {
  double frame_seconds = 0.0;  ///< per frame
  double step_seconds = 0.0;   ///< of which spent on the integration steps counted in `steps`
  long steps = 0;
};

void report(benchmark::State& state, const Camera& cam, const FrameAnswers& answers, const RenderStats& stats,
            const Timing& t) {
  std::vector<double> errors;
  long mismatches = 0;
  for (int row = 0; row < cam.height(); ++row)
    for (int col = 0; col < cam.width(); ++col) {
      const std::size_t i =
          static_cast<std::size_t>(row) * static_cast<std::size_t>(cam.width()) + static_cast<std::size_t>(col);
      const auto exact_dir = exact::asymptotic_direction(cam.pixel_state(col, row), kMetric.mass);
      if (static_cast<bool>(answers.escaped[i]) != exact_dir.has_value()) {
        ++mismatches;
        continue;
      }
      if (exact_dir) errors.push_back(exact::angular_distance(answers.direction[i], *exact_dir));
    }
  const auto summary = work_precision::summarize(errors);
  const double rays = static_cast<double>(cam.width()) * cam.height();
  state.counters["rays_per_second"] = rays / t.frame_seconds;
  state.counters["threads"] = stats.threads;
  state.counters["ns_per_step"] =
      t.steps > 0 ? t.step_seconds * stats.threads * 1e9 / static_cast<double>(t.steps) : 0.0;
  state.counters["max_error"] = summary.max;
  state.counters["median_error"] = summary.median;
  state.counters["mismatches"] = static_cast<double>(mismatches);
  state.counters["failures"] = static_cast<double>(stats.failures());
}

/// The frame traced and shaded as render_frame does (each tile's rays traced together: TileOutcomes), every pixel's
/// outcome also stored in `answers` (FrameAnswers or MetricAnswers, judged after the timed loop).
template <class Tracer, class Answers>
RenderStats render_answers(const Tracer& tracer, const Camera& cam, Image& image, Answers& answers) {
  return render_image(
      image, [&] { return TileOutcomes(cam, tracer); },
      [&](int col, int row, TileOutcomes& tile) {
        const RayOutcome& o = tile.at(col, row);
        answers.store(image.index(col, row), o);
        return tracer.scene().shade(o);
      },
      quiet_options());
}

/// The general tracer as grtrace-render runs it (the exact continuation starts at the last accepted step).
template <class T, class C>
void frame_general(benchmark::State& state, int n, double rtol) {
  const Camera cam = seed_camera(n);
  const auto tracer =
      make_general_tracer<T, C>(kMetric, settings_for(rtol), AngleCorrection::exact, background_scene({}));
  Image image(n, n);
  FrameAnswers answers(cam);
  RenderStats stats;
  Timing t;
  for (auto _ : state) {
    stats = render_answers(tracer, cam, image, answers);
    t.frame_seconds += stats.seconds;
  }
  t.frame_seconds /= static_cast<double>(state.iterations());
  t.step_seconds = t.frame_seconds;
  t.steps = stats.total_steps;
  report(state, cam, answers, stats, t);
}

/// The symmetric-sky tracer as grtrace-render runs it (--tracer symmetric / auto).
template <class T, class C>
void frame_symmetric(benchmark::State& state, int n, double table_rtol, int nodes_per_side) {
  const Camera cam = seed_camera(n);
  Image image(n, n);
  FrameAnswers answers(cam);
  RenderStats stats;
  Timing t;
  double table_seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const SymmetricSceneTracer<T, C, BackgroundScene> tracer(kMetric, settings_for(table_rtol), cam,
                                                             AngleCorrection::exact, background_scene({}),
                                                             nodes_per_side);
    table_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    t.steps = tracer.table().table_steps();
    stats = render_answers(tracer, cam, image, answers);
    t.frame_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const double iterations = static_cast<double>(state.iterations());
  t.frame_seconds /= iterations;
  t.step_seconds = table_seconds / iterations;
  report(state, cam, answers, stats, t);
  state.counters["table_rays"] = 2.0 * nodes_per_side;
  state.counters["table_ms"] = t.step_seconds * 1e3;
  state.counters["ns_per_pixel"] =
      (t.frame_seconds - t.step_seconds) * stats.threads * 1e9 / (static_cast<double>(n) * n);
}

void configure(benchmark::internal::Benchmark* b, int n) {
  b->Unit(benchmark::kMillisecond)->UseRealTime();
  if (n > 256) b->Iterations(1);  // the 1024 x 1024 general frames take seconds each
}

template <class T, class C>
void register_general(const std::string& name, double rtol, std::initializer_list<int> sizes) {
  for (const int n : sizes)
    configure(benchmark::RegisterBenchmark(("frame/general/" + name + "/" + std::to_string(n)).c_str(),
                                           [=](benchmark::State& s) { frame_general<T, C>(s, n, rtol); }),
              n);
}

template <class T, class C>
void register_symmetric(const std::string& name, double rtol, int nodes, std::initializer_list<int> sizes) {
  for (const int n : sizes)
    benchmark::RegisterBenchmark(("frame/symmetric/" + name + "/" + std::to_string(n)).c_str(),
                                 [=](benchmark::State& s) { frame_symmetric<T, C>(s, n, rtol, nodes); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
}

// ---- the general tracer per metric ---------------------------------------------------------------------------

template <class Metric>
Camera metric_camera(const Metric& metric, int n) {
  CameraSpec spec;
  spec.position = Vec4(0.0, 50.0, 80.0 * std::numbers::pi / 180.0, 0.0);
  spec.spherical_position = true;
  spec.observer = ObserverKind::zamo;
  spec.width = spec.height = n;
  spec.fov_degrees = 60.0;
  return make_camera(metric, spec);
}

/// Per pixel: end object, direction, end radius and redshift (as the tracer reports them).
struct MetricAnswers {
  std::vector<SkyDirection> where;
  std::vector<int> object;
  std::vector<unsigned char> failed;
  std::vector<double> radius, redshift;
  explicit MetricAnswers(std::size_t n) : where(n), object(n, -1), failed(n, 0), radius(n), redshift(n) {}
  void store(std::size_t i, const RayOutcome& o) {
    where[i] = o.where;
    object[i] = o.object;
    failed[i] = is_failure(o.status) ? 1 : 0;
    radius[i] = o.radius;
    redshift[i] = o.redshift;
  }
};

/// One row: the frame traced by `tracer` (a scene tracer for metric and scene), judged against the general tracer
/// (frames up to 256 pixels a side: the reference of a 1024 frame at rtol 1e-12 takes minutes).
template <class Tracer, class Metric, class SceneT>
void frame_metric_with(benchmark::State& state, const Tracer& tracer, const Metric& metric, const SceneT& scene, int n) {
  const Camera cam = metric_camera(metric, n);
  Image image(n, n);
  MetricAnswers answers(static_cast<std::size_t>(n) * static_cast<std::size_t>(n));
  RenderStats stats;
  double seconds = 0.0;
  const std::clock_t cpu_start = std::clock();  // the process's processor time, all threads
  for (auto _ : state) {
    stats = render_answers(tracer, cam, image, answers);
    seconds += stats.seconds;
  }
  const double cpu_seconds =
      static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC / static_cast<double>(state.iterations());
  seconds /= static_cast<double>(state.iterations());
  const double rays = static_cast<double>(n) * n;
  state.counters["rays_per_second"] = rays / seconds;
  state.counters["threads"] = stats.threads;
  state.counters["us_per_ray_core"] = cpu_seconds * 1e6 / rays;  // processor time: all threads together
  if (stats.total_steps > 0) {
    state.counters["ns_per_step"] = seconds * stats.threads * 1e9 / static_cast<double>(stats.total_steps);
    state.counters["cpu_ns_per_step"] = cpu_seconds * 1e9 / static_cast<double>(stats.total_steps);
    state.counters["steps_per_ray"] = static_cast<double>(stats.total_steps) / rays;
  }
  state.counters["failures"] = static_cast<double>(stats.failures());
  if (n > 256) return;
  // Judged against a much tighter trace of the same frame (not timed).
  const auto reference_tracer =
      make_general_tracer<Fehlberg78, IController>(metric, settings_for(1e-12), AngleCorrection::flat, scene);
  MetricAnswers reference(answers.where.size());
  Image reference_image(n, n);
  render_answers(reference_tracer, cam, reference_image, reference);
  std::vector<double> errors;
  long mismatches = 0;
  double hit_radius_error = 0.0, hit_redshift_error = 0.0;  // relative, over pixels on a scene object (the disk)
  for (std::size_t i = 0; i < answers.where.size(); ++i) {
    if (answers.failed[i] || reference.failed[i]) continue;
    if (answers.object[i] != reference.object[i]) {
      ++mismatches;
      continue;
    }
    if (answers.object[i] != kHorizonObject) errors.push_back(exact::angular_distance(answers.where[i], reference.where[i]));
    if (answers.object[i] >= kFirstSceneObject) {
      hit_radius_error = std::max(hit_radius_error, std::abs(answers.radius[i] / reference.radius[i] - 1.0));
      hit_redshift_error = std::max(hit_redshift_error, std::abs(answers.redshift[i] / reference.redshift[i] - 1.0));
    }
  }
  state.counters["hit_radius_error"] = hit_radius_error;
  state.counters["hit_redshift_error"] = hit_redshift_error;
  const auto summary = work_precision::summarize(errors);
  // The max is one pixel near the photon ring, where round-off is amplified: the upper quantiles say more.
  std::sort(errors.begin(), errors.end());
  auto quantile = [&](double q) {
    return errors.empty() ? 0.0 : errors[static_cast<std::size_t>(q * static_cast<double>(errors.size() - 1))];
  };
  state.counters["p99_error"] = quantile(0.99);
  state.counters["p999_error"] = quantile(0.999);
  state.counters["max_error"] = summary.max;
  state.counters["median_error"] = summary.median;
  state.counters["mismatches"] = static_cast<double>(mismatches);
}

template <class T, class C, class Metric, class SceneT>
void frame_metric(benchmark::State& state, const Metric& metric, const SceneT& scene, int n, double rtol) {
  frame_metric_with(state, make_general_tracer<T, C>(metric, settings_for(rtol), AngleCorrection::flat, scene), metric,
                    scene, n);
}

/// The same frame through the reduced Kerr tracer (trace/kerr_mino_tracer.hpp), Boyer-Lindquist.
template <class T, class C, class SceneT>
void frame_mino(benchmark::State& state, const KerrMetric& metric, const SceneT& scene, int n, double rtol) {
  frame_metric_with(state, make_kerr_mino_tracer<T, C>(metric, settings_for(rtol), AngleCorrection::flat, scene),
                    metric, scene, n);
}

/// The same frame in closed form (trace/kerr_closed_form_tracer.hpp): nothing integrated but its fallback rays.
template <class T, class C, class SceneT>
void frame_closed_form(benchmark::State& state, const KerrMetric& metric, const SceneT& scene, int n, double rtol) {
  const auto tracer = make_kerr_closed_form_tracer<T, C>(metric, settings_for(rtol), AngleCorrection::flat, scene);
  frame_metric_with(state, tracer, metric, scene, n);
  state.counters["fallback_rays"] =
      static_cast<double>(tracer.fallback_rays()) / static_cast<double>(state.iterations());
}

/// The Kerr disk frame (a = 0.9, prograde disk from the ISCO to 20 M, ZAMO camera at r = 50 M, 80 degrees,
/// fov 60), as grtrace-render --metric kerr --spin 0.9 --scene disk draws it.
DiskScene kerr_disk() {
  StandardSceneSpec spec;
  spec.name = "disk";
  spec.disk.r_in = exact::isco_radius(0.9, exact::Orbit::prograde);
  return disk_scene(spec);
}

template <class T, class C>
void register_metric_frames(const std::string& method, double rtol, int n) {
  auto add = [&](const std::string& metric_name, auto run) {
    benchmark::RegisterBenchmark(("frame/metric/" + metric_name + "/" + method + "/" + std::to_string(n)).c_str(),
                                 run)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  };
  add("schwarzschild", [=](benchmark::State& s) {
    frame_metric<T, C>(s, SchwarzschildMetric{1.0}, background_scene({}), n, rtol);
  });
  add("kerr_bl", [=](benchmark::State& s) {
    frame_metric<T, C>(s, KerrMetric{1.0, 0.9}, background_scene({}), n, rtol);
  });
  add("kerr_ks", [=](benchmark::State& s) {
    frame_metric<T, C>(s, KerrSchildMetric{1.0, 0.9, KerrSchildSlicing::outgoing}, background_scene({}), n, rtol);
  });
  add("schwarzschild_disk", [=](benchmark::State& s) {
    StandardSceneSpec spec;
    spec.name = "disk";
    frame_metric<T, C>(s, SchwarzschildMetric{1.0}, disk_scene(spec), n, rtol);
  });
  add("kerr_bl_disk", [=](benchmark::State& s) { frame_metric<T, C>(s, KerrMetric{1.0, 0.9}, kerr_disk(), n, rtol); });
  add("kerr_ks_disk", [=](benchmark::State& s) {
    frame_metric<T, C>(s, kerr_schild_for_camera_rays(1.0, 0.9), kerr_disk(), n, rtol);
  });
  add("kerr_bl_mino", [=](benchmark::State& s) { frame_mino<T, C>(s, KerrMetric{1.0, 0.9}, background_scene({}), n, rtol); });
  add("kerr_bl_disk_mino", [=](benchmark::State& s) { frame_mino<T, C>(s, KerrMetric{1.0, 0.9}, kerr_disk(), n, rtol); });
  add("kerr_bl_disk_closed_form", [=](benchmark::State& s) {
    frame_closed_form<T, C>(s, KerrMetric{1.0, 0.9}, kerr_disk(), n, rtol);
  });
}


const bool registered = [] {
  // General tracer: the defaults chosen from the chart (tsit5 + I, rtol 2e-9; tsit5 + PI, 3e-9), grtrace-render's
  // previous default (dopri5 + PI, 1e-10), the cheapest with the continuation from the last step (rkf78 + I, 1e-9),
  // and the seed's integrator (RK4 + step doubling) for scale.
  register_general<Tsitouras54, IController>("tsit5/i/2e-9", 2e-9, {256, 1024});
  register_general<Tsitouras54, PIController>("tsit5/pi/3e-9", 3e-9, {256, 1024});
  register_general<DormandPrince54, PIController>("dopri5/pi/1e-10", 1e-10, {256, 1024});
  register_general<Fehlberg78, IController>("rkf78/i/1e-9", 1e-9, {256, 1024});
  register_general<ClassicRK4, StepDoubling>("rk4/doubling/1e-8", 1e-8, {256});
  // Symmetric-sky tracer (the table rays use the same method): the chosen defaults with 1024 and 512 table rays
  // per side, grtrace-render's previous default, and Fehlberg78 at 1e-13.
  register_symmetric<Tsitouras54, IController>("tsit5-i-2e-9-1024", 2e-9, 1024, {256, 1024});
  register_symmetric<Tsitouras54, PIController>("tsit5-pi-3e-9-1024", 3e-9, 1024, {1024});
  register_symmetric<Tsitouras54, IController>("tsit5-i-2e-9-512", 2e-9, 512, {1024});
  register_symmetric<DormandPrince54, PIController>("dopri5-pi-1e-10-1024", 1e-10, 1024, {1024});
  register_symmetric<Fehlberg78, PIController>("rkf78-pi-1e-13-1024", 1e-13, 1024, {1024});
  // The general tracer per metric and per tableau.
  register_metric_frames<Tsitouras54, IController>("tsit5/i/2e-9", 2e-9, 128);
  register_metric_frames<DormandPrince54, PIController>("dopri5/pi/1e-10", 1e-10, 128);
  register_metric_frames<Fehlberg78, IController>("rkf78/i/1e-9", 1e-9, 128);
  register_metric_frames<ClassicRK4, StepDoubling>("rk4/doubling/1e-8", 1e-8, 128);
  // The Kerr disk frame at looser tolerances (its accuracy target is 1e-6 in hit radius and redshift).
  for (const double rtol : {2e-8, 2e-7, 1e-6}) {
    char name[64];
    std::snprintf(name, sizeof name, "frame/metric/kerr_bl_disk/tsit5/i/%g/128", rtol);
    benchmark::RegisterBenchmark(name, [=](benchmark::State& s) {
      frame_metric<Tsitouras54, IController>(s, KerrMetric{1.0, 0.9}, kerr_disk(), 128, rtol);
    })->Unit(benchmark::kMillisecond)->UseRealTime();
  }
  // The Kerr disk frame at 1024 x 1024, reduced tracer against closed form (read the ratio in one run).
  for (const auto& [name, closed] :
       {std::pair{"kerr_bl_disk_mino", false}, std::pair{"kerr_bl_disk_closed_form", true}}) {
    benchmark::RegisterBenchmark(
        ("frame/metric/" + std::string(name) + "/tsit5/i/2e-9/1024").c_str(),
        [closed = closed](benchmark::State& s) {
          if (closed) frame_closed_form<Tsitouras54, IController>(s, KerrMetric{1.0, 0.9}, kerr_disk(), 1024, 2e-9);
          else frame_mino<Tsitouras54, IController>(s, KerrMetric{1.0, 0.9}, kerr_disk(), 1024, 2e-9);
        })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
