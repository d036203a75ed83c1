#pragma once
// RGB-D SLAM of the capture client: tracks world_from_sensor for every frame of a registered
// colour + depth stream and builds the relocalisable background map stored with a clip.
//
// Per frame (frame-to-map, in the spirit of ORB-SLAM2's RGB-D mode):
//  1. ORB features outside the (grown) person mask, each lifted to 3D where depth is
//     reliable (orb_features.h). The subject never contributes a feature, so never a map
//     point.
//     With options.readout_ratio > 0, keypoints are moved to where a global-shutter camera
//     would have seen them, using the predicted rotation (rolling_shutter.h).
//  2. Prediction by constant velocity; the points of the local map (the keyframes that share
//     points with the last frame, plus the newest ones) are projected and matched within a
//     radius (feature_matching.h), retried with a wider radius when too few match.
//  3. PnP in RANSAC (AP3P minimal solver, common/estimate/ransac.h), then motion-only
//     refinement on reprojection + depth residuals with Huber's loss (pose_refinement.h); a
//     second, tighter projection search at the refined pose and a last refinement.
//  4. Too few inliers: frame-to-frame cv::rgbd::RgbdOdometry against the previous frame
//     (status kOdometryFallback; opencv_odometry.h), else relocalisation against the whole
//     map by descriptors + RANSAC PnP, else kLost. While lost, every frame tries to
//     relocalise (kRelocalised on success).
//  5. Keyframes when tracking weakens (inliers below keyframe_min_tracked_ratio of the last
//     keyframe's points that other keyframes saw too), the sensor moved or turned enough
//     (parallax), after a fallback or relocalisation, or every max_frames_between_keyframes frames.
//     A keyframe adds the nearest unmatched features with depth as new map points, then a local
//     bundle adjustment refines the newest keyframes' poses and their points
//     (local_bundle_adjustment.h), and points that tracking seldom finds are culled.
//
// World frame: the first keyframe's sensor pose is options.initial_world_from_sensor
// (identity by default), metres, OpenCV camera axes for the sensor. Deterministic for equal
// input and options.

#include <Eigen/Geometry>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "capture-client/slam/opencv_odometry.h"
#include "capture-client/slam/slam_map.h"
#include "capture-client/slam/slam_options.h"
#include "capture-client/slam/slam_result.h"
#include "capture-client/slam/vision_names.h"
#include "common/error/expected.h"
#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "proto/clip/map_codec.h"

namespace reenact::capture::slam {

class RgbdSlam {
 public:
  // camera: the colour camera (depth registered to it, same size; distortion allowed).
  // depth_scale_m: metres per depth unit. Preconditions (CHECK): valid camera and options,
  // depth_scale_m > 0 and finite.
  RgbdSlam(const PinholeCamera& camera, double depth_scale_m, SlamOptions options = {});
  ~RgbdSlam();
  RgbdSlam(RgbdSlam&&) noexcept;
  RgbdSlam& operator=(RgbdSlam&&) noexcept;

  // Tracks the next frame. person_mask (255 = subject) may be null or empty. Error
  // "invalid_argument" (the frame is skipped, the state unchanged) when colour is not three
  // channels of the camera's size, depth not one channel of that size, the mask not one
  // channel of that size, or the timestamp not finite.
  Expected<SlamFrameResult> Track(double timestamp_s, const ImageRgb8& color,
                                  const ImageDepthMm& depth,
                                  const ImageGray8* person_mask = nullptr);

  // The next frame's world_from_sensor as step 2 predicts it (the last pose moved on by the
  // last frame-to-frame motion), for a consumer that needs a pose before the frame is tracked
  // (the recorder's skeleton tracker); nullopt before the map is founded and while lost.
  std::optional<Eigen::Isometry3d> PredictedWorldFromSensor() const;

  bool initialised() const;
  bool lost() const;
  int frames_seen() const;
  const SlamMap& map() const;
  const SlamOptions& options() const;
  const PinholeCamera& camera() const;

  // The map to store with a clip: well-observed background points (options.map_export).
  proto::ClipMap ExportClipMap() const;

  struct State;

 private:
  std::unique_ptr<State> state_;
};

}  // namespace reenact::capture::slam
