// Must not compile: depends_on names coordinate 4 (there are 0..3).
#include "grtrace/metric/auto_metric.hpp"

#include <array>
#include <string_view>

struct BadDependsOn {
  static constexpr std::string_view name = "bad-depends-on";
  static constexpr grtrace::Chart chart = grtrace::Chart::spherical;
  static constexpr std::array<int, 2> depends_on = {1, 4};
  template <class S>
  grtrace::Mat4Of<S> metric_components(const grtrace::Vec4Of<S>& /*x*/) const {
    return grtrace::Mat4Of<S>::Identity();
  }
  double radius(const grtrace::Vec4& x) const { return x[1]; }
  double horizon_radius() const { return 0.0; }
};
const grtrace::AutoMetric<BadDependsOn> metric{};
