#pragma once
// Left/right limb swaps: a fit whose left limb explains the right limb's points and the right
// limb the left's (each reaching across the body for the other's data). Gauss-Newton cannot
// undo it: each limb is held by the data it took, and moving either one alone costs more. A
// walk shows it most where the subject turns, the hands then tens of centimetres off.
//
// The swap is recognised as limbs crossed: the left limb's end (LimbEnd: fingertip or sole)
// lies to the right of the right limb's end, along the parent segment's left axis (the chest's
// for the arms, the pelvis's for the legs; y, see articulated_body.h). A subject may cross its
// arms, so crossing only proposes the hypothesis SwappedLimbs: each limb reaching the other's
// end (ReachLimb, extremity_pose.h); the tracker fits from there and keeps the result only when
// it costs clearly less (uncross_step.h).
// Frames: the sensor frame (OpenCV axes, metres).

#include "capture-client/tracker/articulated_body.h"

namespace reenact::capture {

// A left limb and its right counterpart: the arms or the legs.
struct LimbPair {
  Limb left = Limb::kLeftArm;
  Limb right = Limb::kRightArm;
};
inline constexpr LimbPair kArms{Limb::kLeftArm, Limb::kRightArm};
inline constexpr LimbPair kLegs{Limb::kLeftLeg, Limb::kRightLeg};

// True when the pair's ends lie crossed (see above) by more than margin_m (>= 0, metres):
// hands that touch in front of the body lie level, and are not.
bool LimbsCrossed(const ArticulatedBody& body, const PosedBody3& posed, LimbPair pair,
                  double margin_m = 0.01);

// `pose` with the left limb reaching the right limb's end and the right limb the left's; the
// rest of the body as in `pose`. Ends out of reach leave the limb straight towards them.
ArticulatedPose SwappedLimbs(const ArticulatedBody& body, const ArticulatedPose& pose,
                             LimbPair pair, const JointLimits& limits = {});

// The other way to undo a crossing: one limb took the other's data while the other lost it
// (an arm swung forward faster than the fit followed, and the hidden arm behind the body
// reached across for its points). `pose` with `taker` back at its joint angles in `previous`
// (the upper segment's rotation in its parent's frame, the hinge angle) and the other limb
// reaching where `taker` ends in `pose`. SwappedLimbs moves the taker to the other limb's end
// instead, which is a guess wherever the fit left that limb without data, and a fit from a
// guess can cost more than the crossed one; the taker's previous angles are where the data
// last held it. Ends out of reach leave the other limb straight towards the end. `taker` is
// one of the pair (else a bug).
ArticulatedPose ReturnedLimb(const ArticulatedBody& body, const ArticulatedPose& pose,
                             const ArticulatedPose& previous, LimbPair pair, Limb taker,
                             const JointLimits& limits = {});

// Front and back: `pose` turned half a turn about `up` (unit, the floor's normal; about the
// waist joint), each limb then reaching where the opposite limb of `pose` ended, so that the
// turned body lies on the same data with its left and right exchanged: the other answer to a
// depth silhouette's front/back ambiguity. A zero up leaves the pose unturned (limbs swapped).
ArticulatedPose TurnedAround(const ArticulatedBody& body, const ArticulatedPose& pose,
                             const Eigen::Vector3d& up, const JointLimits& limits = {});

}  // namespace reenact::capture
