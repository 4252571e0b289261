// grtrace/tableau/fehlberg45.hpp
// Runge-Kutta-Fehlberg 4(5) (Fehlberg 1969, "Low-order classical Runge-Kutta formulas with stepsize control
// and their application to some heat transfer problems", NASA TR R-315). As Fehlberg intended, the
// fourth-order solution is propagated (b) and the fifth-order one (b_hat) only serves the error estimate, so
// embedded_order (5) is higher than order (4).
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct Fehlberg45 {
  static constexpr std::string_view name = "rkf45";
  static constexpr std::size_t stages = 6;
  static constexpr int order = 4;
  static constexpr int embedded_order = 5;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<6> a = {{
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {1.0 / 4.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {3.0 / 32.0, 9.0 / 32.0, 0.0, 0.0, 0.0, 0.0},
      {1932.0 / 2197.0, -7200.0 / 2197.0, 7296.0 / 2197.0, 0.0, 0.0, 0.0},
      {439.0 / 216.0, -8.0, 3680.0 / 513.0, -845.0 / 4104.0, 0.0, 0.0},
      {-8.0 / 27.0, 2.0, -3544.0 / 2565.0, 1859.0 / 4104.0, -11.0 / 40.0, 0.0},
  }};
  static constexpr TableauRow<6> b = {25.0 / 216.0, 0.0, 1408.0 / 2565.0, 2197.0 / 4104.0, -1.0 / 5.0, 0.0};
  static constexpr TableauRow<6> c = {0.0, 1.0 / 4.0, 3.0 / 8.0, 12.0 / 13.0, 1.0, 1.0 / 2.0};
  static constexpr TableauRow<6> b_hat = {16.0 / 135.0,      0.0,         6656.0 / 12825.0,
                                          28561.0 / 56430.0, -9.0 / 50.0, 2.0 / 55.0};
};
GRTRACE_CHECK_TABLEAU(Fehlberg45);

}  // namespace grtrace
