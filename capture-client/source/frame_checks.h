#pragma once
// Checks the real sensor sources (oni:, openni, tum:) apply to every frame before yielding it.
//
// All-zero depth. A depth stream that never carries a reading is an Error of the source, not a
// per-frame flag: nothing downstream (SLAM, segmentation, the cylinder model) can use such a
// stream, and failing in the source gives one clear message at the start instead of an empty
// map or a model of default radii at the end. A frame without any reading *after* frames with
// readings is passed on unchanged (a hand over the sensor, everything closer than its minimum
// range): consumers treat its pixels as "no reading", as for any zero pixel.

#include <string>
#include <string_view>

#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"

namespace reenact::capture {

// Colour with 3 channels and depth with 1, both non-empty, of the same size, and of the
// camera's size. Error code "corrupt" naming `where` and both sizes otherwise.
Status CheckRegisteredPair(const ImageRgb8& color, const ImageDepthMm& depth,
                           const PinholeCamera& camera, std::string_view where);

// Number of depth pixels with a reading (> 0).
size_t CountDepthReadings(const ImageDepthMm& depth);

// Watches the leading frames of a stream for depth readings (policy above).
class DepthPresenceGuard {
 public:
  // max_leading_empty_frames >= 1: frames in a row from the start of the stream without any
  // reading after which the stream is declared depth-less (30 = 1 s at 30 Hz).
  explicit DepthPresenceGuard(int max_leading_empty_frames = 30);

  // Call for every frame in order. Error (code "no_depth") once the first
  // max_leading_empty_frames frames all lacked readings; ok otherwise.
  Status Observe(const ImageDepthMm& depth, std::string_view source_description);
  // Call when the stream ends: Error (code "no_depth") if it had frames but none had a
  // reading.
  Status AtEnd(std::string_view source_description) const;

 private:
  int max_leading_empty_frames_;
  int frames_ = 0;
  bool seen_reading_ = false;
};

}  // namespace reenact::capture
