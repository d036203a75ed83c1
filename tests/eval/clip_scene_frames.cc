#include "tests/eval/clip_scene_frames.h"

#include <cmath>
#include <string>

#include "common/error/check.h"

namespace reenact::eval {

Expected<std::vector<int>> SceneFramesOfClip(std::span<const double> timestamps_s, double rate_hz,
                                             int frame_count) {
  REENACT_CHECK(std::isfinite(rate_hz) && rate_hz > 0, "rate_hz must be finite and > 0");
  REENACT_CHECK(frame_count >= 0, "frame_count must be >= 0");
  std::vector<int> scene_frames;
  for (size_t n = 0; n < timestamps_s.size(); ++n) {
    const double at = timestamps_s[n] * rate_hz;
    const bool in_scene = std::isfinite(at) && at > -0.5 && at < frame_count - 0.5;
    const double nearest = in_scene ? std::round(at) : 0;
    if (!in_scene || std::abs(at - nearest) > 1e-3 ||
        (!scene_frames.empty() && nearest <= scene_frames.back()))
      return MakeError(
          "internal", "clip frame " + std::to_string(n) + " at " + std::to_string(timestamps_s[n]) +
                          " s is not a later one of the scene's " + std::to_string(frame_count) +
                          " frames at " + std::to_string(rate_hz) + " Hz");
    scene_frames.push_back(static_cast<int>(nearest));
  }
  return scene_frames;
}

}  // namespace reenact::eval
