// grtrace/tableau/fehlberg78.hpp
// Runge-Kutta-Fehlberg 7(8) (Fehlberg 1968, "Classical fifth-, sixth-, seventh-, and eighth-order Runge-Kutta
// formulas with stepsize control", NASA TR R-287). Thirteen stages; stages 12 and 13 exist only for the
// eighth-order weights. Propagated here with local extrapolation: b holds the eighth-order weights and b_hat
// Fehlberg's seventh-order ones; b_hat - b = 41/840 (e1 + e11 - e12 - e13).
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct Fehlberg78 {
  static constexpr std::string_view name = "rkf78";
  static constexpr std::size_t stages = 13;
  static constexpr int order = 8;
  static constexpr int embedded_order = 7;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<13> a = {{
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {2.0 / 27.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {1.0 / 36.0, 1.0 / 12.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {1.0 / 24.0, 0.0, 1.0 / 8.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {5.0 / 12.0, 0.0, -25.0 / 16.0, 25.0 / 16.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {1.0 / 20.0, 0.0, 0.0, 1.0 / 4.0, 1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {-25.0 / 108.0, 0.0, 0.0, 125.0 / 108.0, -65.0 / 27.0, 125.0 / 54.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {31.0 / 300.0, 0.0, 0.0, 0.0, 61.0 / 225.0, -2.0 / 9.0, 13.0 / 900.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {2.0, 0.0, 0.0, -53.0 / 6.0, 704.0 / 45.0, -107.0 / 9.0, 67.0 / 90.0, 3.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {-91.0 / 108.0, 0.0, 0.0, 23.0 / 108.0, -976.0 / 135.0, 311.0 / 54.0, -19.0 / 60.0, 17.0 / 6.0, -1.0 / 12.0, 0.0,
       0.0, 0.0, 0.0},
      {2383.0 / 4100.0, 0.0, 0.0, -341.0 / 164.0, 4496.0 / 1025.0, -301.0 / 82.0, 2133.0 / 4100.0, 45.0 / 82.0,
       45.0 / 164.0, 18.0 / 41.0, 0.0, 0.0, 0.0},
      {3.0 / 205.0, 0.0, 0.0, 0.0, 0.0, -6.0 / 41.0, -3.0 / 205.0, -3.0 / 41.0, 3.0 / 41.0, 6.0 / 41.0, 0.0, 0.0, 0.0},
      {-1777.0 / 4100.0, 0.0, 0.0, -341.0 / 164.0, 4496.0 / 1025.0, -289.0 / 82.0, 2193.0 / 4100.0, 51.0 / 82.0,
       33.0 / 164.0, 12.0 / 41.0, 0.0, 1.0, 0.0},
  }};
  static constexpr TableauRow<13> b = {0.0,          0.0,          0.0,         0.0,         0.0,
                                       34.0 / 105.0, 9.0 / 35.0,   9.0 / 35.0,  9.0 / 280.0, 9.0 / 280.0,
                                       0.0,          41.0 / 840.0, 41.0 / 840.0};
  static constexpr TableauRow<13> c = {0.0,       2.0 / 27.0, 1.0 / 9.0, 1.0 / 6.0, 5.0 / 12.0, 1.0 / 2.0, 5.0 / 6.0,
                                       1.0 / 6.0, 2.0 / 3.0,  1.0 / 3.0, 1.0,       0.0,        1.0};
  static constexpr TableauRow<13> b_hat = {41.0 / 840.0, 0.0,        0.0,        0.0,         0.0,
                                           34.0 / 105.0, 9.0 / 35.0, 9.0 / 35.0, 9.0 / 280.0, 9.0 / 280.0,
                                           41.0 / 840.0, 0.0,        0.0};
};
GRTRACE_CHECK_TABLEAU(Fehlberg78);

}  // namespace grtrace
