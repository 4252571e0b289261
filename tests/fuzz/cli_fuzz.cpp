// Fuzz target for the tools' command-line parser (examples/common/command_line.hpp; AFL++, see README.md).
// The input file is split at newlines into arguments, parsed against options and flags like grtrace-render's,
// and every value is read as text, number, integer and list (also --config FILE, read only; inputs naming
// --write-config are skipped). UsageError is a refusal (fine); anything else
// -- another exception type, a crash, a sanitizer report, a hang -- is a finding.
//   cli_fuzz FILE...   (afl-fuzz runs: cli_fuzz @@)
#include "command_line.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  int refused = 0;
  for (int f = 1; f < argc; ++f) {
    std::ifstream in(argv[f], std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string data = ss.str();
    std::vector<std::string> args{"cli_fuzz"};
    std::string cur;
    for (const char c : data) {
      if (c == '\n') {
        args.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    if (!cur.empty()) args.push_back(cur);
    // --write-config would write wherever the input points: not from a fuzzer (--config only reads, and stays in).
    bool writes = false;
    for (const auto& arg : args) writes = writes || arg.find("write-config") != std::string::npos;
    if (writes) continue;
    std::vector<char*> av;
    for (auto& a : args) av.push_back(a.data());
    av.push_back(nullptr);

    grtrace::tools::CommandLine cli("cli_fuzz", "fuzz target");
    cli.option("width", "1024", "w").option("rtol", "2e-9", "r").option("velocity", "0,0,0", "v");
    cli.option("out", "render.exr", "o").flag("status-map", "s").flag("json", "j");
    try {
      if (!cli.parse(static_cast<int>(av.size() - 1), av.data())) continue;  // --help
      for (const char* name : {"width", "rtol", "velocity", "out"}) {
        (void)cli.text(name);
        try { (void)cli.number(name); } catch (const grtrace::tools::UsageError&) { ++refused; }
        try { (void)cli.integer(name); } catch (const grtrace::tools::UsageError&) { ++refused; }
        try { (void)cli.numbers(name, 0); } catch (const grtrace::tools::UsageError&) { ++refused; }
        try { (void)cli.numbers(name, 3); } catch (const grtrace::tools::UsageError&) { ++refused; }
      }
      (void)cli.flag_set("status-map");
      (void)cli.flag_set("json");
      (void)cli.values();
    } catch (const grtrace::tools::UsageError&) {
      ++refused;
    }
  }
  (void)refused;
  return 0;
}
