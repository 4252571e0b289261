// grtrace/tableau/tsitouras54.hpp
// Tsitouras (2011), "Runge-Kutta pairs of order 5(4) satisfying only the first column simplifying
// assumption", Comput. Math. Appl. 62(2), 770-775: seven stages, FSAL, fifth-order solution propagated,
// fourth-order embedded estimate, plus the free continuous extension of degree 4 given in the same paper.
// Apart from c2..c4 and a72 the coefficients have no short closed form; they are given here as the correctly
// rounded doubles of the ~85-digit values computed from the paper's formulas (as tabulated in diffrax). The
// dense weights are the paper's factored polynomials expanded, b_i(theta) = sum_d dense[i][d] theta^(d+1),
// corrected (by < 1e-16) onto the exact order-4 conditions of the continuous extension.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct Tsitouras54 {
  static constexpr std::string_view name = "tsit5";
  static constexpr std::size_t stages = 7;
  static constexpr int order = 5;
  static constexpr int embedded_order = 4;
  static constexpr bool fsal = true;
  static constexpr TableauMatrix<7> a = {{
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {0.161, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {-0.0084806554923569887, 0.335480655492357, 0.0, 0.0, 0.0, 0.0, 0.0},
      {2.8971530571054935, -6.3594484899750752, 4.3622954328695815, 0.0, 0.0, 0.0, 0.0},
      {5.3258648284392569, -11.748883564062828, 7.4955393428898365, -0.092495066361755252, 0.0, 0.0, 0.0},
      {5.8614554429464203, -12.92096931784711, 8.1593678985761589, -0.071584973281400996, -0.028269050394068383, 0.0,
       0.0},
      {0.09646076681806523, 0.01, 0.4798896504144996, 1.3790085741037419, -3.2900695154360808, 2.3247105240997739, 0.0},
  }};
  static constexpr TableauRow<7> b = {
      0.09646076681806523, 0.01, 0.4798896504144996, 1.3790085741037419, -3.2900695154360808, 2.3247105240997739, 0.0};
  static constexpr TableauRow<7> c = {0.0, 0.161, 0.327, 0.9, 0.98002554090450966, 1.0, 1.0};
  static constexpr TableauRow<7> b_hat = {
      0.094680755765839453, 0.009183565540343254, 0.4877705284247616, 1.234297566930479,
      -2.7077123499835256,  1.866628418170587,    1.0 / 66.0};
  static constexpr int dense_degree = 4;
  static constexpr std::array<std::array<double, 4>, 7> dense = {{
      {1.0, -2.7637061972748258, 2.9132554618219126, -1.0530884977290216},
      {0.0, 0.1317, -0.2234, 0.1017},
      {0.0, 3.9302962368947516, -5.9410338721315048, 2.4906272856512528},
      {0.0, -12.411077166933676, 30.338188630282321, -16.548102889244902},
      {0.0, 37.509313416511041, -88.178904894766404, 47.379521962819283},
      {0.0, -27.896526289197286, 65.091894674793664, -34.870657861496611},
      {0.0, 1.5, -4.0, 2.5},
  }};
};
GRTRACE_CHECK_TABLEAU(Tsitouras54);

}  // namespace grtrace
