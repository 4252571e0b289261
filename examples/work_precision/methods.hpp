// examples/work_precision/methods.hpp
// The (tableau, controller) pairs grtrace-work-precision can run, as a table of function pointers.
// Only valid pairs are instantiated (I and PI need an embedded pair: is_valid_method). The instantiations
// are spread over several translation units (methods_*.cpp) so that a 2-core build compiles them in parallel.
#pragma once

#include "grtrace/trace/method_dispatch.hpp"
#include "work_precision.hpp"

#include <string_view>
#include <type_traits>
#include <vector>

namespace grtrace::work_precision {

using RunFunction = RunStats (*)(const RaySet&, const SweepPoint&, const RunOptions&);

struct Method {
  std::string_view tableau;
  std::string_view controller;
  int order;        ///< order of the propagated solution
  bool fixed_step;  ///< the sweep is over the step size, not the tolerance
  RunFunction run;
};

/// Appends every valid (T, C) pair for the tableaux Ts, controllers in kControllerNames order.
template <class... Ts>
void append_methods(std::vector<Method>& out) {
  auto one_tableau = [&]<class T>(std::type_identity<T>) {
    auto one_controller = [&]<class C>(std::type_identity<C>) {
      if constexpr (is_valid_method<T, C>)
        out.push_back({T::name, C::name, T::order, C::estimate == ErrorEstimate::none, &run_configuration<T, C>});
    };
    one_controller(std::type_identity<FixedStep>{});
    one_controller(std::type_identity<StepDoubling>{});
    one_controller(std::type_identity<IController>{});
    one_controller(std::type_identity<PIController>{});
  };
  (one_tableau(std::type_identity<Ts>{}), ...);
}

// Each defined in its own translation unit.
std::vector<Method> methods_low_order();    // euler, midpoint, heun, rk4, rk38, bs3
std::vector<Method> methods_fifth_order();  // rkf45, cashkarp, dopri5, tsit5
std::vector<Method> methods_high_order();   // vern6, rkf78

/// Every valid pair, in AllTableaux order.
inline std::vector<Method> all_methods() {
  std::vector<Method> all = methods_low_order();
  for (auto part : {methods_fifth_order(), methods_high_order()}) all.insert(all.end(), part.begin(), part.end());
  return all;
}

}  // namespace grtrace::work_precision
