#include "capture-client/slam/rgbd_slam.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "capture-client/slam/rolling_shutter.h"
#include "capture-client/slam/slam_state.h"
#include "common/error/check.h"

namespace reenact::capture::slam {
namespace {

Status CheckFrame(const PinholeCamera& camera, double timestamp_s, const ImageRgb8& color,
                  const ImageDepthMm& depth, const ImageGray8* mask) {
  const std::string size = std::to_string(camera.width) + "x" + std::to_string(camera.height);
  if (!std::isfinite(timestamp_s))
    return MakeError("invalid_argument", "SLAM frame: the timestamp is not a finite number");
  if (color.width != camera.width || color.height != camera.height || color.channels != 3 ||
      color.data.size() != static_cast<size_t>(color.width) * color.height * 3) {
    return MakeError("invalid_argument", "SLAM frame: colour is " + std::to_string(color.width) +
                                             "x" + std::to_string(color.height) + " with " +
                                             std::to_string(color.channels) +
                                             " channels; the camera needs " + size + " RGB");
  }
  if (depth.width != camera.width || depth.height != camera.height || depth.channels != 1 ||
      depth.data.size() != static_cast<size_t>(depth.width) * depth.height) {
    return MakeError("invalid_argument",
                     "SLAM frame: depth is " + std::to_string(depth.width) + "x" +
                         std::to_string(depth.height) + " with " + std::to_string(depth.channels) +
                         " channels; it must be registered to colour (" + size + ", one channel)");
  }
  if (mask != nullptr && !mask->empty() &&
      (mask->width != camera.width || mask->height != camera.height || mask->channels != 1 ||
       mask->data.size() != static_cast<size_t>(mask->width) * mask->height)) {
    return MakeError("invalid_argument",
                     "SLAM frame: the person mask is " + std::to_string(mask->width) + "x" +
                         std::to_string(mask->height) + "; it must be one channel of " + size);
  }
  return {};
}

// The frame's ORB features, corrected for the rolling shutter once a motion is known.
FrameFeatures FrameOrbFeatures(const RgbdSlam::State& s, const cv::Mat& gray,
                               const ImageDepthMm& depth, const ImageGray8* person_mask) {
  FrameFeatures features =
      ExtractOrbFeatures(gray, depth, s.depth_scale_m, person_mask, s.camera, s.options.features);
  if (s.last_sensor_from_world) {
    CompensateRollingShutter(s.velocity.linear(), s.options.readout_ratio, s.camera.height,
                             features);
  }
  return features;
}

// Before the map exists: a frame with enough features with depth founds it at the initial
// pose (sensor_from_world).
std::optional<Eigen::Isometry3d> Initialise(RgbdSlam::State& s, const FrameFeatures& features,
                                            SlamFrameResult& r) {
  std::optional<Eigen::Isometry3d> pose;
  if (features.CountWithDepth() >= s.options.min_initial_points) {
    pose = s.options.initial_world_from_sensor.inverse();
    r.status = SlamStatus::kInitialised;
    s.initialised = true;
  } else {
    r.status = SlamStatus::kLost;
    r.lost_reason = SlamLostReason::kNotInitialised;
  }
  return pose;
}

// With a map: the frame's pose (sensor_from_world) tracked against the local map from the
// predicted pose, else by odometry from the frame before, else relocalised against the whole
// map; nullopt when lost. r gets the status (and why lost) and the match counts; est the
// estimate whose inliers the frame keeps.
std::optional<Eigen::Isometry3d> LocateFrame(RgbdSlam::State& s, const FrameFeatures& features,
                                             const cv::Mat& gray, const ImageDepthMm& depth,
                                             const ImageGray8* person_mask, SlamFrameResult& r,
                                             PoseEstimate& est) {
  std::optional<Eigen::Isometry3d> pose;
  const int min_inliers = s.options.min_tracking_inliers;
  const bool enough_features = r.features >= min_inliers;
  r.status = SlamStatus::kLost;
  if (!s.lost && s.last_sensor_from_world && enough_features) {
    est = TrackLocalMap(s, features, s.velocity * *s.last_sensor_from_world, min_inliers);
    if (est.ok) {
      pose = est.sensor_from_world;
      r.status = SlamStatus::kTracked;
    }
  }
  if (!pose && s.odometry && s.last_sensor_from_world && !s.previous_gray.empty()) {
    cv::Ptr<cv::rgbd::OdometryFrame> previous = s.odometry->Prepare(
        s.previous_gray, s.previous_depth, s.previous_mask.empty() ? nullptr : &s.previous_mask);
    cv::Ptr<cv::rgbd::OdometryFrame> current = s.odometry->Prepare(gray, depth, person_mask);
    if (const auto motion = s.odometry->Compute(previous, current, s.velocity)) {
      pose = *motion * *s.last_sensor_from_world;
      r.status = SlamStatus::kOdometryFallback;
      est = PoseEstimate{};
    }
  }
  if (!pose && enough_features) {
    est = Relocalise(s, features);
    if (est.ok) {
      pose = est.sensor_from_world;
      r.status = SlamStatus::kRelocalised;
    }
  }
  if (!pose) {
    r.lost_reason = !enough_features ? SlamLostReason::kTooFewFeatures
                    : s.lost         ? SlamLostReason::kNotRelocalised
                                     : SlamLostReason::kTooFewInliers;
  }
  r.matches = est.matches;
  r.inliers = static_cast<int>(est.inliers.size());
  return pose;
}

// A located frame: a keyframe when it needs to be (its pose then refined by the bundle
// adjustment), and the motion model and tracked points moved on to it.
void AcceptPose(RgbdSlam::State& s, const Eigen::Isometry3d& located, const FrameFeatures& features,
                const PoseEstimate& est, double timestamp_s, SlamFrameResult& r) {
  Eigen::Isometry3d pose = located;  // sensor_from_world
  ++s.frames_since_keyframe;
  const bool keyframe = r.status != SlamStatus::kTracked || NeedKeyframe(s, pose, r.inliers);
  if (keyframe) {
    const int max_new = r.status == SlamStatus::kInitialised
                            ? std::numeric_limits<int>::max()
                            : s.options.max_new_points_per_keyframe;
    const int id =
        InsertKeyframe(s, r.frame_index, timestamp_s, features, pose, est.inliers, max_new);
    pose = s.map.keyframes()[id].sensor_from_world;  // after local bundle adjustment
    r.keyframe = true;
  }
  s.velocity = s.last_sensor_from_world && r.status != SlamStatus::kRelocalised
                   ? pose * s.last_sensor_from_world->inverse()
                   : Eigen::Isometry3d::Identity();
  s.last_sensor_from_world = pose;
  s.lost = false;
  s.last_inlier_points.clear();
  for (const FeatureMatch& m : est.inliers) s.last_inlier_points.push_back(m.id);
  r.world_from_sensor = pose.inverse();
}

void LoseTrack(RgbdSlam::State& s) {
  s.lost = s.initialised;
  s.last_sensor_from_world.reset();
  s.velocity = Eigen::Isometry3d::Identity();
  s.last_inlier_points.clear();
}

}  // namespace

RgbdSlam::RgbdSlam(const PinholeCamera& camera, double depth_scale_m, SlamOptions options)
    : state_(std::make_unique<State>()) {
  camera.Check();
  options.Check();
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0, "depth_scale_m must be > 0");
  options.noise.scale_factor = options.features.scale_factor;
  state_->camera = camera;
  state_->depth_scale_m = depth_scale_m;
  state_->options = options;
  if (options.odometry_fallback) {
    state_->odometry = std::make_unique<OpenCvOdometry>(camera, depth_scale_m, options.odometry);
  }
}

RgbdSlam::~RgbdSlam() = default;
RgbdSlam::RgbdSlam(RgbdSlam&&) noexcept = default;
RgbdSlam& RgbdSlam::operator=(RgbdSlam&&) noexcept = default;

std::optional<Eigen::Isometry3d> RgbdSlam::PredictedWorldFromSensor() const {
  const State& s = *state_;
  if (!s.last_sensor_from_world) return std::nullopt;
  return Eigen::Isometry3d((s.velocity * *s.last_sensor_from_world).inverse());
}

bool RgbdSlam::initialised() const { return state_->initialised; }
bool RgbdSlam::lost() const { return state_->lost; }
int RgbdSlam::frames_seen() const { return state_->frames_seen; }
const SlamMap& RgbdSlam::map() const { return state_->map; }
const SlamOptions& RgbdSlam::options() const { return state_->options; }
const PinholeCamera& RgbdSlam::camera() const { return state_->camera; }

proto::ClipMap RgbdSlam::ExportClipMap() const {
  return state_->map.ExportClipMap(state_->options.map_export);
}

Expected<SlamFrameResult> RgbdSlam::Track(double timestamp_s, const ImageRgb8& color,
                                          const ImageDepthMm& depth,
                                          const ImageGray8* person_mask) {
  State& s = *state_;
  if (Status valid = CheckFrame(s.camera, timestamp_s, color, depth, person_mask); !valid.ok())
    return valid.error();
  if (person_mask != nullptr && person_mask->empty()) person_mask = nullptr;
  const auto start = std::chrono::steady_clock::now();

  SlamFrameResult r;
  r.frame_index = s.frames_seen;
  r.timestamp_s = timestamp_s;
  const cv::Mat rgb(color.height, color.width, CV_8UC3, const_cast<uint8_t*>(color.data.data()));
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_RGB2GRAY);
  const FrameFeatures features = FrameOrbFeatures(s, gray, depth, person_mask);
  r.features = static_cast<int>(features.size());

  PoseEstimate est;
  const std::optional<Eigen::Isometry3d> pose =  // sensor_from_world
      s.initialised ? LocateFrame(s, features, gray, depth, person_mask, r, est)
                    : Initialise(s, features, r);
  if (pose)
    AcceptPose(s, *pose, features, est, timestamp_s, r);
  else
    LoseTrack(s);

  if (s.odometry) {
    s.previous_gray = gray;
    s.previous_depth = depth;
    s.previous_mask = person_mask != nullptr ? *person_mask : ImageGray8();
  }
  ++s.frames_seen;
  r.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace reenact::capture::slam
