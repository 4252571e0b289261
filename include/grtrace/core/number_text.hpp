// grtrace/core/number_text.hpp
// Numbers written by users, read the same way wherever they write one: the tools' options, scene files and
// camera-path CSVs. So a number the command line takes, a CSV takes too, and every refusal says the same thing.
//
//   parse_finite_number(" 1.5e-3 ")  -> {0.0015, NumberText::ok}
//   parse_finite_number("1e400")     -> {inf, NumberText::not_finite}      ("nan", "inf" too)
//   parse_whole_number("12")         -> {12, NumberText::ok}
//   parse_whole_number("1.5")        -> {.., NumberText::not_a_number}
//   parse_whole_number("99999999999999999999") -> {.., NumberText::out_of_range}
//
// Rules: the whole text is the number, blanks (space, tab, CR) around it allowed; decimal or C99 hexadecimal
// floating point (strtod in the "C" locale's format); a number too small for a double reads as strtod gives it
// (zero or subnormal), one too large is not finite. Whole numbers are decimal, in the range of a long.
#pragma once

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace grtrace {

enum class NumberText {
  ok,
  not_a_number,  ///< empty, or characters that are not (all) one number
  not_finite,    ///< inf, nan, or beyond the largest double
  out_of_range,  ///< a whole number beyond a long
};

struct ParsedNumber {
  double value = 0.0;
  NumberText result = NumberText::not_a_number;
};

struct ParsedWholeNumber {
  long value = 0;
  NumberText result = NumberText::not_a_number;
};

namespace detail {
inline bool number_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
/// The text without the blanks around it.
inline std::string trim_number_blanks(const std::string& text) {
  std::size_t begin = 0, end = text.size();
  while (begin < end && number_blank(text[begin])) ++begin;
  while (end > begin && number_blank(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}
}  // namespace detail

/// A finite double from `text` (see the file comment for the rules).
inline ParsedNumber parse_finite_number(const std::string& text) {
  const std::string t = detail::trim_number_blanks(text);
  if (t.empty() || std::isspace(static_cast<unsigned char>(t[0]))) return {};  // strtod would skip a newline
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (end != t.c_str() + t.size()) return {};
  if (!std::isfinite(v)) return {v, NumberText::not_finite};
  return {v, NumberText::ok};
}

/// A whole decimal number in the range of a long from `text` (see the file comment for the rules).
inline ParsedWholeNumber parse_whole_number(const std::string& text) {
  const std::string t = detail::trim_number_blanks(text);
  if (t.empty() || std::isspace(static_cast<unsigned char>(t[0]))) return {};
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(t.c_str(), &end, 10);
  if (end != t.c_str() + t.size()) return {};
  if (errno == ERANGE) return {v, NumberText::out_of_range};  // strtol saturates silently: refused instead
  return {v, NumberText::ok};
}

/// What is wrong with a number that was not NumberText::ok, as the end of a sentence naming it:
/// "is not a number", "is not finite", "is out of range (whole numbers up to 9223372036854775807)".
inline std::string number_text_problem(NumberText result) {
  switch (result) {
    case NumberText::ok: return "is a number";
    case NumberText::not_a_number: return "is not a number";
    case NumberText::not_finite: return "is not finite";
    case NumberText::out_of_range:
      return "is out of range (whole numbers up to " + std::to_string(std::numeric_limits<long>::max()) + ")";
  }
  return "is not a number";
}

/// The shortest text that reads back as the same double (what a refusal prints of a number, and what the Python
/// module hands the option reader for a Python number).
inline std::string shortest_number_text(double v) {
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return ec == std::errc() ? std::string(buffer, end) : std::to_string(v);
}

/// An option's number, whole number or comma-separated numbers, read by the rules above with the refusal every grtrace
/// tool and the Python module give (std::invalid_argument naming --name; `from` is added to the message, e.g. " (from
/// the frame's header)").
inline double option_number(std::string_view name, const std::string& text, const std::string& from = "") {
  const ParsedNumber n = parse_finite_number(text);
  if (n.result == NumberText::not_finite)
    throw std::invalid_argument("--" + std::string(name) + " must be finite, got '" + text + "'" + from);
  if (n.result != NumberText::ok)
    throw std::invalid_argument("--" + std::string(name) + " expects a number, got '" + text + "'" + from);
  return n.value;
}

inline long option_integer(std::string_view name, const std::string& text, const std::string& from = "") {
  const ParsedWholeNumber n = parse_whole_number(text);
  if (n.result == NumberText::out_of_range)
    throw std::invalid_argument("--" + std::string(name) + " " + text + " " + number_text_problem(n.result) + from);
  if (n.result != NumberText::ok)
    throw std::invalid_argument("--" + std::string(name) + " expects a whole number, got '" + text + "'" + from);
  return n.value;
}

/// Exactly `count` numbers (0: any number of them), each read as option_number reads one.
inline std::vector<double> option_numbers(std::string_view name, const std::string& text, std::size_t count) {
  // getline drops an empty last item: "1,2,3," would read as three numbers.
  if (!text.empty() && text.back() == ',')
    throw std::invalid_argument("--" + std::string(name) + " '" + text +
                                "' ends with a comma; give the numbers separated by commas, without one at the end");
  std::vector<double> out;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) out.push_back(option_number(name, item));
  if (count != 0 && out.size() != count)
    throw std::invalid_argument("--" + std::string(name) + " expects " + std::to_string(count) +
                                " comma-separated numbers, got '" + text + "'");
  return out;
}

}  // namespace grtrace
