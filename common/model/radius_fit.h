#pragma once
// Radius ratios from the representative frame (thesis Sec. 3.3.3): fit a rectangle to each
// body part's region of the person mask and take its width.
//
// Each subject pixel goes to the part whose projected axis segment is nearest in the image
// (pixels beyond either end of every segment are left out). Along each part's axis, between
// 10% and 90% of its length, the pixels are cut into slices; a slice's rectangle has the
// slice's length along the projected axis and the width that gives it the slice's pixel
// count (area / length: unbiased whatever the axis's direction in the image). The part's
// rectangle width w (pixels) is the median slice width. A cylinder of radius r whose nearest
// surface lies at depth z (the median depth reading of the part's pixels) shows a silhouette
// of width w = 2 r f / (z + r), f the focal length across the projected axis, so
// r = w z / (2 f - w). The rectangle's half width is the radius: radius_ratio = r / ||s_a - s_b||.
// Depth holes (0) inside the mask still count towards the silhouette's area; a part without
// any depth reading keeps its default ratio.

#include <array>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

struct RadiusFitOptions {
  int slices = 8;              // slices along each axis, >= 1
  int min_pixels_per_slice = 3;  // a slice with fewer pixels is ignored, >= 1
  int min_slices = 2;          // a part with fewer valid slices keeps its default ratio, >= 1
  double depth_scale_m = 0.001;  // metres per depth unit, > 0

  void Check() const;
};

struct RadiusFitResult {
  RadiusRatios radius_ratio{};                 // fitted or DefaultRadiusRatios()
  std::array<bool, kBodyPartCount> fitted{};   // false: the default was kept
  std::array<int, kBodyPartCount> pixel_count{};
  int fitted_count() const;
};

// skeleton_in_sensor: the representative frame's skeleton in its sensor frame.
// camera, depth and mask: the same image grid (depth registered to colour), mask 255 = subject.
RadiusFitResult FitRadiusRatios(const Skeleton& skeleton_in_sensor, const PinholeCamera& camera,
                                const ImageDepthMm& depth, const ImageGray8& mask,
                                const RadiusFitOptions& options = {});

}  // namespace reenact
