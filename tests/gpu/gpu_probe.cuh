// tests/gpu/gpu_probe.cuh
// One ray integrated by one GPU thread and by the host, from the same bytes, step by step: the lambda, step size and
// state of each accepted step, how the ray ended, and inverse_root (the one core function with a device path of its
// own). Where a GPU draws wrong frames, the first departing step says where its integration leaves the CPU's.
// Used by tests/gpu/gpu_frame_test.cu (GpuProbe, optimised as the backend is) and by gpu_probe_unoptimised.cu
// (device code at -O0: a departure in one and not the other points at the optimiser).
#pragma once

#include "grtrace/core/inverse_root.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/schwarzschild.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/observer/camera_spec.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"
#include "grtrace/trace/kerr_mino_system.hpp"
#include "grtrace/trace/sky_continuation.hpp"

#include <cuda_runtime.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace gpu_probe {

using namespace grtrace;

/// An accepted step: where it ended (lambda), its size and the system's state there (the first
/// System::dimension components; the pixel's start is record 0 with h = 0).
struct StepRecord {
  double lambda = 0.0, h = 0.0;
  double state[8] = {};
};

inline constexpr int kTrailSteps = 40;

/// What one probe records: the first kTrailSteps accepted steps, how the ray ended, and inverse_root (the one
/// function with a code path of its own on the device: its tables) at a few arguments.
struct RayTrail {
  StepRecord start;
  StepRecord steps[kTrailSteps];
  int recorded = 0;
  int status = -1;
  int accepted = 0;
  int rejected = 0;
  double lambda_end = 0.0;
  double inverse_roots[4] = {};
};

template <class V>
GRTRACE_HD StepRecord record_of(double lambda, double h, const V& z) {
  StepRecord s;
  s.lambda = lambda;
  s.h = h;
  for (int i = 0; i < static_cast<int>(z.size()) && i < 8; ++i) s.state[i] = z[i];
  return s;
}

/// trace_geodesic_system's observer: records each accepted step (theta_end == 1) while there is room.
struct TrailObserver {
  RayTrail* trail;
  template <class Integrator>
  GRTRACE_HD void operator()(const Integrator& integ, double theta_end) const {
    if (theta_end != 1.0 || trail->recorded >= kTrailSteps) return;
    trail->steps[trail->recorded++] = record_of(integ.lambda(), integ.last_step(), integ.state());
  }
};

inline GRTRACE_HD void note_end(RayTrail& t, const TraceResult& r) {
  t.status = static_cast<int>(r.status);
  t.accepted = r.accepted;
  t.rejected = r.rejected;
  t.lambda_end = r.lambda;
  const double x[4] = {0.37, 2.5e-3, 1.0, 7.9e4};
  for (int i = 0; i < 4; ++i) t.inverse_roots[i] = inverse_root<8>(x[i]);
}

/// The general tracer's system (the geodesic equation) for a Schwarzschild pixel, rkf78 + I.
struct GeneralSystemProbe {
  Camera camera;
  SchwarzschildMetric metric;
  TraceSettings settings;
  int col, row;
  GRTRACE_HD void operator()(RayTrail& t) const {
    const GeodesicState y0 = camera.pixel_state(col, row);
    t.start = record_of(0.0, 0.0, y0);
    const GeodesicTracer<SchwarzschildMetric, Fehlberg78, IController> tracer(metric, settings, IController{});
    note_end(t, tracer.trace_observed(y0, TrailObserver{&t}));
  }
};

/// The reduced Kerr tracer's system (Mino time) for a Kerr pixel, rkf78 + I.
struct KerrMinoSystemProbe {
  Camera camera;
  KerrMetric metric;
  TraceSettings settings;
  int col, row;
  GRTRACE_HD void operator()(RayTrail& t) const {
    const GeodesicState y0 = camera.pixel_state(col, row);
    const KerrMinoSystem system(metric, y0);
    const KerrMinoSystem::State z0 = system.initial_state(y0);
    t.start = record_of(0.0, 0.0, z0);
    note_end(t, trace_geodesic_system<Fehlberg78>(system, settings, IController{}, z0, metric.horizon_radius(), false,
                                                  TrailObserver{&t}));
  }
};

/// The reduced Kerr tracer's continuation to the sky (kerr_direction_at_infinity) from a Mino state z of the ray
/// that starts at y0: records in start the direction (theta, phi), whether it was found (1) or not (0), the Mino time
/// to infinity from z and the first four components of the system's right-hand side at z.
struct KerrContinuationProbe {
  KerrMetric metric;
  GeodesicState y0;
  KerrMinoSystem::State z;
  Tolerance tol;
  GRTRACE_HD void operator()(RayTrail& t) const {
    const KerrMinoSystem system(metric, y0);
    const auto d = kerr_direction_at_infinity<Fehlberg78>(system, tol, z);
    const KerrMinoSystem::State f = system(z);
    Vector<8> record;
    record << (d ? d->theta : -1.0), (d ? d->phi : -1.0), (d ? 1.0 : 0.0), system.mino_time_to_infinity(z), f[0], f[1],
        f[2], f[3];
    t.start = record_of(0.0, 0.0, record);
    t.status = d ? 1 : 0;
  }
};

template <class Probe>
__global__ void run_probe(Probe probe, RayTrail* out) {
  probe(*out);
}

/// The probe run by one GPU thread; *error receives CUDA's words when a call fails (the trail is then the empty one).
template <class Probe>
RayTrail trail_on_gpu(const Probe& probe, std::string* error) {
  RayTrail trail;
  RayTrail* d = nullptr;
  cudaError_t e = cudaMalloc(&d, sizeof(RayTrail));
  if (e == cudaSuccess) e = cudaMemcpy(d, &trail, sizeof(RayTrail), cudaMemcpyHostToDevice);
  if (e == cudaSuccess) {
    run_probe<<<1, 1>>>(probe, d);
    e = cudaGetLastError();
  }
  if (e == cudaSuccess) e = cudaDeviceSynchronize();
  if (e == cudaSuccess) e = cudaMemcpy(&trail, d, sizeof(RayTrail), cudaMemcpyDeviceToHost);
  if (d) cudaFree(d);
  if (e != cudaSuccess && error) *error = cudaGetErrorString(e);
  return trail;
}

/// |a - b| relative to the larger, 0 for two equal numbers (NaN too).
inline double departure(double a, double b) {
  if (a == b || (std::isnan(a) && std::isnan(b))) return 0.0;
  return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300});
}

inline double departure(const StepRecord& a, const StepRecord& b) {
  double worst = std::max(departure(a.lambda, b.lambda), departure(a.h, b.h));
  for (int i = 0; i < 8; ++i) worst = std::max(worst, departure(a.state[i], b.state[i]));
  return worst;
}

inline std::string describe(const StepRecord& s) {
  char text[64];
  std::snprintf(text, sizeof text, "lambda %.17g h %.17g state", s.lambda, s.h);
  std::string out = text;
  for (double v : s.state) {
    std::snprintf(text, sizeof text, " %.17g", v);
    out += text;
  }
  return out;
}

/// The device's trail against the host's, each difference beyond round-off in words (none: the same trail), after
/// one summary line on stdout.
inline std::vector<std::string> compare_trails(const char* what, const RayTrail& host, const RayTrail& gpu) {
  std::printf("[gpu] %s: host %d steps, %d rejected, status %d, lambda %.6g", what, host.accepted, host.rejected,
              host.status, host.lambda_end);
  std::printf("; device %d steps, %d rejected, status %d, lambda %.6g", gpu.accepted, gpu.rejected, gpu.status,
              gpu.lambda_end);
  std::printf("; inverse_root<8> device/host - 1:");
  for (int i = 0; i < 4; ++i) std::printf(" %.3g", gpu.inverse_roots[i] / host.inverse_roots[i] - 1.0);
  std::printf("\n");
  constexpr double round_off = 1e-9;  // the device's libm differs from the host's in the last bits
  std::vector<std::string> problems;
  const std::string name = what;
  if (departure(gpu.start, host.start) > round_off)
    problems.push_back(name + ": the start departs\n  host   " + describe(host.start) + "\n  device " +
                       describe(gpu.start));
  for (int i = 0; i < std::min(host.recorded, gpu.recorded); ++i)
    if (departure(gpu.steps[i], host.steps[i]) > round_off) {
      problems.push_back(name + ": the device departs at accepted step " + std::to_string(i + 1) + "\n  host   " +
                         describe(host.steps[i]) + "\n  device " + describe(gpu.steps[i]));
      break;
    }
  if (gpu.status != host.status || gpu.accepted != host.accepted)
    problems.push_back(name + ": the ray ends differently (status " + std::to_string(gpu.status) + " after " +
                       std::to_string(gpu.accepted) + " steps on the device, " + std::to_string(host.status) +
                       " after " + std::to_string(host.accepted) + " on the host)");
  for (int i = 0; i < 4; ++i)
    if (departure(gpu.inverse_roots[i], host.inverse_roots[i]) > 1e-15)
      problems.push_back(name + ": inverse_root<8> differs at argument " + std::to_string(i));
  return problems;
}

/// The camera of the probes' frames: at radius r and polar angle theta (degrees), size x size pixels.
template <class M>
Camera probe_camera(const M& metric, double r, double theta_degrees, double fov, int size) {
  CameraSpec cs;
  cs.position = Vec4(0.0, r, theta_degrees * std::numbers::pi / 180.0, 0.0);
  cs.spherical_position = true;
  cs.width = cs.height = size;
  cs.fov_degrees = fov;
  return make_camera(metric, cs);
}

/// The probes' settings: the tests' sky sphere, and a step cap that a lost ray reaches in a fraction of a second.
inline TraceSettings probe_settings() {
  TraceSettings settings;
  settings.escape_radius = 400.0;
  settings.max_steps = 2000;
  return settings;
}

/// A pixel of the main frame (64x64, Schwarzschild, from r = 200 in the equator, 90 degrees; its ray escapes).
inline GeneralSystemProbe main_frame_probe() {
  const SchwarzschildMetric metric{1.0};
  return {probe_camera(metric, 200.0, 90.0, 90.0, 64), metric, probe_settings(), 20, 9};
}

/// A pixel of the Kerr disk frame (64x64, a = 0.9, from r = 50 at 80 degrees, 60 degrees; its ray falls in).
inline KerrMinoSystemProbe kerr_frame_probe() {
  const KerrMetric metric{1.0, 0.9};
  return {probe_camera(metric, 50.0, 80.0, 60.0, 64), metric, probe_settings(), 30, 35};
}

}  // namespace gpu_probe
