#pragma once
// `reenact-eval tracker` on real depth: the depth skeleton tracker (capture-client/tracker/)
// against the Kinect SDK's skeletons recorded with the same frames.
//
//   reenact-eval tracker --source rgbd:DIR --reference kinect:FILE [--json FILE]
//                        [--pictures DIR]
//   reenact-eval tracker --dataset utd-mhad:ROOT [--sequences aA_sS_tT,...] [--json FILE]
//                        [--pictures DIR]
//
// --source and --reference: one sequence, any frame source (capture-client/source/
// frame_source.h) and any skeleton track (capture-client/skeleton/skeleton_track_spec.h),
// both given as they are. --dataset utd-mhad:ROOT: every aA_sS_tT folder under ROOT
// (utd_mhad.h; --sequences: only these), its depth read as rgbd:DIR?mirrored=1 and its
// skeleton.txt as kinect:FILE?variant=utd-mhad.
//
// Per sequence, frames in order through one new tracker (SkeletonTracker with the source's
// depth camera and depth scale, default options; Track(depth, no pose, no up, the frame's
// timestamp)); the skeleton it returns (sensor frame, 16 joints, confidence 0 = not given) is
// compared with the reference's skeleton of the same frame (SkeletonTrack::ForFrame) by the
// figures of reference_agreement.h: MPJPE over all 16 joints and over the sequence's moving
// joints (the reference's joints that move more than 10 cm from their mean position), PCK at
// 10 cm, the share of the reference's joints the tracker gives, the tracked share after the
// first second (frame_rate_hz frames), the frames before the first skeleton, and the
// tracker's wall time per frame (steady_clock around Track() alone: reading and decoding
// the frame are outside it), median and mean.
//
// Raw and offset figures: "raw" compares the tracker's joints as they are; "offset" after a
// constant per-joint offset is taken out (JointOffsetFit of reference_agreement.h: the mean of
// reference - tracked over the tracked frames, in the tracked skeleton's body frame, so it
// turns with the person), fitted on the sequences of the OTHER subjects in the run (leave one
// subject out: a subject's own frames never fit its correction). A sequence whose subject is
// unknown (a --source folder not named aA_sS_tT), or whose other subjects have no tracked
// frame, has no offset figures. PCK is given after the offset.
//
// Baselines, per sequence from the reference alone (MeanPoseAtCentre of
// reference_agreement.h): "baseline" the reference's mean pose over the sequence placed at its
// own hip centre (waist) on every frame, on our 16 joints (what the tracker rows compare
// with); with --dataset also "baseline_kinect20", the same over the Kinect's 20 joints read
// from skeleton.txt itself (hip_center; the moving joints of those 20). A baseline has no
// offset to take out: its offset columns repeat its raw figures.
//
// Output (command "tracker"): the table "" (overall: rows tracker, baseline and, with
// --dataset, baseline_kinect20), "actions" (the tracker per action, with the action's name
// and the baseline's two MPJPE) and "subjects" (the same per subject), columns: sequences,
// frames, tracked_pct, first_skeleton (median over the sequences that got one),
// untracked_seq, joints_pct, mpjpe_cm, mpjpe_offset_cm, moving_cm, moving_offset_cm,
// pck10_offset_pct, ms_median, ms_mean; then the worst action (largest moving_offset_cm, or
// moving_cm where no offsets). A figure without data prints "-" (and is left out of the
// JSON). --json FILE adds the table "sequences" (one row per sequence with its action,
// subject, frames, moving joints and every figure above, raw and offset, and both baselines).
// Actions and subjects only for sequences named aA_sS_tT.
// --pictures DIR: for the kPictureCount frames of the run with the largest per-frame error
// after the offset (raw where the sequence has no offsets), DIR/SEQUENCE_fNNNN.png: the depth
// frame as the source gives it with the reference (green) and the tracker's skeleton after
// the offset (red) drawn on it (skeleton_overlay.h).
//
// Errors: "invalid_argument" when a skeleton track and its depth frames disagree on the
// frame count (both counts and both sources named); the sources' and readers' errors.

#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "capture-client/skeleton/skeleton_track.h"
#include "capture-client/source/frame_source.h"
#include "capture-client/tracker/skeleton_tracker.h"
#include "common/cli/command_line.h"
#include "common/error/expected.h"
#include "proto/report/report_table.h"
#include "tests/eval/reference_agreement.h"

namespace reenact::eval {

inline constexpr int kPictureCount = 6;

struct ReferenceSequenceSpec {
  std::string name;            // e.g. "a14_s3_t1"
  std::string source_spec;     // OpenFrameSource's form
  std::string reference_spec;  // LoadSkeletonTrack's form
  std::optional<int> action, subject;
  std::string joints20_path;  // UTD-MHAD's skeleton.txt for baseline_kinect20; "" = none
};

struct KinectReferenceOptions {
  std::vector<ReferenceSequenceSpec> sequences;
  capture::SkeletonTrackerOptions tracker;
  std::optional<std::string> pictures_dir;
  int pictures = kPictureCount;  // >= 0
  int max_frames = -1;           // frames per sequence at most (-1: all); for tests
  std::ostream* progress = nullptr;  // one line per sequence tracked, where given
};

// One sequence tracked: per frame (index = position in the source), the reference and the
// tracker's skeleton (sensor frame) and the wall time of Track(), ms.
struct TrackedSequence {
  ReferenceSequenceSpec spec;
  double frame_rate_hz = 30;
  std::vector<std::optional<Skeleton>> reference, tracked;
  std::vector<double> track_ms;
};

// Tracks every frame of `source` (at most max_frames, -1: all) against `reference`. The
// frame count of the reference (a track keyed by frame index: its last index + 1 less its
// frame_index_offset; keyed by timestamp: its size) must equal the source's (SensorInfo's
// frame_count where known, else the frames it yields): "invalid_argument" naming both counts,
// spec.source_spec and spec.reference_spec otherwise.
Expected<TrackedSequence> TrackSequence(const ReferenceSequenceSpec& spec,
                                        capture::FrameSource* source,
                                        const capture::SkeletonTrack& reference,
                                        const capture::SkeletonTrackerOptions& tracker = {},
                                        int max_frames = -1);

struct SequenceResult {
  ReferenceSequenceSpec spec;
  SequenceAgreement raw;
  std::optional<SequenceAgreement> offset;  // nullopt: no offsets (see the header)
  SequenceAgreement baseline;
  std::optional<SequenceAgreement> baseline20;
  std::vector<double> track_ms;
  int offset_fit_frames = 0;  // frames the sequence's offsets were fitted on
};

// A picture written with --pictures.
struct WorstFrame {
  std::string sequence, path;
  int frame = 0;
  double error_cm = 0;
};

struct KinectReferenceRun {
  std::vector<SequenceResult> sequences;
  std::vector<WorstFrame> pictures;
};

// The figures of tracked sequences (offsets left one subject out, baselines); joints20: per
// sequence, the 20-joint reference for baseline20 (empty or shorter: none).
std::vector<SequenceResult> EvaluateSequences(
    const std::vector<TrackedSequence>& sequences,
    const std::vector<std::vector<std::optional<JointPoints>>>& joints20 = {});

// Opens, tracks and evaluates every sequence of the options, then writes the pictures.
Expected<KinectReferenceRun> RunKinectReferenceEval(const KinectReferenceOptions& options);

// The tables of the header. for_json: also the tables "sequences", "worst" and "pictures"
// (sequence, frame, error_cm, path), a figure without data left out (else "-").
proto::Report KinectReferenceReport(const KinectReferenceRun& run, bool for_json);
// The line naming the worst action (see the header).
std::string WorstActionLine(const KinectReferenceRun& run);

struct KinectReferenceCommand {
  KinectReferenceOptions options;
  std::optional<std::string> json_path;
};

// The flags of this mode (beside --json, which TrackerFlags() has).
std::set<std::string> KinectReferenceFlags();
// Whether the command line asks for this mode: any of its flags given.
bool WantsKinectReference(const CommandLine& command_line);

// Errors (code "usage", naming the flags): --source without --reference or the reverse,
// --dataset with --source, --sequences without --dataset, an unknown --dataset kind (the
// message lists utd-mhad) or one without ":ROOT", a root without any aA_sS_tT folder, a
// --sequences name not among the root's, a flag of the synthetic scenes (--scenario, ...);
// "not_found" for a root that is not a folder; "io" for an unwritable --json or a --pictures
// folder that cannot be created.
Expected<KinectReferenceCommand> ParseKinectReferenceCommand(const CommandLine& command_line);

// Runs the command: the tables on stdout, the worst action, the pictures written, --json.
int RunKinectReferenceCommand(const CommandLine& command_line);

}  // namespace reenact::eval
