// grtrace-geodesic's share of the method matrix for euler, midpoint, heun, rk4, rk38, bs3 (see geodesic_run.hpp).
#include "geodesic_run.hpp"

#include "grtrace/tableau/all_tableaux.hpp"

namespace grtrace::geodesic_tool {

std::optional<JsonObject> run_low_order(const Request& q, const Outputs& files, std::string_view tableau,
                                        std::string_view control) {
  return run_among<ExplicitEuler, ExplicitMidpoint, Heun, ClassicRK4, Rule38, BogackiShampine32>(q, files, tableau, control);
}

}  // namespace grtrace::geodesic_tool
