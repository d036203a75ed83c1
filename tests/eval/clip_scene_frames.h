#pragma once

#include <span>
#include <vector>

#include "common/error/expected.h"

namespace reenact::eval {

// The scene frame each clip frame was recorded from, found from the clip frames' timestamps
// (seconds; SyntheticSource stamps scene frame n at n / rate_hz). A clip holds a subset of the
// scene's frames in order: the recorder stores no frame without a skeleton. Error "internal"
// when a timestamp lies more than a thousandth of a frame from a frame's time, outside
// [0, frame_count), or not after the previous one's frame (or is not finite).
// Preconditions (CheckError): rate_hz finite and > 0, frame_count >= 0.
Expected<std::vector<int>> SceneFramesOfClip(std::span<const double> timestamps_s, double rate_hz,
                                             int frame_count);

}  // namespace reenact::eval
