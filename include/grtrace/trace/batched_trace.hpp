// grtrace/trace/batched_trace.hpp
// Many rays through one metric, W at a time in the lanes of a BatchedIntegrator (integrate/batch_integrator.hpp),
// each ray's result bit for bit what GeodesicTracer::trace gives it alone.
//
// Why: the general tracer's step is a latency-bound chain (docs/benchmarks.md, "A shorter chain per step"), so
// W rays side by side run W chains per instruction. What makes a ray's life interesting (a surface crossed, the
// constraint guard failing, the polar axis, max_steps, a step below h_min) is rare: a lane takes the ray's steps
// only while nothing of that happens, and hands the ray to the scalar tracing loop (TraceLoop::run, the same code
// trace() runs) at the point before the step that needs it; the loop takes that step again, bit for bit the same,
// does what is due, and gives the ray back to the lane if it goes on. A ray costs one step more than alone for each
// such event (the step taken twice; e.g. one for a capture, one more for each crossing of a disk's plane).
//
// Takes:   a GeodesicTracer, the rays' initial states y0 and their events (as for trace()).
// Returns: out[i] = tracer.trace(y0[i], events...) for every i, bit for bit (tests/batched_trace_test.cpp).
// Assumes: out.size() == y0.size(). Rays whose loop needs more than a lane offers take the scalar loop from their
//          start: controllers without an embedded estimate (step doubling, fixed steps), events that sample the
//          inside of every step (interior_samples), a camera inside the horizon guard (the guard not yet armed).
#pragma once

#include "grtrace/integrate/batch_integrator.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <array>
#include <cstddef>
#include <optional>
#include <span>

namespace grtrace {

/// Rays per batch: four doubles fill a 256-bit register (AVX2, the build machine's; docs/benchmarks.md).
inline constexpr int kTraceLanes = 4;

/// True when trace_batched integrates in lanes (see the top of this file): an embedded error estimate, and no event
/// that samples the inside of every step.
template <class Controller, class... Events>
inline constexpr bool lanes_can_trace = Controller::estimate == ErrorEstimate::embedded &&
                                        ((event_interior_samples<Events>() == 0) && ...);

template <int W = kTraceLanes, MetricPolicy Metric, ExplicitTableau Tableau, StepController Controller, class... Events>
void trace_batched(const GeodesicTracer<Metric, Tableau, Controller>& tracer, std::span<const GeodesicState> y0,
                   std::span<TraceResult> out, const Events&... events) {
  // A CUDA compilation's device pass (core/host_device.hpp) sees the plain loop only: this is host code, and the
  // lanes' vector types would make nvcc compile device copies of the shared scalar/lane templates they reach.
  if constexpr (!lanes_can_trace<Controller, Events...> || GRTRACE_DEVICE_PASS) {
    for (std::size_t i = 0; i < y0.size(); ++i) out[i] = tracer.trace(y0[i], events...);
  } else {
    if (y0.empty()) return;
    using System = MetricGeodesicSystem<Metric>;
    using Loop = TraceLoop<Tableau, Controller, System, Events...>;
    using Integrator = typename Loop::Integrator;
    constexpr auto lanes_count = static_cast<std::size_t>(W);
    const Metric& metric = tracer.metric();
    const TraceSettings& settings = tracer.settings();
    const System rhs(metric, y0.front());  // the right-hand side is the metric's alone: any ray's system will do
    BatchedIntegrator<Tableau, Controller, 8, W> lanes(settings.integrator);
    std::array<std::optional<Loop>, lanes_count> loop;
    std::array<typename Loop::Progress, lanes_count> progress;
    std::array<std::size_t, lanes_count> ray{};
    std::size_t next = 0;

    // Lane l takes the next ray that needs integrating; rays that end at their start, or need the scalar loop
    // throughout, are traced on the way.
    const auto fill = [&](int l) {
      const auto s = static_cast<std::size_t>(l);
      while (next < y0.size()) {
        const std::size_t i = next++;
        const GeodesicState& z0 = y0[i];
        loop[s].emplace(System(metric, z0), settings, capture_radius_of(metric, z0), events...);
        Integrator integ(settings.integrator, tracer.controller());
        if (auto ended = loop[s]->begin(z0, leaves_interior_of(metric, z0), progress[s], integ)) {
          out[i] = *ended;
          continue;
        }
        if (!progress[s].guard_armed) {
          out[i] = loop[s]->run(integ, progress[s], NullObserver{});
          continue;
        }
        ray[s] = i;
        lanes.load(l, integ);
        return;
      }
      lanes.idle(l);
    };
    // The scalar loop takes one step of lane l's ray from the lane's point (before its last trial when that was
    // not committed) and does what is due after it; a ray that goes on comes back into the lane, an ended one
    // leaves it to the next ray.
    const auto hand_over = [&](int l) {
      const auto s = static_cast<std::size_t>(l);
      Integrator integ(settings.integrator, tracer.controller());
      lanes.unload(l, integ);
      Optional<TraceResult> ended = loop[s]->step(integ, progress[s], NullObserver{});
      if (!ended && integ.accepted() >= settings.max_steps) ended = loop[s]->out_of_steps(integ, progress[s]);
      if (!ended && progress[s].guard_armed) return lanes.load(l, integ);
      out[ray[s]] = ended ? *ended : loop[s]->run(integ, progress[s], NullObserver{});
      fill(l);
    };

    for (int l = 0; l < W; ++l) fill(l);
    for (;;) {
      bool any = false;
      for (int l = 0; l < W; ++l) {
        // The last allowed step is the loop's: it ends the ray with max_steps (or what that step meets).
        if (lanes.busy(l) && lanes.counters(l).accepted + 1 >= settings.max_steps) hand_over(l);
        any = any || lanes.busy(l);
      }
      if (!any) return;
      const auto verdict = lanes.trial(rhs);
      for (int l = 0; l < W; ++l) {
        const auto s = static_cast<std::size_t>(l);
        if (verdict[s] == TrialVerdict::not_taken) {
          hand_over(l);
        } else if (verdict[s] == TrialVerdict::accepted) {
          if (loop[s]->uneventful(lanes.candidate(l), progress[s])) lanes.commit(l);
          else hand_over(l);
        }
      }
    }
  }
}

}  // namespace grtrace
