#pragma once
// `reenact-bench sources`: how long the real frame sources take to deliver a frame.

#include "common/cli/command_line.h"

namespace reenact::bench {

// reenact-bench sources [--oni FILE] [--tum DIR] [--repeats R] [--json FILE]
int RunSourceBench(const CommandLine& cl);

}  // namespace reenact::bench
