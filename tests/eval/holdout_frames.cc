#include "tests/eval/holdout_frames.h"

#include <string>

namespace reenact::eval {
namespace {

std::string Flags(int every, int window) {
  std::string flags = "--every ";
  flags += std::to_string(every);
  flags += " --window ";
  flags += std::to_string(window);
  return flags;
}

}  // namespace

Expected<HeldOutFrames> SelectHeldOutFrames(int frame_count, int every, int window) {
  REENACT_CHECK(frame_count >= 0, "frame_count must be >= 0");
  if (every < 1)
    return MakeError("usage",
                     "--every must be a whole number >= 1 (every K-th frame is held out), "
                     "got " +
                         std::to_string(every));
  if (window < 0)
    return MakeError("usage",
                     "--window must be a whole number >= 0 (neighbours left out on each "
                     "side of a held-out frame), got " +
                         std::to_string(window));
  HeldOutFrames frames;
  frames.excluded.assign(static_cast<size_t>(frame_count), false);
  for (long long k = every; k + window < frame_count; k += every) {
    if (k < window) continue;
    frames.held_out.push_back(static_cast<int>(k));
    for (long long n = k - window; n <= k + window; ++n) frames.excluded[n] = true;
  }
  for (bool e : frames.excluded) frames.kept += !e;
  const std::string n = std::to_string(frame_count);
  if (frames.held_out.empty())
    return MakeError("usage", Flags(every, window) + ": no frame of the " + n +
                                  " can be held out (frames K, 2K, ... with W frames on each side "
                                  "inside the recording); give a smaller --every or --window, or "
                                  "a longer recording");
  if (frames.kept == 0)
    return MakeError("usage",
                     Flags(every, window) + " leave no frame to texture from: each of the " + n +
                         " frames is held out or among the W = " + std::to_string(window) +
                         " neighbours on either side of one; give --every above 2W + 1 = " +
                         std::to_string(2 * window + 1) + " or a smaller --window");
  return frames;
}

}  // namespace reenact::eval
