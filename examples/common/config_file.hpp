// examples/common/config_file.hpp
// Scene files for the grtrace tools (`--config FILE`, `--write-config FILE`; command_line.hpp applies them):
// - a TOML file (toml++) whose keys are option names without the dashes and whose values are strings, numbers
//   or booleans (a flag takes a boolean): `scene = "disk"`, `camera-r = 30`, `disk-retrograde = true`;
// - or an OpenEXR written by grtrace-render, whose header records every option as an `option_<name>` string
//   attribute and the options that were given as `options_given` (comma-separated names). Only the header's
//   string attributes are read, by the small reader below: the tools that do not link OpenEXR read it too.
// This layer only reads and types the entries; which keys exist and which kinds they take is CommandLine's.
#pragma once

#include "grtrace/render/output_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace grtrace::tools {

/// A config file that cannot be used (missing, unreadable, not TOML, a damaged EXR header): the message names
/// the file and says what to change. command_line.hpp turns it into a UsageError (exit code 2).
struct ConfigError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a config entry's value is: a TOML string, a number, a boolean; a text attribute of an EXR header (typed
/// later, like a command-line word); or something no option takes (an array, a table, a date), named in
/// ConfigEntry::type_name.
enum class ConfigValueKind { string, number, boolean, header_text, unsupported };

/// One key of a config file and its value as the text a command line would carry (numbers in their shortest
/// exact form, booleans as "true"/"false").
struct ConfigEntry {
  std::string key;
  ConfigValueKind kind = ConfigValueKind::string;
  std::string text;
  std::string type_name;  ///< the TOML type, for messages ("array", "table", ...)
  long line = 0;          ///< line in a TOML file (0 for an EXR header)
  bool given = true;      ///< false: an EXR's recorded default (sets the default, does not count as given)
};

/// Every entry of one config file, in file order (TOML tables keep no order: sorted by key).
struct ConfigFile {
  std::string path;
  bool from_exr = false;
  std::vector<ConfigEntry> entries;
};

/// The largest scene file read, and the most of an EXR read for its header (a scene file is a few hundred bytes, a
/// frame's header a few kilobytes; its pixels, after the header, are never read).
inline constexpr std::uintmax_t kMaxConfigBytes = 1u << 20;

namespace config_detail {

/// Takes a finite or non-finite double; returns the shortest text that reads back as the same double ("0.3",
/// "1e-08", "inf"), so a TOML float given in a config reaches the tool exactly as written.
inline std::string shortest_text(double v) {
  std::array<char, 64> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), result.ptr);
}

/// Takes a TOML node; returns its entry (kind, text) under `key`. Assumes nothing about the key.
inline ConfigEntry entry_from_toml(const std::string& key, const toml::node& node) {
  ConfigEntry e;
  e.key = key;
  e.line = static_cast<long>(node.source().begin.line);
  if (const auto* s = node.as_string()) {
    e.kind = ConfigValueKind::string;
    e.text = s->get();
  } else if (const auto* i = node.as_integer()) {
    e.kind = ConfigValueKind::number;
    e.text = std::to_string(i->get());
  } else if (const auto* f = node.as_floating_point()) {
    e.kind = ConfigValueKind::number;
    e.text = shortest_text(f->get());
  } else if (const auto* b = node.as_boolean()) {
    e.kind = ConfigValueKind::boolean;
    e.text = b->get() ? "true" : "false";
  } else {
    e.kind = ConfigValueKind::unsupported;
    e.type_name = node.is_array() ? "an array" : node.is_table() ? "a table" : "a date or time";
  }
  return e;
}

/// Takes the bytes of a file; returns true when they start with the OpenEXR magic number.
inline bool is_exr(std::string_view bytes) {
  return bytes.size() >= 4 && static_cast<unsigned char>(bytes[0]) == 0x76 &&
         static_cast<unsigned char>(bytes[1]) == 0x2f && static_cast<unsigned char>(bytes[2]) == 0x31 &&
         static_cast<unsigned char>(bytes[3]) == 0x01;
}

/// Takes the bytes of an OpenEXR file (magic checked); returns the string attributes of its (first) header.
/// Every length is checked against the bytes at hand, so a damaged or hostile file is refused (ConfigError), never
/// read beyond its end. Layout: magic, version (4 bytes each), then attributes "name\0type\0" + int32 size (little
/// endian) + value, ended by an empty name.
inline std::map<std::string, std::string> exr_string_attributes(std::string_view bytes, const std::string& path) {
  std::map<std::string, std::string> out;
  const auto damaged = [&](const std::string& what) {
    return ConfigError("--config '" + path + "': damaged EXR header (" + what +
                       "); give a TOML scene file or an EXR written by grtrace-render");
  };
  std::size_t at = 8;
  const auto read_name = [&]() {
    const std::size_t end = bytes.find('\0', at);
    if (end == std::string_view::npos || end - at > 255) throw damaged("an attribute name or type is not ended");
    std::string s(bytes.substr(at, end - at));
    at = end + 1;
    return s;
  };
  while (true) {
    const std::string name = read_name();
    if (name.empty()) return out;
    const std::string type = read_name();
    if (bytes.size() - at < 4) throw damaged("attribute '" + name + "' has no size");
    std::uint32_t size = 0;
    for (int i = 3; i >= 0; --i) size = (size << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
    at += 4;
    if (size > bytes.size() - at) throw damaged("attribute '" + name + "' runs past the end of the file");
    if (type == "string") out[name] = std::string(bytes.substr(at, size));
    at += size;
  }
}

/// Takes an EXR header's string attributes; returns the names of the options that were given when the frame was
/// rendered: its `options_given` attribute, or for older frames the `--name` words of its `command_line`.
inline std::vector<std::string> given_option_names(const std::map<std::string, std::string>& attributes) {
  std::vector<std::string> names;
  if (const auto it = attributes.find("options_given"); it != attributes.end()) {
    std::stringstream ss(it->second);
    for (std::string name; std::getline(ss, name, ',');)
      if (!name.empty()) names.push_back(name);
    return names;
  }
  if (const auto it = attributes.find("command_line"); it != attributes.end()) {
    std::stringstream ss(it->second);
    for (std::string word; ss >> word;)
      if (word.rfind("--", 0) == 0) names.push_back(word.substr(2, word.find('=') - 2));
  }
  return names;
}

/// Takes the bytes of an EXR; returns its `option_<name>` attributes as entries (kind header_text), each marked
/// given or recorded default.
inline ConfigFile config_from_exr(std::string_view bytes, const std::string& path) {
  const auto attributes = exr_string_attributes(bytes, path);
  const auto given = given_option_names(attributes);
  ConfigFile file{path, true, {}};
  for (const auto& [name, value] : attributes) {
    if (name.rfind("option_", 0) != 0) continue;
    ConfigEntry e;
    e.key = name.substr(7);
    e.kind = ConfigValueKind::header_text;
    e.text = value;
    e.given = std::find(given.begin(), given.end(), e.key) != given.end();
    file.entries.push_back(std::move(e));
  }
  if (file.entries.empty())
    throw ConfigError("--config '" + path + "': this EXR records no options (no option_<name> attributes); give an "
                      "EXR written by grtrace-render or a TOML scene file");
  return file;
}

}  // namespace config_detail

/// Reads `path` as a config: an EXR (by its magic number) or TOML. Throws ConfigError naming the file for a
/// missing, unreadable, oversized or damaged file and for a TOML syntax error (with its line and column). Keys
/// and kinds are not checked here.
inline ConfigFile read_config_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st))
    throw ConfigError("--config '" + path + "': no such file; give the path of a TOML scene file (or of an EXR "
                      "written by grtrace-render)");
  if (fs::is_directory(st)) throw ConfigError("--config '" + path + "' is a directory; give a TOML scene file");
  // A device or a socket is never a scene file (/dev/zero would read as a megabyte of NULs); a pipe is read, up to
  // the size limit (--config <(generate-toml) is a pipe).
  if (fs::is_character_file(st) || fs::is_block_file(st) || fs::is_socket(st))
    throw ConfigError("--config '" + path + "' is " + grtrace::entry_kind_name(st) +
                      ", not a file; give a TOML scene file (or an EXR written by grtrace-render)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError("--config '" + path + "' cannot be read (" + std::strerror(errno) + "); check its permissions");
  // At most the limit and one byte more: a frame's header lies at the start of its EXR (a few kilobytes, its
  // pixels after it, of any size), and a TOML file over the limit is refused whole. A pipe is read the same way.
  std::string bytes(static_cast<std::size_t>(kMaxConfigBytes) + 1, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw ConfigError("--config '" + path + "' cannot be read; check the file");
  if (config_detail::is_exr(bytes))
    return config_detail::config_from_exr(std::string_view(bytes).substr(0, kMaxConfigBytes), path);
  if (bytes.size() > kMaxConfigBytes)
    throw ConfigError("--config '" + path + "' is larger than 1 MiB; a scene file is a few lines of TOML");

  ConfigFile file{path, false, {}};
  try {
    const toml::table table = toml::parse(std::string_view(bytes), std::string_view(path));
    for (const auto& [key, node] : table) file.entries.push_back(config_detail::entry_from_toml(std::string(key.str()), node));
  } catch (const toml::parse_error& e) {
    throw ConfigError("--config '" + path + "' line " + std::to_string(e.source().begin.line) + ", column " +
                      std::to_string(e.source().begin.column) + ": " + std::string(e.description()) +
                      "; write one 'name = value' per line (TOML: strings in quotes, numbers and true/false bare)");
  }
  return file;
}

/// Takes an option's text; returns it as a TOML value: a bare integer, float or boolean when that reads back to
/// exactly the same text (so `width = 48`, `fov = 60`, `rtol = 1e-08`... stay numbers), else a quoted string
/// ("0,0,0.3", "disk", "2e-9": the text reaches the tool unchanged either way).
inline std::string toml_value_text(const std::string& text) {
  if (!text.empty()) {
    try {
      const toml::table probe = toml::parse(std::string_view("v = " + text));
      if (const auto* node = probe.get("v"); node && (node->is_integer() || node->is_floating_point())) {
        const ConfigEntry e = config_detail::entry_from_toml("v", *node);
        if (e.text == text) return text;
      }
    } catch (const toml::parse_error&) {
      // not a TOML number: written as a string below
    }
  }
  // A one-line TOML basic string (never a multi-line one: the line may be written commented out).
  std::string quoted = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      std::array<char, 8> escape{};
      std::snprintf(escape.data(), escape.size(), "\\u%04x", byte);
      quoted += escape.data();
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

}  // namespace grtrace::tools
