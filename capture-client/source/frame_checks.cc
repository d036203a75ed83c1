#include "capture-client/source/frame_checks.h"

#include <algorithm>

namespace reenact::capture {
namespace {

std::string Size(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

Error NoDepthError(int frames, std::string_view source) {
  return MakeError("no_depth",
                   "the first " + std::to_string(frames) + " frame(s) of " + std::string(source) +
                       " have no depth reading at all (every depth pixel is 0): the depth "
                       "stream is empty or unusable; check that the depth images are 16-bit "
                       "and non-empty, or that the sensor's projector is not covered");
}

}  // namespace

Status CheckRegisteredPair(const ImageRgb8& color, const ImageDepthMm& depth,
                           const PinholeCamera& camera, std::string_view where) {
  if (color.empty() || color.channels != 3)
    return MakeError("corrupt", std::string(where) + ": the colour image is empty or not RGB (" +
                                    Size(color.width, color.height) + ", " +
                                    std::to_string(color.channels) + " channels)");
  if (depth.empty() || depth.channels != 1)
    return MakeError("corrupt", std::string(where) + ": the depth image is empty or has " +
                                    std::to_string(depth.channels) + " channels");
  if (color.width != depth.width || color.height != depth.height)
    return MakeError("corrupt", std::string(where) + ": colour is " +
                                    Size(color.width, color.height) + " but depth is " +
                                    Size(depth.width, depth.height) +
                                    "; colour and depth must be registered images of one size");
  if (color.width != camera.width || color.height != camera.height)
    return MakeError("corrupt",
                     std::string(where) + ": the images are " + Size(color.width, color.height) +
                         " but the camera intrinsics are for " + Size(camera.width, camera.height));
  return {};
}

size_t CountDepthReadings(const ImageDepthMm& depth) {
  return static_cast<size_t>(
      std::count_if(depth.data.begin(), depth.data.end(), [](uint16_t d) { return d > 0; }));
}

DepthPresenceGuard::DepthPresenceGuard(int max_leading_empty_frames)
    : max_leading_empty_frames_(max_leading_empty_frames) {
  REENACT_CHECK(max_leading_empty_frames >= 1, "max_leading_empty_frames must be >= 1");
}

Status DepthPresenceGuard::Observe(const ImageDepthMm& depth, std::string_view source_description) {
  ++frames_;
  if (seen_reading_) return {};
  seen_reading_ =
      std::any_of(depth.data.begin(), depth.data.end(), [](uint16_t d) { return d > 0; });
  if (!seen_reading_ && frames_ >= max_leading_empty_frames_)
    return NoDepthError(frames_, source_description);
  return {};
}

Status DepthPresenceGuard::AtEnd(std::string_view source_description) const {
  if (frames_ > 0 && !seen_reading_) return NoDepthError(frames_, source_description);
  return {};
}

}  // namespace reenact::capture
