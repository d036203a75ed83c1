#pragma once
// Image-quality measures of a reenacted subject against ground truth, both given as colour +
// silhouette mask of the same size (RGB, mask 255 = subject).
//
// The subject is compared on a black background: each image keeps its colour inside its own
// mask and is 0 outside, over the bounding box of the union of the two silhouettes, so a
// missing or extra limb counts as error and the empty background does not inflate the score.
//   PSNR = 10 log10(255^2 / MSE)  (MSE over the box's pixels and 3 channels; +inf if MSE = 0)
//   SSIM: Wang et al. 2004 on luma, 11x11 Gaussian window (sigma 1.5), K1 0.01, K2 0.03,
//         averaged over the box.
//   IoU = |A and B| / |A or B| of the silhouettes (1 when both are empty).
//   colour_mae: mean absolute difference (0..255) over channels where both masks are set.

#include "common/image/image.h"

namespace reenact::eval {

// The comparison box: the bounding box of the union of two silhouettes (mask > 127), pixels
// [x, x + width) x [y, y + height); width = height = 0 when both are empty. Precondition
// (CHECK): the masks share one size.
struct PixelBox {
  int x = 0, y = 0, width = 0, height = 0;
  bool empty() const { return width == 0 || height == 0; }
};
PixelBox UnionBox(const ImageGray8& mask_a, const ImageGray8& mask_b);

struct SubjectComparison {
  double psnr_db = 0;
  double ssim = 0;
  double iou = 0;
  double colour_mae = 0;  // NaN-free: 0 when the silhouettes do not overlap
  int union_pixels = 0;
};

SubjectComparison CompareSubject(const ImageRgb8& rendered, const ImageGray8& rendered_mask,
                                 const ImageRgb8& truth, const ImageGray8& truth_mask);

}  // namespace reenact::eval
