// grtrace/tableau/bogacki_shampine32.hpp
// Bogacki & Shampine (1989), "A 3(2) pair of Runge-Kutta formulas", Appl. Math. Lett. 2(4), 321-325. Four
// stages with FSAL (three new evaluations per step); the propagated solution is the third-order one and b_hat
// is the second-order solution that uses the FSAL stage.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct BogackiShampine32 {
  static constexpr std::string_view name = "bs3";
  static constexpr std::size_t stages = 4;
  static constexpr int order = 3;
  static constexpr int embedded_order = 2;
  static constexpr bool fsal = true;
  static constexpr TableauMatrix<4> a = {{
      {0.0, 0.0, 0.0, 0.0},
      {1.0 / 2.0, 0.0, 0.0, 0.0},
      {0.0, 3.0 / 4.0, 0.0, 0.0},
      {2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0, 0.0},
  }};
  static constexpr TableauRow<4> b = {2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0, 0.0};
  static constexpr TableauRow<4> c = {0.0, 1.0 / 2.0, 3.0 / 4.0, 1.0};
  static constexpr TableauRow<4> b_hat = {7.0 / 24.0, 1.0 / 4.0, 1.0 / 3.0, 1.0 / 8.0};
};
GRTRACE_CHECK_TABLEAU(BogackiShampine32);

}  // namespace grtrace
