// tests/gpu/outcome_comparison.hpp
// How a GPU's outcomes are judged against the CPU's for the same pixels, written once: gpu_frame_test asserts on
// the result (expect_gpu_outcomes_match_cpu), gpu_kernel_benchmark prints it (--host).
//
// Takes:   the two sides' outcomes of the same pixels, in the same order.
// Returns: the counts and the largest differences below. A pixel whose object differs is a silhouette (a ray
//          grazing an edge may end on either side when the last bits of its path differ) and is not compared
//          further, nor is one whose status differs (counted) or a failed ray. Of the rest, the redshift is compared
//          for every ray; the direction (sky direction, or hit point) and the hit radius for escaped and hit rays.
//          A captured ray's end on the horizon guard is reported apart (captured), not judged: towards a Kerr
//          horizon in Boyer-Lindquist coordinates its azimuth winds without bound (k^phi ~ -900 there), so a
//          last-bit difference anywhere on the way moves it by up to ~1e-3 rad.
#pragma once

#include "grtrace/core/sky_direction.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace grtrace::testing_support {

struct OutcomeComparison {
  long compared = 0;        ///< pixels with the same object and status, not failed
  long silhouette = 0;      ///< pixels whose object differs
  long status_differs = 0;  ///< pixels with the same object and another status
  long order_differs = 0;   ///< compared pixels whose image order differs (RayOutcome::order)
  double redshift = 0.0;    ///< largest redshift difference of the compared pixels
  double direction = 0.0;   ///< largest angle between the sky directions or hit points (escaped and hit rays)
  double radius = 0.0;      ///< largest relative difference of the hit radius
  double captured = 0.0;    ///< largest angle between captured rays' ends on the horizon guard (not judged)
};

/// The comparison; on_direction(i, angle) sees each escaped or hit pixel i compared and its angle.
template <class OnDirection>
OutcomeComparison compare_outcomes(const std::vector<RayOutcome>& gpu, const std::vector<RayOutcome>& cpu,
                                   OnDirection&& on_direction) {
  OutcomeComparison r;
  for (std::size_t i = 0; i < gpu.size() && i < cpu.size(); ++i) {
    const RayOutcome &g = gpu[i], &c = cpu[i];
    if (g.object != c.object) {
      ++r.silhouette;
      continue;
    }
    if (g.status != c.status) {
      ++r.status_differs;
      continue;
    }
    if (is_failure(c.status)) continue;
    ++r.compared;
    if (g.order != c.order) ++r.order_differs;
    r.redshift = std::max(r.redshift, std::abs(g.redshift - c.redshift));
    const double angle = angular_distance(g.where, c.where);
    if (c.status == RayStatus::captured) {
      r.captured = std::max(r.captured, angle);
      continue;
    }
    r.direction = std::max(r.direction, angle);
    if (c.status == RayStatus::hit) r.radius = std::max(r.radius, std::abs(g.radius / c.radius - 1.0));
    on_direction(i, angle);
  }
  return r;
}

inline OutcomeComparison compare_outcomes(const std::vector<RayOutcome>& gpu, const std::vector<RayOutcome>& cpu) {
  return compare_outcomes(gpu, cpu, [](std::size_t, double) {});
}

}  // namespace grtrace::testing_support
