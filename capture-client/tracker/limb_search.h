#pragma once
// Re-posing limbs that the local fit (body_fit.h) cannot follow: an arm raised overhead in
// one frame, a kick. Gauss-Newton only pulls a capsule to points near it, and points beyond
// outlier_m of every capsule pull nothing; so for each limb (upper arm and forearm, or thigh
// and shin with the foot) we try a fixed set of hypotheses with the rest of the body held:
// the upper segment pointing along each of the 26 directions of a cube's faces, edges and
// corners (in its parent's frame: chest or pelvis), straight, or bent by 60 or 110 degrees
// in four planes around the bone (234 in all), each kept within the joint limits. A
// hypothesis's cost is the fit's cost (body_fit.h) with every data point's residual the
// smaller of its residual to the held body and to the limb, capped at cap_m (so points of
// other objects cost the same for every hypothesis), plus the limb's silhouette/free-space
// samples. The cheapest hypothesis replaces the limb's pose when it costs at least min_gain
// (relative) less than the current pose. Limbs are searched in turn (left arm, right arm,
// left leg, right leg), each against the body as re-posed so far.
//
// The same hypotheses, ranked (RankLimbHypotheses), start the tracker's limb re-check: a
// limb that lies on the wrong side of the body has its points explained, worse, by the torso,
// so no coarse hypothesis beats its current pose, but one near the truth does once fitted.
// Points that no hypothesis of the limb can reach closer than they already are (farther from
// the limb's joint than its length allows) cost the same for every hypothesis and are summed
// once.

#include <vector>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"

namespace reenact::capture {

struct LimbSearchOptions {
  double cap_m = 0.25;     // residual cap, > 0
  double min_gain = 0.02;  // relative cost decrease required, [0, 1)

  void Check() const;
};

// Returns the number of limbs re-posed (0 to 4); *pose is changed only for those.
int SearchLimbs(const ArticulatedBody& body, const BodyObservation& observation,
                const BodyFitOptions& fit, const JointLimits& limits,
                const LimbSearchOptions& options, ArticulatedPose* pose);

// The `count` (>= 0) cheapest hypotheses for `limb` by the search's cost, at most one per
// direction of the upper segment, cheapest first; `pose` with only that limb re-posed. Empty
// for an observation without points.
std::vector<ArticulatedPose> RankLimbHypotheses(const ArticulatedBody& body,
                                                const BodyObservation& observation,
                                                const BodyFitOptions& fit,
                                                const JointLimits& limits,
                                                const LimbSearchOptions& options,
                                                const ArticulatedPose& pose, Limb limb, int count);

}  // namespace reenact::capture
