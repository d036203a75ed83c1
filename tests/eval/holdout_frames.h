#pragma once
// Which frames `reenact-eval holdout` leaves out of a recording of N frames (0 .. N-1), for
// --every K --window W:
//   held out: k = K, 2K, 3K, ... (every K-th frame; never frame 0), each whose window
//             [k - W, k + W] lies wholly inside [0, N), so every held-out frame has its full
//             window and the same distance W + 1 to the nearest frame that may texture it;
//   excluded from the recording: every held-out frame and its W neighbours on each side;
//   kept: the rest, the only frames the clip is recorded from.

#include <vector>

#include "common/error/expected.h"

namespace reenact::eval {

struct HeldOutFrames {
  std::vector<int> held_out;   // ascending
  std::vector<bool> excluded;  // per frame (size N): held out or within W of one
  int kept = 0;                // frames not excluded
};

// Errors (code "usage", naming --every and --window and what to change): every < 1 or
// window < 0; no frame qualifies to be held out; no frame is left to record and texture from.
// Precondition (CHECK): frame_count >= 0.
Expected<HeldOutFrames> SelectHeldOutFrames(int frame_count, int every, int window);

}  // namespace reenact::eval
