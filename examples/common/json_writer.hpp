// examples/common/json_writer.hpp
// One-line JSON objects for the tools' machine-readable output, on nlohmann-json (ordered: keys stay in the order
// the tool adds them). Numbers are printed in the shortest form that reads back as the same double; non-finite
// numbers become null; strings are escaped as JSON requires (bytes that are not UTF-8 become U+FFFD).
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace grtrace::tools {

class JsonObject {
 public:
  JsonObject& add(std::string_view key, double v) { return set(key, std::isfinite(v) ? Json(v) : Json(nullptr)); }
  JsonObject& add(std::string_view key, long v) { return set(key, Json(v)); }
  JsonObject& add(std::string_view key, int v) { return set(key, Json(v)); }
  JsonObject& add(std::string_view key, bool v) { return set(key, Json(v)); }
  JsonObject& add(std::string_view key, std::string_view v) { return set(key, Json(std::string(v))); }
  JsonObject& add(std::string_view key, const char* v) { return set(key, Json(std::string(v))); }
  JsonObject& add(std::string_view key, const JsonObject& v) { return set(key, v.json_); }
  JsonObject& add(std::string_view key, const std::vector<int>& v) { return set(key, Json(v)); }
  JsonObject& add_null(std::string_view key) { return set(key, Json(nullptr)); }

  /// The object on one line ("{}" when empty).
  std::string str() const { return dump(json_); }

  /// Takes any double; returns "%.17g" text (exact; "null" when non-finite). For messages and header attributes,
  /// which are not JSON output and keep the form they always had.
  static std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
  }

  /// Takes any bytes; returns them as a quoted JSON string.
  static std::string quote(std::string_view s) { return dump(Json(std::string(s))); }

 private:
  using Json = nlohmann::ordered_json;

  /// Takes a JSON value; returns it on one line. Invalid UTF-8 is replaced rather than thrown on: a file name is
  /// reported, not refused, after the work is done.
  static std::string dump(const Json& j) { return j.dump(-1, ' ', false, Json::error_handler_t::replace); }

  JsonObject& set(std::string_view key, Json value) {
    json_[std::string(key)] = std::move(value);
    return *this;
  }
  Json json_ = Json::object();
};

}  // namespace grtrace::tools
