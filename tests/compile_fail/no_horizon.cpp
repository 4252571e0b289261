// Must not compile: horizon_radius() is missing.
#include "grtrace/metric/auto_metric.hpp"

#include <array>
#include <string_view>

struct NoHorizon {
  static constexpr std::string_view name = "no-horizon";
  static constexpr grtrace::Chart chart = grtrace::Chart::spherical;
  template <class S>
  grtrace::Mat4Of<S> metric_components(const grtrace::Vec4Of<S>& /*x*/) const {
    return grtrace::Mat4Of<S>::Identity();
  }
  double radius(const grtrace::Vec4& x) const { return x[1]; }
};
const grtrace::AutoMetric<NoHorizon> metric{};
