// Must not compile: metric_components is not const.
#include "grtrace/metric/auto_metric.hpp"

#include <array>
#include <string_view>

struct NotConst {
  static constexpr std::string_view name = "not-const";
  static constexpr grtrace::Chart chart = grtrace::Chart::spherical;
  template <class S>
  grtrace::Mat4Of<S> metric_components(const grtrace::Vec4Of<S>& /*x*/) {
    return grtrace::Mat4Of<S>::Identity();
  }
  double radius(const grtrace::Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 0.0; }
};
const grtrace::AutoMetric<NotConst> metric{};
