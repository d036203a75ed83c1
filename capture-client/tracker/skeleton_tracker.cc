#include "capture-client/tracker/skeleton_tracker.h"

#include <algorithm>
#include <cmath>

#include "capture-client/tracker/body_fitter.h"
#include "capture-client/tracker/body_start.h"
#include "capture-client/tracker/correction_step.h"
#include "capture-client/tracker/gap_ratio.h"
#include "capture-client/tracker/head_size.h"
#include "capture-client/tracker/joint_confidence.h"
#include "common/error/check.h"
#include "common/estimate/median.h"

namespace reenact::capture {

std::string_view TrackStateName(TrackState state) {
  switch (state) {
    case TrackState::kWaitingForCalibration:
      return "waiting_for_calibration";
    case TrackState::kTracking:
      return "tracking";
    case TrackState::kLost:
      return "lost";
  }
  return "unknown";
}

SkeletonTracker::SkeletonTracker(const PinholeCamera& depth_camera, double depth_scale_m,
                                 const SkeletonTrackerOptions& options)
    : SkeletonTracker(depth_camera, depth_scale_m, options, DefaultTrackerMethod(options)) {}

SkeletonTracker::SkeletonTracker(const PinholeCamera& depth_camera, double depth_scale_m,
                                 const SkeletonTrackerOptions& options, TrackerMethod method)
    : detector_(depth_camera, depth_scale_m, method.detect),
      camera_(depth_camera),
      options_(options),
      method_(std::move(method)),
      good_{options.good_inlier_share, options.min_coverage},
      measurement_(method_.measurement, method_.calibration),
      static_scene_(depth_camera, method_.static_scene) {
  options.Check();
  method_.Check();
}

void SkeletonTracker::Reset() {
  state_ = TrackState::kWaitingForCalibration;
  calibration_.reset();
  body_.reset();
  last_fit_.reset();
  has_previous_ = false;
  pose_time_s_.reset();
  previous_time_s_.reset();
  gap_ratio_ = 1;
  bad_frames_ = 0;
  uncalibrated_frames_ = 0;
  taller_frames_ = 0;
  waiting_neck_depths_.clear();
  for (const auto& step : method_.steps) step->Reset();
  static_scene_.Clear();
  measurement_.Clear();
  detector_.ResetFloor();
}

Eigen::Vector3d SkeletonTracker::RootStep() const {
  if (!has_previous_) return Eigen::Vector3d::Zero();
  return gap_ratio_ * (pose_.root_translation - previous_pose_.root_translation);
}

void SkeletonTracker::AdoptPose(const ArticulatedPose& pose, std::optional<double> timestamp_s,
                                bool restart) {
  previous_pose_ = restart ? pose : pose_;
  previous_time_s_ = restart ? std::nullopt : pose_time_s_;
  pose_ = pose;
  pose_time_s_ = timestamp_s;
  has_previous_ = !restart;
}

void SkeletonTracker::CheckTallerThanBody(const PersonBlob& blob, const BodyFitResult& fit) {
  if (!calibration_ || calibration_->from_calibration_pose || !blob.floor_in_sensor ||
      blob.floor_source == FloorSource::kAssumedStature)
    return;
  const double above = blob.top_height_m - PosedTopHeight(*body_, fit.posed.skeleton,
                                                          *blob.floor_in_sensor);
  taller_frames_ = above > method_.start.restart_taller_m ? taller_frames_ + 1 : 0;
  if (taller_frames_ < method_.start.restart_taller_frames) return;
  taller_frames_ = 0;
  state_ = TrackState::kWaitingForCalibration;
  uncalibrated_frames_ = std::max(0, options_.start_without_calibration_after - 1);
  measurement_.Clear();
}

void SkeletonTracker::LoseFrame(TrackFrameResult* out) {
  if (state_ == TrackState::kTracking && ++bad_frames_ >= options_.lost_after_frames)
    state_ = TrackState::kLost;
  out->state = state_;
}

std::optional<BodyFitResult> SkeletonTracker::StartTrackOnBlob(const PersonBlob& blob,
                                                               const BodyObservation& obs,
                                                               bool* from_extremities) {
  const BodyFitter fitter(*body_, method_.fitter);
  std::optional<StartedFit> s =
      StartTrack(fitter, good_, blob, obs, method_.calibration, method_.start,
                 has_previous_ ? std::optional(pose_) : std::nullopt, state_ == TrackState::kLost);
  *from_extremities = s && s->from_extremities;
  if (!s) return std::nullopt;
  for (const auto& step : method_.steps) step->OnTrackStart(s->start);
  return std::move(s->fit);
}

TrackFrameResult SkeletonTracker::Track(const ImageDepthMm& depth,
                                        const std::optional<Eigen::Isometry3d>& world_from_sensor,
                                        const std::optional<Eigen::Vector3d>& world_up,
                                        std::optional<double> timestamp_s) {
  TrackFrameResult out;
  last_fit_.reset();
  if (timestamp_s &&
      (!std::isfinite(*timestamp_s) || (pose_time_s_ && *timestamp_s <= *pose_time_s_)))
    timestamp_s.reset();
  gap_ratio_ = GapRatio(timestamp_s, pose_time_s_, previous_time_s_, options_.max_gap_ratio);
  const bool tracking = state_ == TrackState::kTracking;
  const PersonBlob blob =
      detector_.Detect(depth, world_from_sensor, world_up,
                       tracking ? std::optional<Eigen::Vector3d>(centroid_) : std::nullopt);
  out.detect = blob.status;
  if (blob.status != DetectStatus::kOk) {
    LoseFrame(&out);
    return out;
  }
  if (state_ == TrackState::kWaitingForCalibration)
    return WaitForCalibration(blob, timestamp_s, std::move(out));

  BodyObservation obs = MakeObservation(camera_, blob.grid_step_px, blob.mask, blob.depth_m,
                                        blob.points, blob.pixels, options_.subsample);
  if (method_.static_scene.enabled && world_from_sensor)
    static_scene_.DropStatic(*world_from_sensor, blob.floor_in_sensor, &obs);
  out.points = static_cast<int>(obs.points.size());
  if (state_ == TrackState::kLost)
    return Recover(blob, std::move(obs), timestamp_s, std::move(out));
  return TrackFrame(blob, std::move(obs), world_from_sensor, timestamp_s, std::move(out));
}

TrackFrameResult SkeletonTracker::WaitForCalibration(const PersonBlob& blob,
                                                     std::optional<double> timestamp_s,
                                                     TrackFrameResult out) {
  // The frame's observation as CalibrateBody makes it, built only when a fit is taken.
  std::optional<BodyObservation> observation;
  const auto obs = [&]() -> const BodyObservation& {
    if (!observation)
      observation = MakeObservation(camera_, blob.grid_step_px, blob.mask, blob.depth_m,
                                    blob.points, blob.pixels, options_.subsample);
    return *observation;
  };
  BodyCalibration c = CalibrateBody(blob, camera_, options_.subsample, method_.calibration);
  if (c.status == CalibrationStatus::kOk && good_.Good(c.fit)) {
    for (const auto& step : method_.steps) step->OnTrackStart(TrackStart::kCalibrationPose);
  } else {
    std::optional<BodyCalibration> p = StartWithoutCalibrationPose(blob, obs(), &out);
    if (!p) {
      out.state = state_;
      return out;
    }
    c = std::move(*p);
  }
  body_.emplace(c.shape);
  AdoptPose(c.pose, timestamp_s, true);
  centroid_ = c.fit.inlier_centroid;
  state_ = TrackState::kTracking;
  bad_frames_ = 0;
  out.calibrated = out.good_fit = true;
  out.inlier_share = c.fit.inlier_share;
  out.outlier_share = c.fit.outlier_share;
  out.points = c.fit.points;
  const double inlier_m =
      c.from_calibration_pose ? method_.calibration.fit.inlier_m : method_.fitter.fit.inlier_m;
  out.skeleton = WithJointConfidence(*body_, c.fit, obs(), inlier_m, true, method_.confidence);
  MarkJointsOutOfView(camera_, &*out.skeleton);
  calibration_ = std::move(c);
  out.state = state_;
  return out;
}

std::optional<BodyCalibration> SkeletonTracker::StartWithoutCalibrationPose(
    const PersonBlob& blob, const BodyObservation& obs, TrackFrameResult* out) {
  const int after = options_.start_without_calibration_after;
  if (after < 0) return std::nullopt;
  if (const auto head = MeasureHeadSize(blob, camera_.fy, method_.head_size)) {
    constexpr size_t kKept = 64;  // the latest, while a start keeps failing
    if (waiting_neck_depths_.size() == kKept)
      waiting_neck_depths_.erase(waiting_neck_depths_.begin());
    waiting_neck_depths_.push_back(head->neck_below_top_m);
  }
  if (++uncalibrated_frames_ < after) return std::nullopt;
  std::optional<double> neck_depth;
  if (!waiting_neck_depths_.empty()) neck_depth = Median(waiting_neck_depths_);
  BodyCalibration p = ProportionalBody(blob, method_.calibration, neck_depth);
  if (p.status != CalibrationStatus::kOk) return std::nullopt;
  body_.emplace(p.shape);
  has_previous_ = false;
  std::optional<BodyFitResult> r = StartTrackOnBlob(blob, obs, &out->from_extremities);
  if (!r) {
    body_.reset();
    return std::nullopt;
  }
  p.pose = r->pose;
  p.fit = std::move(*r);
  return p;
}

TrackFrameResult SkeletonTracker::Recover(const PersonBlob& blob, BodyObservation obs,
                                          std::optional<double> timestamp_s, TrackFrameResult out) {
  std::optional<BodyFitResult> r = StartTrackOnBlob(blob, obs, &out.from_extremities);
  if (!r) {
    out.state = state_;
    return out;
  }
  state_ = TrackState::kTracking;
  bad_frames_ = 0;
  AdoptPose(r->pose, timestamp_s, true);
  centroid_ = r->inlier_centroid;
  out.recovered = out.good_fit = true;
  out.inlier_share = r->inlier_share;
  out.outlier_share = r->outlier_share;
  out.skeleton =
      WithJointConfidence(*body_, *r, obs, method_.fitter.fit.inlier_m, true, method_.confidence);
  MarkJointsOutOfView(camera_, &*out.skeleton);
  out.state = state_;
  last_fit_ = LastFit{std::move(obs), std::move(*r)};
  return out;
}

TrackFrameResult SkeletonTracker::TrackFrame(
    const PersonBlob& blob, BodyObservation obs,
    const std::optional<Eigen::Isometry3d>& world_from_sensor, std::optional<double> timestamp_s,
    TrackFrameResult out) {
  const Eigen::Vector3d root_step = RootStep();
  ArticulatedPose start = pose_;
  start.root_translation += root_step;
  KeepPointsNearBody(*body_, body_->Pose(start),
                     options_.keep_near_model_m * std::max(1.0, gap_ratio_), &obs);
  out.points = static_cast<int>(obs.points.size());
  const BodyFitter fitter(*body_, method_.fitter);
  const StepFrame frame{fitter, good_, blob, obs, world_from_sensor, start, root_step, {}};
  BodyFitResult fit = FitAsTrack(method_.steps, method_.steps.size(), frame);
  out.inlier_share = fit.inlier_share;
  out.outlier_share = fit.outlier_share;
  out.coverage = fit.coverage;
  out.good_fit = good_.Good(fit);
  centroid_ = fit.inlier_centroid;
  if (!out.good_fit) {
    LoseFrame(&out);
    if (state_ == TrackState::kLost) return out;
  } else {
    bad_frames_ = 0;
  }
  AdoptPose(fit.pose, timestamp_s, false);
  if (out.good_fit) {
    if (method_.static_scene.enabled && world_from_sensor)
      static_scene_.Learn(blob, detector_.rays(), *world_from_sensor, *body_, fit.posed);
    measurement_.Add(fit, obs, blob, camera_, method_.fitter, {*calibration_, body_, pose_});
    CheckTallerThanBody(blob, fit);
  }
  out.skeleton = WithJointConfidence(*body_, fit, obs, method_.fitter.fit.inlier_m, out.good_fit,
                                     method_.confidence);
  MarkJointsOutOfView(camera_, &*out.skeleton);
  out.state = state_;
  last_fit_ = LastFit{std::move(obs), std::move(fit)};
  return out;
}

}  // namespace reenact::capture
