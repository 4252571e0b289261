// grtrace/tableau/cash_karp54.hpp
// Cash & Karp (1990), "A variable order Runge-Kutta method for initial value problems with rapidly varying
// right-hand sides", ACM Trans. Math. Softw. 16(3), 201-222. Six stages; the fifth-order solution is
// propagated and the fourth-order one is the embedded estimate (the pairing used by Numerical Recipes' rkck).
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct CashKarp54 {
  static constexpr std::string_view name = "cashkarp";
  static constexpr std::size_t stages = 6;
  static constexpr int order = 5;
  static constexpr int embedded_order = 4;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<6> a = {{
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0},
      {3.0 / 10.0, -9.0 / 10.0, 6.0 / 5.0, 0.0, 0.0, 0.0},
      {-11.0 / 54.0, 5.0 / 2.0, -70.0 / 27.0, 35.0 / 27.0, 0.0, 0.0},
      {1631.0 / 55296.0, 175.0 / 512.0, 575.0 / 13824.0, 44275.0 / 110592.0, 253.0 / 4096.0, 0.0},
  }};
  static constexpr TableauRow<6> b = {37.0 / 378.0, 0.0, 250.0 / 621.0, 125.0 / 594.0, 0.0, 512.0 / 1771.0};
  static constexpr TableauRow<6> c = {0.0, 1.0 / 5.0, 3.0 / 10.0, 3.0 / 5.0, 1.0, 7.0 / 8.0};
  static constexpr TableauRow<6> b_hat = {2825.0 / 27648.0, 0.0,      18575.0 / 48384.0, 13525.0 / 55296.0,
                                          277.0 / 14336.0,  1.0 / 4.0};
};
GRTRACE_CHECK_TABLEAU(CashKarp54);

}  // namespace grtrace
