#pragma once
// Options of the RGB-D SLAM tracker (rgbd_slam.h). Every field: unit, default, range.

#include <Eigen/Geometry>
#include <cstdint>

#include "capture-client/slam/local_bundle_adjustment.h"
#include "capture-client/slam/opencv_odometry.h"
#include "capture-client/slam/slam_map.h"
#include "capture-client/slam/vision_names.h"

namespace reenact::capture::slam {

struct SlamOptions {
  OrbFeatureOptions features{.subpixel = true};
  ObservationNoise noise;  // its scale_factor is taken from features.scale_factor
  PoseRefinementOptions pose_refinement;
  BundleOptions bundle_adjustment;
  MapExportOptions map_export;
  OpenCvOdometryOptions odometry;  // the fallback (method kRgbd by default)

  // Rolling shutter of the colour camera: readout time / frame interval, [0, 1]; 0 = global
  // shutter (rolling_shutter.h). Default 0.
  double readout_ratio = 0;

  // Start: the first frame with at least min_initial_points features with depth founds the
  // map; its pose is initial_world_from_sensor (identity: the world is the first camera).
  int min_initial_points = 80;                                                  // >= 3
  Eigen::Isometry3d initial_world_from_sensor = Eigen::Isometry3d::Identity();  // rigid

  // Tracking against the map.
  double search_radius_px = 12;       // guided search radius at level 0, pixels, > 0
  double wide_search_radius_px = 40;  // retried when the first search finds too few, > 0
  int max_descriptor_distance = 70;   // Hamming, [0, 256]
  double match_ratio = 0.9;           // best / second best, (0, 1]
  double ransac_max_error_px = 5.0;   // PnP RANSAC inlier threshold, pixels, > 0
  int ransac_max_iterations = 200;    // >= 1
  int min_tracking_inliers = 30;      // fewer: the frame is not tracked by features, >= 3
  int local_keyframes = 8;            // recent keyframes whose points are searched, >= 1

  // Relocalisation when lost: descriptor matching against the whole map.
  int relocalisation_min_inliers = 40;          // >= 3
  int relocalisation_ransac_iterations = 2000;  // >= 1

  // Fallback: frame-to-frame cv::rgbd odometry when feature tracking fails.
  bool odometry_fallback = true;

  // Keyframes: a tracked frame becomes one when any of these holds.
  int max_frames_between_keyframes = 15;    // >= 1
  double keyframe_min_tracked_ratio = 0.7;  // inliers / points of the last keyframe, [0, 1]
  double keyframe_translation_m = 0.08;     // from the last keyframe, > 0
  double keyframe_rotation_deg = 8;         // from the last keyframe, > 0
  int max_new_points_per_keyframe = 500;    // nearest unmatched features with depth, >= 0

  // Local bundle adjustment over the newest keyframes after each keyframe.
  bool local_bundle_adjustment = true;
  int bundle_window_keyframes = 5;  // free poses, >= 1 (older observers are held fixed)

  // Map point culling: a point created `cull_after_keyframes` keyframes ago is dropped when
  // found / visible < cull_min_found_ratio.
  int cull_after_keyframes = 3;        // >= 1
  double cull_min_found_ratio = 0.25;  // [0, 1]

  uint64_t seed = 0;  // RANSAC seed: equal input and seed give equal output

  // Throws CheckError when a field (or a nested options struct) is out of range.
  void Check() const;
};

}  // namespace reenact::capture::slam
