// Limbs reaching targets (targets from the forward kinematics of known limb poses) and the
// extremity hypothesis on a ray-cast capsule body.
#include "capture-client/tracker/extremity_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using S = BodySegment;
using tracker_test::FacingSensor;
using tracker_test::LevelFloor;
using tracker_test::RenderBodyPoints;
using tracker_test::Rx;
using tracker_test::Ry;

constexpr double kPi = std::numbers::pi;

TEST(ReachLimb, ReachesTargetsOfKnownLimbPoses) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArticulatedPose rest = FacingSensor(body);
  // Limb poses within the joint limits, bent and straight.
  struct Case {
    Limb limb;
    Eigen::Matrix3d upper;
    double hinge;
  };
  const Case cases[] = {
      {Limb::kLeftArm, Rx(kPi / 2), 0.0},                // out sideways, straight
      {Limb::kRightArm, Rx(0.95 * kPi), 0.3},            // raised overhead
      {Limb::kLeftArm, Ry(-kPi / 2), 1.2},               // forward, bent
      {Limb::kRightArm, Rx(-kPi / 4) * Ry(-0.5), 2.0},   // a guard
      {Limb::kRightLeg, Ry(-kPi / 2), 0.4},              // a front kick
      {Limb::kLeftLeg, Ry(-0.6), 1.5},                   // knee up, shin down
      {Limb::kLeftLeg, Eigen::Matrix3d::Identity(), 0},  // standing
  };
  for (const Case& c : cases) {
    ArticulatedPose truth = rest;
    truth.local[static_cast<int>(LimbUpper(c.limb))] = c.upper;
    truth.hinge_angle[static_cast<int>(LimbLower(c.limb))] = c.hinge;
    const Eigen::Vector3d target = LimbEnd(body, body.Pose(truth), c.limb);
    const ArticulatedPose reached = ReachLimb(body, rest, c.limb, target);
    EXPECT_LT((LimbEnd(body, body.Pose(reached), c.limb) - target).norm(), 1e-3)
        << static_cast<int>(c.limb) << " hinge " << c.hinge;
    // The rest of the body is held.
    const Skeleton a = body.Pose(rest).skeleton, b = body.Pose(reached).skeleton;
    for (Joint j : {Joint::kHead, Joint::kWaist, Joint::kLeftShoulder, Joint::kRightHip})
      EXPECT_LT((a[j] - b[j]).norm(), 1e-9);
  }
}

TEST(ReachLimb, ATargetOutOfReachGetsTheLimbStraightTowardsIt) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArticulatedPose rest = FacingSensor(body);
  const PosedBody3 posed = body.Pose(rest);
  const Eigen::Vector3d shoulder = posed.skeleton[Joint::kLeftShoulder];
  const Eigen::Vector3d target = shoulder + Eigen::Vector3d(3, 0, 0);  // 3 m to the side
  const ArticulatedPose r = ReachLimb(body, rest, Limb::kLeftArm, target);
  const Eigen::Vector3d end = LimbEnd(body, body.Pose(r), Limb::kLeftArm);
  EXPECT_GT((end - shoulder).normalized().dot(Eigen::Vector3d::UnitX()), 1 - 1e-4);
  const double reach = body.shape().upper_arm + body.shape().forearm + body.shape().forearm_radius;
  EXPECT_NEAR((end - shoulder).norm(), reach, 2e-3);
  EXPECT_LT(r.hinge_angle[static_cast<int>(S::kLeftForearm)], 0.1);
}

TEST(ReachLimb, ATargetAtTheJointOrNotFiniteIsDefined) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArticulatedPose rest = FacingSensor(body);
  const PosedBody3 posed = body.Pose(rest);
  const ArticulatedPose same =
      ReachLimb(body, rest, Limb::kRightArm,
                Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_TRUE(
      body.Pose(same).skeleton[Joint::kRightHand].isApprox(posed.skeleton[Joint::kRightHand]));
  // At the shoulder itself: folded as far as the elbow allows, every joint finite.
  const ArticulatedPose folded =
      ReachLimb(body, rest, Limb::kRightArm, posed.skeleton[Joint::kRightShoulder]);
  const Skeleton s = body.Pose(folded).skeleton;
  for (int j = 0; j < kJointCount; ++j) EXPECT_TRUE(s.position[j].allFinite());
  EXPECT_LE(folded.hinge_angle[static_cast<int>(S::kRightForearm)], JointLimits{}.elbow_max);
}

TEST(PoseFromExtremities, PlacesTheLimbsOfARaisedArmAndAKick) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArticulatedPose rest = FacingSensor(body);
  ArticulatedPose truth = rest;
  truth.local[static_cast<int>(S::kRightUpperArm)] = Rx(-kPi * 0.8);  // raised, out to the right
  truth.local[static_cast<int>(S::kLeftUpperArm)] = Rx(kPi / 2);      // out to the left
  truth.local[static_cast<int>(S::kRightThigh)] = Ry(-1.0);           // a kick forward
  truth.hinge_angle[static_cast<int>(S::kRightShin)] = 0.3;
  const Skeleton t = body.Pose(truth).skeleton;
  const GeodesicExtremities g =
      FindGeodesicExtremities(RenderBodyPoints(body, truth), LevelFloor());
  int placed = 0;
  const ArticulatedPose h = PoseFromExtremities(body, rest, g, {}, &placed);
  EXPECT_EQ(placed, 4);
  const Skeleton s = body.Pose(h).skeleton;
  // Bound: the end reaches the extremity exactly, and the extremity lies within the end cap
  // plus a voxel of the true end (geodesic_extremities_test.cc), so the hands are within
  // forearm_radius + voxel (7 cm) of the truth; the joint between is placed by the bend
  // hint, not observed, and not compared. The kicking foot: the extremity anywhere on the foot
  // capsule (foot_length + foot_radius + voxel, 19 cm) from the reach's sole.
  EXPECT_LT((s[Joint::kRightHand] - t[Joint::kRightHand]).norm(), 0.07 + 0.04);
  EXPECT_LT((s[Joint::kLeftHand] - t[Joint::kLeftHand]).norm(), 0.07 + 0.04);
  EXPECT_LT((s[Joint::kRightFoot] - t[Joint::kRightFoot]).norm(), 0.19 + 0.08);
  // Left and right are not swapped: each hand on its own side.
  EXPECT_LT(s[Joint::kRightHand].x(), 0);  // the subject's right is the sensor's -x
  EXPECT_GT(s[Joint::kLeftHand].x(), 0);
}

TEST(PoseFromExtremities, LimbsAlreadyAtTheirExtremitiesAreNotPlaced) {
  // The body standing as the start pose stands: every extremity lies at the start's limb
  // ends (the feet) or is none (hanging hands lie in the thighs' surface), so with a
  // min_offset of 25 cm nothing is placed and the start comes back unchanged.
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArticulatedPose rest = FacingSensor(body);
  const GeodesicExtremities g = FindGeodesicExtremities(RenderBodyPoints(body, rest), LevelFloor());
  ASSERT_FALSE(g.WithLabel(ExtremityLabel::kFoot).empty());
  int placed = -1;
  const ArticulatedPose h = PoseFromExtremities(body, rest, g, {}, &placed, 0.25);
  EXPECT_EQ(placed, 0);
  const Skeleton a = body.Pose(rest).skeleton, b = body.Pose(h).skeleton;
  for (int j = 0; j < kJointCount; ++j) EXPECT_LT((a.position[j] - b.position[j]).norm(), 1e-9);
}

}  // namespace
}  // namespace reenact::capture
