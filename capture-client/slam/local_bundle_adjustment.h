#pragma once
// Bundle adjustment of a window of keyframe poses and the map points they observe:
// Levenberg-Marquardt on the whitened reprojection + depth residuals of observation_model.h
// with Huber's loss, solved through the Schur complement (points eliminated, one dense
// 6F x 6F system for the F free poses). Poses outside the window that observe the same
// points enter as fixed cameras and anchor the gauge; at least one camera must be fixed.
// Runs in rounds: after each, observations whose chi-square exceeds the 95% quantile are
// flagged outliers and left out of the next round.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "capture-client/slam/vision_names.h"

namespace reenact::capture::slam {

struct BundleProblem {
  std::vector<Eigen::Isometry3d> sensor_from_world;  // per camera
  std::vector<char> camera_fixed;                    // per camera, 1 = held constant
  std::vector<Eigen::Vector3d> points_in_world;
  struct Observation {
    int camera = 0;
    int point = 0;
    KeypointObservation keypoint;
  };
  std::vector<Observation> observations;
};

struct BundleOptions {
  int rounds = 2;      // outlier re-classification rounds, >= 1
  int iterations = 5;  // LM iterations per round, >= 1

  void Check() const;
};

struct BundleResult {
  double initial_cost = 0;   // Huber cost before, over every observation
  double final_cost = 0;     // Huber cost after, over the final inliers
  int iterations = 0;        // accepted LM steps
  std::vector<char> inlier;  // per observation, at the final estimate
};

// Solves in place. Preconditions (CHECK): valid options and noise, fx, fy > 0, indices in
// range, sizes consistent, at least one fixed camera.
BundleResult SolveBundle(BundleProblem& problem, double fx, double fy,
                         const ObservationNoise& noise, const BundleOptions& options = {});

}  // namespace reenact::capture::slam
