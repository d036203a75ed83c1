#pragma once
// Poses from geodesic extremities (geodesic_extremities.h): the re-initialisation hypothesis
// of the tracker's recovery (body_start.h).
//
// ReachLimb places one limb's end at a target, the rest of the body held, analytically (two
// bones, law of cosines): with the limb's root joint j (shoulder or hip), upper length a and
// reach b to the end (arm: elbow to the fingertips, forearm + forearm_radius, the end of the
// forearm capsule; leg: knee to the sole, shin + ankle_height), and d = |target - j| clamped
// to [|a - b| + 1 mm, a + b]:
//    upper direction  u = cos(alpha) n + sin(alpha) m,   cos(alpha) = (a^2 + d^2 - b^2) / (2 a d)
// where n = (target - j) / d and m is the unit bend hint made perpendicular to n (the side
// the elbow or knee goes to: the elbow behind the arm, -forward; the knee in front, +forward;
// the body's forward, else its down, when the hint is parallel to n). The hinge angle is the
// angle between u and the lower bone, the hinge axis set so that the lower bone bends the way
// the hinge allows (forearm forwards of the upper arm's x axis, shin backwards, see
// articulated_body.h). The result is clamped to the joint limits (a target out of reach
// leaves the limb straight towards it).
//
// PoseFromExtremities turns a start pose (an upright body at a heading, heading.h) into the
// hypothesis: the hands labelled by the extremities reached by the arms, the feet by the
// legs; with two hands (feet), the one more to the body's left goes to the left limb; with
// one, the nearer limb root's side (shoulders, hips). Limbs without an extremity, or whose
// end in the start pose already lies within min_offset_m of it, keep the start pose's (a
// hypothesis that changes nothing is no new hypothesis; front and back fit nearly alike, so
// one would only add a chance to pick the wrong one).
// Frames: the sensor frame (OpenCV axes, metres).

#include <Eigen/Core>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/geodesic_extremities.h"

namespace reenact::capture {

// The limb's end (fingertip or sole, as above) in pose `posed`.
Eigen::Vector3d LimbEnd(const ArticulatedBody& body, const PosedBody3& posed, Limb limb);

// The pose with limb's end at target (see above); non-finite targets leave the pose as it is.
ArticulatedPose ReachLimb(const ArticulatedBody& body, const ArticulatedPose& pose, Limb limb,
                          const Eigen::Vector3d& target, const JointLimits& limits = {});

// The hypothesis (see above); returns how many limbs were placed in *placed when given.
ArticulatedPose PoseFromExtremities(const ArticulatedBody& body, const ArticulatedPose& start,
                                    const GeodesicExtremities& extremities,
                                    const JointLimits& limits = {}, int* placed = nullptr,
                                    double min_offset_m = 0);

}  // namespace reenact::capture
