// gpu_status for a build without the CUDA backend (no CUDA compiler found, or GRTRACE_CUDA=OFF).
#include "grtrace/app/frame_tracer.hpp"

namespace grtrace::app {

const GpuStatus& gpu_status() {
  static const GpuStatus status{false, false, "",
                                "this build has no CUDA backend (configured without a CUDA compiler, or with "
                                "-DGRTRACE_CUDA=OFF)"};
  return status;
}

}  // namespace grtrace::app
