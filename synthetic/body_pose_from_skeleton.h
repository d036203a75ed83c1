#pragma once
// Retargeting onto the procedural body (body_model.h): the BodyPose whose forward kinematics
// (PoseBody) best reproduces a target skeleton's bone directions. The body keeps its own
// BodyDimensions, so only directions transfer (as on the skinned body, skinned_body.h); the
// waist's floor position is the target's, its height PoseBody's (the lower ankle
// ankle_height above the floor).
//
// Frames: the target in the world frame of body_model.h (z up, metres). The body frame B is
// Rz(root_yaw) * Rz(-pi/2) (x forward, y left, z up); the lower and upper torso frames L, U
// and the limb frames as PoseBody builds them.
//
// Bones (unit directions d = (b - a) / |b - a|, target t against fitted f):
//   spine      waist -> torso, torso -> neck (waist -> neck when the torso is missing)
//   lines      r_shoulder -> l_shoulder, r_hip -> l_hip
//   head       neck -> head
//   limbs      shoulder -> elbow, elbow -> hand, hip -> knee, knee -> foot (each side)
// A bone is used when both of its joints are present (confidence > 0), finite, and at least
// kMinBoneLength apart; otherwise its DOFs keep their rest value (0) unless another bone
// fixes them.
//
// Steps, each stage in the frame its parent stage fixed:
//  1. root_yaw: the horizontal part of the hip line is body +y (hips hang on B directly);
//     when that part is shorter than kMinBoneLength, the shoulder line's; when both are, 0.
//  2. spine_bend, spine_twist: analytic start (bend = 2 atan2(x, z) of waist -> torso in B,
//     twist from the shoulder line's turn about z), then Levenberg-Marquardt on the spine
//     bones' and the shoulder line's direction errors.
//  3. head_pitch: exact, from neck -> head in U, less the rest offset's angle
//     atan2(head_forward, head_rise).
//  4. arms (in U) and legs (in B): upper bone direction u = R(a, f) (0, 0, -1) with
//     R = Rx(s a) Ry(-f), s = +1 left, -1 right, is solved in closed form on both branches
//     (cos f >= 0 and cos f < 0, which differ by a half turn about the bone); the hinge
//     (elbow Ry(-e), knee Ry(+k)) from the lower bone projected onto the hinge plane; then
//     Levenberg-Marquardt on both bones' direction errors (the arm has no humeral rotation,
//     so a forearm out of the elbow's plane is fitted in the least-squares sense); the branch
//     of lower final error wins (ties: cos f >= 0).
//  5. ankle and ankle_roll: the sole level (the 16-joint skeleton has no toes): the foot's
//     forward and left axes horizontal, within the limits.
//  6. root_xy: the target's waist (x, y); without a waist the hips' mid-point; else 0.
// Every angle is kept within BodyPoseLimits (projected steps); root_yaw in (-pi, pi].
//
// Exactness: for a skeleton made by PoseBody from a pose within the limits (any
// BodyDimensions with the same head offset), the refitted pose reproduces every joint to
// solver tolerance (about 1e-9 m); angles may differ where the joints do not fix them (a
// straight limb's branch, the abduction of a limb pointing straight forward).
// Degenerate input (missing joints, zero-length bones, vertical or parallel lines) gives a
// defined pose: never NaN, every angle within the limits.

#include <string>

#include "common/skeleton/skeleton.h"
#include "synthetic/body_model.h"

namespace reenact::capture {

// Bones shorter than this (metres) carry no direction.
inline constexpr double kMinBoneLength = 1e-6;

// The range of each DOF, radians (min <= max). Wide enough for the scenarios' motions
// (turn-and-kick's arm overhead: flexion 168 degrees; raise-and-crouch's squat: hips 105,
// knees 135, bend 50) and a real walk.
struct BodyPoseLimits {
  double spine_bend_min = -0.5, spine_bend_max = 1.4;
  double spine_twist_max = 0.9;  // |spine_twist|
  double head_pitch_max = 0.9;   // |head_pitch|
  double arm_abduction_min = -0.6, arm_abduction_max = 3.1;
  double arm_flexion_min = -1.2, arm_flexion_max = 3.1;
  double elbow_max = 2.6;  // elbow in [0, elbow_max]
  double leg_flexion_min = -0.8, leg_flexion_max = 2.3;
  double leg_abduction_min = -0.6, leg_abduction_max = 1.3;
  double knee_max = 2.6;  // knee in [0, knee_max]
  double ankle_min = -0.7, ankle_max = 0.9;
  double ankle_roll_max = 0.6;  // |ankle_roll|

  // Throws CheckError unless every range is finite, non-empty and shorter than a full turn
  // (max >= 0 for the symmetric and hinge ranges).
  void Check() const;
};

struct BodyPoseFromSkeletonOptions {
  BodyDimensions dims;  // the procedural body whose pose is fitted
  BodyPoseLimits limits;
  int iterations = 30;  // Levenberg-Marquardt iterations per stage, >= 0 (0: analytic only)

  // Throws CheckError when a field is out of range.
  void Check() const;
};

struct BodyPoseFit {
  BodyPose pose;
  // Root mean square over the bones used of |f - t| (unit directions; 2 sin(angle / 2)),
  // 0 when no bone was used.
  double rms_direction_error = 0;
  int bones_used = 0;    // of the 13 bones listed above
  std::string yaw_from;  // "hips", "shoulders" or "none"
};

BodyPoseFit BodyPoseFromSkeleton(const Skeleton& target,
                                 const BodyPoseFromSkeletonOptions& options = {});

}  // namespace reenact::capture
