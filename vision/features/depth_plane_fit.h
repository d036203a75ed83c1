#pragma once
// Depth at a keypoint from a plane fitted to the depth readings around it, instead of the one
// reading under it. A disparity-based sensor's errors (Gaussian noise and the rounding of its
// disparity) are about constant in inverse depth w = 1/z, and a plane in space is a plane in
// (u, v, w), so the fit is linear least squares in inverse depth:
//
//   w(u0 + du, v0 + dv) = a + b du + c dv       over the (2r+1)^2 window around (u0, v0)
//
// with (u0, v0) the keypoint's pixel (rounded). The first plane goes through the readings
// within rel_tolerance of the keypoint's own (in w); readings that disagree with a plane by
// more than rel_tolerance * w(u0, v0) belong to another surface, and the plane is fitted
// again to the others (two rounds). The depth is 1 / w at the keypoint's sub-pixel position. On a
// wall 5 m away a Kinect v1 reading is off by about 5 cm (noise and 7 cm disparity steps);
// 81 readings average that down by some 9 times where the wall is flat over the window.
//
// Returns nullopt where the fit is not trusted, and the caller keeps the single reading: no
// reading under the keypoint, fewer than min_support of the window's pixels agree with the
// plane, the plane is degenerate (readings on a line), or the fitted depth is not positive
// and finite.

#include <optional>

#include "common/image/image.h"

namespace reenact::vision {

struct DepthPlaneFitOptions {
  int radius_px = 4;            // window half side, [1, 16]
  double rel_tolerance = 0.03;  // agreement with the plane, relative to w; (0, 1)
  double min_support = 0.6;     // share of the window's pixels on the plane, (0, 1]

  void Check() const;  // throws CheckError when out of range
};

// depth in millimetres (0 = no reading) times depth_scale_m gives metres; (x, y) the
// keypoint in pixels (centres at integers). Preconditions (CHECK): valid options,
// depth_scale_m > 0 and finite.
std::optional<double> FitDepthPlane(const ImageDepthMm& depth, double depth_scale_m, double x,
                                    double y, const DepthPlaneFitOptions& options = {});

}  // namespace reenact::vision
