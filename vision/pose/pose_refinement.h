#pragma once
// Motion-only refinement of one frame's pose against known map points: Levenberg-Marquardt
// on the whitened reprojection + depth residuals of observation_model.h with Huber's loss,
// in rounds (as ORB-SLAM's pose optimisation): after each round every observation is
// re-classified (inlier when its chi-square is below the 95% quantile) and the next round
// uses the inliers only. Map points stay fixed.
//
// Degenerate input gives a defined result: fewer than 3 usable observations, or a system
// that does not improve, keeps the initial pose and reports num_inliers from it.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "vision/pose/observation_model.h"

namespace reenact::vision {

struct PoseRefinementOptions {
  int rounds = 3;      // outlier re-classification rounds, >= 1
  int iterations = 8;  // LM iterations per round, >= 1

  void Check() const;
};

struct PointObservation {
  Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();
  KeypointObservation observation;
};

struct PoseRefinementResult {
  Eigen::Isometry3d sensor_from_world = Eigen::Isometry3d::Identity();
  std::vector<char> inlier;  // per observation, 1 = inlier at the final pose
  int num_inliers = 0;
  // J^T W J over the final inliers at the final pose (Huber weights W, whitened residuals):
  // the inverse covariance of the pose update delta (observation_model.h). Zero when fewer
  // than 3 inliers.
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
};

// fx, fy: the camera's focal lengths in pixels. Preconditions (CHECK): valid options and
// noise, finite fx, fy > 0.
PoseRefinementResult RefinePose(const Eigen::Isometry3d& initial_sensor_from_world,
                                const std::vector<PointObservation>& observations, double fx,
                                double fy, const ObservationNoise& noise,
                                const PoseRefinementOptions& options = {});

}  // namespace reenact::vision
