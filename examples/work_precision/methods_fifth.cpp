// Instantiations for grtrace-work-precision: the 4(5)/5(4) pairs (see methods.hpp).
#include "grtrace/tableau/all_tableaux.hpp"
#include "methods.hpp"

namespace grtrace::work_precision {
std::vector<Method> methods_fifth_order() {
  std::vector<Method> m;
  append_methods<Fehlberg45, CashKarp54, DormandPrince54, Tsitouras54>(m);
  return m;
}
}  // namespace grtrace::work_precision
