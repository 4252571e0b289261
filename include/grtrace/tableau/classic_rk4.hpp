// grtrace/tableau/classic_rk4.hpp
// The classic fourth-order Runge-Kutta method (Kutta 1901), the seed report's integrator.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct ClassicRK4 {
  static constexpr std::string_view name = "rk4";
  static constexpr std::size_t stages = 4;
  static constexpr int order = 4;
  static constexpr int embedded_order = 0;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<4> a = {{
      {0.0, 0.0, 0.0, 0.0},
      {0.5, 0.0, 0.0, 0.0},
      {0.0, 0.5, 0.0, 0.0},
      {0.0, 0.0, 1.0, 0.0},
  }};
  static constexpr TableauRow<4> b = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
  static constexpr TableauRow<4> c = {0.0, 0.5, 0.5, 1.0};
  static constexpr TableauRow<4> b_hat = {0.0, 0.0, 0.0, 0.0};
};
GRTRACE_CHECK_TABLEAU(ClassicRK4);

}  // namespace grtrace
