// grtrace/tableau/explicit_midpoint.hpp
// Explicit midpoint rule (Runge 1895, "Ueber die numerische Aufloesung von Differentialgleichungen", Math.
// Ann. 46, 167-178): two stages, order 2, no error estimate.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct ExplicitMidpoint {
  static constexpr std::string_view name = "midpoint";
  static constexpr std::size_t stages = 2;
  static constexpr int order = 2;
  static constexpr int embedded_order = 0;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<2> a = {{
      {0.0, 0.0},
      {1.0 / 2.0, 0.0},
  }};
  static constexpr TableauRow<2> b = {0.0, 1.0};
  static constexpr TableauRow<2> c = {0.0, 1.0 / 2.0};
  static constexpr TableauRow<2> b_hat = {0.0, 0.0};
};
GRTRACE_CHECK_TABLEAU(ExplicitMidpoint);

}  // namespace grtrace
