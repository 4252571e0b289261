// Instantiations for grtrace-work-precision: the high-order pairs (see methods.hpp).
#include "grtrace/tableau/all_tableaux.hpp"
#include "methods.hpp"

namespace grtrace::work_precision {
std::vector<Method> methods_high_order() {
  std::vector<Method> m;
  append_methods<Verner65, Fehlberg78>(m);
  return m;
}
}  // namespace grtrace::work_precision
