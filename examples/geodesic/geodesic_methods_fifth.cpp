// grtrace-geodesic's share of the method matrix for rkf45, cashkarp, dopri5, tsit5 (see geodesic_run.hpp).
#include "geodesic_run.hpp"

#include "grtrace/tableau/all_tableaux.hpp"

namespace grtrace::geodesic_tool {

std::optional<JsonObject> run_fifth_order(const Request& q, const Outputs& files, std::string_view tableau,
                                          std::string_view control) {
  return run_among<Fehlberg45, CashKarp54, DormandPrince54, Tsitouras54>(q, files, tableau, control);
}

}  // namespace grtrace::geodesic_tool
