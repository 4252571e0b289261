// grtrace/tableau/explicit_euler.hpp
// Forward Euler: one stage, order 1. Kept as the baseline every other method is measured against.
#pragma once

#include "grtrace/tableau/butcher_tableau.hpp"

namespace grtrace {

struct ExplicitEuler {
  static constexpr std::string_view name = "euler";
  static constexpr std::size_t stages = 1;
  static constexpr int order = 1;
  static constexpr int embedded_order = 0;
  static constexpr bool fsal = false;
  static constexpr TableauMatrix<1> a = {{{0.0}}};
  static constexpr TableauRow<1> b = {1.0};
  static constexpr TableauRow<1> c = {0.0};
  static constexpr TableauRow<1> b_hat = {0.0};
};
GRTRACE_CHECK_TABLEAU(ExplicitEuler);

}  // namespace grtrace
