// examples/common/app_options.hpp
// The tools' command line as the application library reads requests (grtrace/app/front_door.hpp): an
// app::OptionSource over a CommandLine (or any source with given/declares/text), the render options declared from
// the library's table (names, defaults, help: the same as the Python module's keywords), and the library's
// refusals (app::RequestError) as the tools' UsageError (exit code 2).
#pragma once

#include "command_line.hpp"
#include "grtrace/app/front_door.hpp"

#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>

namespace grtrace::tools {

/// A CommandLine (its scene file included) as the library's option source.
class CommandLineOptions : public app::OptionSource {
 public:
  explicit CommandLineOptions(const CommandLine& cli) : cli_(cli) {}
  bool given(const std::string& name) const override { return cli_.declares(name) && cli_.given(name); }
  std::optional<std::string> text(const std::string& name) const override {
    if (!cli_.declares(name)) return std::nullopt;
    return cli_.text(name);
  }

 private:
  const CommandLine& cli_;
};

/// Declares every render option of the library's table (app::render_options) but those in `skip`, with the default
/// `defaults` gives for it where it names one.
inline void declare_render_options(CommandLine& cli, const std::set<std::string>& skip = {},
                                   const std::map<std::string, std::string>& defaults = {}) {
  for (const app::OptionInfo& o : app::render_options()) {
    const std::string name(o.name);
    if (skip.count(name)) continue;
    if (o.flag) {
      cli.flag(name, std::string(o.help));
    } else {
      const auto d = defaults.find(name);
      cli.option(name, d != defaults.end() ? d->second : std::string(o.default_text), std::string(o.help));
    }
  }
}

/// The help of one of the library's render options (app::render_options), for a tool that declares it itself.
inline std::string render_option_help(const std::string& name) {
  for (const app::OptionInfo& o : app::render_options())
    if (o.name == name) return std::string(o.help);
  throw std::logic_error("option --" + name + " is not a render option");
}

/// f(), the library's refusal of the request (app::RequestError, or another std::invalid_argument from the checks)
/// as UsageError: the tool exits with code 2 and the library's message.
template <class F>
decltype(auto) as_usage_error(F&& f) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace grtrace::tools
