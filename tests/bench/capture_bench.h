#pragma once
// `reenact-bench capture`: milliseconds per frame of each stage of `reenact-capture record`
// on 640x480 (segmentation, SLAM, encoding, map keyframes), and the frame rate of the whole
// pipeline, for the ways a clip gets recorded.

#include "common/cli/command_line.h"

namespace reenact::bench {

// reenact-bench capture [--frames N] [--repeats R] [--tum DIR] [--json FILE]
int RunCaptureBench(const CommandLine& cl);

}  // namespace reenact::bench
