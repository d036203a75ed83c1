#pragma once
// Re-posing limbs that the local fit (body_fit.h) cannot follow: an arm raised overhead in
// one frame, a kick. Gauss-Newton only pulls a capsule to points near it, and points beyond
// outlier_m of every capsule pull nothing; so for each limb (upper arm and forearm, or thigh
// and shin with the foot) we try a fixed set of hypotheses with the rest of the body held:
// the upper segment pointing along each of the 26 directions of a cube's faces, edges and
// corners (in its parent's frame: chest or pelvis), straight, or bent by 60 or 110 degrees
// in four planes around the bone (234), and the upper segment held where it is with the
// lower one bent by 20, 45, 70, 95 or 120 degrees in held_twists planes around the bone (40
// at the default 8), each kept within the joint limits. The held ones re-pose a forearm or
// shin alone: where the upper segment is still tracked, a cube direction up to 22.5 degrees
// off it moves the upper segment off its points, and costs more than the pose that lost the
// forearm (a forearm swung back while the subject stands at the image's edge). A
// hypothesis's cost is the fit's cost (body_fit.h) with every data point's residual the
// smaller of its residual to the held body and to the limb, capped at cap_m (so points of
// other objects cost the same for every hypothesis), plus the limb's silhouette/free-space
// samples.
//
// The search is for a limb the model lost, so only lost points justify re-posing one: the
// points beyond outlier_m of every capsule. A limb is searched when more than min_lost_share
// of the points are lost within its reach, and only its hypotheses that take at least half of
// those (bring them within outlier_m of the limb) count; the cheapest of them is the limb's
// candidate when it costs at least min_gain (relative) less than the current pose. Of the
// limbs' candidates, the one taking the most lost points (then: the larger decrease) is
// applied, the lost points are found again, and the other limbs follow in the same way.
// Without this rule the cheapest hypothesis anywhere wins, and the limb searched first takes
// it: where a body part is larger than its capsule (a skinned head), its points lie within
// outlier_m but are explained poorly, and an arm raised beside it costs less while the lost
// points are the other hand's.
//
// Points that no hypothesis of the limb can reach closer than they already are (farther from
// the limb's joint than its length allows) cost the same for every hypothesis and are summed
// once.

#include <vector>

#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"

namespace reenact::capture {

struct LimbSearchOptions {
  double cap_m = 0.25;            // residual cap, > 0
  double min_gain = 0.02;         // relative cost decrease required, [0, 1)
  double min_lost_share = 0.005;  // share of the points lost within a limb's reach, [0, 1]
  int held_twists = 8;            // hinge-plane turns with the upper segment held, >= 0 (0: none)

  void Check() const;
};

// One posing of a limb (in-range joint values): the upper segment's rotation in its parent's
// frame and the hinge's angle (radians), and the index of the upper segment's direction: 0-25
// the cube's, kHeldLimbDirection for the held ones.
struct LimbHypothesis {
  int direction = 0;
  Eigen::Matrix3d upper_local = Eigen::Matrix3d::Identity();
  double hinge_angle = 0;
};
inline constexpr int kHeldLimbDirection = 26;

// The search's hypotheses for `limb` at `pose` (above), in that order, each clamped to the
// limits. One that the limits clamp onto an earlier one of the same direction (within 1e-9
// rad) is left out, since it could only tie with it: a thigh's twist beyond its range, a
// direction outside the hip's cone (22 % of a leg's 274 on the procedural turn-and-kick and
// CMU walk; an arm's stay distinct). Options out of range are a bug.
std::vector<LimbHypothesis> LimbHypotheses(const ArticulatedPose& pose, Limb limb,
                                           const JointLimits& limits,
                                           const LimbSearchOptions& options = {});

// Returns the number of limbs re-posed (0 to 4); *pose is changed only for those.
int SearchLimbs(const ArticulatedBody& body, const BodyObservation& observation,
                const BodyFitOptions& fit, const JointLimits& limits,
                const LimbSearchOptions& options, ArticulatedPose* pose);

}  // namespace reenact::capture
