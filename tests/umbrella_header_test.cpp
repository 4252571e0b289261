// <grtrace/grtrace.hpp> must compile on its own with the standard library and Eigen only, and expose the core.
#include "grtrace/grtrace.hpp"

// Nothing of the render floor comes with it: no POSIX signal handling (render/output_file.hpp), no OpenEXR
// (render/exr_io.hpp). Checked before anything else is included.
#if defined(SIGINT) || defined(SIGTERM)
#error "<grtrace/grtrace.hpp> pulled in <signal.h>: the core must not depend on POSIX signals (render/ only)"
#endif
#if defined(INCLUDED_IMF_RGBA_FILE_H) || defined(INCLUDED_IMF_OUTPUT_FILE_H) || defined(OPENEXR_VERSION_MAJOR)
#error "<grtrace/grtrace.hpp> pulled in OpenEXR: the core must not depend on it (render/exr_io.hpp only)"
#endif

#include <gtest/gtest.h>

TEST(UmbrellaHeader, ExposesCoreAndComputes) {
  using namespace grtrace;
  const GeodesicTracer<SchwarzschildMetric, DormandPrince54, PIController> tracer(SchwarzschildMetric{1.0},
                                                                                  TraceSettings{});
  const DeflectionResult d = measure_deflection(tracer, 10.0);
  ASSERT_EQ(d.trace.status, RayStatus::escaped);
  EXPECT_NEAR(d.deflection, exact::deflection_angle(10.0), 1e-6);
  EXPECT_EQ(tableau_names().size(), 12u);
}
