#pragma once
// Joint error after the joint-definition offset measured on the calibration frame is removed,
// for `reenact-eval tracker`'s aligned_mpjpe_cm.
//
// A tracker and a motion-capture rig put a joint at different places on the same body (a rig's
// hips at the crotch, its shoulders where a collarbone starts; the tracker's where its capsules
// meet). Validations of depth trackers against motion capture separate that from the tracking
// error with a static trial: while the subject stands still, both record it, the offset of
// each joint between them is fixed in the tracked segment's own frame, and the tracked segment
// carries it on every later frame. Here the static trial is the tracker's calibration frame
// (the subject in the calibration pose). It uses the truth on that frame only, so what
// remains is the tracking error plus how far the offset changes with the pose (a rig's joint
// that a segment does not carry rigidly), not a fit to the clip.
//
// Segment frames, built on the tracked skeleton (3x3, columns x, y, z):
//   trunk joints (head, neck, torso, waist, shoulders, hips): B = BodyFrame
//     (joint_error_table.h);
//   a limb joint (elbow, hand, knee, foot), whose bone runs from its parent joint (shoulder ->
//     elbow, elbow -> hand, hip -> knee, knee -> foot) in direction d: R B, R the smallest
//     rotation taking the rest direction -B.z (every limb hanging down along the spine) onto
//     d, or the half turn about B.y (forward) where d points up along the spine (within
//     1e-6 rad). So an offset turns with the limb as the limb swings: the top of an arm held
//     out is its outer side when it hangs.
// On the calibration frame c, offset_j = F_j(c)^T (truth_j(c) - estimate_j(c)) (metres);
// on any frame, aligned_j = estimate_j + F_j offset_j.

#include <Eigen/Core>
#include <array>
#include <optional>

#include "common/skeleton/skeleton.h"

namespace reenact::eval {

// The segment frame of joint j in skeleton s (above), or nullopt when the body frame is
// undefined (joint_error_table.h), j or its parent is missing, or the bone is shorter than
// 1 mm.
std::optional<Eigen::Matrix3d> SegmentFrame(const Skeleton& s, Joint j);

class CalibrationAlignment {
 public:
  // The offsets of the calibration frame (both skeletons in one frame), or nullopt when some
  // joint is missing from either or some segment frame of the estimate is undefined.
  static std::optional<CalibrationAlignment> FromCalibrationFrame(const Skeleton& estimate,
                                                                  const Skeleton& truth);

  // The estimate with every joint moved by its offset in the estimate's segment frame; a
  // joint whose frame is undefined in this estimate stays where it is.
  Skeleton Aligned(const Skeleton& estimate) const;

  // The offsets, metres, in each joint's segment frame.
  const std::array<Eigen::Vector3d, kJointCount>& offsets() const { return offset_; }

 private:
  std::array<Eigen::Vector3d, kJointCount> offset_{};
};

}  // namespace reenact::eval
