#pragma once
// A limb that jumps out of its data: an alternative fit whose hand or foot lies far from where
// the track's own fit has it, in view, while the data show (almost) none of that limb there.
//
// The fit's free-space term charges a capsule only where it projects onto pixels that show
// something farther away or nothing at all; a limb moved behind the body, where the trunk or
// the head hides it, costs nothing there. So a fit from another start (the turned starts of
// turned_starts_step.h) can swing an arm behind the head, leave its points to the trunk, and
// come out cheaper on a frame the own fit explains poorly, although its forearm then has no
// points where the own fit's had most of those it expects in view.
//
// The test is on the limb's end segment (forearm or shin), which carries the hand or foot; the
// upper segment keeps the points about its joint wherever the limb swings. It asks for the own
// fit's end segment in view, because a limb the own fit has (nearly) hidden tells nothing: on
// the CMU walk 131_01 seen at 15 frames a second, turned fits that moved such a forearm 0.5 m
// (1-9 points on about 30 expected, none after) were right. A turned fit that re-finds a limb
// the own fit had wrong moves it as far but keeps a fair share of its end segment's points
// (72-100 % in the cases measured there). Nor is a swap: a fit in which the opposite limb's end
// segment took at least half of the points this one left (the arms' data swapped, not left;
// the crossed-limb code, limb_swap.h, judges swaps): counted as a jump, it would discard a fit
// that may have put swapped limbs right.
// Frames: the sensor frame (OpenCV axes, metres).

#include <optional>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"

namespace reenact::capture {

struct LimbJumpOptions {
  double max_move_m = 0.5;     // a limb's end moved farther than this (> 0, metres)
  double in_view_share = 0.5;  // the own fit's end segment in view: support >= this share of
                               // its expected support (BodyFitResult), [0, 1]
  double kept_share = 0.1;     // jumped: the other fit's end segment keeps less than this share
                               // of the own fit's support, [0, 1]
  double swap_share = 0.5;     // swapped, not jumped: the opposite limb's end segment gained at
                               // least this share of the points lost, [0, 1]
  void Check() const;
};

// The first limb (in Limb's order) that jumped from `own` to `other` (above): its end (LimbEnd,
// extremity_pose.h) more than max_move_m apart in the two, its end segment in view in `own`
// with some support, with less than kept_share of that support in `other`, and not swapped
// (the opposite limb's end segment gained less than swap_share of the points lost); nullopt
// when none. Options out of range are a bug.
std::optional<Limb> LimbJumpedFromItsData(const ArticulatedBody& body, const BodyFitResult& own,
                                          const BodyFitResult& other,
                                          const LimbJumpOptions& options = {});

}  // namespace reenact::capture
