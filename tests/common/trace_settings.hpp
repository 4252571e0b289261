// tests/common/trace_settings.hpp
// The trace settings most tracer tests compare at: a relative tolerance, an absolute one a hundred times smaller,
// and the sky sphere's radius; everything else at its default. One helper instead of a copy per test file.
#pragma once

#include "grtrace/trace/geodesic_tracer.hpp"

namespace grtrace::test_settings {

/// TraceSettings with tolerances (rtol, rtol / 100) and the sky sphere at `sky_radius`.
inline TraceSettings settings_at(double rtol, double sky_radius) {
  TraceSettings s;
  s.integrator.tolerance = {rtol, 1e-2 * rtol};
  s.escape_radius = sky_radius;
  return s;
}

}  // namespace grtrace::test_settings
