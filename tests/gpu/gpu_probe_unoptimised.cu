// gpu_probe_unoptimised: the GpuProbe rays (gpu_probe.cuh) on one GPU thread with the device code compiled without
// optimisation (cicc and ptxas at -O0), against the host. Beside gpu_frame_test's GpuProbe (device code optimised as
// the backend's is): a departure in that one and not in this one points at the optimiser, or at code whose meaning
// the optimiser may change (a read of something never written). Built by cmake/gpu-check.sh pack only (not part of
// the default build); prints one line per ray and the departures; exit 0 when the trails agree, 1 when not, 2 when
// CUDA fails.
#include "gpu_probe.cuh"

#include <cstdio>
#include <string>
#include <vector>

int main() {
  using namespace gpu_probe;
  int failures = 0;
  const auto check = [&](const char* what, const auto& probe) {
    RayTrail host;
    probe(host);
    std::string error;
    const RayTrail gpu = trail_on_gpu(probe, &error);
    if (!error.empty()) {
      std::printf("[gpu] %s: CUDA: %s\n", what, error.c_str());
      return false;
    }
    for (const std::string& problem : compare_trails(what, host, gpu)) {
      std::printf("%s\n", problem.c_str());
      ++failures;
    }
    return true;
  };
  if (!check("unoptimised device code, Schwarzschild, geodesic equation", main_frame_probe()) ||
      !check("unoptimised device code, Kerr, Mino-time system", kerr_frame_probe()))
    return 2;
  return failures == 0 ? 0 : 1;
}
