// The CUDA backend's kernels for the metrics written as components and differentiated by dual numbers
// (metric/auto_metric.hpp; see gpu_tracers.hpp): Reissner-Nordstrom, Schwarzschild-de Sitter, the Ellis wormhole and
// Schwarzschild in Eddington-Finkelstein coordinates.
#include "gpu_tracers_cuda.cuh"

namespace grtrace::app {

GRTRACE_APP_GPU_GENERAL(AutoReissnerNordstrom)
GRTRACE_APP_GPU_GENERAL(AutoSchwarzschildDeSitter)
GRTRACE_APP_GPU_GENERAL(AutoEllisWormhole)
GRTRACE_APP_GPU_GENERAL(AutoEddingtonFinkelstein)

}  // namespace grtrace::app
