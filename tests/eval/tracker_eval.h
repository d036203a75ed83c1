#pragma once
// `reenact-eval tracker`: the depth skeleton tracker (capture-client/tracker/) against the
// synthetic scene's ground-truth skeleton.
//
//   reenact-eval tracker [--scenario S[,S...]] [--variants V[,V...]] [--iterations N[,N...]]
//                        [--subsample K[,K...]] [--body FILE.glb|procedural]
//                        [--turn-starts DEG] [--without PART[,PART...]] [--noise on|off]
//                        [--sensor-pose truth|slam|none] [--timestamps on|off] [--floor on|off]
//                        [--frames on|off] [--seeds N[,N...]] [--json FILE]
//
// --seeds: the scene's seeds, each a run of its own (default 1): the seed draws the depth
// noise (and walk-handheld's hand shake), and a tracker fits every frame from the last one,
// so a change that moves one frame's fit by a little can send a whole row another way; the
// mean over seeds tells a change's effect from that chance.
// --turn-starts DEG: the tracker's turned starts, +-DEG degrees about up, 0 = off
// (SkeletonTrackerOptions::turn_start_deg, default 25).
// --without PART[,PART...]: the tracker's method without these steps or parts of steps
// (tracker_experiment.h lists them: turned-starts, limb-jump, uncross-arms, uncross-legs,
// uncross-return, front-check, front-confirm, travel-heading, limb-search, held-twists,
// static-scene, trunk-breadth, torso-depth); default: the product's method.
// --timestamps on|off: each frame's time given to the tracker (default on), which scales its
// prediction by the gap since the last frame (SkeletonTrackerOptions::max_gap_ratio); off:
// every frame taken as one interval after the last, as before timestamps were passed.
// --sensor-pose truth|slam|none: the sensor pose (and the world's up) the tracker is given with
// each frame: the scene's true one (default), or the one the recorder gives it for a sensor
// without poses (clip_recorder.h's FramePoseHint): RGB-D SLAM's constant-velocity prediction for
// the frame (slam/rgbd_slam.h; none until SLAM has founded its map on the first frame), SLAM
// then tracking the frame's colour and depth with the rendered person mask (the recorder's is
// segmented from the tracked skeleton), its world anchored at the first frame's true pose; or
// none: neither a pose nor the world's up on any frame (a real camera recorded without SLAM).
// ms_per_frame stays the tracker's alone.
// --floor on|off: the body model's floor beside the track (default off; one fit more a frame,
// outside the timing): on every tracked frame but the track's start (its calibration), the
// tracker's body as it is then is posed from the ground truth's skeleton and fitted to that
// frame's observation (tracker_experiment.h's FitLastFrameFrom), as if the track had never lost
// anything.
// floor_posed_mpjpe_cm is that pose's mean 16-joint error before the fit (the body's
// proportions and its joint placement against the truth's rig), floor_mpjpe_cm after it (what
// the data and this model give near the truth): a row near its floor is the model's, a row
// far above it the tracking's, unless the cost prefers the track's pose. floor_cheaper_rate:
// the share of those frames on which that fit costs less than the fit the track kept
// (OracleFit's costs, on the same observation): a minimum the track's search
// missed; where the rate is low, the data and the model prefer the track's pose, and the
// distance above the floor is the model's as well. Means and shares over those frames;
// written only with --floor on.
// --frames on|off: the table "frames" (default off), one row per frame given to the tracker,
// in order, so that a row's mean can be read as the frames where it was made (where a track
// slid off, what the fit saw then): frame (the scene's frame index), state (the tracker's
// after the frame: waiting_for_calibration, tracking, lost), calibrated and recovered (1 on
// the frame that started or restarted the track), points (the fit's data points),
// inlier_share, outlier_share and coverage (BodyFitResult's, of the frame's fit; 0 where none
// ran); where
// the frame gave a skeleton: mpjpe_cm (its mean 16-joint error: the row's mpjpe_cm is the
// mean of these), worst_joint and worst_cm (the joint farthest from the truth), l_hand_cm,
// r_hand_cm, l_foot_cm, r_foot_cm, and with --floor on floor_mpjpe_cm and floor_cheaper (1
// where the fit from the truth cost less than the track's) where the floor's fit ran.
// Per scenario, variant and speed setting (iterations x subsample), every sensor frame is
// rendered with Kinect-like depth noise (on by default) and tracked, frames in order through
// one tracker that is given the sensor pose and the world's up (as the synthetic source gives
// them). Variants construct the hard cases the issue names:
//   normal  the scenario as it is
//   fast    every 2nd frame only: the motion at twice its speed (60 fps motion seen at 30)
//   near    the sensor moved forward along its optical axis (by at most 1.2 m) until the
//           subject's waist is 1.8 m ahead: the subject is partly outside the image (shins
//           and feet cut off, raised hands leave the top)
//   drops   frames dropped unevenly, as a live sensor drops them when its queue overflows or
//           its colour and depth streams part (openni_source.cc): after each frame seen, 0, 1,
//           2 or 3 frames dropped with probabilities 0.6, 0.25, 0.1 and 0.05, drawn from the
//           seed (1.6 frame intervals between the frames seen on average)
// Figures per row: frames, tracked_rate (frames with a skeleton), mpjpe_cm (mean over the
// tracked frames of the mean 16-joint error, every joint whatever its confidence), p90_cm
// (90th percentile of the per-frame errors); over the tracked frames, split by what the sensor
// shows (in_view_error.h: a truth joint is in view when it lies ahead of the sensor and projects
// inside the image; reported: confidence above 0): in_view_mpjpe_cm (mean over the frames of
// the mean error of the in-view joints the tracker reported), in_view_reported (the share of
// in-view joints reported) and invented (the share of out-of-view joints reported anyway, which
// should be flagged not seen). Where every joint stays in view (a row without partly_outside
// frames) and is reported, in_view_mpjpe_cm equals mpjpe_cm, the goal's figure. Where joints
// leave the image (upper-body-turn, whose knees and feet are never in view; the near
// variant) the goal's figure is in_view_mpjpe_cm, with in_view_reported near 1 and invented
// near 0: mpjpe_cm there also counts the places given to joints no frame shows. Then
// heading_deg (median over the tracked frames of the heading error, body_heading.h: how far
// the tracked body is turned about the vertical from the truth's) and reversed_rate (the share
// of those frames with a heading error above 90 degrees: front and back confused),
// calibration frame, losses and recoveries, aligned_mpjpe_cm (the mean 16-joint error over the
// tracked frames after the calibration frame, each joint moved by the offset
// between the track and the truth on the calibration frame, in the tracked segment's frame:
// calibration_aligned_error.h; only for a track started from the calibration pose, each
// calibration from that pose taking new offsets; it separates the tracking error from a
// rig's joint definition, the goal's figure stays mpjpe_cm), torso_depth_cm and
// torso_breadth_cm (the tracked body's trunk at the end of the run: its depth as calibrated or
// measured from side views, torso_depth.h; 0 for a track that never started), ms_per_frame (median
// wall time of the tracker alone, rendering excluded) and its median CPU time (all of the tracker's
// threads).
// A second table breaks every row down by the frames that show a hard case according to the
// ground truth (a case no frame shows gets no row):
//   back_facing     the body's forward ((l_shoulder - r_shoulder) x (neck - waist)) points
//                   more than 120 degrees away from the sensor
//   arm_in_front    a hand or elbow projects inside the torso's image box (between the
//                   shoulders, neck to waist) at least 10 cm nearer than the torso joint
//   fast_motion     some joint moved faster than 2 m/s since the previous frame
//   partly_outside  some joint projects outside the image (the near variant)
//   turning         the body's heading (body_heading.h) turned faster than 60 degrees per
//                   second since the previous frame (a quarter turn in 1.5 s)
// A third table, "joints", breaks every row down by joint over its tracked frames
// (joint_error_table.h): mean_cm (mean error), the mean error vector bias_x/y/z_cm in the
// ground-truth body frame of each frame (x the subject's left to its right, y forward, z up
// along the spine), its norm bias_cm (a constant offset, such as a rig placing a joint
// elsewhere than the tracker's model) and spread_cm (RMS of the error less that mean: the
// tracking error proper). A fourth, "confidence", breaks every row's joint estimates down by
// the confidence the tracker reported for them (confidence_error_table.h): their share, mean
// error and share more than 10 cm off per confidence bin. A fifth, "limbs", splits every
// row's tracked frames, per limb, into those where the frame shows the limb and those where
// it is hidden (by the body, or beyond the image's edge), by the ground truth's visible part
// areas (limb_visibility_table.h), with the hand's (foot's) and the elbow's (knee's) mean
// error over each: a limb far off while in view is the tracker's failure, one far off while
// hidden a guess the data do not correct.
// Bodies: the procedural scenarios play on the procedural body and bvh: scenarios on
// --body (default ../shared/data/models/CesiumMan.glb); --body FILE.glb plays every scenario
// on that skinned body (the procedural scenarios retargeted), --body procedural every
// scenario on the procedural body (bvh: retargeted by body_pose_from_skeleton.h, its
// ground-truth joints where the tracker's model puts them). A skinned body's ground-truth
// joints sit where its skin's joints are (skinned_body.h), not where the tracker's
// anthropometric model puts them, which adds a definitional offset to its error.

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "capture-client/tracker/skeleton_tracker.h"
#include "common/cli/command_line.h"
#include "common/error/expected.h"
#include "proto/report/report_table.h"
#include "tests/eval/confidence_error_table.h"
#include "tests/eval/joint_error_table.h"
#include "tests/eval/limb_visibility_table.h"

namespace reenact::eval {

struct TrackerEvalOptions {
  std::vector<std::string> scenarios{"turn-and-kick", "walk-handheld"};
  std::vector<std::string> variants{"normal"};  // normal, fast, near, drops
  std::vector<int> iterations{8};               // each >= 1
  std::vector<int> subsample{2};                // each >= 1
  // The skinned body for bvh: scenarios; empty: the procedural body.
  std::string body_path = "../shared/data/models/CesiumMan.glb";
  bool body_for_all = false;  // every scenario on body_path (set by --body), not only bvh:
  bool depth_noise = true;
  std::vector<int> seeds{1};  // each >= 1: the scene's seed, one run per seed
  int max_frames = -1;        // frames per run at most (-1: all); for tests
  // The sensor pose the tracker is given: the truth, or (--sensor-pose slam) the RGB-D SLAM's
  // prediction as the recorder gives it for a sensor without poses, or (--sensor-pose none,
  // withhold_sensor_pose) none and no world up. At most one of the two set.
  bool slam_poses = false;
  bool withhold_sensor_pose = false;
  // Each frame's timestamp given to the tracker (SkeletonTrackerOptions::max_gap_ratio).
  bool timestamps = true;
  // The model's floor on every tracked frame (--floor; see the header comment).
  bool floor = false;
  // One row per frame (--frames; see the header comment).
  bool frames = false;
  capture::SkeletonTrackerOptions tracker;
  std::set<std::string> without;  // ablations (tracker_experiment.h)
};

struct TrackerEvalRow {
  std::string scenario, variant;
  int iterations = 0, subsample = 0, seed = 1;
  int frames = 0, tracked = 0;
  double tracked_rate = 0, mpjpe_cm = 0, p90_cm = 0;
  double in_view_mpjpe_cm = 0, in_view_reported = 0, invented = 0;  // see the header comment
  double heading_deg = 0, reversed_rate = 0;                        // see the header comment
  int calibration_frame = -1, losses = 0, recoveries = 0;
  // See the header comment; nullopt where the track never started from the calibration pose.
  std::optional<double> aligned_mpjpe_cm;
  // --floor on only (see the header comment).
  std::optional<double> floor_posed_mpjpe_cm, floor_mpjpe_cm, floor_cheaper_rate;
  double torso_depth_cm = 0, torso_breadth_cm = 0;
  double ms_per_frame = 0, cpu_ms_per_frame = 0;
};

struct TrackerCaseRow {
  std::string scenario, variant, hard_case;
  int iterations = 0, subsample = 0, seed = 1;
  int frames = 0, tracked = 0;
  double tracked_rate = 0, mpjpe_cm = 0;
};

struct TrackerJointRow {
  std::string scenario, variant;
  int iterations = 0, subsample = 0, seed = 1;
  Joint joint = Joint::kHead;
  JointErrorStats stats;
};

struct TrackerConfidenceRow {
  std::string scenario, variant;
  int iterations = 0, subsample = 0, seed = 1;
  int bin = 0;  // ConfidenceErrorTable's bin
  ConfidenceBinStats stats;
};

struct TrackerLimbRow {
  std::string scenario, variant;
  int iterations = 0, subsample = 0, seed = 1;
  int limb = 0;  // EvalLimbName's index
  LimbVisibilityStats stats;
};

// --frames on only: one frame of a run (see the header comment).
struct TrackerFrameRow {
  std::string scenario, variant;
  int iterations = 0, subsample = 0, seed = 1;
  int frame = 0;
  capture::TrackState state = capture::TrackState::kWaitingForCalibration;
  bool calibrated = false, recovered = false;
  int points = 0;
  double inlier_share = 0, outlier_share = 0, coverage = 0;
  std::optional<double> mpjpe_cm;  // the rest only where the frame gave a skeleton
  Joint worst_joint = Joint::kHead;
  double worst_cm = 0;
  double l_hand_cm = 0, r_hand_cm = 0, l_foot_cm = 0, r_foot_cm = 0;
  std::optional<double> floor_mpjpe_cm;
  bool floor_cheaper = false;  // with floor_mpjpe_cm only
};

// One setting (scenario, variant, iterations, subsample) over its seeds: the mean, least and
// largest of the rows' mpjpe_cm, and the means of p90_cm and tracked_rate.
struct TrackerSeedSummary {
  std::string scenario, variant;
  int iterations = 0, subsample = 0;
  int seeds = 0;
  double mpjpe_cm = 0, min_mpjpe_cm = 0, max_mpjpe_cm = 0, p90_cm = 0, tracked_rate = 0;
};

struct TrackerEvalRun {
  std::vector<TrackerEvalRow> rows;
  std::vector<TrackerCaseRow> cases;
  std::vector<TrackerJointRow> joints;           // kJointCount per row, in Joint order
  std::vector<TrackerConfidenceRow> confidence;  // kConfidenceBinCount per row, in bin order
  std::vector<TrackerLimbRow> limbs;             // kEvalLimbCount per row, in limb order
  std::vector<TrackerFrameRow> frames;           // --frames on: every row's frames in order
};

// The rows' settings over their seeds, in the order each setting first appears.
std::vector<TrackerSeedSummary> SummariseSeeds(const std::vector<TrackerEvalRow>& rows);

// Errors: "not_found" for an unknown scenario; "usage" for an unknown variant, no seed or a
// seed below 1; the scene's errors for a bvh: file or body that cannot be used.
Expected<TrackerEvalRun> RunTrackerEval(const TrackerEvalOptions& options);

// Tables and --json rows (command "tracker"), each opening with the setting (scenario,
// variant, iterations, subsample, seed): the main table (n, tracked_rate, mpjpe_cm, p90_cm,
// in_view_mpjpe_cm, in_view_reported, invented, calib_frame, losses, recoveries, ms_per_frame,
// cpu_ms_per_frame) and the table "cases"
// (case, n, tracked_rate, mpjpe_cm) and the table "joints" (joint, n, mean_cm, bias_x_cm,
// bias_y_cm, bias_z_cm, bias_cm, spread_cm) and the table "confidence" (confidence, n, share,
// mean_cm, gross_share) and the table "limbs" (limb, in_view_n, hidden_n, in_view_end_cm,
// hidden_end_cm, in_view_middle_cm, hidden_middle_cm); with --frames on the table "frames"
// (see the header comment); with more than one seed, the table "seeds"
// (SummariseSeeds: scenario, variant, iterations, subsample, seeds, mpjpe_cm, min_mpjpe_cm,
// max_mpjpe_cm, p90_cm, tracked_rate).
proto::Report TrackerReport(const TrackerEvalRun& run);

struct TrackerCommand {
  TrackerEvalOptions options;
  std::optional<std::string> json_path;
};

std::set<std::string> TrackerFlags();

// --body procedural: every scenario on the procedural body (body_path empty, body_for_all).
// Errors (code "usage", naming the flag): empty lists or names, numbers that are not whole
// numbers >= 1, an unknown variant, an unknown --without part, --turn-starts other than one
// number from 0 to 89, --noise other than on or off, --sensor-pose other than truth, slam or
// none, --seeds
// other than whole numbers from 1 to 1000 without repeats; ("io") an unwritable --json.
Expected<TrackerCommand> ParseTrackerCommand(const CommandLine& command_line);

}  // namespace reenact::eval
