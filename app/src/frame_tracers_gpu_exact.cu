// The CUDA backend's kernels for the metrics with closed-form accelerations (see gpu_tracers.hpp): Schwarzschild,
// Kerr in Boyer-Lindquist (general and kerr-mino) and in Kerr-Schild coordinates. Only trace_on_gpu is compiled here;
// everything around the kernel is the frame tracer units'.
#include "gpu_tracers_cuda.cuh"

namespace grtrace::app {

GRTRACE_APP_GPU_GENERAL(SchwarzschildMetric)
GRTRACE_APP_GPU_GENERAL(KerrMetric)
GRTRACE_APP_GPU_GENERAL(KerrSchildMetric)
GRTRACE_APP_GPU_KERR_MINO()

/// The first CUDA device, asked once.
const GpuStatus& gpu_status() {
  static const GpuStatus status = [] {
    const gpu::GpuDevice d = gpu::first_gpu();
    return GpuStatus{true, d.present, d.name, d.why_not};
  }();
  return status;
}

}  // namespace grtrace::app
