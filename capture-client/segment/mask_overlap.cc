#include "capture-client/segment/mask_overlap.h"

#include "common/error/check.h"

namespace reenact::capture {

MaskOverlap CompareMasks(const ImageGray8& mask, const ImageGray8& truth) {
  REENACT_CHECK(mask.channels == 1 && truth.channels == 1 && mask.width == truth.width &&
                    mask.height == truth.height,
                "masks must be one-channel and of one size");
  MaskOverlap o;
  for (size_t i = 0; i < mask.data.size(); ++i) {
    const bool a = mask.data[i] > 127, t = truth.data[i] > 127;
    o.mask_pixels += a;
    o.truth_pixels += t;
    o.intersection += a && t;
  }
  const long long united = o.mask_pixels + o.truth_pixels - o.intersection;
  if (united > 0) o.iou = static_cast<double>(o.intersection) / united;
  if (o.mask_pixels > 0) o.precision = static_cast<double>(o.intersection) / o.mask_pixels;
  if (o.truth_pixels > 0) o.recall = static_cast<double>(o.intersection) / o.truth_pixels;
  return o;
}

}  // namespace reenact::capture
