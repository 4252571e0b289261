// grtrace/app/tool_methods.hpp
// The integration methods the rendering tools offer (grtrace-render, grtrace-view and their flights): a short,
// declared list of (tableau, step controller) pairs, each compiled once into the application layer per metric and
// tracer that supports it. The full matrix (every tableau with every controller, 40 pairs) is a research instrument
// and lives in grtrace-work-precision and grtrace-geodesic only: a program that offers all 40 for every metric,
// scene and tracer compiles about 800 tracers, which costs a newcomer half an hour of build for nothing they use.
//
// Why these pairs (docs/benchmarks.md, the work-precision charts of the seed's main frame and the Kerr disk frame):
//   rkf78 + i         the default: the cheapest pair whose largest error stays below 1e-6 on both frames
//   tsit5 + i         the cheapest fifth-order pair per accepted step (fast previews, flights)
//   dopri5 + pi       the classic Dormand-Prince pair (grtrace-view's default; what most peers use)
//   vern6 + i         sixth order: between the fifth- and eighth-order pairs in cost per digit
//   rk4 + fixed       teaching: the seed's classic RK4 with a fixed step (watch it fail near the horizon)
//   rk4 + doubling    teaching: the seed's step doubling (grtrace-view's orbit default)
// Not offered: rkf78 + pi. On the main frame's rays it needs 1.2x the evaluations of rkf78 + i for a similar largest
// error (26.3 against 21.7 us a ray at 1e-6 rad), and every pair costs the tools' build its tracers: this
// eighth-order one was a fifth of the application layer's compile time (frame_tracers_rn_sds.cpp at -O3, alone:
// 72.2 s with it, 57.6 s without; docs/benchmarks.md, "Compile time"). grtrace-work-precision and grtrace-geodesic
// have it, with every other pair.
// A user's own program is not limited by this list: it names any tableau and controller as template arguments.
#pragma once

#include "grtrace/integrate/step_controller.hpp"
#include "grtrace/tableau/classic_rk4.hpp"
#include "grtrace/tableau/dormand_prince54.hpp"
#include "grtrace/tableau/fehlberg78.hpp"
#include "grtrace/tableau/tsitouras54.hpp"
#include "grtrace/tableau/verner65.hpp"
#include "grtrace/trace/geodesic_tracer.hpp"

#include <array>
#include <string>
#include <string_view>
#include <type_traits>

namespace grtrace::app {

/// One offered pair: its names as the command line spells them, and why it is offered.
struct ToolMethod {
  std::string_view tableau, control, purpose;
};

/// A method chosen by name, with the settings the tool read for it (tolerances, initial step, and whatever else the
/// tool sets: escape radius, max steps). The option group examples/common/method_options.hpp reads it.
struct MethodChoice {
  std::string tableau, control;
  TraceSettings settings;
};

template <class T, class C>
struct MethodPair {
  using Tableau = T;
  using Controller = C;
};

template <class... Pairs>
struct MethodList {};

/// The offered pairs as types, in the order of kToolMethods (the first is every tool's default).
using ToolMethodTypes = MethodList<MethodPair<Fehlberg78, IController>, MethodPair<Tsitouras54, IController>,
                                   MethodPair<DormandPrince54, PIController>, MethodPair<Verner65, IController>,
                                   MethodPair<ClassicRK4, FixedStep>, MethodPair<ClassicRK4, StepDoubling>>;

inline constexpr std::array<ToolMethod, 6> kToolMethods = {{
    {"rkf78", "i", "default: below 1e-6 on the main and Kerr disk frames at the least cost"},
    {"tsit5", "i", "cheapest fifth-order step: previews and flights"},
    {"dopri5", "pi", "the classic Dormand-Prince pair"},
    {"vern6", "i", "sixth order, between the fifth- and eighth-order pairs; the media's method"},
    {"rk4", "fixed", "teaching: the seed's classic RK4 with a fixed step"},
    {"rk4", "doubling", "teaching: the seed's step doubling"},
}};

/// The one method emitting media are drawn with (--scene accretion, torus, riaf): Verner 6(5), whose error estimate
/// sees the light's integral along a ray (trace/emission_system.hpp estimate_sees_integrals; the default's,
/// Fehlberg 7(8)'s, is zero for one).
inline constexpr std::size_t kMediaMethod = 3;

namespace detail {
template <class... P>
constexpr bool names_match(MethodList<P...>) {
  constexpr std::array<std::string_view, sizeof...(P)> tableaux = {P::Tableau::name...};
  constexpr std::array<std::string_view, sizeof...(P)> controls = {P::Controller::name...};
  if (sizeof...(P) != kToolMethods.size()) return false;
  for (std::size_t i = 0; i < sizeof...(P); ++i)
    if (tableaux[i] != kToolMethods[i].tableau || controls[i] != kToolMethods[i].control) return false;
  return true;
}
}  // namespace detail
static_assert(detail::names_match(ToolMethodTypes{}),
              "kToolMethods must name the pairs of ToolMethodTypes, in the same order");

/// Calls f.template operator()<T, C>() for the offered pair named (tableau, control) and returns true; returns
/// false, calling nothing, for a pair that is not offered. Only the offered pairs are instantiated.
template <class F>
bool dispatch_tool_method(std::string_view tableau, std::string_view control, F&& f) {
  return [&]<class... P>(MethodList<P...>) {
    return ((P::Tableau::name == tableau && P::Controller::name == control
                 ? (f.template operator()<typename P::Tableau, typename P::Controller>(), true)
                 : false) ||
            ...);
  }(ToolMethodTypes{});
}

/// True when (tableau, control) is one of the offered pairs.
bool is_tool_method(std::string_view tableau, std::string_view control);

/// "rkf78 + i, tsit5 + i, ...": the list for --help and for messages (each tool names its own default).
std::string tool_methods_list();

/// The tableau names the tools offer ("rkf78|tsit5|dopri5|vern6|rk4") and the controllers ("i|pi|fixed|doubling"),
/// for --help.
std::string tool_tableau_names();
std::string tool_control_names();

/// Refuses a pair the tools do not offer (std::invalid_argument): an unknown tableau or controller, a controller
/// that needs an embedded error estimate the tableau lacks, or a valid pair outside the list, each with what to
/// choose instead and where every pair is (grtrace-work-precision, grtrace-geodesic).
void check_tool_method(std::string_view tableau, std::string_view control);

}  // namespace grtrace::app
