#include "common/cli/command_line.h"

#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>

namespace reenact {
namespace {

std::optional<double> ToDouble(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

Expected<CommandLine> CommandLine::Parse(int argc, const char* const* argv, int first,
                                         const CommandLineSpec& spec) {
  CommandLine cl;
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0 || arg.size() == 2) {
      cl.positionals_.push_back(arg);
      continue;
    }
    std::string name = arg.substr(2);
    std::optional<std::string> inline_value;
    if (const auto eq = name.find('='); eq != std::string::npos) {
      inline_value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    if (spec.switch_flags.count(name) && !inline_value) {
      cl.switches_.insert(name);
    } else if (spec.value_flags.count(name)) {
      if (inline_value) {
        cl.values_[name] = *inline_value;
      } else if (i + 1 < argc) {
        cl.values_[name] = argv[++i];
      } else {
        return MakeError("usage", "option --" + name + " needs a value");
      }
    } else {
      return MakeError("usage", "unknown option --" + name);
    }
  }
  return cl;
}

bool CommandLine::Has(const std::string& flag) const {
  return switches_.count(flag) || values_.count(flag);
}

std::optional<std::string> CommandLine::Get(const std::string& flag) const {
  const auto it = values_.find(flag);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string CommandLine::GetOr(const std::string& flag, const std::string& fallback) const {
  return Get(flag).value_or(fallback);
}

Expected<std::string> CommandLine::Require(const std::string& flag) const {
  if (auto v = Get(flag)) return *v;
  return MakeError("usage", "missing required option --" + flag);
}

Expected<double> CommandLine::GetDouble(const std::string& flag, double fallback) const {
  const auto v = Get(flag);
  if (!v) return fallback;
  if (auto d = ToDouble(*v)) return *d;
  return MakeError("usage", "option --" + flag + " expects a number, got '" + *v + "'");
}

Expected<double> CommandLine::RequireDouble(const std::string& flag) const {
  if (!Get(flag)) return MakeError("usage", "missing required option --" + flag);
  return GetDouble(flag, 0);
}

Expected<long long> CommandLine::GetInt(const std::string& flag, long long fallback) const {
  const auto v = Get(flag);
  if (!v) return fallback;
  char* end = nullptr;
  const long long n = std::strtoll(v->c_str(), &end, 10);
  if (v->empty() || end != v->c_str() + v->size())
    return MakeError("usage", "option --" + flag + " expects an integer, got '" + *v + "'");
  return n;
}

int ReportFailure(const std::string& tool, const Error& error) {
  std::cerr << tool << ": " << error.message << "\n";
  return error.code == "usage" ? 2 : 1;
}

int RunTool(const std::string& tool, const std::string& usage, CommandLineSpec spec,
            const std::map<std::string, CommandHandler>& commands, int argc,
            const char* const* argv) {
  spec.switch_flags.insert("help");
  const auto cl = CommandLine::Parse(argc, argv, 1, spec);
  if (!cl.ok()) {
    std::cerr << tool << ": " << cl.error().message << "\n" << usage;
    return 2;
  }
  const std::string command = cl->positionals().empty() ? "" : cl->positionals()[0];
  if (cl->Has("help") || command == "help") {
    std::cout << usage;
    return 0;
  }
  const auto it = commands.find(command);
  if (it == commands.end()) {
    std::cerr << tool << ": "
              << (command.empty() ? "no command given" : "unknown command '" + command + "'")
              << "\n"
              << usage;
    return 2;
  }
  try {
    return it->second(*cl);
  } catch (const std::exception& e) {
    std::cerr << tool << ": internal error: " << e.what() << "\n";
    return 3;
  }
}

Expected<std::pair<double, double>> ParseLatLon(const std::string& text) {
  const auto comma = text.find(',');
  const auto bad =
      MakeError("usage", "expected LAT,LON in degrees (e.g. 48.1374,11.5755), got '" + text + "'");
  if (comma == std::string::npos) return bad;
  const auto lat = ToDouble(text.substr(0, comma));
  const auto lon = ToDouble(text.substr(comma + 1));
  if (!lat || !lon) return bad;
  if (*lat < -90 || *lat > 90 || *lon < -180 || *lon > 180)
    return MakeError(
        "usage", "latitude must lie in [-90, 90] and longitude in [-180, 180], got '" + text + "'");
  return std::pair{*lat, *lon};
}

}  // namespace reenact
