// examples/common/json_writer.hpp
// One-line JSON objects for the tools' machine-readable output. Non-finite numbers become null.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

namespace grtrace::tools {

class JsonObject {
 public:
  JsonObject& add(std::string_view key, double v) { return raw(key, number(v)); }
  JsonObject& add(std::string_view key, long v) { return raw(key, std::to_string(v)); }
  JsonObject& add(std::string_view key, int v) { return raw(key, std::to_string(v)); }
  JsonObject& add(std::string_view key, bool v) { return raw(key, v ? "true" : "false"); }
  JsonObject& add(std::string_view key, std::string_view v) { return raw(key, quote(v)); }
  JsonObject& add(std::string_view key, const char* v) { return raw(key, quote(v)); }
  JsonObject& add(std::string_view key, const JsonObject& v) { return raw(key, v.str()); }
  JsonObject& add_null(std::string_view key) { return raw(key, "null"); }

  std::string str() const { return "{" + body_ + "}"; }

  static std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
  }

  static std::string quote(std::string_view s) {
    std::string q = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') q += '\\';
      if (c == '\n') {
        q += "\\n";
        continue;
      }
      q += c;
    }
    return q + "\"";
  }

 private:
  JsonObject& raw(std::string_view key, const std::string& value) {
    if (!body_.empty()) body_ += ",";
    body_ += quote(key) + ":" + value;
    return *this;
  }
  std::string body_;
};

}  // namespace grtrace::tools
