// Must not compile: g written on doubles only, so AutoMetric has nothing to differentiate.
#include "grtrace/metric/auto_metric.hpp"

#include <array>
#include <string_view>

struct NotATemplate {
  static constexpr std::string_view name = "not-a-template";
  static constexpr grtrace::Chart chart = grtrace::Chart::spherical;
  grtrace::Mat4 metric_components(const grtrace::Vec4& /*x*/) const { return grtrace::Mat4::Identity(); }
  double radius(const grtrace::Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 0.0; }
};
const grtrace::AutoMetric<NotATemplate> metric{};
