// grtrace/gpu/gpu_frame.cuh
// A frame traced on a CUDA GPU: one GPU thread per traced pixel runs the tracer's own trace_quietly, the same source
// the CPU runs (the hot path is marked GRTRACE_HD: core/host_device.hpp); the host then shades, mirrors, counts and
// records the frame exactly as render_frame does (render/frame.hpp), from those outcomes.
//
// clang-format off
//   #include "grtrace/gpu/gpu_frame.cuh"   // in a .cu file: nvcc -std=c++20 --expt-relaxed-constexpr
//   const auto tracer = make_general_tracer<Fehlberg78, IController>(metric, settings, AngleCorrection::exact, scene);
//   if (gpu::first_gpu().present) frame = gpu::render_frame_on_gpu(camera, tracer);
// clang-format on
//
// Takes:   a Camera and a scene tracer with trace_quietly (GeneralSceneTracer, KerrMinoSceneTracer), whose metric and
//          scene objects are GPU-callable (their surface, accepts, emitter_velocity, metric and acceleration marked
//          GRTRACE_HD; a user's own metric or object marks its functions the same way).
// Returns: the Frame render_frame returns, its rays traced on the GPU (fp64, the same tableau, controller, events and
//          continuation; one thread a pixel, a warp a 4 x 8 tile of pixels: warp_tiles.hpp), and the device's name
//          in the header ("device").
// Assumes: the tracer is copied to the GPU byte for byte: the device reads only what tracing reads (the metric,
//          settings, controller and scene objects, which are plain values); the sky and horizon painters and the
//          CPU-side statistics travel along unread. Throws GpuError when CUDA reports an error.
#pragma once

#if !defined(__CUDACC__)
#error "grtrace/gpu/gpu_frame.cuh is CUDA source: include it from a .cu file compiled by nvcc"
#endif

#include "grtrace/gpu/warp_tiles.hpp"
#include "grtrace/observer/camera.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <cuda_runtime.h>

#include <chrono>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace grtrace::gpu {

/// A CUDA call that failed: the call and CUDA's own words.
class GpuError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The first CUDA device, or why there is none (no driver, no device: CUDA's message).
struct GpuDevice {
  bool present = false;
  std::string name;     ///< e.g. "NVIDIA H100 80GB HBM3"
  std::string why_not;  ///< when not present
};

/// Why CUDA cannot count devices, in words that name the cause. CUDA answers "driver version is insufficient for
/// CUDA runtime version" both for an old driver and for no driver at all (no libcuda, no kernel module): the latter
/// is told apart by the driver's control device, and the former gets both versions.
inline std::string cuda_unavailable_reason(cudaError_t e) {
  if (e == cudaErrorNoDevice) return "CUDA finds no device";
  if (e == cudaErrorInsufficientDriver) {
    if (!std::filesystem::exists("/dev/nvidiactl"))
      return "no NVIDIA driver is loaded on this machine (no /dev/nvidiactl): it has no usable NVIDIA GPU";
    int driver = 0, runtime = 0;
    cudaDriverGetVersion(&driver);
    cudaRuntimeGetVersion(&runtime);
    const auto version = [](int v) { return std::to_string(v / 1000) + "." + std::to_string(v % 1000 / 10); };
    return "the NVIDIA driver supports CUDA " + (driver > 0 ? version(driver) : std::string("(unknown)")) +
           ", older than this build's CUDA runtime " + version(runtime) + "; update the driver";
  }
  return std::string("CUDA reports: ") + cudaGetErrorString(e);
}

inline GpuDevice first_gpu() {
  GpuDevice d;
  int count = 0;
  if (const cudaError_t e = cudaGetDeviceCount(&count); e != cudaSuccess) {
    d.why_not = cuda_unavailable_reason(e);
    cudaGetLastError();  // clear it
    return d;
  }
  if (count < 1) {
    d.why_not = "CUDA finds no device";
    return d;
  }
  cudaDeviceProp prop{};
  if (const cudaError_t e = cudaGetDeviceProperties(&prop, 0); e != cudaSuccess) {
    d.why_not = std::string("CUDA reports: ") + cudaGetErrorString(e);
    return d;
  }
  d.present = true;
  d.name = prop.name;
  return d;
}

namespace detail {

inline void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw GpuError(std::string("GPU: ") + what + " failed: " + cudaGetErrorString(e));
}

/// Device memory for n values of T, freed on every path out.
template <class T>
class DeviceArray {
 public:
  explicit DeviceArray(std::size_t n) : n_(n) { check(cudaMalloc(&p_, n * sizeof(T)), "cudaMalloc"); }
  ~DeviceArray() { cudaFree(p_); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  T* get() const { return static_cast<T*>(p_); }
  /// The bytes of n host values (a byte copy: see the top of this file).
  void upload(const T* host) {
    check(cudaMemcpy(p_, static_cast<const void*>(host), n_ * sizeof(T), cudaMemcpyHostToDevice), "upload");
  }
  void download(T* host) const {
    check(cudaMemcpy(static_cast<void*>(host), p_, n_ * sizeof(T), cudaMemcpyDeviceToHost), "download");
  }

 private:
  void* p_ = nullptr;
  std::size_t n_;
};

/// A CUDA event, destroyed on every path out.
class DeviceEvent {
 public:
  DeviceEvent() { check(cudaEventCreate(&event_), "cudaEventCreate"); }
  ~DeviceEvent() { cudaEventDestroy(event_); }
  DeviceEvent(const DeviceEvent&) = delete;
  DeviceEvent& operator=(const DeviceEvent&) = delete;
  cudaEvent_t get() const { return event_; }

 private:
  cudaEvent_t event_ = nullptr;
};

/// The outcome of this thread's pixel of the traced block (its warp's tile: warp_tiles.hpp), as the CPU's trace would
/// give it, stored row by row (width to a row).
template <class Tracer>
__global__ void trace_pixel_block(const Tracer* tracer, const Camera* camera, WarpTiles tiles, RayOutcome* out) {
  const long t = static_cast<long>(blockIdx.x) * blockDim.x + threadIdx.x;
  PixelIndex p;
  if (!tiles.pixel_of(t, p)) return;  // the last block's threads past thread_count() too
  out[static_cast<long>(p.row) * tiles.width() + p.col] = tracer->trace_quietly(camera->pixel_state(p.col, p.row));
}

}  // namespace detail

/// A scene tracer the GPU can run: it traces a ray without touching CPU-side state (trace_quietly) and takes the
/// outcomes' statistics back afterwards (note_escaped).
template <class Tracer>
concept GpuSceneTracer = SceneTracer<Tracer> &&
    requires(const Tracer& t, const GeodesicState& y, const std::vector<RayOutcome>& outcomes) {
  { t.trace_quietly(y) } -> std::same_as<RayOutcome>;
  t.note_escaped(outcomes);
};

/// What the GPU spent on a block of pixels, in seconds: memory, the upload and the kernel's loading, the kernel (its
/// own time, from CUDA events), the download (wall clock on the host), and the whole call's wall time.
struct GpuTiming {
  double upload = 0.0, trace = 0.0, download = 0.0, total = 0.0;
};

/// The outcomes of the camera's top-left width x height pixels, row by row, each traced by one GPU thread (a warp
/// traces a 4 x 8 tile: warp_tiles.hpp).
template <GpuSceneTracer Tracer>
std::vector<RayOutcome> trace_pixels(const Camera& camera, const Tracer& tracer, int width, int height,
                                     GpuTiming* timing = nullptr) {
  using Clock = std::chrono::steady_clock;
  const auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  const long count = static_cast<long>(width) * height;
  if (count <= 0) return {};
  const auto t0 = Clock::now();
  // The host's array of outcomes is built on a thread of its own while CUDA creates its context (a new process's
  // first CUDA call: ~0.1 s), copies and traces: a million default-constructed outcomes, their first touch of fresh
  // memory included, cost the host 50-90 ms on an H200's machine, longer than the Kerr frame's kernel
  // (docs/benchmarks-archive.md, "GPU"). Joined on every path out (std::jthread); what it throws is rethrown here.
  std::vector<RayOutcome> outcomes;
  std::exception_ptr host_failure;
  std::jthread host_side([&outcomes, &host_failure, count] {
    try {
      outcomes.resize(static_cast<std::size_t>(count));
    } catch (...) {
      host_failure = std::current_exception();
    }
  });
  detail::DeviceArray<Tracer> d_tracer(1);
  detail::DeviceArray<Camera> d_camera(1);
  detail::DeviceArray<RayOutcome> d_out(static_cast<std::size_t>(count));
  d_tracer.upload(&tracer);
  d_camera.upload(&camera);
  // The kernel's code is loaded into the context at its first use (CUDA's lazy loading: a few ms for the large
  // kernels, once a process): done here, so that the kernel's time is the tracing's (the load stays in the total).
  cudaFuncAttributes kernel{};
  detail::check(cudaFuncGetAttributes(&kernel, detail::trace_pixel_block<Tracer>), "loading the kernel");
  detail::DeviceEvent started, finished;
  const auto t1 = Clock::now();
  constexpr int threads = 128;  // fp64 and many registers a thread: small blocks keep more of them resident
  static_assert(threads % WarpTiles::warp_size == 0, "whole warps to a block: a warp traces one tile");
  const WarpTiles tiles(width, height);
  const auto blocks = static_cast<unsigned>((tiles.thread_count() + threads - 1) / threads);
  detail::check(cudaEventRecord(started.get()), "cudaEventRecord");
  detail::trace_pixel_block<<<blocks, threads>>>(d_tracer.get(), d_camera.get(), tiles, d_out.get());
  detail::check(cudaGetLastError(), "kernel launch");
  detail::check(cudaEventRecord(finished.get()), "cudaEventRecord");
  detail::check(cudaDeviceSynchronize(), "tracing kernel");
  float kernel_ms = 0.0f;
  detail::check(cudaEventElapsedTime(&kernel_ms, started.get(), finished.get()), "cudaEventElapsedTime");
  host_side.join();
  if (host_failure) std::rethrow_exception(host_failure);
  const auto t2 = Clock::now();
  d_out.download(outcomes.data());
  const auto t3 = Clock::now();
  if (timing) *timing = {seconds(t0, t1), 1e-3 * static_cast<double>(kernel_ms), seconds(t2, t3), seconds(t0, t3)};
  return outcomes;
}

/// render_frame (render/frame.hpp) with the traced region's rays traced on the GPU (render_frame_traced_by); the
/// header records the device ("device"), the kernel's time ("gpu_trace_seconds") and the GPU's whole share of the
/// time, memory and copies included ("gpu_seconds").
template <GpuSceneTracer Tracer>
Frame render_frame_on_gpu(const Camera& camera, const Tracer& tracer, const RenderOptions& options = {},
                          std::vector<SkyDirection>* directions = nullptr) {
  GpuTiming timing;
  Frame frame = render_frame_traced_by(
      camera, tracer, [&](int width, int height) { return trace_pixels(camera, tracer, width, height, &timing); },
      options, directions);
  frame.image.metadata["device"] = first_gpu().name;
  frame.image.metadata["gpu_trace_seconds"] = exact_number(timing.trace);
  frame.image.metadata["gpu_seconds"] = exact_number(timing.total);
  return frame;
}

}  // namespace grtrace::gpu
