#pragma once
// Sub-pixel corner position by the gradient-weighted least squares that cv::cornerSubPix
// iterates (Foerstner): at a corner q every image gradient g_i in the window is orthogonal to
// p_i - q, so q solves
//     (sum_i w_i g_i g_i^T) q = sum_i w_i g_i g_i^T p_i,
// with w_i = exp(-(dx_i / h)^2 - (dy_i / h)^2) for the offset (dx_i, dy_i) of p_i from the
// window's centre and h the half window. The window ((2h+1)^2 samples, pixel centres at
// integers) is re-centred on the new q and the solve repeated until q moves less than
// epsilon_px or after max_iterations. Gradients are central differences of the bilinearly
// interpolated image at the window's sample points (without the 1/2, which cancels).
//
// Unlike cv::cornerSubPix it works on one point without allocating, with the weights made
// once per half window, and it stops (returns nothing) rather than reading a replicated
// border when the window leaves the image.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

namespace reenact::vision {

struct SubpixelCornerOptions {
  int max_iterations = 10;   // [1, 100]
  double epsilon_px = 0.01;  // stop when q moves less than this, > 0

  void Check() const;
};

class SubpixelCornerRefiner {
 public:
  explicit SubpixelCornerRefiner(const SubpixelCornerOptions& options = {});

  // The corner near start (pixel coordinates of gray, CV_8UC1, pixel centres at integers),
  // window half side half_window in [1, 64]. Nothing when the window leaves the image (at
  // start or on the way), when the window is flat or a straight edge (the normal equations
  // are singular), or when q ends more than half_window from start along x or y.
  // Preconditions (CHECK): gray is CV_8UC1, half_window in [1, 64].
  std::optional<Eigen::Vector2f> Refine(const cv::Mat& gray, const Eigen::Vector2f& start,
                                        int half_window) const;

 private:
  const std::vector<float>& Weights(int half_window) const;

  SubpixelCornerOptions options_;
  mutable std::vector<std::vector<float>> weights_;  // per half window, (2h+1)^2, made lazily
  mutable std::vector<float> samples_;               // the interpolated window, (2h+3)^2
};

}  // namespace reenact::vision
