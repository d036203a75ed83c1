#pragma once
// What the SLAM tracker reports for every frame.

#include <Eigen/Geometry>
#include <optional>
#include <string_view>

namespace reenact::capture::slam {

enum class SlamStatus {
  kInitialised,       // this frame founded the map; its pose is the initial pose
  kTracked,           // pose from features matched against the map (PnP + refinement)
  kOdometryFallback,  // too few feature inliers; pose from cv::rgbd odometry against the
                      // previous frame
  kRelocalised,       // was lost; pose found again against the whole map
  kLost,              // no pose for this frame (see SlamLostReason)
};

enum class SlamLostReason {
  kNone,            // not lost
  kNotInitialised,  // no map yet: too few features with depth to found one
  kTooFewFeatures,  // too few ORB features in the frame to track
  kTooFewInliers,   // features matched too few map points (and no fallback succeeded)
  kNotRelocalised,  // lost before, and relocalisation against the map failed
};

// "initialised", "tracked", "odometry_fallback", "relocalised", "lost".
std::string_view SlamStatusName(SlamStatus status);
// "none", "not_initialised", "too_few_features", "too_few_inliers", "not_relocalised".
std::string_view SlamLostReasonName(SlamLostReason reason);

struct SlamFrameResult {
  int frame_index = 0;  // 0-based position in the input stream
  double timestamp_s = 0;
  SlamStatus status = SlamStatus::kLost;
  SlamLostReason lost_reason = SlamLostReason::kNone;
  // The sensor's pose in the map's world frame; empty exactly when status is kLost.
  std::optional<Eigen::Isometry3d> world_from_sensor;
  int features = 0;       // ORB keypoints detected (outside the person mask)
  int matches = 0;        // keypoint-to-map-point matches before outlier rejection
  int inliers = 0;        // matches consistent with the final pose
  bool keyframe = false;  // the frame was added to the map as a keyframe
  double ms = 0;          // wall time of Track() for this frame, milliseconds

  bool has_pose() const { return world_from_sensor.has_value(); }
};

}  // namespace reenact::capture::slam
