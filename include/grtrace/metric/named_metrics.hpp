// grtrace/metric/named_metrics.hpp
// The metrics a program can choose by name at run time (grtrace-render --metric NAME, grtrace.render(metric=...)),
// and the one place where a name becomes a type: with_named_metric(spec, f) calls f(metric) with a
// SchwarzschildMetric, a KerrMetric, an AutoMetric<EllisWormhole>, ..., so one generic lambda renders any of them
// (each type is its own instantiation: no virtual call in the hot loop).
//
//   name              metric (chart)                                          parameters
//   schwarzschild     SchwarzschildMetric (t, r, theta, phi)                  mass
//   minkowski         MinkowskiSpherical (flat: straight lines)               -
//   kerr              KerrMetric, Boyer-Lindquist (chart "bl")                mass, spin |a| < M
//                     KerrSchildMetric, Cartesian Kerr-Schild (chart "ks"),   (cameras are placed in BL coordinates;
//                     outgoing slicing: camera rays cross the horizon)        the outgoing chart takes past-directed
//                     rays; (ingoing with MetricSpec::slicing: flights fall in)     a flight's camera crosses in the
//                     ingoing one)
//   rn                Reissner-Nordstrom, automatic Christoffels             mass, charge |Q| < M
//   sds               Schwarzschild-de Sitter, automatic Christoffels        mass, lambda in (0, 1/(9 M^2))
//   wormhole          Ellis wormhole (t, l, theta, phi), no horizon          throat b0 > 0
//   schwarzschild-ef  Schwarzschild, outgoing Eddington-Finkelstein           mass (horizon-penetrating for camera
//   rays)
// Each is refused (std::invalid_argument, naming the option and the range) before any work when its parameters
// make no black hole or no spacetime: |a| >= M, |Q| >= M, Lambda outside the range with two horizons, b0 <= 0.
//
// Adding a metric: one entry below (a struct with its name, parameters, checks and with_metric, listed in
// NamedMetricEntries) and, for a parameter no metric had before, a field of MetricSpec. Everything that takes a
// metric by name reads this list: the tools' options and their help (--metric, --spin, ...), the refusals, the
// frame header's record, the Python module's keywords. The application layer (app/) compiles each metric's tracers
// in one of its units: name the new type there too (app/src/frame_tracers.hpp says where).
#pragma once

#include "grtrace/metric/examples/eddington_finkelstein.hpp"
#include "grtrace/metric/examples/ellis_wormhole.hpp"
#include "grtrace/metric/examples/reissner_nordstrom.hpp"
#include "grtrace/metric/examples/schwarzschild_de_sitter.hpp"
#include "grtrace/metric/kerr.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/metric/minkowski.hpp"
#include "grtrace/metric/schwarzschild.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

namespace grtrace {

struct MetricSpec {
  std::string name = "schwarzschild";  ///< one of kMetricNames
  double mass = 1.0;                   ///< M (the metrics whose entry has_mass)
  double spin = 0.0;                   ///< kerr: a, |a| < M (negative: rotation towards -phi)
  std::string chart = "bl";            ///< kerr: "bl" (Boyer-Lindquist) or "ks" (Kerr-Schild); others: "bl" only
  /// kerr, chart ks: outgoing (single frames: camera rays, traced into the past, cross the past horizon and are
  /// captured inside it) or ingoing (flights: the falling camera crosses the future horizon, kerr_schild_for_flights).
  KerrSchildSlicing slicing = KerrSchildSlicing::outgoing;
  double charge = 0.5;   ///< rn: Q, |Q| < M
  double lambda = 1e-5;  ///< sds: cosmological constant, 0 < Lambda < 1 / (9 M^2) (r_c ~ 547 M)
  double throat = 1.0;   ///< wormhole: throat radius b0
};

/// A named metric's own parameter (beyond the mass): the option that sets it (grtrace-render --spin, Python
/// spin=), its default as the option's text, what it means, and the MetricSpec field it fills.
struct MetricParameter {
  std::string_view option;
  std::string_view default_text;
  std::string_view help;
  double MetricSpec::*field;
};

namespace named {

inline bool finite(double v) { return std::isfinite(v); }

/// std::to_string's fixed notation, as the refusals have always printed a parameter.
inline std::string text(double v) { return std::to_string(v); }

struct Schwarzschild {
  static constexpr std::string_view name = "schwarzschild";
  static constexpr std::string_view help = "schwarzschild";
  static constexpr bool has_mass = true;
  static constexpr std::array<std::string_view, 1> charts = {"bl"};
  /// Added to the refusal of another chart: where the tools do have a chart across the horizon.
  static constexpr std::string_view chart_hint =
      "; across the horizon: --metric schwarzschild-ef, or --metric kerr --spin 0 --chart ks";
  static constexpr std::array<MetricParameter, 0> parameters{};
  static void check(const MetricSpec&) {}
  template <class F>
  static decltype(auto) with_metric(const MetricSpec& s, F&& f) {
    return f(SchwarzschildMetric{s.mass});
  }
};

struct Minkowski {
  static constexpr std::string_view name = "minkowski";
  static constexpr std::string_view help = "minkowski (flat: straight lines, never integrated)";
  static constexpr bool has_mass = false;
  static constexpr std::array<std::string_view, 1> charts = {"bl"};
  static constexpr std::string_view chart_hint = "";
  static constexpr std::array<MetricParameter, 0> parameters{};
  static void check(const MetricSpec&) {}
  template <class F>
  static decltype(auto) with_metric(const MetricSpec&, F&& f) {
    return f(MinkowskiSpherical{});
  }
};

struct Kerr {
  static constexpr std::string_view name = "kerr";
  static constexpr std::string_view help = "kerr";
  static constexpr bool has_mass = true;
  static constexpr std::array<std::string_view, 2> charts = {"bl", "ks"};
  static constexpr std::string_view chart_hint = "";
  static constexpr std::array<MetricParameter, 1> parameters = {
      {{"spin", "0", "kerr: spin a, |a| < M (negative: rotation towards -phi)", &MetricSpec::spin}}};
  static void check(const MetricSpec& s) {
    if (!finite(s.spin) || !(std::abs(s.spin) < s.mass))
      throw std::invalid_argument("--spin must satisfy |a| < M (|a| >= M has no horizon); got " + text(s.spin));
  }
  template <class F>
  static decltype(auto) with_metric(const MetricSpec& s, F&& f) {
    if (s.chart == "ks")
      return f(s.slicing == KerrSchildSlicing::ingoing ? kerr_schild_for_flights(s.mass, s.spin)
                                                       : kerr_schild_for_camera_rays(s.mass, s.spin));
    return f(KerrMetric::checked(s.mass, s.spin));
  }
};

struct ReissnerNordstrom {
  static constexpr std::string_view name = "rn";
  static constexpr std::string_view help = "rn (Reissner-Nordstrom)";
  static constexpr bool has_mass = true;
  static constexpr std::array<std::string_view, 1> charts = {"bl"};
  static constexpr std::string_view chart_hint = "";
  static constexpr std::array<MetricParameter, 1> parameters = {
      {{"charge", "0.5", "rn: charge Q, |Q| < M", &MetricSpec::charge}}};
  static void check(const MetricSpec& s) {
    if (!finite(s.charge) || !(std::abs(s.charge) < s.mass))
      throw std::invalid_argument("--charge must satisfy |Q| < M (|Q| >= M has no horizon); got " + text(s.charge));
  }
  template <class F>
  static decltype(auto) with_metric(const MetricSpec& s, F&& f) {
    AutoReissnerNordstrom m;
    m.mass = s.mass;
    m.charge = s.charge;
    return f(m);
  }
};

struct SchwarzschildDeSitter {
  static constexpr std::string_view name = "sds";
  static constexpr std::string_view help = "sds (Schwarzschild-de Sitter)";
  static constexpr bool has_mass = true;
  static constexpr std::array<std::string_view, 1> charts = {"bl"};
  static constexpr std::string_view chart_hint = "";
  static constexpr std::array<MetricParameter, 1> parameters = {
      {{"lambda", "1e-5",
        "sds: cosmological constant, 0 < Lambda < 1/(9 M^2); the sky sphere must lie inside the cosmological horizon",
        &MetricSpec::lambda}}};
  static void check(const MetricSpec& s) {
    if (!finite(s.lambda) || !(s.lambda > 0.0 && 9.0 * s.lambda * s.mass * s.mass < 1.0))
      throw std::invalid_argument("--lambda must lie in (0, 1/(9 M^2)) for a black hole with two horizons; got " +
                                  text(s.lambda));
  }
  template <class F>
  static decltype(auto) with_metric(const MetricSpec& s, F&& f) {
    AutoSchwarzschildDeSitter m;
    m.mass = s.mass;
    m.lambda = s.lambda;
    return f(m);
  }
};

struct Wormhole {
  static constexpr std::string_view name = "wormhole";
  static constexpr std::string_view help = "wormhole (Ellis)";
  static constexpr bool has_mass = false;
  static constexpr std::array<std::string_view, 1> charts = {"bl"};
  static constexpr std::string_view chart_hint = "";
  static constexpr std::array<MetricParameter, 1> parameters = {
      {{"throat", "1",
        "wormhole: throat radius b0 (--camera-r is then the proper distance l; l < 0 is the other side, whose sky "
        "is drawn differently: green-violet checker, orange stars)",
        &MetricSpec::throat}}};
  static void check(const MetricSpec& s) {
    if (!(s.throat > 0.0 && finite(s.throat))) throw std::invalid_argument("--throat must be a positive number");
  }
  template <class F>
  static decltype(auto) with_metric(const MetricSpec& s, F&& f) {
    AutoEllisWormhole m;
    m.throat = s.throat;
    return f(m);
  }
};

struct EddingtonFinkelstein {
  static constexpr std::string_view name = "schwarzschild-ef";
  static constexpr std::string_view help = "schwarzschild-ef (Eddington-Finkelstein)";
  static constexpr bool has_mass = true;
  static constexpr std::array<std::string_view, 1> charts = {"bl"};
  static constexpr std::string_view chart_hint = "";
  static constexpr std::array<MetricParameter, 0> parameters{};
  static void check(const MetricSpec&) {}
  template <class F>
  static decltype(auto) with_metric(const MetricSpec& s, F&& f) {
    AutoEddingtonFinkelstein m;
    m.mass = s.mass;
    m.outgoing = true;  // camera rays are past-directed: the outgoing chart carries them through r = 2M
    return f(m);
  }
};

}  // namespace named

/// Every named metric, in the order the tools list them (the first is the default).
using NamedMetricEntries = std::tuple<named::Schwarzschild, named::Minkowski, named::Kerr, named::ReissnerNordstrom,
                                      named::SchwarzschildDeSitter, named::Wormhole, named::EddingtonFinkelstein>;

/// Calls f.template operator()<Entry>() for each entry of NamedMetricEntries, in order.
template <class F>
constexpr void for_each_named_metric(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f.template operator()<std::tuple_element_t<I, NamedMetricEntries>>(), ...);
  }
  (std::make_index_sequence<std::tuple_size_v<NamedMetricEntries>>{});
}

inline constexpr std::array<std::string_view, std::tuple_size_v<NamedMetricEntries>> kMetricNames = [] {
  std::array<std::string_view, std::tuple_size_v<NamedMetricEntries>> names{};
  std::size_t i = 0;
  for_each_named_metric([&]<class E>() { names[i++] = E::name; });
  return names;
}();

inline bool is_named_metric(std::string_view name) {
  for (std::string_view n : kMetricNames)
    if (n == name) return true;
  return false;
}

/// "a, b or c" of a list of names (the refusals' way of listing the choices).
template <class Names>
std::string choice_list(const Names& names) {
  std::string out;
  std::size_t i = 0;
  const std::size_t n = std::size(names);
  for (const auto& name : names) {
    out += i == 0 ? "" : i + 1 == n ? " or " : ", ";
    out += std::string_view(name);
    ++i;
  }
  return out;
}

/// One parameter of one named metric (named_metric_parameters).
struct NamedMetricParameter {
  std::string_view metric;
  MetricParameter parameter;
};

/// The parameters of every named metric, in the order of the entries: what the tools declare as options (--spin,
/// --charge, ...) and the Python module takes as keywords.
inline std::vector<NamedMetricParameter> named_metric_parameters() {
  std::vector<NamedMetricParameter> out;
  for_each_named_metric([&]<class E>() {
    for (const MetricParameter& p : E::parameters) out.push_back({E::name, p});
  });
  return out;
}

/// Whether the named metric has a mass (--mass means something), and the list of its charts.
inline bool named_metric_has_mass(std::string_view name) {
  bool has = false;
  for_each_named_metric([&]<class E>() { has = has || (E::name == name && E::has_mass); });
  return has;
}

/// The parameters of the spec's metric as (option, value): what a frame's header records beside the name and mass.
inline std::vector<std::pair<std::string_view, double>> metric_parameter_values(const MetricSpec& s) {
  std::vector<std::pair<std::string_view, double>> out;
  for_each_named_metric([&]<class E>() {
    if (E::name == s.name)
      for (const MetricParameter& p : E::parameters) out.emplace_back(p.option, s.*p.field);
  });
  return out;
}

/// Refuses a spec that names no metric or whose parameters make none (std::invalid_argument saying what to change).
inline void check_metric_spec(const MetricSpec& s) {
  if (!is_named_metric(s.name))
    throw std::invalid_argument("unknown metric '" + s.name + "'; choose " + choice_list(kMetricNames));
  for_each_named_metric([&]<class E>() {
    if (E::name != s.name) return;
    if (E::has_mass && !(s.mass > 0.0 && named::finite(s.mass)))
      throw std::invalid_argument("--mass must be a positive number");
    bool chart_known = false;
    for (std::string_view c : E::charts) chart_known = chart_known || c == s.chart;
    if (!chart_known) {
      if (E::charts.size() > 1)
        throw std::invalid_argument("--chart must be " + choice_list(E::charts) + ", got '" + s.chart + "'");
      // The metrics with one chart each: a chart asked for would be ignored.
      throw std::invalid_argument("--chart " + s.chart + " goes with --metric kerr; --metric " + s.name +
                                  " has one chart (leave --chart out" + std::string(E::chart_hint) + ")");
    }
    E::check(s);
  });
}

namespace named {
/// with_named_metric's search from entry I on: the entry whose name the (checked) spec gives calls f.
template <std::size_t I, class F>
decltype(auto) with_entry_from(const MetricSpec& s, F&& f) {
  using E = std::tuple_element_t<I, NamedMetricEntries>;
  if constexpr (I + 1 == std::tuple_size_v<NamedMetricEntries>) {
    return E::with_metric(s, f);
  } else {
    if (E::name == s.name) return E::with_metric(s, f);
    return with_entry_from<I + 1>(s, f);
  }
}
}  // namespace named

/// Calls f(metric) with the named metric (checked first). All calls of f must return the same type.
template <class F>
decltype(auto) with_named_metric(const MetricSpec& s, F&& f) {
  check_metric_spec(s);
  return named::with_entry_from<0>(s, f);
}

}  // namespace grtrace
