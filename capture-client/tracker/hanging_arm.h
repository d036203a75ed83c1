#pragma once
// An arm the fit has lost, started again from hanging at its shoulder.
//
// An arm hidden behind the body for a while drifts (nothing in the data holds it), and when it
// reappears hanging beside the hip its points lie within outlier_m of the trunk's and the
// thigh's capsules, which explain them, worse: nothing counts them as lost, so the limb search
// (limb_search.h) is not started, and the local fit does not reach them from where the arm
// drifted. On CesiumMan's walk-handheld the right forearm showed 102-291 points a frame after
// frames 110-170 behind the body, all of them owned by the pelvis, lower spine and right thigh
// at the tracked pose, 39-97 % by the arm at the true one (docs/measurements.md, session 46).
// A walking or standing arm mostly hangs, so an arm the fit hardly supports is also fitted from
// there. Started everywhere (the limb re-check, skeleton_tracker.h) the search finds poses
// that take the trunk's and the legs' poorly explained points instead (set B 8.03 -> 10.82 cm).
//
// Rule: where `fit` leaves an arm's two segments with less than min_support of their expected
// support (BodyFitResult), the body is fitted from `fit`'s pose with that arm hanging (its upper
// arm's local rotation about the body's left axis by -swing_rad, 0 and +swing_rad, i.e. along
// the chest's down axis swung forward, straight down and back; the elbow bent by elbow_rad),
// each within the joint limits. The cheapest of those fits that moves no other limb's elbow,
// hand, knee or foot by more than max_other_move_m (it would re-interpret their data) replaces
// `fit` when it costs at most (1 - gain) times as much, each with the points it leaves beyond
// outlier_m counted (CostWithLostPoints, body_fit.h). The left arm is tried first, then the right
// from the result. An arm hidden behind the body mostly stays: hanging, it would stand where
// the silhouette shows nothing, which the silhouette term charges. Not always: on the
// procedural CMU 131_01 walk with dropped frames (seed 1, frame 194) a right hand raised
// behind the head was pulled down with 3 of 91 expected points, 62.7 cm off two frames later
// (docs/measurements.md, session 47).
// Frames: the sensor frame (OpenCV axes, metres).

#include <vector>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"

namespace reenact::capture {

struct HangingArmOptions {
  double min_support = 0.2;       // [0, 1]; 0: off
  double swing_rad = 0.4;         // >= 0
  double elbow_rad = 0.3;         // [0, pi)
  double gain = 0.1;              // [0, 1)
  double max_other_move_m = 0.1;  // > 0

  void Check() const;
};

// `pose` with `arm` (kLeftArm or kRightArm: CHECK) hanging, one pose per swing (above).
std::vector<ArticulatedPose> HangingArmStarts(const ArticulatedPose& pose, Limb arm,
                                              const JointLimits& limits,
                                              const HangingArmOptions& options = {});

// The rule above; returns the fit to keep. Options out of range are a bug.
BodyFitResult HangUnsupportedArms(const ArticulatedBody& body, BodyFitResult fit,
                                  const BodyObservation& observation,
                                  const BodyFitOptions& fit_options, const JointLimits& limits,
                                  const HangingArmOptions& options = {});

}  // namespace reenact::capture
