#pragma once
// The argument of a source spec after "kind:", with options in URL query form:
//   tum:/data/rgbd_dataset_freiburg1_xyz?camera=fr1&undistort=0
//   -> path "/data/rgbd_dataset_freiburg1_xyz", options {camera: fr1, undistort: 0}
// The path ends at the last '?', so a path that itself contains '?' must be followed by an
// empty query ("DIR?with?marks?").

#include <initializer_list>
#include <map>
#include <string>
#include <string_view>

#include "common/error/expected.h"

namespace reenact::capture {

struct SourceArgument {
  std::string path;
  std::map<std::string, std::string> options;
};

// Errors (code "usage", naming `kind` and the accepted options): an option not in `known`,
// an option without "=value" or with an empty name, an option given twice.
Expected<SourceArgument> ParseSourceArgument(std::string_view kind, std::string_view argument,
                                             std::initializer_list<std::string_view> known);

// "1", "true", "yes", "on" / "0", "false", "no", "off"; an Error (code "usage") naming the
// option otherwise.
Expected<bool> ParseBoolOption(std::string_view kind, std::string_view name,
                               std::string_view value);

}  // namespace reenact::capture
