#include "capture-client/tracker/skeleton_tracker.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <numbers>

#include "common/error/check.h"
#include "common/estimate/median.h"

namespace reenact::capture {
namespace {

using S = BodySegment;

// The segments adjacent to each joint (Index(Joint) order), for its confidence.
const std::array<std::array<S, 2>, kJointCount> kJointSegments = {{
    {S::kHead, S::kHead},
    {S::kHead, S::kChest},
    {S::kChest, S::kLowerSpine},
    {S::kPelvis, S::kLowerSpine},
    {S::kChest, S::kLeftUpperArm},
    {S::kLeftUpperArm, S::kLeftForearm},
    {S::kLeftForearm, S::kLeftForearm},
    {S::kChest, S::kRightUpperArm},
    {S::kRightUpperArm, S::kRightForearm},
    {S::kRightForearm, S::kRightForearm},
    {S::kPelvis, S::kLeftThigh},
    {S::kLeftThigh, S::kLeftShin},
    {S::kLeftShin, S::kLeftShin},
    {S::kPelvis, S::kRightThigh},
    {S::kRightThigh, S::kRightShin},
    {S::kRightShin, S::kRightShin},
}};

}  // namespace

void SkeletonTrackerOptions::Check() const {
  detect.Check();
  fit.Check();
  calibration.Check();
  REENACT_CHECK(subsample >= 1, "subsample must be >= 1");
  REENACT_CHECK(keep_near_model_m > 0, "keep_near_model_m must be > 0");
  REENACT_CHECK(max_gap_ratio >= 1 && std::isfinite(max_gap_ratio), "max_gap_ratio must be >= 1");
  static_scene.Check();
  REENACT_CHECK(limb_search_trigger >= 0 && limb_search_trigger <= 1,
                "limb_search_trigger in [0, 1]");
  limb_search.Check();
  turn_start_jump.Check();
  hanging_arm.Check();
  REENACT_CHECK(uncross_gain >= 0 && uncross_gain < 1, "uncross_gain in [0, 1)");
  REENACT_CHECK(limb_search_gain >= 0 && limb_search_gain < 1, "limb_search_gain in [0, 1)");
  REENACT_CHECK(limb_recheck_hypotheses >= 0 && limb_recheck_gain >= 0 && limb_recheck_gain < 1,
                "limb_recheck_hypotheses must be >= 0 and limb_recheck_gain in [0, 1)");
  REENACT_CHECK(limb_recheck_max_other_move_m > 0 && limb_recheck_iterations >= 1,
                "limb_recheck_max_other_move_m must be > 0 and limb_recheck_iterations >= 1");
  REENACT_CHECK(good_inlier_share > 0 && good_inlier_share <= 1, "good_inlier_share in (0, 1]");
  REENACT_CHECK(min_coverage > 0 && min_coverage <= 1, "min_coverage in (0, 1]");
  REENACT_CHECK(lost_after_frames >= 1 && recovery_iterations >= 1,
                "lost_after_frames and recovery_iterations must be >= 1");
  REENACT_CHECK(start_without_calibration_after >= -1,
                "start_without_calibration_after must be >= -1");
  REENACT_CHECK(heading_candidates >= 1, "heading_candidates must be >= 1");
  extremities.Check();
  head_size.Check();
  REENACT_CHECK(extremity_min_offset_m >= 0, "extremity_min_offset_m must be >= 0");
  travel.Check();
  REENACT_CHECK(travel_flip_cos >= -1 && travel_flip_cos <= 1, "travel_flip_cos in [-1, 1]");
  REENACT_CHECK(flip_cost_tolerance >= 1, "flip_cost_tolerance must be >= 1");
  REENACT_CHECK(turn_start_deg >= 0 && turn_start_deg < 90, "turn_start_deg must be in [0, 90)");
  REENACT_CHECK(heading_check_cooldown_frames >= 0, "heading_check_cooldown_frames must be >= 0");
  REENACT_CHECK(front_check_frames >= 0 && front_check_every >= 1 && front_check_gain >= 0 &&
                    front_check_gain < 1 && front_check_confirm_frames >= 0,
                "front_check_frames must be >= 0, front_check_every >= 1, front_check_gain in "
                "[0, 1), front_check_confirm_frames >= 0");
  REENACT_CHECK(
      motion_calibration_frames >= 0 && motion_frame_spacing >= 1 && motion_min_leg_spread_rad >= 0,
      "motion_calibration_frames >= 0, motion_frame_spacing >= 1, "
      "motion_min_leg_spread_rad >= 0");
  crotch.Check();
  REENACT_CHECK(min_crotch_frames >= 1 && average_crotch_ratio > 0 && leg_scale_noise >= 0 &&
                    min_leg_scale > 0 && min_leg_scale <= 1 && max_leg_scale >= 1,
                "need min_crotch_frames >= 1, average_crotch_ratio > 0, leg_scale_noise >= 0 "
                "and 0 < min_leg_scale <= 1 <= max_leg_scale");
  torso_depth.Check();
  REENACT_CHECK(full_support_ratio > 0 && full_support_ratio <= 1, "full_support_ratio in (0, 1]");
  REENACT_CHECK(min_confidence > 0 && min_confidence <= 1, "min_confidence in (0, 1]");
}

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
    : detector_(depth_camera, depth_scale_m, options.detect),
      camera_(depth_camera),
      options_(options),
      travel_(options.travel),
      torso_depth_(options.torso_depth),
      static_scene_(depth_camera, options.static_scene) {
  options.Check();
}

void SkeletonTracker::Reset() {
  state_ = TrackState::kWaitingForCalibration;
  calibration_.reset();
  body_.reset();
  last_observation_.reset();
  has_previous_ = false;
  pose_time_s_.reset();
  previous_time_s_.reset();
  gap_ratio_ = 1;
  bad_frames_ = 0;
  uncalibrated_frames_ = 0;
  waiting_neck_depths_.clear();
  travel_.Clear();
  heading_cooldown_ = 0;
  frames_since_silhouette_start_ = -1;
  front_rival_.reset();
  recheck_limb_ = 0;
  static_scene_.Clear();
  motion_obs_.clear();
  motion_poses_.clear();
  since_motion_frame_ = 0;
  crotch_heights_.clear();
  torso_depth_.Clear();
  detector_.ResetFloor();
}

bool SkeletonTracker::Good(const BodyFitResult& fit) const {
  return fit.points > 0 && fit.inlier_share >= options_.good_inlier_share &&
         fit.coverage >= options_.min_coverage;
}

Skeleton SkeletonTracker::WithConfidence(const BodyFitResult& fit, const BodyObservation& obs,
                                         double inlier_m, bool good) const {
  Skeleton s = fit.posed.skeleton;
  const SegmentSupport support = SupportAt(*body_, fit.posed, obs, inlier_m);
  std::array<double, kBodySegmentCount> seg{};
  for (int k = 0; k < kBodySegmentCount; ++k)
    seg[k] = fit.expected_support[k] > 0
                 ? support.exclusive[k] / (fit.expected_support[k] * options_.full_support_ratio)
                 : 0.0;
  for (int j = 0; j < kJointCount; ++j) {
    const double c = std::max(seg[static_cast<int>(kJointSegments[j][0])],
                              seg[static_cast<int>(kJointSegments[j][1])]);
    double conf = std::clamp(c, options_.min_confidence, 1.0);
    if (!good) conf = std::max(options_.min_confidence, 0.5 * conf);
    s.confidence[j] = conf;
  }
  return s;
}

BodyFitResult SkeletonTracker::Refine(BodyFitResult fit, const BodyObservation& obs) const {
  if (fit.outlier_share <= options_.limb_search_trigger) return fit;
  ArticulatedPose pose = fit.pose;
  if (SearchLimbs(*body_, obs, options_.fit, options_.limits, options_.limb_search, &pose) == 0)
    return fit;
  BodyFitResult again = FitBody(*body_, pose, obs, options_.fit, options_.limits);
  if (CostWithLostPoints(again, options_.fit) <=
      (1 - options_.limb_search_gain) * CostWithLostPoints(fit, options_.fit))
    return again;
  return CheaperOf(std::move(fit), std::move(again));
}

BodyFitResult SkeletonTracker::Uncross(BodyFitResult fit, const BodyObservation& obs,
                                       const ArticulatedPose& predicted) const {
  for (const LimbPair pair : {kArms, kLegs}) {
    if (!LimbsCrossed(*body_, fit.posed, pair)) continue;
    std::vector<ArticulatedPose> starts = {SwappedLimbs(*body_, fit.pose, pair, options_.limits)};
    if (options_.uncross_returns_limb && pair.left == kArms.left &&
        !LimbsCrossed(*body_, body_->Pose(predicted), pair))
      for (const Limb taker : {pair.left, pair.right})
        starts.push_back(ReturnedLimb(*body_, fit.pose, predicted, pair, taker, options_.limits));
    std::optional<BodyFitResult> best;
    for (const ArticulatedPose& start : starts) {
      BodyFitResult r = Refine(FitBody(*body_, start, obs, options_.fit, options_.limits), obs);
      if (!best || r.cost < best->cost) best = std::move(r);
    }
    if (best->cost < (1 - options_.uncross_gain) * fit.cost) fit = std::move(*best);
  }
  return fit;
}

BodyFitResult SkeletonTracker::FitTurned(const ArticulatedPose& start, const Eigen::Vector3d& up,
                                         double angle_rad, const BodyObservation& obs) const {
  return Refine(FitBody(*body_, TurnedBy(start, up, angle_rad), obs, options_.fit, options_.limits),
                obs);
}

BodyFitResult SkeletonTracker::CheaperOf(BodyFitResult fit, BodyFitResult other) const {
  if (other.cost < fit.cost &&
      CostWithLostPoints(other, options_.fit) < CostWithLostPoints(fit, options_.fit))
    return other;
  return fit;
}

BodyFitResult SkeletonTracker::RecheckLimb(BodyFitResult fit, const BodyObservation& obs,
                                           Limb limb) const {
  const std::vector<ArticulatedPose> starts =
      RankLimbHypotheses(*body_, obs, options_.fit, options_.limits, options_.limb_search, fit.pose,
                         limb, options_.limb_recheck_hypotheses);
  const double bound = (1 - options_.limb_recheck_gain) * fit.cost;
  const double depth_bound =
      std::max(options_.limb_recheck_trunk_depth_m, ArmTrunkDepth(*body_, fit.posed, limb));
  std::optional<BodyFitResult> best;
  BodyFitOptions fo = options_.fit;
  fo.iterations = options_.limb_recheck_iterations;
  for (const ArticulatedPose& start : starts) {
    BodyFitResult r = FitBody(*body_, start, obs, fo, options_.limits);
    if (r.cost > bound || (best && r.cost >= best->cost)) continue;
    if (ArmTrunkDepth(*body_, r.posed, limb) <= depth_bound &&
        !LimbEndsMoved(r.posed, fit.posed, limb, options_.limb_recheck_max_other_move_m))
      best = std::move(r);
  }
  return best ? std::move(*best) : fit;
}

std::optional<BodyFitResult> SkeletonTracker::Recover(const PersonBlob& blob,
                                                      const BodyObservation& obs,
                                                      bool* from_extremities) {
  if (from_extremities) *from_extremities = false;
  front_rival_.reset();
  // From the calibration pose, when shown.
  const CalibrationPoseTest test = TestCalibrationPose(blob, options_.calibration);
  BodyFitOptions fit = options_.fit;
  fit.iterations = options_.recovery_iterations;
  if (auto start = CalibrationStartPose(*body_, blob, test)) {
    BodyFitResult r = FitBody(*body_, *start, obs, fit, options_.limits);
    if (Good(r)) {
      frames_since_silhouette_start_ = -1;
      return r;
    }
  }
  if (!options_.recover_from_silhouette || !blob.floor_in_sensor) return std::nullopt;
  // From the silhouette: upright hypotheses at the blob.
  std::vector<Eigen::Vector3d> headings =
      CandidateHeadings(blob.floor_in_sensor->normal, -blob.centroid, options_.heading_candidates);
  if (headings.empty()) return std::nullopt;
  if (has_previous_)
    if (auto f = HorizontalForward(pose_, blob.floor_in_sensor->normal)) headings.push_back(*f);
  std::optional<GeodesicExtremities> extremities;
  if (options_.recover_from_extremities && state_ == TrackState::kLost)
    extremities = FindGeodesicExtremities(blob.points, blob.floor_in_sensor, options_.extremities);
  std::optional<BodyFitResult> best =
      BestHeading(blob, obs, headings, extremities ? &*extremities : nullptr, from_extremities);
  if (best && Good(*best)) {
    frames_since_silhouette_start_ = 0;
    return best;
  }
  if (from_extremities) *from_extremities = false;
  return std::nullopt;
}

std::optional<BodyFitResult> SkeletonTracker::BestHeading(
    const PersonBlob& blob, const BodyObservation& obs,
    const std::vector<Eigen::Vector3d>& headings, const GeodesicExtremities* extremities,
    bool* from_extremities) const {
  if (from_extremities) *from_extremities = false;
  if (!blob.floor_in_sensor) return std::nullopt;
  const Eigen::Vector3d up = blob.floor_in_sensor->normal;
  const Eigen::Vector3d ground =
      blob.centroid - blob.floor_in_sensor->SignedDistance(blob.centroid) * up;
  BodyFitOptions fit = options_.fit;
  fit.iterations = options_.recovery_iterations;
  std::optional<BodyFitResult> best;
  for (const Eigen::Vector3d& forward : headings) {
    const ArticulatedPose start = UprightPose(*body_, ground, up, forward);
    BodyFitResult r = Refine(FitBody(*body_, start, obs, fit, options_.limits), obs);
    if (!best || r.cost < best->cost) {
      best = std::move(r);
      if (from_extremities) *from_extremities = false;
    }
    if (!extremities) continue;
    int placed = 0;
    const ArticulatedPose reach = PoseFromExtremities(*body_, start, *extremities, options_.limits,
                                                      &placed, options_.extremity_min_offset_m);
    if (placed == 0) continue;
    BodyFitResult e = Refine(FitBody(*body_, reach, obs, fit, options_.limits), obs);
    if (e.cost < best->cost) {
      best = std::move(e);
      if (from_extremities) *from_extremities = true;
    }
  }
  return best;
}

ArticulatedPose SkeletonTracker::Predicted(ArticulatedPose pose) const {
  if (has_previous_)
    pose.root_translation +=
        gap_ratio_ * (pose_.root_translation - previous_pose_.root_translation);
  return pose;
}

void SkeletonTracker::AdoptPose(const ArticulatedPose& pose, std::optional<double> timestamp_s,
                                bool restart) {
  previous_pose_ = restart ? pose : pose_;
  previous_time_s_ = restart ? std::nullopt : pose_time_s_;
  pose_ = pose;
  pose_time_s_ = timestamp_s;
  has_previous_ = !restart;
}

BodyFitResult SkeletonTracker::FitFromPrediction(const ArticulatedPose& start,
                                                 const PersonBlob& blob,
                                                 const BodyObservation& obs) const {
  // The turned starts, each on a thread of its own while this one fits the prediction.
  std::vector<std::future<BodyFitResult>> turned;
  if (options_.turn_start_deg > 0 && blob.floor_in_sensor) {
    const Eigen::Vector3d up = blob.floor_in_sensor->normal;
    const double angle = options_.turn_start_deg * std::numbers::pi / 180;
    for (const double a : {-angle, angle})
      turned.push_back(std::async(std::launch::async, [this, &start, &obs, up, a] {
        return FitTurned(start, up, a, obs);
      }));
  }
  BodyFitResult fit = Refine(FitBody(*body_, start, obs, options_.fit, options_.limits), obs);
  const std::optional<BodyFitResult> own =
      options_.turn_start_jump_check && !turned.empty() ? std::optional(fit) : std::nullopt;
  for (std::future<BodyFitResult>& t : turned) {
    BodyFitResult r = t.get();
    if (own && LimbJumpedFromItsData(*body_, *own, r, options_.turn_start_jump)) continue;
    fit = CheaperOf(std::move(fit), std::move(r));
  }
  if (options_.uncross_limbs) fit = Uncross(std::move(fit), obs, start);
  if (options_.limb_recheck_hypotheses > 0)
    fit = RecheckLimb(std::move(fit), obs, static_cast<Limb>(recheck_limb_));
  return HangUnsupportedArms(*body_, std::move(fit), obs, options_.fit, options_.limits,
                             options_.hanging_arm);
}

BodyFitResult SkeletonTracker::CheckFront(BodyFitResult fit, const PersonBlob& blob,
                                          const BodyObservation& obs) {
  if (frames_since_silhouette_start_ < 0) return fit;
  const int k = ++frames_since_silhouette_start_;
  if (front_rival_) return FollowFrontRival(std::move(fit), blob, obs);
  if (k > options_.front_check_frames) {
    frames_since_silhouette_start_ = -1;
    return fit;
  }
  if (k % options_.front_check_every != 0 || !blob.floor_in_sensor || !Good(fit)) return fit;
  const ArticulatedPose start =
      TurnedAround(*body_, fit.pose, blob.floor_in_sensor->normal, options_.limits);
  BodyFitResult around = Refine(FitBody(*body_, start, obs, options_.fit, options_.limits), obs);
  if (!Good(around) || around.cost > (1 - options_.front_check_gain) * fit.cost) return fit;
  if (options_.front_check_confirm_frames == 0) return around;
  front_rival_ = FrontRival{around.pose};
  return fit;
}

BodyFitResult SkeletonTracker::FollowFrontRival(BodyFitResult fit, const PersonBlob& blob,
                                                const BodyObservation& obs) {
  FrontRival& rival = *front_rival_;
  BodyFitResult r = FitFromPrediction(Predicted(rival.pose), blob, obs);
  if (!Good(r)) {
    front_rival_.reset();
    return fit;
  }
  rival.pose = r.pose;
  rival.rival_cost += r.cost;
  rival.track_cost += fit.cost;
  const double keep = 1 - options_.front_check_gain;
  const bool confirmed = rival.rival_cost <= keep * rival.track_cost;
  const bool vetoed = rival.track_cost <= keep * rival.rival_cost;
  if (!confirmed && !vetoed && ++rival.frames < options_.front_check_confirm_frames) return fit;
  front_rival_.reset();
  return vetoed ? fit : r;
}

BodyFitResult SkeletonTracker::CheckTravelHeading(
    BodyFitResult fit, const PersonBlob& blob, const BodyObservation& obs,
    const std::optional<Eigen::Isometry3d>& world_from_sensor) {
  if (!blob.floor_in_sensor) return fit;
  const Eigen::Vector3d up = blob.floor_in_sensor->normal;
  Eigen::Matrix3d world_from_sensor_r = Eigen::Matrix3d::Identity();
  if (world_from_sensor) world_from_sensor_r = world_from_sensor->linear();
  travel_.Add(world_from_sensor ? Eigen::Vector3d(*world_from_sensor * fit.pose.root_translation)
                                : fit.pose.root_translation);
  if (heading_cooldown_ > 0) {
    --heading_cooldown_;
    return fit;
  }
  const auto travel_world = travel_.Direction(world_from_sensor_r * up);
  if (!travel_world) return fit;
  const Eigen::Vector3d travel = world_from_sensor_r.transpose() * *travel_world;
  const auto forward = HorizontalForward(fit.pose, up);
  if (!forward || forward->dot(travel) >= options_.travel_flip_cos) return fit;
  heading_cooldown_ = options_.heading_check_cooldown_frames;
  BodyFitOptions fo = options_.fit;
  fo.iterations = options_.recovery_iterations;
  std::optional<BodyFitResult> best = BestHeading(blob, obs, {travel});
  BodyFitResult turned =
      Refine(FitBody(*body_, TurnedTo(fit.pose, up, travel), obs, fo, options_.limits), obs);
  if (!best || turned.cost < best->cost) best = std::move(turned);
  if (Good(*best) && best->cost <= options_.flip_cost_tolerance * fit.cost) return *best;
  return fit;
}

bool SkeletonTracker::OnTheFlyCalibrationPending() const {
  return calibration_ && !calibration_->from_calibration_pose && calibration_->motion_frames == 0 &&
         options_.motion_calibration_frames > 0;
}

void SkeletonTracker::CollectMotionFrame(const BodyFitResult& fit, const BodyObservation& obs) {
  if (!OnTheFlyCalibrationPending()) return;
  ++since_motion_frame_;
  if (!motion_obs_.empty() && since_motion_frame_ < options_.motion_frame_spacing) return;
  const auto& seg = fit.posed.sensor_from_segment;
  const Eigen::Vector3d l = seg[static_cast<int>(S::kLeftThigh)].linear().col(2);
  const Eigen::Vector3d r = seg[static_cast<int>(S::kRightThigh)].linear().col(2);
  if (std::acos(std::clamp(l.dot(r), -1.0, 1.0)) < options_.motion_min_leg_spread_rad) return;
  motion_obs_.push_back(obs);
  motion_poses_.push_back(fit.pose);
  since_motion_frame_ = 0;
  if (static_cast<int>(motion_obs_.size()) < options_.motion_calibration_frames) return;
  std::vector<const BodyObservation*> observations;
  for (const BodyObservation& o : motion_obs_) observations.push_back(&o);
  if (static_cast<int>(crotch_heights_.size()) >= options_.min_crotch_frames) {
    std::vector<double> h = crotch_heights_;
    const size_t k = std::min(h.size() - 1, static_cast<size_t>(0.9 * h.size()));
    std::nth_element(h.begin(), h.begin() + k, h.end());
    const BodyShape& shape = body_->shape();
    const double m = 1 + (h[k] - options_.average_crotch_ratio * calibration_->height_m) /
                             (shape.thigh + shape.shin);
    if (m > 0)
      body_.emplace(
          WithLegsScaled(shape, ScaleBeyondNoise(m, options_.leg_scale_noise,
                                                 options_.min_leg_scale, options_.max_leg_scale)));
  }
  const MultiFrameShapeFit sf =
      FitBodyShapeFrames(body_->shape(), motion_poses_, observations, calibration_->height_m,
                         options_.fit, options_.calibration.shape, options_.limits);
  AdoptShape(sf.shape);
  calibration_->motion_frames = static_cast<int>(motion_obs_.size());
  pose_ = sf.poses.back();
  motion_obs_.clear();
  motion_poses_.clear();
  crotch_heights_.clear();
}

void SkeletonTracker::AdoptShape(const BodyShape& shape) {
  body_.emplace(shape);
  calibration_->shape = shape;
  const auto lengths = shape.PartLengths();
  const auto radii = shape.PartRadii();
  for (int i = 0; i < kBodyPartCount; ++i) calibration_->radius_ratio[i] = radii[i] / lengths[i];
}

void SkeletonTracker::CollectTorsoWidths(const BodyFitResult& fit, const PersonBlob& blob) {
  if (!options_.measure_torso_depth || torso_depth_.done() ||
      !(calibration_->from_calibration_pose || options_.measure_torso_depth_uncalibrated))
    return;
  const std::optional<double> half_depth =
      torso_depth_.Add(MeasureTrunkWidths(*body_, fit.posed, blob, camera_, options_.torso_depth));
  if (half_depth)
    AdoptShape(WithTorsoDepth(body_->shape(), *half_depth, options_.torso_depth.min_depth_ratio));
}

void SkeletonTracker::CollectCrotchHeight(const BodyFitResult& fit, const PersonBlob& blob) {
  if (!OnTheFlyCalibrationPending()) return;
  const auto& joints = fit.posed.skeleton.position;
  const auto c = MeasureCrotchHeight(blob, camera_, joints[static_cast<int>(Joint::kLeftFoot)],
                                     joints[static_cast<int>(Joint::kRightFoot)], options_.crotch);
  if (c) crotch_heights_.push_back(*c);
}

TrackFrameResult SkeletonTracker::Track(const ImageDepthMm& depth,
                                        const std::optional<Eigen::Isometry3d>& world_from_sensor,
                                        const std::optional<Eigen::Vector3d>& world_up,
                                        std::optional<double> timestamp_s) {
  TrackFrameResult out;
  last_observation_.reset();
  if (timestamp_s &&
      (!std::isfinite(*timestamp_s) || (pose_time_s_ && *timestamp_s <= *pose_time_s_)))
    timestamp_s.reset();
  gap_ratio_ = GapRatio(timestamp_s, pose_time_s_, previous_time_s_, options_.max_gap_ratio);
  const bool tracking = state_ == TrackState::kTracking;
  const PersonBlob blob =
      detector_.Detect(depth, world_from_sensor, world_up,
                       tracking ? std::optional<Eigen::Vector3d>(centroid_) : std::nullopt);
  out.detect = blob.status;
  const auto lose_frame = [&] {
    if (state_ == TrackState::kTracking && ++bad_frames_ >= options_.lost_after_frames)
      state_ = TrackState::kLost;
    out.state = state_;
  };
  if (blob.status != DetectStatus::kOk) {
    lose_frame();
    return out;
  }

  if (state_ == TrackState::kWaitingForCalibration) {
    // The frame's observation as CalibrateBody makes it, built only when a fit is taken.
    std::optional<BodyObservation> observation;
    const auto obs = [&]() -> const BodyObservation& {
      if (!observation)
        observation = MakeObservation(camera_, blob.grid_step_px, blob.mask, blob.depth_m,
                                      blob.points, blob.pixels, options_.subsample);
      return *observation;
    };
    BodyCalibration c = CalibrateBody(blob, camera_, options_.subsample, options_.calibration);
    if (c.status != CalibrationStatus::kOk || !Good(c.fit)) {
      const int after = options_.start_without_calibration_after;
      if (after < 0) {
        out.state = state_;
        return out;
      }
      if (const auto head = MeasureHeadSize(blob, camera_.fy, options_.head_size)) {
        constexpr size_t kKept = 64;  // the latest, while a start keeps failing
        if (waiting_neck_depths_.size() == kKept)
          waiting_neck_depths_.erase(waiting_neck_depths_.begin());
        waiting_neck_depths_.push_back(head->neck_below_top_m);
      }
      if (++uncalibrated_frames_ < after) {
        out.state = state_;
        return out;
      }
      std::optional<double> neck_depth;
      if (!waiting_neck_depths_.empty()) neck_depth = Median(waiting_neck_depths_);
      BodyCalibration p = ProportionalBody(blob, options_.calibration, neck_depth);
      if (p.status != CalibrationStatus::kOk) {
        out.state = state_;
        return out;
      }
      body_.emplace(p.shape);
      has_previous_ = false;
      auto r = Recover(blob, obs(), &out.from_extremities);
      if (!r) {
        body_.reset();
        out.state = state_;
        return out;
      }
      p.pose = r->pose;
      p.fit = *r;
      c = std::move(p);
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
    out.skeleton = WithConfidence(
        c.fit, obs(),
        c.from_calibration_pose ? options_.calibration.fit.inlier_m : options_.fit.inlier_m, true);
    calibration_ = std::move(c);
    out.state = state_;
    return out;
  }

  BodyObservation obs = MakeObservation(camera_, blob.grid_step_px, blob.mask, blob.depth_m,
                                        blob.points, blob.pixels, options_.subsample);
  const bool use_static_scene = options_.static_scene.enabled && world_from_sensor.has_value();
  if (use_static_scene) static_scene_.DropStatic(*world_from_sensor, blob.floor_in_sensor, &obs);
  out.points = static_cast<int>(obs.points.size());
  if (state_ == TrackState::kLost) {
    auto r = Recover(blob, obs, &out.from_extremities);
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
    out.skeleton = WithConfidence(*r, obs, options_.fit.inlier_m, true);
    out.state = state_;
    last_observation_ = std::move(obs);
    last_fit_cost_ = CostWithLostPoints(*r, options_.fit);
    return out;
  }

  const ArticulatedPose start = Predicted(pose_);
  KeepPointsNearBody(*body_, body_->Pose(start),
                     options_.keep_near_model_m * std::max(1.0, gap_ratio_), &obs);
  out.points = static_cast<int>(obs.points.size());
  BodyFitResult fit = FitFromPrediction(start, blob, obs);
  fit = CheckFront(std::move(fit), blob, obs);
  if (options_.limb_recheck_hypotheses > 0) recheck_limb_ = (recheck_limb_ + 1) % kLimbCount;
  if (Good(fit)) fit = CheckTravelHeading(std::move(fit), blob, obs, world_from_sensor);
  out.inlier_share = fit.inlier_share;
  out.outlier_share = fit.outlier_share;
  out.coverage = fit.coverage;
  out.good_fit = Good(fit);
  centroid_ = fit.inlier_centroid;
  if (!out.good_fit) {
    lose_frame();
    if (state_ == TrackState::kLost) return out;
  } else {
    bad_frames_ = 0;
  }
  AdoptPose(fit.pose, timestamp_s, false);
  if (out.good_fit) {
    if (use_static_scene)
      static_scene_.Learn(blob, detector_.rays(), *world_from_sensor, *body_, fit.posed);
    CollectMotionFrame(fit, obs);
    CollectCrotchHeight(fit, blob);
    CollectTorsoWidths(fit, blob);
  }
  out.skeleton = WithConfidence(fit, obs, options_.fit.inlier_m, out.good_fit);
  out.state = state_;
  last_observation_ = std::move(obs);
  last_fit_cost_ = CostWithLostPoints(fit, options_.fit);
  return out;
}

std::optional<SkeletonTracker::OracleFit> SkeletonTracker::FitLastFrameFrom(
    const Skeleton& start_in_sensor) const {
  if (!body_ || !last_observation_) return std::nullopt;
  const ArticulatedPose start = body_->PoseFromSkeleton(start_in_sensor);
  OracleFit out;
  out.posed = body_->Pose(start).skeleton;
  const BodyFitResult fit =
      FitBody(*body_, start, *last_observation_, options_.fit, options_.limits);
  out.fitted = fit.posed.skeleton;
  out.fitted_cost = CostWithLostPoints(fit, options_.fit);
  out.track_cost = last_fit_cost_;
  return out;
}

}  // namespace reenact::capture
