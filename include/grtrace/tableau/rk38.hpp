// grtrace/tableau/rk38.hpp
// Kutta's 3/8 rule (Kutta 1901, "Beitrag zur naeherungsweisen Integration totaler Differentialgleichungen",
// Z. Math. Phys. 46, 435-453): the four-stage, order-4 companion of the classic RK4 with nodes 0, 1/3, 2/3,
// 1.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct Rule38 {
  static constexpr std::string_view name = "rk38";
  static constexpr std::size_t stages = 4;
  static constexpr int order = 4;
  static constexpr int embedded_order = 0;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<4> a = {{
      {0.0, 0.0, 0.0, 0.0},
      {1.0 / 3.0, 0.0, 0.0, 0.0},
      {-1.0 / 3.0, 1.0, 0.0, 0.0},
      {1.0, -1.0, 1.0, 0.0},
  }};
  static constexpr TableauRow<4> b = {1.0 / 8.0, 3.0 / 8.0, 3.0 / 8.0, 1.0 / 8.0};
  static constexpr TableauRow<4> c = {0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0};
  static constexpr TableauRow<4> b_hat = {0.0, 0.0, 0.0, 0.0};
};
GRTRACE_CHECK_TABLEAU(Rule38);

}  // namespace grtrace
