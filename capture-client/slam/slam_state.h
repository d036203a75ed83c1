#pragma once
// Internal to the SLAM tracker (rgbd_slam.h): its state and the steps Track() composes,
// split over slam_tracking.cc (pose against the map, relocalisation) and slam_keyframes.cc
// (keyframe insertion, local bundle adjustment, point culling).

#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "capture-client/slam/opencv_odometry.h"
#include "capture-client/slam/rgbd_slam.h"
#include "capture-client/slam/slam_map.h"
#include "capture-client/slam/slam_options.h"
#include "capture-client/slam/vision_names.h"

namespace reenact::capture::slam {

struct RgbdSlam::State {
  PinholeCamera camera;
  double depth_scale_m = 0.001;
  SlamOptions options;
  SlamMap map;
  std::unique_ptr<OpenCvOdometry> odometry;  // the fallback; null when disabled

  int frames_seen = 0;
  bool initialised = false;
  bool lost = false;
  // Pose of the previous frame (empty when it had none) and the constant-velocity motion
  // sensor_previous_from_sensor_before_that.
  std::optional<Eigen::Isometry3d> last_sensor_from_world;
  Eigen::Isometry3d velocity = Eigen::Isometry3d::Identity();
  int last_keyframe = -1;
  int frames_since_keyframe = 0;
  std::vector<int> last_inlier_points;  // map points matched by the previous frame

  // The previous frame, for the odometry fallback.
  cv::Mat previous_gray;
  ImageDepthMm previous_depth;
  ImageGray8 previous_mask;

  std::vector<int> stamp;  // per map point, for de-duplicating sets of points
  int stamp_value = 0;
};

// A pose from feature matches and the matches that agree with it.
struct PoseEstimate {
  bool ok = false;
  Eigen::Isometry3d sensor_from_world = Eigen::Isometry3d::Identity();
  int matches = 0;
  std::vector<FeatureMatch> inliers;  // id = map point id
};

// Steps 2-3 of rgbd_slam.h from a predicted pose; ok when at least min_inliers agree.
PoseEstimate TrackLocalMap(RgbdSlam::State& s, const FrameFeatures& features,
                           const Eigen::Isometry3d& predicted_sensor_from_world, int min_inliers);
// Descriptor matching against every map point, RANSAC PnP, then TrackLocalMap.
PoseEstimate Relocalise(RgbdSlam::State& s, const FrameFeatures& features);

// Whether a frame tracked against the map should become a keyframe.
bool NeedKeyframe(const RgbdSlam::State& s, const Eigen::Isometry3d& sensor_from_world,
                  int inliers);
// Adds the frame as a keyframe: observations of its inlier matches, new points from the
// nearest unmatched features with depth (at most max_new_points), then local bundle
// adjustment and culling. Returns the keyframe id.
int InsertKeyframe(RgbdSlam::State& s, int frame_index, double timestamp_s,
                   const FrameFeatures& features, const Eigen::Isometry3d& sensor_from_world,
                   const std::vector<FeatureMatch>& inliers, int max_new_points);

}  // namespace reenact::capture::slam
