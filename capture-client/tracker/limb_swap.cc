#include "capture-client/tracker/limb_swap.h"

#include <numbers>

#include "capture-client/tracker/extremity_pose.h"
#include "capture-client/tracker/heading.h"
#include "common/error/check.h"

namespace reenact::capture {

bool LimbsCrossed(const ArticulatedBody& body, const PosedBody3& posed, LimbPair pair,
                  double margin_m) {
  const Eigen::Vector3d left_axis =
      posed.sensor_from_segment[SegmentParent(LimbUpper(pair.left))].linear().col(1);
  return (LimbEnd(body, posed, pair.left) - LimbEnd(body, posed, pair.right)).dot(left_axis) <
         -margin_m;
}

ArticulatedPose SwappedLimbs(const ArticulatedBody& body, const ArticulatedPose& pose,
                             LimbPair pair, const JointLimits& limits) {
  const PosedBody3 posed = body.Pose(pose);
  const Eigen::Vector3d left_end = LimbEnd(body, posed, pair.left);
  const Eigen::Vector3d right_end = LimbEnd(body, posed, pair.right);
  const ArticulatedPose reached = ReachLimb(body, pose, pair.left, right_end, limits);
  return ReachLimb(body, reached, pair.right, left_end, limits);
}

ArticulatedPose ReturnedLimb(const ArticulatedBody& body, const ArticulatedPose& pose,
                             const ArticulatedPose& previous, LimbPair pair, Limb taker,
                             const JointLimits& limits) {
  REENACT_CHECK(taker == pair.left || taker == pair.right, "taker must be one of the pair");
  const Limb other = taker == pair.left ? pair.right : pair.left;
  const Eigen::Vector3d taken_end = LimbEnd(body, body.Pose(pose), taker);
  ArticulatedPose returned = pose;
  const int upper = static_cast<int>(LimbUpper(taker)), lower = static_cast<int>(LimbLower(taker));
  returned.local[upper] = previous.local[upper];
  returned.hinge_angle[lower] = previous.hinge_angle[lower];
  return ReachLimb(body, returned, other, taken_end, limits);
}

ArticulatedPose TurnedAround(const ArticulatedBody& body, const ArticulatedPose& pose,
                             const Eigen::Vector3d& up, const JointLimits& limits) {
  const PosedBody3 posed = body.Pose(pose);
  ArticulatedPose turned = TurnedBy(pose, up, std::numbers::pi);
  for (const LimbPair pair : {kArms, kLegs}) {
    turned = ReachLimb(body, turned, pair.left, LimbEnd(body, posed, pair.right), limits);
    turned = ReachLimb(body, turned, pair.right, LimbEnd(body, posed, pair.left), limits);
  }
  return turned;
}

}  // namespace reenact::capture
