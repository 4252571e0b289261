// Uses the installed headers for real: the Schwarzschild metric, the Dormand-Prince tableau's compile-time
// checks, and one traced photon on each side of the photon sphere. Exit code 0 = every check passed.
#include <grtrace/core/ray_status.hpp>
#include <grtrace/metric/schwarzschild.hpp>
#include <grtrace/tableau/dormand_prince54.hpp>
#include <grtrace/trace/geodesic_tracer.hpp>
#include <grtrace/version.hpp>  // generated at configure time and installed beside the other headers

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <string_view>

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  std::printf("%s: %s\n", ok ? "ok  " : "FAIL", what);
  if (!ok) ++failures;
}

/// A photon in the equatorial plane at radius r, moving inwards with unit energy and impact parameter b.
grtrace::GeodesicState photon_at(const grtrace::SchwarzschildMetric& m, double r, double b) {
  const double f = 1.0 - 2.0 * m.mass / r;
  const grtrace::Vec4 x(0.0, r, std::numbers::pi / 2.0, 0.0);
  const grtrace::Vec4 k(1.0 / f, -std::sqrt(1.0 - f * b * b / (r * r)), 0.0, b / (r * r));
  return grtrace::make_state(x, k);
}

}  // namespace

int main() {
  static_assert(grtrace::tableau_is_valid<grtrace::DormandPrince54>());
  check(grtrace::tableau_is_valid<grtrace::DormandPrince54>(), "DormandPrince54 passes its tableau checks");

  const grtrace::SchwarzschildMetric metric{1.0};
  const grtrace::Mat4 g = metric.metric(grtrace::Vec4(0.0, 10.0, std::numbers::pi / 2.0, 0.0));
  check(std::abs(g(0, 0) - 0.8) < 1e-15, "Schwarzschild g_tt(r = 10) = 0.8");

  // Critical impact parameter 3 sqrt(3) M = 5.196: b = 7 escapes, b = 5 falls in.
  const grtrace::GeodesicTracer<grtrace::SchwarzschildMetric, grtrace::DormandPrince54, grtrace::PIController> tracer(
      metric, grtrace::TraceSettings{});
  const grtrace::TraceResult wide = tracer.trace(photon_at(metric, 50.0, 7.0));
  const grtrace::TraceResult close = tracer.trace(photon_at(metric, 50.0, 5.0));
  std::printf("b = 7: %s after %d steps; b = 5: %s after %d steps\n", grtrace::to_string(wide.status).data(),
              wide.accepted, grtrace::to_string(close.status).data(), close.accepted);
  check(wide.status == grtrace::RayStatus::escaped, "photon with b = 7 escapes");
  check(close.status == grtrace::RayStatus::captured, "photon with b = 5 is captured");
  check(std::abs(wide.constraint_drift) < 1e-6, "g(k, k) stays null along the b = 7 ray");

  std::printf("grtrace %s\n", grtrace::kVersion.data());
  check(grtrace::kVersion == std::to_string(GRTRACE_VERSION_MAJOR) + "." + std::to_string(GRTRACE_VERSION_MINOR) +
                                 "." + std::to_string(GRTRACE_VERSION_PATCH),
        "grtrace/version.hpp: kVersion is MAJOR.MINOR.PATCH");
#ifdef GRTRACE_EXPECTED_VERSION
  check(grtrace::kVersion == GRTRACE_EXPECTED_VERSION, "grtrace/version.hpp matches the package version");
#endif

  return failures == 0 ? 0 : 1;
}
