// grtrace/tableau/all_tableaux.hpp
// Every Butcher tableau grtrace ships, as one compile-time list, with helpers to loop over it and to pick a
// tableau by its run-time name.
//
//   name        struct              order(embedded)  notes
//   "euler"     ExplicitEuler       1                baseline
//   "midpoint"  ExplicitMidpoint    2
//   "heun"      Heun                2(1)             explicit trapezoid, forward Euler as the estimate
//   "rk4"       ClassicRK4          4
//   "rk38"      Rule38              4                Kutta's 3/8 rule
//   "bs3"       BogackiShampine32   3(2)             FSAL
//   "rkf45"     Fehlberg45          4(5)             propagates the 4th-order solution
//   "cashkarp"  CashKarp54          5(4)
//   "dopri5"    DormandPrince54     5(4)             FSAL, dense output (degree 4)
//   "tsit5"     Tsitouras54         5(4)             FSAL, dense output (degree 4)
//   "vern6"     Verner65            6(5)             Verner 1978 (DVERK) pair
//   "rkf78"     Fehlberg78          8(7)             13 stages, local extrapolation
//
// Every header runs GRTRACE_CHECK_TABLEAU on its tableau, so including this file re-verifies all of them.
#pragma once

#include "grtrace/tableau/bogacki_shampine32.hpp"
#include "grtrace/tableau/butcher_tableau.hpp"
#include "grtrace/tableau/cash_karp54.hpp"
#include "grtrace/tableau/classic_rk4.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/tableau/explicit_euler.hpp"
#include "grtrace/tableau/explicit_midpoint.hpp"
#include "grtrace/tableau/fehlberg45.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/tableau/heun.hpp"
#include "grtrace/tableau/rk38.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/tableau/verner65.hpp"

#include <array>
#include <cstddef>
#include <string_view>
#include <type_traits>
#include <vector>

namespace grtrace {

template <class... T>
struct TypeList {};

/// All tableaux, roughly by increasing order; tableau_names() lists them in this order.
using AllTableaux = TypeList<ExplicitEuler, ExplicitMidpoint, Heun, ClassicRK4, Rule38, BogackiShampine32, Fehlberg45,
                             CashKarp54, DormandPrince54, Tsitouras54, Verner65, Fehlberg78>;

/// Calls f(std::type_identity<T>{}) for every tableau T in AllTableaux, in order.
/// Inside f, `using T = typename decltype(tag)::type;` recovers the tableau.
template <class F>
constexpr void for_each_tableau(F&& f) {
  [&]<class... T>(TypeList<T...>) { (static_cast<void>(f(std::type_identity<T>{})), ...); }(AllTableaux{});
}

/// Calls f(std::type_identity<T>{}) for the tableau whose T::name equals `name`.
/// Returns false (and calls nothing) if no tableau has that name.
template <class F>
bool dispatch_tableau(std::string_view name, F&& f) {
  return [&]<class... T>(TypeList<T...>) {
    return ((T::name == name ? (static_cast<void>(f(std::type_identity<T>{})), true) : false) || ...);
  }(AllTableaux{});
}

/// The names of all tableaux, in AllTableaux order.
inline std::vector<std::string_view> tableau_names() {
  std::vector<std::string_view> names;
  for_each_tableau([&](auto tag) { names.push_back(decltype(tag)::type::name); });
  return names;
}

namespace tableau_detail {
template <class... T>
constexpr bool names_are_unique(TypeList<T...>) {
  constexpr std::array<std::string_view, sizeof...(T)> names = {T::name...};
  for (std::size_t i = 0; i < names.size(); ++i)
    for (std::size_t j = i + 1; j < names.size(); ++j)
      if (names[i] == names[j]) return false;
  return true;
}
}  // namespace tableau_detail

static_assert(tableau_detail::names_are_unique(AllTableaux{}),
              "two tableaux share a name; dispatch_tableau needs unique names");

}  // namespace grtrace
