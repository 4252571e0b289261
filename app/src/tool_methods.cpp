// The offered methods' names and the refusal of any other pair (grtrace/app/tool_methods.hpp).
#include "grtrace/app/tool_methods.hpp"

#include "grtrace/trace/method_dispatch.hpp"

#include <stdexcept>
#include <string>

namespace grtrace::app {

bool is_tool_method(std::string_view tableau, std::string_view control) {
  for (const ToolMethod& m : kToolMethods)
    if (m.tableau == tableau && m.control == control) return true;
  return false;
}

std::string tool_methods_list() {
  std::string list;
  for (std::size_t i = 0; i < kToolMethods.size(); ++i) {
    list.append(i ? ", " : "").append(kToolMethods[i].tableau).append(" + ").append(kToolMethods[i].control);
  }
  return list;
}

namespace {
/// The distinct values of one column of kToolMethods, in order, joined by '|'.
template <class Column>
std::string distinct(Column column) {
  std::string out;
  for (std::size_t i = 0; i < kToolMethods.size(); ++i) {
    bool seen = false;
    for (std::size_t j = 0; j < i; ++j) seen = seen || column(kToolMethods[j]) == column(kToolMethods[i]);
    if (!seen) out.append(out.empty() ? "" : "|").append(column(kToolMethods[i]));
  }
  return out;
}
}  // namespace

std::string tool_tableau_names() {
  return distinct([](const ToolMethod& m) { return m.tableau; });
}
std::string tool_control_names() {
  return distinct([](const ToolMethod& m) { return m.control; });
}

void check_tool_method(std::string_view tableau, std::string_view control) {
  if (is_tool_method(tableau, control)) return;
  // Names that exist nowhere, or a pair that cannot work, get the library's own message first.
  const DispatchError error = dispatch_method(tableau, control, []<class T, class C>() {});
  const std::string offered = "the rendering tools offer " + tool_methods_list();
  if (error != DispatchError::none) throw std::invalid_argument(describe(error, tableau, control) + "; " + offered);
  throw std::invalid_argument("tableau '" + std::string(tableau) + "' with control '" + std::string(control) +
                              "' is not among the methods the rendering tools offer: choose one of " +
                              tool_methods_list() +
                              ". Every pair of tableau and controller is in grtrace-work-precision and "
                              "grtrace-geodesic, or in your own program through the headers");
}

}  // namespace grtrace::app
