#include "capture-client/source/source_argument.h"

#include <algorithm>

namespace reenact::capture {
namespace {

std::string KnownList(std::initializer_list<std::string_view> known) {
  if (known.size() == 0) return "none";
  std::string list;
  for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
  return list;
}

}  // namespace

Expected<SourceArgument> ParseSourceArgument(std::string_view kind, std::string_view argument,
                                             std::initializer_list<std::string_view> known) {
  SourceArgument out;
  const size_t mark = argument.rfind('?');
  out.path = std::string(argument.substr(0, mark));
  if (mark == std::string_view::npos) return out;
  std::string_view query = argument.substr(mark + 1);
  while (!query.empty()) {
    const size_t amp = query.find('&');
    const std::string_view item = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view() : query.substr(amp + 1);
    if (item.empty()) continue;
    const size_t eq = item.find('=');
    const std::string name(item.substr(0, eq));
    if (eq == std::string_view::npos || name.empty())
      return MakeError("usage", std::string(kind) + ": option '" + std::string(item) +
                                    "' must be NAME=VALUE; options: " + KnownList(known));
    if (std::find(known.begin(), known.end(), name) == known.end())
      return MakeError("usage", std::string(kind) + ": unknown option '" + name +
                                    "'; options: " + KnownList(known));
    if (!out.options.emplace(name, std::string(item.substr(eq + 1))).second)
      return MakeError("usage", std::string(kind) + ": option '" + name + "' given twice");
  }
  return out;
}

Expected<bool> ParseBoolOption(std::string_view kind, std::string_view name,
                               std::string_view value) {
  for (std::string_view yes : {"1", "true", "yes", "on"})
    if (value == yes) return true;
  for (std::string_view no : {"0", "false", "no", "off"})
    if (value == no) return false;
  return MakeError("usage", std::string(kind) + ": option " + std::string(name) + "=" +
                                std::string(value) + " must be 1 or 0 (true/false)");
}

}  // namespace reenact::capture
