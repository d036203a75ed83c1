#pragma once
// Skeleton tracking from depth alone: a skeleton source for sensors without NiTE. A state
// machine over an articulated capsule body (articulated_body.h, body_fit.h), one depth frame
// at a time (docs/tracker.md draws it):
//  - Waiting: find the person (person_detector.h). When the blob shows the calibration pose
//    (arms out sideways, facing the sensor), calibrate the body (body_calibration.h: height,
//    arm span, 16-joint skeleton, radii) and start tracking. A person who has not shown it
//    after start_without_calibration_after frames gets a body of average proportions for its
//    standing height, its head scaled by the neck depth measured while waiting (head_size.h),
//    placed as a recovery from the silhouette places it (body_start.h); its bones are then
//    measured as it moves (body_measurement.h). Such a body goes back to waiting, to start
//    again at once, when the person stands well above it (it started seated:
//    BodyStartOptions::restart_taller_m). Starts from the silhouette face the sensor unless
//    the back fits clearly better (BodyStartOptions::facing_sensor_gain).
//  - Tracking: find the person near its last centroid, keep the points within
//    keep_near_model_m of the predicted body (the last pose moved on by the last root
//    displacement, scaled by the time since the last frame: gap_ratio.h) and, given the
//    sensor's pose, outside the static scene learned beside the person (static_scene_voxels.h),
//    fit the body from the prediction (body_fitter.h: the local fit and the limb search), then
//    run the correction steps (correction_step.h, in tracker_method.h's order). A good frame
//    (fit_acceptance.h) feeds the body's measurement; lost_after_frames frames in a row without
//    a good fit lose the track, the frames before that still giving a skeleton, its
//    confidences halved.
//  - Lost: each frame with a person, start again from the calibration pose or the silhouette
//    (body_start.h), with the limbs also reaching the region's extremities.
// Bone lengths are fixed while tracking and joint limits are enforced on every step, so
// neither can be violated. Per-joint confidence: joint_confidence.h; joints outside the image are
// reported missing (MarkJointsOutOfView). No floor need be in view (person_detector.h gives
// the person a floor of its own). Output skeletons are in
// the sensor frame (OpenCV axes, metres). Not thread-safe: one caller at a time (the turned
// starts run on threads of the tracker's own within Track).

#include <Eigen/Geometry>
#include <optional>
#include <string_view>
#include <vector>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_calibration.h"
#include "capture-client/tracker/body_fit.h"
#include "capture-client/tracker/body_measurement.h"
#include "capture-client/tracker/person_detector.h"
#include "capture-client/tracker/skeleton_tracker_options.h"
#include "capture-client/tracker/static_scene_voxels.h"
#include "capture-client/tracker/tracker_method.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

enum class TrackState { kWaitingForCalibration = 0, kTracking, kLost };
std::string_view TrackStateName(TrackState state);

struct TrackFrameResult {
  TrackState state = TrackState::kWaitingForCalibration;  // after this frame
  DetectStatus detect = DetectStatus::kNoDepth;
  std::optional<Skeleton> skeleton;  // sensor frame; none while waiting or lost
  bool calibrated = false;           // the track started on this frame
  bool recovered = false;            // recovered from a loss on this frame
  // The recovery's (or the start's) pose came from the extremity starts.
  bool from_extremities = false;
  bool good_fit = false;
  double inlier_share = 0, outlier_share = 0;
  double coverage = 0;  // BodyFitResult::coverage
  int points = 0;       // data points fitted
};

class SkeletonTracker {
 public:
  // Preconditions (CHECK): a valid camera, depth_scale_m > 0, valid options and method.
  SkeletonTracker(const PinholeCamera& depth_camera, double depth_scale_m,
                  const SkeletonTrackerOptions& options = {});
  // With a method of the caller's (an experiment's; DefaultTrackerMethod(options) otherwise).
  SkeletonTracker(const PinholeCamera& depth_camera, double depth_scale_m,
                  const SkeletonTrackerOptions& options, TrackerMethod method);

  // One depth frame (the camera's size: CHECK). world_from_sensor and world_up: when known
  // (they give the floor's up direction for a tilted or moving sensor). timestamp_s: the
  // frame's time in seconds, when known (max_gap_ratio); a time that does not increase counts
  // as unknown.
  TrackFrameResult Track(const ImageDepthMm& depth,
                         const std::optional<Eigen::Isometry3d>& world_from_sensor = std::nullopt,
                         const std::optional<Eigen::Vector3d>& world_up = std::nullopt,
                         std::optional<double> timestamp_s = std::nullopt);

  TrackState state() const { return state_; }
  // The calibration, once calibrated.
  const std::optional<BodyCalibration>& calibration() const { return calibration_; }
  // The body as it is now, once calibrated.
  const std::optional<ArticulatedBody>& body() const { return body_; }
  const TrackerMethod& method() const { return method_; }
  // The last frame's observation and the fit kept on it, when that frame was tracked or
  // recovered (nullopt after a calibration frame, a frame without a person, or none yet).
  struct LastFit {
    BodyObservation observation;
    BodyFitResult fit;
  };
  const std::optional<LastFit>& last_fit() const { return last_fit_; }
  // Forgets everything (a new subject).
  void Reset();

 private:
  TrackFrameResult WaitForCalibration(const PersonBlob& blob, std::optional<double> timestamp_s,
                                      TrackFrameResult out);
  // The average-proportions start after start_without_calibration_after frames (above).
  std::optional<BodyCalibration> StartWithoutCalibrationPose(const PersonBlob& blob,
                                                             const BodyObservation& obs,
                                                             TrackFrameResult* out);
  TrackFrameResult Recover(const PersonBlob& blob, BodyObservation obs,
                           std::optional<double> timestamp_s, TrackFrameResult out);
  TrackFrameResult TrackFrame(const PersonBlob& blob, BodyObservation obs,
                              const std::optional<Eigen::Isometry3d>& world_from_sensor,
                              std::optional<double> timestamp_s, TrackFrameResult out);
  // A good fit that starts a track on the current body (body_start.h), the steps told.
  std::optional<BodyFitResult> StartTrackOnBlob(const PersonBlob& blob, const BodyObservation& obs,
                                                bool* from_extremities);
  // Counts the frame towards BodyStartOptions::restart_taller_frames and, once they are reached,
  // sends the tracker back to waiting, to start again at once with the person's new height.
  void CheckTallerThanBody(const PersonBlob& blob, const BodyFitResult& fit);
  // A frame without a good fit (or a person) while tracking.
  void LoseFrame(TrackFrameResult* out);
  // The track's last root displacement times this frame's gap ratio (zero after a start).
  Eigen::Vector3d RootStep() const;
  // A new pose of the track at timestamp_s; a start or a recovery (restart) has no previous.
  void AdoptPose(const ArticulatedPose& pose, std::optional<double> timestamp_s, bool restart);

  PersonDetector detector_;
  PinholeCamera camera_;
  SkeletonTrackerOptions options_;
  TrackerMethod method_;
  GoodFitCriteria good_;
  TrackState state_ = TrackState::kWaitingForCalibration;
  std::optional<BodyCalibration> calibration_;
  std::optional<ArticulatedBody> body_;
  std::optional<LastFit> last_fit_;
  ArticulatedPose pose_, previous_pose_;
  bool has_previous_ = false;
  // The times of pose_ and previous_pose_, when known; this frame's gap ratio.
  std::optional<double> pose_time_s_, previous_time_s_;
  double gap_ratio_ = 1;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
  int bad_frames_ = 0;
  int uncalibrated_frames_ = 0;
  int taller_frames_ = 0;  // good frames in a row with the person above the body (body_start.h)
  std::vector<double> waiting_neck_depths_;  // head_size.h's, on the frames waited
  BodyMeasurement measurement_;
  StaticSceneVoxels static_scene_;
};

}  // namespace reenact::capture
