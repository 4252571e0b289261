// grtrace/tableau/dormand_prince54.hpp
// Dormand & Prince (1980) 5(4) pair, FSAL, with the order-4 continuous extension of Hairer, Norsett &
// Wanner I (sec. II.6, the DOPRI5 code). The propagated solution is the fifth-order one.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

namespace dopri5_detail {
// Hairer's dense-output form  y(theta) = y0 + theta(D + (1-theta)(h k1 - D + theta(2D - h k1 - h k7 + (1-theta) h sum d_i k_i)))
// with D = y1 - y0 = h sum b_i k_i, expanded into per-stage polynomials b_i(theta) = sum_d dense[i][d] theta^(d+1).
inline constexpr TableauRow<7> d = {-12715105075.0 / 11282082432.0, 0.0, 87487479700.0 / 32700410799.0,
                                    -10690763975.0 / 1880347072.0,  701980252875.0 / 199316789632.0,
                                    -1453857185.0 / 822651844.0,    69997945.0 / 29380423.0};

constexpr std::array<std::array<double, 4>, 7> dense_weights(const TableauRow<7>& b) {
  std::array<std::array<double, 4>, 7> w{};
  for (std::size_t i = 0; i < 7; ++i) {
    const double first = i == 0 ? 1.0 : 0.0;  // delta_{i,1}
    const double last = i == 6 ? 1.0 : 0.0;   // delta_{i,7}
    w[i] = {first, 3.0 * b[i] - 2.0 * first - last + d[i], -2.0 * b[i] + first + last - 2.0 * d[i], d[i]};
  }
  return w;
}
}  // namespace dopri5_detail

struct DormandPrince54 {
  static constexpr std::string_view name = "dopri5";
  static constexpr std::size_t stages = 7;
  static constexpr int order = 5;
  static constexpr int embedded_order = 4;
  static constexpr bool fsal = true;
  static constexpr TableauMatrix<7> a = {{
      {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0, 0.0},
      {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0, 0.0},
      {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0, 0.0},
      {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0, 0.0},
      {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0, 0.0},
  }};
  static constexpr TableauRow<7> b = {35.0 / 384.0,     0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0,
                                      11.0 / 84.0,      0.0};
  static constexpr TableauRow<7> c = {0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0};
  static constexpr TableauRow<7> b_hat = {5179.0 / 57600.0,     0.0,           7571.0 / 16695.0, 393.0 / 640.0,
                                          -92097.0 / 339200.0, 187.0 / 2100.0, 1.0 / 40.0};
  static constexpr int dense_degree = 4;
  static constexpr std::array<std::array<double, 4>, 7> dense = dopri5_detail::dense_weights(b);
};
GRTRACE_CHECK_TABLEAU(DormandPrince54);

}  // namespace grtrace
