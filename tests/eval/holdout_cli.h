#pragma once
// The command line of `reenact-eval holdout` (holdout_eval.h), checked before the run starts:
//
//   reenact-eval holdout --source SRC [--skeleton source|track|SPEC] [--poses auto|slam]
//                        --every K --window W [--methods LIST] [--frames N] [--json FILE]
//                        [--images DIR]
//
// The source, the skeleton track's file and the held-out rule against the source's length
// are checked by the run itself (RunHoldout).

#include <optional>
#include <set>
#include <string>

#include "common/cli/command_line.h"
#include "common/error/expected.h"
#include "proto/report/report_table.h"
#include "tests/eval/holdout_eval.h"

namespace reenact::eval {

struct HoldoutCommand {
  HoldoutOptions options;
  std::optional<std::string> json_path;
};

// The value flags ParseHoldoutCommand reads.
std::set<std::string> HoldoutFlags();

// Errors (code "usage", naming the flag and what is wrong): no --source, --every or --window;
// --every not a whole number >= 1, --window not a whole number >= 0, --frames not a whole
// number >= 1; --skeleton or --poses empty or unknown (--skeleton: source, track or a track
// spec); an unknown method or an empty item in --methods; (code "io") a --json file that
// cannot be written or an --images folder that cannot be created.
Expected<HoldoutCommand> ParseHoldoutCommand(const CommandLine& command_line);

// Command "holdout": one row per method: method, n, psnr_db, ssim, iou, colour_mae,
// texture_gap, held_out, recorded (the frames of the clip that textures).
proto::Report HoldoutReport(const HoldoutRun& run);

// The whole command: parse, run, print (exit codes as every reenact-eval command).
int RunHoldoutCommand(const CommandLine& command_line);

}  // namespace reenact::eval
