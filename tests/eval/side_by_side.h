#pragma once
// The picture of one compared frame for the docs: ground truth | reenactment | per-pixel
// error, side by side, so a reader can look, not only read the table.
//
// The three panels show exactly what image_metrics.h compares: the comparison box (the union
// of both silhouettes' bounding boxes) grown by margin_px on every side (clamped to the
// image), each image's subject on black (its colour inside its own mask, 0 outside). The
// error panel maps e = mean over R, G, B of |truth - reenactment| (of the on-black images, 0
// to 255) through the inferno colour map on a fixed scale: black at 0, brightest at
// error_full_scale and above, so pictures from different runs compare. Panels are separated
// by gap_px columns of mid grey (128). Both silhouettes empty: the whole image is shown.

#include "common/image/image.h"

namespace reenact::eval {

struct SideBySideOptions {
  int margin_px = 8;              // >= 0
  int gap_px = 4;                 // >= 0
  double error_full_scale = 128;  // (0, 255]
  void Check() const;
};

// Preconditions (CHECK): colour images RGB, masks 1 channel, all four the same size, not
// empty; options pass Check(). Result: height = box height, width = 3 box width + 2 gap.
ImageRgb8 SideBySide(const ImageRgb8& truth, const ImageGray8& truth_mask,
                     const ImageRgb8& rendered, const ImageGray8& rendered_mask,
                     const SideBySideOptions& options = {});

}  // namespace reenact::eval
