// grtrace-geodesic's share of the method matrix for vern6, rkf78 (see geodesic_run.hpp).
#include "geodesic_run.hpp"

#include "grtrace/tableau/all_tableaux.hpp"

namespace grtrace::geodesic_tool {

std::optional<JsonObject> run_high_order(const Request& q, const Outputs& files, std::string_view tableau,
                                         std::string_view control) {
  return run_among<Verner65, Fehlberg78>(q, files, tableau, control);
}

}  // namespace grtrace::geodesic_tool
