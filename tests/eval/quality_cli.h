#pragma once
// The command line of `reenact-eval quality`, checked before the run starts (recording and
// rendering take a while; a typo or an unwritable output path should not cost that):
//
//   reenact-eval quality [--scenario S] [--methods LIST] [--views DEG,...] [--step K]
//                        [--json FILE] [--markdown FILE] [--images DIR]
//                        [--image-pairs FRAME@DEG,...]
//
// The scenario name is checked by the run itself (QualityHarness::Create).

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/cli/command_line.h"
#include "common/error/expected.h"
#include "tests/eval/quality_eval.h"

namespace reenact::eval {

struct QualityCommand {
  QualityOptions options;
  std::optional<std::string> json_path;
  std::optional<std::string> markdown_path;
};

// The value flags ParseQualityCommand reads.
std::set<std::string> QualityFlags();

// Errors (code "usage", naming the flag and what is wrong): an unknown method, an empty list,
// a view or frame that is not a finite number, --step below 1 or not an integer, an
// --image-pairs item not FRAME@DEG, --image-pairs without --images; (code "io") a --json or
// --markdown file that cannot be written (missing folder, no permission, a directory) or an
// --images folder that cannot be created.
Expected<QualityCommand> ParseQualityCommand(const CommandLine& command_line);

// A comma-separated list of quality methods (--methods), each known: error "usage" for an
// empty list, an empty item or an unknown name.
Expected<std::vector<std::string>> ParseMethodList(const std::string& text);

// Whether a file could be written at path without creating folders: error "io" naming the
// flag and the reason otherwise. Nothing is created.
Status CheckWritableFile(const std::string& flag, const std::string& path);

// Whether a folder exists or could be created at path (with its parents): error "io" naming
// the flag and the reason otherwise. Nothing is created.
Status CheckCreatableFolder(const std::string& flag, const std::string& path);

}  // namespace reenact::eval
