// <grtrace/grtrace.hpp> must compile on its own with Eigen + GLM only, and expose the core.
#include "grtrace/grtrace.hpp"

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
