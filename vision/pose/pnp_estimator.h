#pragma once
// Perspective-n-point as a RANSAC estimator (common/estimate/ransac.h): a sample pairs a
// map point (world frame, metres) with the undistorted normalised image coordinates of the
// keypoint that sees it; the model is sensor_from_world. The minimal solver is OpenCV's
// AP3P (Ke and Roumeliotis 2017; up to four poses from three pairs); more pairs (local
// optimisation, final refit) go through SQPnP (Terzakis and Lourakis 2020). The residual is
// the reprojection error in pixels, |(fx (X/Z - x_n), fy (Y/Z - y_n))|, infinite for a point
// behind the camera (so never an inlier).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace reenact::vision {

struct PnpEstimator {
  struct Sample {
    Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();
    Eigen::Vector2d normalized = Eigen::Vector2d::Zero();  // undistorted (x_n, y_n)
  };
  using Model = Eigen::Isometry3d;  // sensor_from_world
  static constexpr int kMinSampleSize = 3;

  double fx = 500, fy = 500;  // pixels per normalised unit, for residuals in pixels

  // The poses consistent with the samples (none for a degenerate draw).
  std::vector<Model> Estimate(const std::vector<Sample>& samples) const;
  std::vector<double> Residuals(const Model& sensor_from_world,
                                const std::vector<Sample>& samples) const;
};

}  // namespace reenact::vision
