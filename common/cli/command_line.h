#pragma once
// Command-line parsing shared by the executables: positional words, then "--flag value" or
// "--switch" options. Unknown flags and missing values are errors a user can act on.
//
//   reenact-capture record --source synthetic:turn-and-kick --out clips/a --frames 60
//   -> positionals {"record"}, values {"source": ..., "out": ..., "frames": "60"}

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/error/expected.h"

namespace reenact {

struct CommandLineSpec {
  std::set<std::string> value_flags;   // flags that take a value: "--out DIR"
  std::set<std::string> switch_flags;  // flags without a value: "--headless"
};

class CommandLine {
 public:
  // Parses argv[first..argc); flags named without the leading "--".
  static Expected<CommandLine> Parse(int argc, const char* const* argv, int first,
                                     const CommandLineSpec& spec);

  const std::vector<std::string>& positionals() const { return positionals_; }
  bool Has(const std::string& flag) const;
  std::optional<std::string> Get(const std::string& flag) const;
  std::string GetOr(const std::string& flag, const std::string& fallback) const;

  // Typed access: an Error naming the flag when the value is absent (Require*) or malformed.
  Expected<std::string> Require(const std::string& flag) const;
  Expected<double> GetDouble(const std::string& flag, double fallback) const;
  Expected<long long> GetInt(const std::string& flag, long long fallback) const;
  Expected<double> RequireDouble(const std::string& flag) const;

 private:
  std::vector<std::string> positionals_;
  std::map<std::string, std::string> values_;
  std::set<std::string> switches_;
};

// The frame of every executable's main: parses argv, answers --help, runs the handler named
// by the first positional word, and turns failures into one line on stderr:
//   usage errors (unknown option, unknown command): the line and the usage text, exit 2;
//   an exception escaping a handler (a bug): "TOOL: internal error: ...", exit 3.
using CommandHandler = std::function<int(const CommandLine&)>;
int RunTool(const std::string& tool, const std::string& usage, CommandLineSpec spec,
            const std::map<std::string, CommandHandler>& commands, int argc,
            const char* const* argv);

// Prints "TOOL: message" on stderr; returns 2 for code "usage", else 1.
int ReportFailure(const std::string& tool, const Error& error);

// Parses "LAT,LON" in degrees; an Error unless both are numbers in range.
Expected<std::pair<double, double>> ParseLatLon(const std::string& text);

}  // namespace reenact
