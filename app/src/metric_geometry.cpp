// A named metric's geometry outside the hot loop (grtrace/app/front_door.hpp, MetricGeometry), the flights' paths and
// cameras: compiled once for every named metric, in one unit (the paths' integrations, sample_worldline and the
// proper-time searches of observer/flight_path.hpp, with their integrator steps), instead of once per tool.
#include "grtrace/app/front_door.hpp"
#include "grtrace/metric/metric_traits.hpp"
#include "grtrace/trace/traced_path.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>

namespace grtrace::app {

namespace {

template <MetricPolicy M>
class GeometryOf final : public MetricGeometry {
 public:
  explicit GeometryOf(const M& metric) : metric_(metric) {}
  Mat4 metric(const Vec4& x) const override { return metric_.metric(x); }
  Vec3 to_cartesian(const Vec4& x) const override { return metric_.to_cartesian(x); }
  double radius(const Vec4& x) const override { return metric_.radius(x); }
  double horizon_radius() const override { return metric_.horizon_radius(); }
  Vec4 from_spherical(const Vec4& x) const override { return event_from_spherical(metric_, x); }
  Vec4 to_spherical(const Vec4& x) const override {
    if constexpr (M::chart == Chart::spherical) {
      return x;
    } else if constexpr (HasSphericalChart<M>) {
      return metric_.spherical_event(x);
    } else {  // a flat Cartesian chart: the embedding's own spherical coordinates
      const double r = std::sqrt(x[1] * x[1] + x[2] * x[2] + x[3] * x[3]);
      return Vec4(x[0], r, r > 0.0 ? std::acos(std::clamp(x[3] / r, -1.0, 1.0)) : 0.0, std::atan2(x[2], x[1]));
    }
  }
  Camera make_camera(const CameraSpec& spec) const override { return grtrace::make_camera(metric_, spec); }
  Camera make_moving_camera(const Vec4& x, const Vec4& u, const CameraView& view) const override {
    return grtrace::make_moving_camera(metric_, x, u, view);
  }
  Worldline flight(const FlightPathSpec& spec) const override { return flight_path(metric_, spec); }
  TracedPath worldline_path(const Worldline& w) const override { return grtrace::worldline_path(metric_, w); }

 private:
  M metric_;
};

}  // namespace

std::unique_ptr<MetricGeometry> MetricGeometry::create(const MetricSpec& spec) {
  return with_named_metric(spec, [](const auto& m) -> std::unique_ptr<MetricGeometry> {
    return std::make_unique<GeometryOf<std::remove_cvref_t<decltype(m)>>>(m);
  });
}

Worldline flight_worldline(const MetricSpec& metric, const FlightPathSpec& spec) {
  return with_named_metric(metric, [&](const auto& m) { return flight_path(m, spec); });
}

std::vector<Camera> flight_cameras(const MetricSpec& metric, const Worldline& path, const CameraView& view) {
  return with_named_metric(metric, [&](const auto& m) { return grtrace::flight_cameras(m, path, view); });
}

}  // namespace grtrace::app
