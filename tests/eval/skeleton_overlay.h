#pragma once
// A depth frame with two skeletons drawn on it, for looking at the frames where a tracker
// and a reference disagree most (`reenact-eval tracker --pictures DIR`).
//
// The depth as grey: a reading of 0 black, the others from 255 (the frame's nearest
// reading) down to 80 (its farthest), so the person stands out whatever their distance.
// Each skeleton's bones (the body parts' joint pairs, PartJoints of skeleton.h, and neck to
// each shoulder, waist to each hip) as lines between its joints projected with the depth camera (pixel centres at integer coordinates),
// a bone only where both joints are given and in front of the camera; each joint a small
// disc. The picture is the frame scaled up by `scale` (nearest pixel), the lines drawn at
// that size. Colours: reference green (0, 200, 0), estimate red (230, 30, 30), drawn last.

#include <optional>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"

namespace reenact::eval {

struct SkeletonOverlayOptions {
  int scale = 2;      // 1-8
  int thickness = 2;  // line width in picture pixels, 1-8
  void Check() const;
};

// Preconditions (CHECK): depth not empty, the camera's size the depth's; options Check().
ImageRgb8 SkeletonOverlay(const ImageDepthMm& depth, const PinholeCamera& camera,
                          const std::optional<Skeleton>& reference,
                          const std::optional<Skeleton>& estimate,
                          const SkeletonOverlayOptions& options = {});

}  // namespace reenact::eval
