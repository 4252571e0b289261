// grtrace/tableau/heun.hpp
// Heun's method, the explicit trapezoidal rule (Heun 1900, "Neue Methoden zur approximativen Integration der
// Differentialgleichungen einer unabhaengigen Veraenderlichen", Z. Math. Phys. 45, 23-38), paired with
// forward Euler as the embedded first-order solution: the Heun-Euler 2(1) pair. The propagated solution is
// order 2.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct Heun {
  static constexpr std::string_view name = "heun";
  static constexpr std::size_t stages = 2;
  static constexpr int order = 2;
  static constexpr int embedded_order = 1;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<2> a = {{
      {0.0, 0.0},
      {1.0, 0.0},
  }};
  static constexpr TableauRow<2> b = {1.0 / 2.0, 1.0 / 2.0};
  static constexpr TableauRow<2> c = {0.0, 1.0};
  static constexpr TableauRow<2> b_hat = {1.0, 0.0};
};
GRTRACE_CHECK_TABLEAU(Heun);

}  // namespace grtrace
