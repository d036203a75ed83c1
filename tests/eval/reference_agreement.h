#pragma once
// How far a skeleton tracker's joints lie from a reference tracker's on the same frames
// (`reenact-eval tracker --dataset utd-mhad:ROOT`, kinect_reference_eval.h): the figures of
// one sequence and their aggregates over groups of sequences. Neither side is ground truth:
// the reference is another tracker's estimate (the Kinect SDK's), with errors of its own.
//
// Poses are JointPoints: one optional position per joint of any joint set (our 16 joints, or
// the Kinect's 20 for the baseline), metres, one frame for both sides of a comparison; a
// joint not given is nullopt (a Skeleton joint with confidence 0). A sequence is a list of
// frames in order (index 0 = the sequence's first frame); a frame without a reference, or
// without an estimate, is nullopt.
//
// Definitions, per sequence:
//   moving joint   a joint whose reference position (in the sensor frame, not relative to
//                  the body) lies more than min_travel_m (10 cm) from its mean position over
//                  the sequence on some frame (max_f |r_j(f) - mean_f r_j| > 0.10 m; frames
//                  without the joint left out). With the baseline below this reproduces the
//                  figures 7.9 cm (all joints) and 19.9 cm (moving joints) of the Kinect's 20
//                  joints on the 108 sequences of UTD-MHAD; the max pairwise distance (16.2)
//                  or the distance from the first frame (17.2) do not, nor positions relative
//                  to the hip centre (21.4).
//   frame error    on a frame with both a reference and an estimate: the mean over the
//                  joints both give of |estimate_j - reference_j| ("all"), and the same over
//                  the moving joints both give ("moving"; none such: no moving error);
//   MPJPE          the mean of the frame errors over the frames that have one, cm;
//   PCK            the share of the compared joint estimates (both sides give the joint, all
//                  frames pooled) within pck_m (10 cm) of the reference;
//   joint share    over the frames with an estimate: the share of the reference's joints the
//                  estimate gives too;
//   tracked share  over the frames from warmup_frames on (index >= warmup_frames, the first
//                  second: 30 frames at 30 fps) that have a reference: the share with an
//                  estimate;
//   first estimate the index of the first frame with an estimate (= the frames before it).
// Per group of sequences (aggregate): sequences and frames summed; tracked share pooled over
// the group's frames; first estimate the median over the sequences that got one; MPJPE,
// moving MPJPE, PCK and joint share the mean over the sequences that have the figure (every
// sequence weighs the same, however long: the baseline figures above are means over
// sequences). A figure without data (no estimate at all) is nullopt, never NaN.
//
// The baseline (MeanPoseAtCentre): the sequence's mean pose placed at the reference's own
// hip centre on every frame: joint j on frame f at c(f) + mean_g (r_j(g) - c(g)), c the
// reference's centre joint. What a tracker that knew where the person stands but not how
// they move would score: a tracker should be well below it on the moving joints.
//
// Constant offsets (JointOffsetFit): the reference and our tracker put joints at different
// places inside the body (the Kinect's hip centre, shoulders and hands are not where our
// cylinders meet), a difference that turns with the body. Per joint, the mean of
// (reference_j - estimate_j) expressed in the estimate's body frame (BodyFrame of
// joint_error_table.h: x the subject's left to its right, y forward, z up the spine, built on
// the estimate alone, so the correction never looks at the reference of the frame it
// corrects), over the frames added; applied as estimate_j + B offset_j on any frame whose
// estimate has a body frame B. Where the estimate's body frame is undefined, the joint's mean
// offset in the sensor frame (over every frame added) is added instead. A joint never
// added has a zero offset. The fit of one subject's sequences is taken from the other
// subjects' (leave one subject out): kinect_reference_eval.h.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "common/skeleton/skeleton.h"

namespace reenact::eval {

using JointPoints = std::vector<std::optional<Eigen::Vector3d>>;

inline constexpr double kMovingTravelM = 0.10;
inline constexpr double kPckThresholdM = 0.10;

struct AgreementOptions {
  double min_travel_m = kMovingTravelM;  // > 0
  double pck_m = kPckThresholdM;         // > 0
  int warmup_frames = 30;                // >= 0
  void Check() const;                    // throws CheckError
};

// Our 16 joints: the position of every joint with confidence > 0 and finite coordinates.
JointPoints PointsOf(const Skeleton& skeleton);

// The moving joints of a sequence's reference (see the header), one flag per joint of its
// largest frame (empty without frames).
std::vector<bool> MovingJoints(const std::vector<std::optional<JointPoints>>& reference,
                               double min_travel_m = kMovingTravelM);

// The baseline of the header for every frame of the reference: nullopt where the reference
// has no frame or no centre; a joint nullopt where the reference never gives it together with
// its centre. centre: an index into the reference's joints.
std::vector<std::optional<JointPoints>> MeanPoseAtCentre(
    const std::vector<std::optional<JointPoints>>& reference, int centre);

// One frame compared (both sides present).
struct FrameAgreement {
  int reference_joints = 0;  // joints the reference gives
  int compared = 0;          // of them, the estimate gives too
  int within = 0;            // of those, within pck_m
  double sum_m = 0;          // sum of the compared joints' distances
  int moving_compared = 0;
  double moving_sum_m = 0;
  std::optional<double> MeanM() const;        // sum_m / compared
  std::optional<double> MovingMeanM() const;  // moving_sum_m / moving_compared
};

// Joints beyond either pose's size count as not given; moving may be shorter (the rest not
// moving).
FrameAgreement CompareFrame(const JointPoints& estimate, const JointPoints& reference,
                            const std::vector<bool>& moving, double pck_m = kPckThresholdM);

// One sequence's figures (see the header); errors in cm, shares in [0, 1].
struct SequenceAgreement {
  int frames = 0;        // frames with a reference
  int tracked = 0;       // of them, with an estimate
  int warm_frames = 0;   // frames with a reference from warmup_frames on
  int warm_tracked = 0;  // of them, with an estimate
  std::optional<int> first_estimate;
  int moving_joints = 0;
  long long reference_joints = 0, given_joints = 0;  // over the frames with an estimate
  long long compared = 0, within = 0;                // joint estimates compared, within pck_m
  std::optional<double> mpjpe_cm, moving_mpjpe_cm, pck, joint_share, tracked_share;
  // Per frame: the frame error "all" in cm where there is one (same length as the input).
  std::vector<std::optional<double>> frame_error_cm;
};

// estimate and reference: one entry per frame (the longer one decides the frame count; a
// missing entry is nullopt). moving: MovingJoints(reference) as the caller chose it.
SequenceAgreement CompareSequence(const std::vector<std::optional<JointPoints>>& estimate,
                                  const std::vector<std::optional<JointPoints>>& reference,
                                  const std::vector<bool>& moving,
                                  const AgreementOptions& options = {});

// A group's figures (see the header).
struct GroupAgreement {
  int sequences = 0, frames = 0, tracked = 0, warm_frames = 0, warm_tracked = 0;
  int untracked_sequences = 0;  // sequences without any estimate
  std::optional<double> tracked_share, first_estimate_median;
  std::optional<double> mpjpe_cm, moving_mpjpe_cm, pck, joint_share;
};

GroupAgreement Aggregate(const std::vector<const SequenceAgreement*>& sequences);

// Constant per-joint offsets (see the header), our 16 joints.
struct JointOffsets {
  std::array<Eigen::Vector3d, kJointCount> in_body;    // metres, the estimate's body frame
  std::array<Eigen::Vector3d, kJointCount> in_sensor;  // metres, the fallback
  JointOffsets();  // all zero
  // The estimate with every given joint moved by its offset (missing joints stay missing).
  Skeleton Apply(const Skeleton& estimate) const;
};

class JointOffsetFit {
 public:
  JointOffsetFit();  // no frames: every offset zero
  // One frame: both skeletons in one frame; joints missing from either side are left out.
  void Add(const Skeleton& estimate, const Skeleton& reference);
  // Adds another fit's frames (to fit on several subjects).
  void Merge(const JointOffsetFit& other);
  JointOffsets Offsets() const;
  int frames() const { return frames_; }

 private:
  int frames_ = 0;
  std::array<Eigen::Vector3d, kJointCount> body_sum_, sensor_sum_;
  std::array<int, kJointCount> body_n_{}, sensor_n_{};
};

}  // namespace reenact::eval
