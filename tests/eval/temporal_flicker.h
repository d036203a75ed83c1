#pragma once
// Flicker (issue 9): at a fixed viewpoint, how much more the reenactment changes from one
// evaluated output frame to the next than the ground truth does.
//
// For two evaluated frames a and b (consecutive in the run, b = a + frame_step) each image is
// its subject on black (colour inside its own mask, mask > 127, and 0 outside). With
// |d(I)| = (1/3) sum_c |I_b - I_a| per pixel (0..255) and U_T the pixels where either true
// silhouette (a or b) is set:
//   reenacted_change = sum over all pixels of |d(R)| / |U_T|
//   truth_change     = sum over all pixels of |d(T)| / |U_T|    (the mean over U_T)
//   flicker          = reenacted_change - truth_change
//   error_change     = sum over all pixels of |d(R - T)| / |U_T|
// Outside all four silhouettes every term is 0, so the sums run over the union of the four.
// Both changes share one normaliser, the true subject's area, which no method changes: a
// method that changes more pixels, or changes them more, scores higher. flicker is the
// issue's signed measure (real motion counts for both and cancels; negative when the
// reenactment changes less than the truth, e.g. smoother texture); error_change is the
// frame-to-frame change of the error image, 0 only when the reenactment changes exactly as
// the truth does (never negative). When U_T is empty the union of all four silhouettes
// normalises instead; when that is empty everything is 0.

#include "common/image/image.h"

namespace reenact::eval {

struct FlickerMeasure {
  double reenacted_change = 0;  // 0..255 per pixel of U_T
  double truth_change = 0;
  double error_change = 0;
  int truth_pixels = 0;  // |U_T|
  double flicker() const { return reenacted_change - truth_change; }
};

// Precondition (CHECK): all eight images share one size; colour images have 3 channels.
FlickerMeasure MeasureFlicker(const ImageRgb8& rendered_a, const ImageGray8& rendered_mask_a,
                              const ImageRgb8& rendered_b, const ImageGray8& rendered_mask_b,
                              const ImageRgb8& truth_a, const ImageGray8& truth_mask_a,
                              const ImageRgb8& truth_b, const ImageGray8& truth_mask_b);

}  // namespace reenact::eval
