#pragma once
// Skeleton tracking from depth alone (issue 8): a skeleton source for sensors without NiTE.
//
// Per depth frame:
//  - Waiting for calibration: detect the person (person_detector.h); when the blob shows the
//    calibration pose (arms out sideways, facing the sensor), calibrate the body
//    (body_calibration.h: height, arm span, 16-joint skeleton, radii); bone lengths are
//    fixed from then on. A subject who has not shown the calibration pose after
//    start_without_calibration_after frames with a detected person gets a body of average
//    proportions for its standing height (ProportionalBody), its head scaled by the median
//    neck depth measured on those frames (head_size.h), placed as when recovering from the
//    silhouette (below); its bone lengths are less exact. Once it walks, its legs are scaled
//    by the crotch's height seen between them (crotch_height.h) and its lengths fitted over
//    frames with the legs apart (motion_calibration_frames, below). A calibrated body's trunk
//    depth, which the calibration's front view does not show, is measured once the subject
//    has turned side-on (torso_depth.h, measure_torso_depth below).
//  - Tracking: detect the person near its previous centroid (of the points the last fit
//    explained, so that an object once merged with the person does not pull it; across the
//    detector's larger tracking_merge_step_m, so a hand behind the head stays), keep the points
//    within keep_near_model_m of the predicted body (the previous pose, its root moved by the last
//    frame's root motion: an object that touches the person is left out) and, given the sensor's
//    pose, outside the static scene learned beside the person on earlier frames
//    (static_scene_voxels.h: an object the person walks up to), fit the
//    articulated body (body_fit.h) from the prediction, and from the prediction turned either
//    way about the floor's up (turn_start_deg), keeping the cheapest fit (a turned one only
//    when it does not swing a limb in view out of its data, limb_jump.h).
//    When many points are left unexplained, limbs are re-posed by a hypothesis search
//    (limb_search.h) and fitted again; optionally, every frame one limb in turn is
//    re-checked from its best few hypotheses, each fitted (limb_recheck_hypotheses, below);
//    optionally, an arm the data hardly show where the fit put it is also fitted from hanging at
//    its shoulder (hanging_arm.h). A fit is good when the data covers at least min_coverage of the
//    model's silhouette within the image (BodyFitResult::coverage: a model that slid off the person
//    covers little; 0.4-0.65 is usual, the body hiding its own parts; a subject partly beyond the
//    image's edge keeps it) and at least good_inlier_share of the points lie within inlier_m of the
//    model's surface. For a while after a start whose heading came from the silhouette, the fit is
//    also tried turned around (front_check_*, below): front and back look alike to a standing body.
//    Unexplained points alone (an object touching the person) do not make a fit bad. Bone lengths
//    are fixed by construction and joint limits are enforced on every step, so neither can be
//    violated; a failed detection or a bad fit counts as a bad frame, and lost_after_frames bad
//    frames in a row mean the track is lost. Bad frames before that still give a skeleton, its
//    confidences halved.
//  - Lost: recovery each frame, either from the calibration pose (when the person shows it
//    again) or from the silhouette: the calibrated body placed upright on the blob (the
//    waist above the floor under the blob's centroid, arms and legs straight down) facing
//    the sensor, away from it, to either side and at the last tracked heading, each fitted
//    with recovery_iterations; and, with recover_from_extremities, the same headings with
//    the limbs re-posed to reach the geodesic extremities of the region (hands and feet,
//    geodesic_extremities.h and extremity_pose.h: a raised arm, arms out), each fitted
//    alike; the best fit of all is taken when it is good. The start without the
//    calibration pose tries the upright starts only (on the bvh: walk, seen from the side at
//    4 m, the extremity starts won with poses that tracked worse).
// Per-joint confidence: each segment's inlier points that no other part explains as well
// over the points its capsules would show if unoccluded (SegmentSupport::exclusive of the
// reported fit, body_fit.h, over BodyFitResult::expected_support: an arm lying on the trunk
// or on the other arm is not confirmed by the points it shares with them), divided by
// full_support_ratio and clamped to [min_confidence, 1]; a joint takes the best of its
// adjacent segments.
// Output skeletons are in the sensor frame (OpenCV axes, metres). Not thread-safe: one caller
// at a time (the turned starts run on threads of the tracker's own within Track).

#include <Eigen/Geometry>
#include <optional>
#include <string_view>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_calibration.h"
#include "capture-client/tracker/body_fit.h"
#include "capture-client/tracker/crotch_height.h"
#include "capture-client/tracker/extremity_pose.h"
#include "capture-client/tracker/gap_ratio.h"
#include "capture-client/tracker/geodesic_extremities.h"
#include "capture-client/tracker/hanging_arm.h"
#include "capture-client/tracker/head_size.h"
#include "capture-client/tracker/heading.h"
#include "capture-client/tracker/limb_jump.h"
#include "capture-client/tracker/limb_search.h"
#include "capture-client/tracker/limb_swap.h"
#include "capture-client/tracker/person_detector.h"
#include "capture-client/tracker/static_scene_voxels.h"
#include "capture-client/tracker/torso_depth.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

struct SkeletonTrackerOptions {
  PersonDetectOptions detect;
  // Speed settings: data points every subsample-th detection grid point (>= 1; with the
  // default grid of 2 px, subsample 2 takes every 4th pixel in x and y), and fit.iterations.
  int subsample = 2;
  BodyFitOptions fit;
  CalibrationOptions calibration;
  JointLimits limits;
  // Limb re-posing (limb_search.h) when more than limb_search_trigger of the points lie
  // beyond outlier_m of the fitted model ([0, 1]; 1 = never), then a second fit from there,
  // kept when it costs less both on the fit's cost and with the points each fit leaves beyond
  // outlier_m counted at outlier_m, or when it costs at most (1 - limb_search_gain) ([0, 1))
  // times as much with them counted. Points beyond outlier_m cost nothing in the fit, so on
  // its cost alone a fit that reached a rising hand's points lost to the one that left them
  // (on the CMU walk 131_01 the right hand raised behind the head was then lost for the rest
  // of the clip); the margin keeps a limb the data do not hold (hidden behind the body) from
  // moving for a few stray points (docs/measurements.md).
  double limb_search_trigger = 0.005;
  double limb_search_gain = 0.1;
  // While tracking, data points farther than this from the predicted body are not the
  // person's (metres, > 0; larger than a limb moves in one frame interval; scaled by the
  // prediction's gap ratio below where that is above 1).
  double keep_near_model_m = 0.4;
  // The prediction in time: given each frame's timestamp (Track's timestamp_s), the last root
  // displacement is carried on scaled by the gap ratio (gap_ratio.h), at most max_gap_ratio
  // (>= 1): a live sensor drops frames when its queue overflows or the colour and depth
  // streams part (openni_source.cc), and a frame without a person in between leaves a gap too.
  // Without timestamps the frames count as evenly spaced. The other frame counts of these
  // options (lost_after_frames, the front check's, the cool-downs, the static scene's) stay
  // counts of frames.
  double max_gap_ratio = 4;
  // The static scene learned while tracking (static_scene_voxels.h), its points dropped before the
  // fit; used only on frames whose sensor pose is given (Track's world_from_sensor).
  StaticSceneOptions static_scene;
  LimbSearchOptions limb_search;
  // Crossed limbs (limb_swap.h): when the fitted arms' (legs') ends lie crossed, the fit from
  // the swapped limbs, re-posed by the limb search above, replaces the frame's when it costs
  // at most (1 - uncross_gain) ([0, 1)) times as much. A subject crossing its arms keeps them
  // crossed: the swapped fit then costs more.
  // For the arms, where the prediction (the fit's start) had them apart, the fit is also
  // started from each arm back at its predicted joint angles and the other reaching where it
  // ended (limb_swap.h's ReturnedLimb: one arm took the other's data), and the cheapest of
  // those and the swap is taken under the same margin (uncross_returns_limb; off: the swap
  // alone, `reenact-eval tracker --uncross-return off`). Not for the legs: on CesiumMan's walk
  // the returned leg left the hips 18 cm high where the swap alone leaves them 16 cm
  // (docs/measurements.md).
  bool uncross_limbs = true;
  double uncross_gain = 0.05;
  bool uncross_returns_limb = true;
  // Limb re-check, every tracked frame for one limb in turn (left arm, right arm, left leg,
  // right leg): its limb_recheck_hypotheses (>= 0; 0 = off) cheapest re-posings
  // (limb_search.h's RankLimbHypotheses) are each fitted from there with
  // limb_recheck_iterations (>= 1) iterations, and the cheapest fit replaces the frame's when
  // it costs at most (1 - limb_recheck_gain) ([0, 1)) times as much. The local fit cannot
  // bring back a limb that lies on the wrong side of the body (a hanging arm's points are
  // then explained, worse, by the torso, and no point lies beyond outlier_m to start the
  // search above); a hypothesis near the truth costs clearly less once fitted. The margin
  // keeps a hidden limb, whose poses cost nearly alike, where it is. A fit is refused that
  // takes another limb's data rather than repairing this limb: one that moves another limb's
  // elbow, hand, knee or foot by more than limb_recheck_max_other_move_m (> 0), or that
  // puts the arm deeper into the trunk (ArmTrunkDepth) than it was and than
  // limb_recheck_trunk_depth_m (a hidden far arm reaching through the chest for the near
  // arm's points). Off by default: on the procedural body it brings the CMU walks from 7.70
  // to 5.21 cm (mean of 12 runs), but on the skinned CesiumMan, whose surface the capsules
  // fit less well, it puts the walk's left arm 35 cm off (docs/measurements.md).
  int limb_recheck_hypotheses = 0;
  double limb_recheck_gain = 0.1;
  double limb_recheck_max_other_move_m = 0.1;
  double limb_recheck_trunk_depth_m = 0.0;
  int limb_recheck_iterations = 8;
  // The hanging arm (hanging_arm.h): an arm the fit hardly supports is also fitted from
  // hanging at its shoulder (hanging_arm.min_support 0: off). Off by default: on CesiumMan it
  // brings set B from 8.03 to 7.81 cm, but its CMU walks stay level (10.16 -> 10.15), the
  // procedural 131_01 walk moves 3.98 -> 4.00 (dropped frames, seed 1: 4.2 -> 5.7), and it
  // costs 11 % more time per frame (docs/measurements.md, session 46); HangingArmOptions{}
  // turns it on.
  HangingArmOptions hanging_arm{.min_support = 0};
  // Turned starts: every tracked frame the fit is also started from the prediction turned about
  // the floor's up by -turn_start_deg and +turn_start_deg (degrees, [0, 90); 0 = off), each
  // start fitted and re-posed as the prediction's is, and the cheapest fit kept; cheaper also
  // with the points it leaves beyond outlier_m counted at outlier_m (a fit that loses a raised
  // arm's points is not taken). The fit from the prediction alone falls behind a fast turn
  // where the body's surface shows the turn little (a rounded trunk, the arms close to it): on
  // the skinned CesiumMan's turn-and-kick it lagged up to 60 degrees, while a fit started from
  // the truth cost 20-60 % less. Three fits a frame instead of one, the turned ones on threads
  // of their own while the calling thread fits the prediction (docs/measurements.md).
  double turn_start_deg = 25;
  // A turned fit is not kept when a limb jumped from its data to it from the prediction's own
  // fit (limb_jump.h): an arm swung behind the head costs nothing in the free-space term, so a
  // turned start could take it there on a frame the own fit explains poorly.
  bool turn_start_jump_check = true;
  LimbJumpOptions turn_start_jump;
  double good_inlier_share = 0.5;       // (0, 1]
  double min_coverage = 0.3;            // (0, 1]
  int lost_after_frames = 3;            // >= 1
  int recovery_iterations = 12;         // >= 1
  bool recover_from_silhouette = true;  // else only the calibration pose recovers
  // Recovery of a lost track also from the region's geodesic extremities (limbs reaching
  // them), see above.
  bool recover_from_extremities = true;
  GeodesicExtremityOptions extremities;
  // A limb is re-posed to its extremity only when the upright start's limb end lies farther
  // than this from it (metres, >= 0; extremity_pose.h's min_offset_m).
  double extremity_min_offset_m = 0.25;
  // Frames with a detected person, without the calibration pose, after which tracking starts
  // with average proportions; -1 = never (wait for the calibration pose). >= -1.
  int start_without_calibration_after = 15;
  // The head's measurement on those frames (head_size.h).
  HeadSizeOptions head_size;
  // Headings tried when starting without the calibration pose and when recovering from the
  // silhouette (heading.h: evenly spaced about up, the first facing the sensor), >= 1.
  int heading_candidates = 8;
  // Front from the walking direction (heading.h's TravelDirection and its options): a fitted
  // forward whose cosine to the travel is below travel_flip_cos ([-1, 1]) is re-fitted facing
  // it, and the new fit kept when it is good and costs at most flip_cost_tolerance (>= 1)
  // times the old one (front and back fit nearly alike, so the walk decides). At most once
  // every heading_check_cooldown_frames (>= 0) frames.
  TravelOptions travel;
  double travel_flip_cos = -0.3;
  double flip_cost_tolerance = 1.3;
  int heading_check_cooldown_frames = 10;
  // Front from the fit, while it is uncertain: for front_check_frames (>= 0; 0 = off) tracked
  // frames after a start whose heading came from the silhouette (a start without the
  // calibration pose, a recovery from the silhouette), every front_check_every-th (>= 1) frame
  // is also fitted from the body turned around on the same data (limb_swap.h's TurnedAround),
  // and that fit kept when it is good and costs at most (1 - front_check_gain) ([0, 1)) times
  // the frame's. The start chose its heading standing still, where front and back fit nearly
  // alike (on CesiumMan the back often better); once the subject moves, the knees and elbows,
  // which bend one way only, tell them apart. Later the track's own continuity is the better
  // guide: checked throughout, a turn made in a fast spin was taken the wrong way round
  // (docs/measurements.md).
  // A turned fit that wins a check is not taken at once when front_check_confirm_frames
  // (>= 0; 0 = taken at once) is positive: it is followed as a rival track, each frame fitted
  // from its own last pose as the track is, and the costs of both summed over the frames
  // followed. The rival replaces the track as soon as its sum is at most (1 - front_check_gain)
  // times the track's, is dropped as soon as the track's is at most that times the rival's,
  // and replaces it when neither has happened after front_check_confirm_frames frames. One
  // frame's cost tells front from back poorly where the body shows few points.
  int front_check_frames = 30;
  int front_check_every = 5;
  double front_check_gain = 0.1;
  int front_check_confirm_frames = 5;
  // On-the-fly calibration of a body started without the calibration pose: the segment
  // lengths of shape_fit.h (its free lengths, priors and the standing height) fitted over
  // motion_calibration_frames (>= 0; 0 = off) tracked frames with good fits, at least
  // motion_frame_spacing (>= 1) frames apart, each with the thighs at least
  // motion_min_leg_spread_rad (>= 0) apart (legs apart show the hips and leg lengths that a
  // straight stance hides); then fixed.
  int motion_calibration_frames = 4;
  int motion_frame_spacing = 4;
  double motion_min_leg_spread_rad = 0.3;
  // Before that fit, once at least min_crotch_frames (>= 1) tracked frames since the start
  // have measured the crotch's height (crotch_height.h), the legs are scaled by it: the 90th
  // percentile c of the heights (the crotch itself; lower readings come from lines up an
  // inner thigh) against average_crotch_ratio H (> 0; what it reads on the procedural body
  // walking, 0.476-0.478 H on both CMU walks) moves the hip joints by c - average_crotch_ratio
  // H, so the legs scale by m = 1 + that / (thigh + shin), shrunk towards 1 by
  // leg_scale_noise and kept within [min_leg_scale, max_leg_scale] (ScaleBeyondNoise), the
  // spine keeping the height (WithLegsScaled). 0 < min_leg_scale <= 1 <= max_leg_scale.
  CrotchHeightOptions crotch;
  int min_crotch_frames = 5;
  double average_crotch_ratio = 0.478;
  double leg_scale_noise = 0.05;
  double min_leg_scale = 0.8;
  double max_leg_scale = 1.2;
  // The trunk's depth from side views (torso_depth.h): once torso_depth.side_frames tracked
  // frames with good fits have seen the trunk within torso_depth.max_side_deg of side-on, the
  // trunk's capsules take the measured depth, their breadth kept; then fixed. false: the
  // calibration's depth. Only for a body calibrated from the calibration pose, unless
  // measure_torso_depth_uncalibrated: a start without it has no measured breadth, and on
  // CesiumMan's CMU walks the deeper trunk left more rows facing backwards for part of the
  // walk (8 of 36 against 2) for no gain in MPJPE (docs/measurements.md).
  bool measure_torso_depth = true;
  bool measure_torso_depth_uncalibrated = false;
  TorsoDepthOptions torso_depth;
  double full_support_ratio = 0.5;  // (0, 1]
  double min_confidence = 0.05;     // (0, 1]: tracked joints are never reported missing

  void Check() const;
};

enum class TrackState { kWaitingForCalibration = 0, kTracking, kLost };
std::string_view TrackStateName(TrackState state);

struct TrackFrameResult {
  TrackState state = TrackState::kWaitingForCalibration;  // after this frame
  DetectStatus detect = DetectStatus::kNoDepth;
  std::optional<Skeleton> skeleton;  // sensor frame; none while waiting or lost
  bool calibrated = false;           // calibrated on this frame
  bool recovered = false;            // recovered from a loss on this frame
  // The recovery's (or the start's) pose came from the extremity hypothesis.
  bool from_extremities = false;
  bool good_fit = false;
  double inlier_share = 0, outlier_share = 0;
  double coverage = 0;  // BodyFitResult::coverage
  int points = 0;       // data points fitted
};

class SkeletonTracker {
 public:
  // Preconditions (CHECK): a valid camera, depth_scale_m > 0, valid options.
  SkeletonTracker(const PinholeCamera& depth_camera, double depth_scale_m,
                  const SkeletonTrackerOptions& options = {});

  // One depth frame (the camera's size: CHECK). world_from_sensor and world_up: when known
  // (they give the floor's up direction for a tilted or moving sensor). timestamp_s: the
  // frame's time in seconds, when known (the prediction in time, max_gap_ratio above); a time
  // that does not increase counts as unknown.
  TrackFrameResult Track(const ImageDepthMm& depth,
                         const std::optional<Eigen::Isometry3d>& world_from_sensor = std::nullopt,
                         const std::optional<Eigen::Vector3d>& world_up = std::nullopt,
                         std::optional<double> timestamp_s = std::nullopt);

  TrackState state() const { return state_; }

  // The model's floor, an oracle for evaluation: what this body model reaches on the last
  // frame from a start it could not know, such as the ground truth's skeleton. `posed`: the
  // current body posed as near start_in_sensor as its shape allows
  // (ArticulatedBody::PoseFromSkeleton: root from the pelvis and torso joints, limbs by their
  // bone directions; every joint of the skeleton is read); `fitted`: that pose fitted to the
  // last frame's observation as a tracked frame's own start is (FitBody with the options' fit
  // and limits; no turned starts, searches or checks). The tracker's state is not touched.
  // nullopt unless the last frame was tracked or recovered (a calibration frame, a frame
  // without a person, or none yet). fitted_cost and track_cost: CostWithLostPoints
  // (body_fit.h) of that fit and of the fit the track kept on the frame, on the same
  // observation: a fit from the truth that costs less is a better minimum the track missed (the
  // search's loss); one that costs as much or more says the data prefer the track's pose (the
  // model's).
  struct OracleFit {
    Skeleton posed, fitted;  // sensor frame
    double fitted_cost = 0, track_cost = 0;
  };
  std::optional<OracleFit> FitLastFrameFrom(const Skeleton& start_in_sensor) const;

  // The calibration, once calibrated.
  const std::optional<BodyCalibration>& calibration() const { return calibration_; }
  // Forgets everything (a new subject).
  void Reset();

 private:
  // The fit's skeleton with per-joint confidence (see above); obs and inlier_m: the fit's.
  Skeleton WithConfidence(const BodyFitResult& fit, const BodyObservation& obs, double inlier_m,
                          bool good) const;
  bool Good(const BodyFitResult& fit) const;
  // `other` when it costs less than `fit` both on the fit's cost and with the lost points
  // counted (body_fit.h's CostWithLostPoints); else `fit`.
  BodyFitResult CheaperOf(BodyFitResult fit, BodyFitResult other) const;
  // The limb search (limb_search.h) where the fit lost points, and the fit from there (see
  // limb_search_trigger and limb_search_gain above).
  BodyFitResult Refine(BodyFitResult fit, const BodyObservation& obs) const;
  BodyFitResult Uncross(BodyFitResult fit, const BodyObservation& obs,
                        const ArticulatedPose& predicted) const;
  // The fit (and Refine) from the start pose turned by angle_rad about up (turn_start_deg),
  // taken over the prediction's by CheaperOf.
  BodyFitResult FitTurned(const ArticulatedPose& start, const Eigen::Vector3d& up, double angle_rad,
                          const BodyObservation& obs) const;
  // The limb re-check of the options for limb `limb`; returns the fit to keep.
  BodyFitResult RecheckLimb(BodyFitResult fit, const BodyObservation& obs, Limb limb) const;
  // The best-costing fit of upright starts facing each of `headings` on the blob's floor,
  // and, given extremities, of the same starts with the limbs reaching them
  // (*from_extremities: whether such a start won).
  std::optional<BodyFitResult> BestHeading(const PersonBlob& blob, const BodyObservation& obs,
                                           const std::vector<Eigen::Vector3d>& headings,
                                           const GeodesicExtremities* extremities = nullptr,
                                           bool* from_extremities = nullptr) const;
  // `pose` moved on by the track's last root displacement times the frame's gap ratio
  // (gap_ratio_; the prediction for this frame).
  ArticulatedPose Predicted(ArticulatedPose pose) const;
  // A new pose of the track at timestamp_s: the last one becomes the previous (a start or a
  // recovery, restart, has none).
  void AdoptPose(const ArticulatedPose& pose, std::optional<double> timestamp_s, bool restart);
  // A tracked frame's fit from the predicted pose `start`: its own fit and the turned starts'
  // (the cheaper kept), limbs uncrossed, limb recheck_limb_ re-checked, as the options ask.
  BodyFitResult FitFromPrediction(const ArticulatedPose& start, const PersonBlob& blob,
                                  const BodyObservation& obs) const;
  // The front check of the options (front_check_*); returns the fit to keep.
  BodyFitResult CheckFront(BodyFitResult fit, const PersonBlob& blob, const BodyObservation& obs);
  // One frame of the front check's rival (front_check_confirm_frames), fitted as the track is;
  // returns the fit to keep.
  BodyFitResult FollowFrontRival(BodyFitResult fit, const PersonBlob& blob,
                                 const BodyObservation& obs);
  // The travel check of the options (front = direction of travel); returns the fit to keep.
  BodyFitResult CheckTravelHeading(BodyFitResult fit, const PersonBlob& blob,
                                   const BodyObservation& obs,
                                   const std::optional<Eigen::Isometry3d>& world_from_sensor);
  std::optional<BodyFitResult> Recover(const PersonBlob& blob, const BodyObservation& obs,
                                       bool* from_extremities = nullptr);

  PersonDetector detector_;
  PinholeCamera camera_;
  SkeletonTrackerOptions options_;
  TrackState state_ = TrackState::kWaitingForCalibration;
  std::optional<BodyCalibration> calibration_;
  std::optional<ArticulatedBody> body_;
  std::optional<BodyObservation> last_observation_;  // of the last tracked or recovered frame
  double last_fit_cost_ = 0;  // CostWithLostPoints of the fit kept on that frame
  ArticulatedPose pose_, previous_pose_;
  bool has_previous_ = false;
  // The times of pose_ and previous_pose_, when known; this frame's gap ratio.
  std::optional<double> pose_time_s_, previous_time_s_;
  double gap_ratio_ = 1;
  Eigen::Vector3d centroid_ = Eigen::Vector3d::Zero();
  int bad_frames_ = 0;
  int uncalibrated_frames_ = 0;
  std::vector<double> waiting_neck_depths_;  // head_size.h's, on the frames waited
  TravelDirection travel_;
  // Frames collected for the on-the-fly calibration, and frames since the last one.
  std::vector<BodyObservation> motion_obs_;
  std::vector<ArticulatedPose> motion_poses_;
  int since_motion_frame_ = 0;
  // A start without the calibration pose whose on-the-fly calibration has not run yet.
  bool OnTheFlyCalibrationPending() const;
  void CollectMotionFrame(const BodyFitResult& fit, const BodyObservation& obs);
  // Crotch heights (crotch_height.h) of the tracked frames before the on-the-fly calibration.
  std::vector<double> crotch_heights_;
  void CollectCrotchHeight(const BodyFitResult& fit, const PersonBlob& blob);
  // The side views of the trunk (measure_torso_depth).
  TorsoDepthCollector torso_depth_;
  void CollectTorsoWidths(const BodyFitResult& fit, const PersonBlob& blob);
  // Replaces the body's shape (same bone lengths or new ones) in the body and the calibration.
  void AdoptShape(const BodyShape& shape);
  int heading_cooldown_ = 0;
  // Tracked frames since a start whose heading came from the silhouette (front_check_*).
  int frames_since_silhouette_start_ = -1;  // -1: none
  // A turned fit that won a front check, followed until it is confirmed or dropped.
  struct FrontRival {
    ArticulatedPose pose;
    double rival_cost = 0;  // summed over the frames followed after the check's
    double track_cost = 0;  // the track's over the same frames
    int frames = 0;         // followed so far
  };
  std::optional<FrontRival> front_rival_;
  int recheck_limb_ = 0;  // the limb to re-check next (Limb)
  StaticSceneVoxels static_scene_;
};

}  // namespace reenact::capture
