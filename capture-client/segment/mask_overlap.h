#pragma once
// Agreement of a mask with a reference mask (pixels > 127 are set):
//   IoU = |A and T| / |A or T|  (1 when both are empty)
//   precision = |A and T| / |A|  (1 when A is empty), recall = |A and T| / |T|  (1 when T is
//   empty).

#include "common/image/image.h"

namespace reenact::capture {

struct MaskOverlap {
  double iou = 1;
  double precision = 1;
  double recall = 1;
  long long intersection = 0;
  long long mask_pixels = 0;
  long long truth_pixels = 0;
};

// Precondition (CHECK): one-channel masks of one size.
MaskOverlap CompareMasks(const ImageGray8& mask, const ImageGray8& truth);

}  // namespace reenact::capture
