#pragma once
// `reenact-bench server`: the sharing service under load.

#include "common/cli/command_line.h"

namespace reenact::bench {

int RunServerBench(const CommandLine& cl);

}  // namespace reenact::bench
