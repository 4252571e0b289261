// Instantiations for grtrace-work-precision: the low-order tableaux (see methods.hpp).
#include "grtrace/tableau/all_tableaux.hpp"
#include "methods.hpp"

namespace grtrace::work_precision {
std::vector<Method> methods_low_order() {
  std::vector<Method> m;
  append_methods<ExplicitEuler, ExplicitMidpoint, Heun, ClassicRK4, Rule38, BogackiShampine32>(m);
  return m;
}
}  // namespace grtrace::work_precision
