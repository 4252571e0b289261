// grtrace/trace/method_dispatch.hpp
// Runtime choice of (tableau, controller) from their names, selecting among compile-time instantiations.
// Only valid pairs are instantiated: the I and PI controllers need an embedded pair.
#pragma once

#include "grtrace/integrate/step_controller.hpp"
#include "grtrace/tableau/all_tableaux.hpp"

#include <array>
#include <string>
#include <string_view>
#include <type_traits>

namespace grtrace {

inline constexpr std::array<std::string_view, 4> kControllerNames = {"fixed", "doubling", "i", "pi"};

template <class F>
bool dispatch_controller(std::string_view name, F&& f) {
  if (name == "fixed") return f(std::type_identity<FixedStep>{}), true;
  if (name == "doubling") return f(std::type_identity<StepDoubling>{}), true;
  if (name == "i") return f(std::type_identity<IController>{}), true;
  if (name == "pi") return f(std::type_identity<PIController>{}), true;
  return false;
}

template <ExplicitTableau T, StepController C>
inline constexpr bool is_valid_method = C::estimate != ErrorEstimate::embedded || has_embedded_pair<T>;

enum class DispatchError { none, unknown_tableau, unknown_controller, needs_embedded_pair };

/// Calls f.template operator()<T, C>() for the named pair; says what was wrong otherwise.
template <class F>
DispatchError dispatch_method(std::string_view tableau, std::string_view controller, F&& f) {
  DispatchError error = DispatchError::none;
  const bool known_tableau = dispatch_tableau(tableau, [&]<class T>(std::type_identity<T>) {
    const bool known_controller = dispatch_controller(controller, [&]<class C>(std::type_identity<C>) {
      if constexpr (is_valid_method<T, C>) f.template operator()<T, C>();
      else error = DispatchError::needs_embedded_pair;
    });
    if (!known_controller) error = DispatchError::unknown_controller;
  });
  if (!known_tableau) error = DispatchError::unknown_tableau;
  return error;
}

/// A message that says what to change.
inline std::string describe(DispatchError e, std::string_view tableau, std::string_view controller) {
  switch (e) {
    case DispatchError::none: return {};
    case DispatchError::unknown_tableau: {
      std::string message = "unknown tableau '";
      message.append(tableau).append("'; choose one of: ");
      const auto names = tableau_names();
      for (std::size_t i = 0; i < names.size(); ++i) message.append(i ? ", " : "").append(names[i]);
      return message;
    }
    case DispatchError::unknown_controller:
      return "unknown controller '" + std::string(controller) + "'; choose one of: fixed, doubling, i, pi";
    case DispatchError::needs_embedded_pair:
      return "controller '" + std::string(controller) + "' needs an embedded error estimate, which tableau '" +
             std::string(tableau) + "' does not have; use --control doubling or fixed with it";
  }
  return {};
}

}  // namespace grtrace
