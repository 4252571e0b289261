// grtrace/trace/tracer_report.hpp
// What a scene tracer can say about itself after a frame, read through optional members (detected at compile time,
// so any SceneTracer works; trace/scene_tracer_concept.hpp):
//   static name                     every tracer: "general", "planar", "symmetric-sky", "straight-line", ...
//   table().table_rays(), table().table_steps()   tracers that build a table of rays per frame (planar, symmetric)
//   fallback_rays()                 tracers that hand some pixels to another tracer (planar -> general)
//   sky_continuation()              how escaped rays are continued to infinity (trace/sky_continuation.hpp)
#pragma once

#include "grtrace/trace/sky_continuation_kind.hpp"

#include <string>

namespace grtrace {

struct TracerReport {
  std::string name;
  long table_rays = 0;     ///< rays in the frame's table (0: no table)
  long table_steps = 0;    ///< accepted steps spent building it
  long fallback_rays = 0;  ///< pixels traced by a fallback tracer
  std::string sky_continuation;  ///< sky_continuation_name of the tracer's continuation ("" if it does not say)
};

template <class Tracer>
TracerReport tracer_report(const Tracer& tracer) {
  TracerReport r;
  r.name = Tracer::name;
  if constexpr (requires { tracer.table().table_rays(); }) {
    r.table_rays = tracer.table().table_rays();
    r.table_steps = tracer.table().table_steps();
  }
  if constexpr (requires { tracer.fallback_rays(); }) r.fallback_rays = tracer.fallback_rays();
  if constexpr (requires { tracer.sky_continuation(); })
    r.sky_continuation = sky_continuation_name(tracer.sky_continuation());
  return r;
}

}  // namespace grtrace
