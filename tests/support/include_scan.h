#pragma once
// The #include lines of the project's own sources, for the dependency tests that hold the
// layer rules of DESIGN.md (tests/unit/*/dependency_test.cc).

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

namespace reenact::test_support {

struct IncludeLine {
  std::string file;    // the including .h/.cc, relative to the source root: "server/http/message.h"
  std::string header;  // as written between <> or "": "proto/api/http_headers.h"
};

// Every quoted or bracketed include of the .h/.cc files below folder (relative to the source
// root, REENACT_SOURCE_DIR), in no particular order.
inline std::vector<IncludeLine> IncludesUnder(const std::string& folder) {
  const std::filesystem::path source_root(REENACT_SOURCE_DIR);
  const std::regex include_re(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  std::vector<IncludeLine> out;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(source_root / folder)) {
    const auto ext = entry.path().extension();
    if (ext != ".h" && ext != ".cc") continue;
    const std::string file = entry.path().lexically_relative(source_root).generic_string();
    std::ifstream in(entry.path());
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (std::regex_search(line, m, include_re)) out.push_back({file, m[1]});
    }
  }
  return out;
}

inline bool StartsWith(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

inline bool StartsWithAnyOf(std::string_view s, std::initializer_list<std::string_view> prefixes) {
  for (const std::string_view prefix : prefixes) {
    if (StartsWith(s, prefix)) return true;
  }
  return false;
}

// A standard library header: <vector>, <cmath>, ... (no directory, no extension).
inline bool IsStdHeader(std::string_view header) {
  return header.find('/') == std::string_view::npos && header.find('.') == std::string_view::npos;
}

// Any OpenCV header, OpenCV 4's <opencv2/...> or the old C API's <opencv/...>.
inline bool IsOpenCvHeader(std::string_view header) {
  return StartsWith(header, "opencv2/") || StartsWith(header, "opencv/");
}

// "FILE includes HEADER" for each include below folder that breaks a rule (breaks(include) is
// true), and a line saying so when the folder has fewer than min_includes includes (a moved or
// emptied folder must not pass by having none): empty when the rule holds, the failure
// message when it does not.
template <typename BreaksRule>
std::vector<std::string> BreakingUnder(const std::string& folder, BreaksRule breaks,
                                       size_t min_includes = 10) {
  const std::vector<IncludeLine> includes = IncludesUnder(folder);
  std::vector<std::string> out;
  for (const IncludeLine& include : includes) {
    if (breaks(include)) out.push_back(include.file + " includes " + include.header);
  }
  if (includes.size() < min_includes) {
    out.push_back(folder + ": only " + std::to_string(includes.size()) + " includes found");
  }
  return out;
}

}  // namespace reenact::test_support
