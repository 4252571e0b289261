// grtrace/tableau/verner65.hpp
// Verner's eight-stage 6(5) pair (J. H. Verner, "Explicit Runge-Kutta methods with estimates of the local
// truncation error", SIAM J. Numer. Anal. 15(4) (1978) 772-790), the pair inside the DVERK code of Hull,
// Enright & Jackson. The sixth-order solution is propagated (b); b_hat is the fifth-order one. Not FSAL.
// Verner's later 9-stage FSAL "most efficient" 6(5) pair (OrdinaryDiffEq.jl's Vern6) is not used: its
// coefficients reach |a_ij| ~ 200 with heavy cancellation, so even correctly rounded doubles leave order
// residuals of ~2e-10 in this checker, above kOrderTolerance.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct Verner65 {
  static constexpr std::string_view name = "vern6";
  static constexpr std::size_t stages = 8;
  static constexpr int order = 6;
  static constexpr int embedded_order = 5;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<8> a = {{
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {1.0 / 6.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {4.0 / 75.0, 16.0 / 75.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {5.0 / 6.0, -8.0 / 3.0, 5.0 / 2.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {-165.0 / 64.0, 55.0 / 6.0, -425.0 / 64.0, 85.0 / 96.0, 0.0, 0.0, 0.0, 0.0},
      {12.0 / 5.0, -8.0, 4015.0 / 612.0, -11.0 / 36.0, 88.0 / 255.0, 0.0, 0.0, 0.0},
      {-8263.0 / 15000.0, 124.0 / 75.0, -643.0 / 680.0, -81.0 / 250.0, 2484.0 / 10625.0, 0.0, 0.0, 0.0},
      {3501.0 / 1720.0, -300.0 / 43.0, 297275.0 / 52632.0, -319.0 / 2322.0, 24068.0 / 84065.0, 0.0, 3850.0 / 26703.0,
       0.0},
  }};
  static constexpr TableauRow<8> b = {3.0 / 40.0,     0.0, 875.0 / 2244.0,  23.0 / 72.0,
                                      264.0 / 1955.0, 0.0, 125.0 / 11592.0, 43.0 / 616.0};
  static constexpr TableauRow<8> c = {0.0, 1.0 / 6.0, 4.0 / 15.0, 2.0 / 3.0, 5.0 / 6.0, 1.0, 1.0 / 15.0, 1.0};
  static constexpr TableauRow<8> b_hat = {13.0 / 160.0, 0.0, 2375.0 / 5984.0, 5.0 / 16.0, 12.0 / 85.0, 3.0 / 44.0,
                                          0.0,          0.0};
};
GRTRACE_CHECK_TABLEAU(Verner65);

}  // namespace grtrace
