// Crossed limbs: recognised in the body's own frame, swapped by reaching, and a fit that took
// the other limb's points undone by fitting from the swap (ray-cast capsule body, exact data).
#include "capture-client/tracker/limb_swap.h"

#include <gtest/gtest.h>

#include <numbers>

#include "capture-client/tracker/body_fit.h"
#include "capture-client/tracker/extremity_pose.h"
#include "common/error/check.h"
#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using S = BodySegment;
using tracker_test::FacingSensor;
using tracker_test::PointsObservation;
using tracker_test::RenderBodyPoints;
using tracker_test::Rx;
using tracker_test::Ry;
using tracker_test::Rz;

constexpr double kPi = std::numbers::pi;

BodyFitOptions PointsOnly() {
  BodyFitOptions o;
  o.silhouette_weight = 0;
  return o;
}

// Facing the sensor, both forearms raised forward in front of the body (elbows bent 90
// degrees), each hand in front of its own shoulder: every arm point visible.
ArticulatedPose ForearmsForward(const ArticulatedBody& body) {
  ArticulatedPose p = FacingSensor(body);
  for (const S s : {S::kLeftUpperArm, S::kRightUpperArm}) p.local[static_cast<int>(s)] = Ry(-0.3);
  for (const S s : {S::kLeftForearm, S::kRightForearm}) p.hinge_angle[static_cast<int>(s)] = 1.4;
  return p;
}

double HandError(const ArticulatedBody& body, const ArticulatedPose& a, const ArticulatedPose& b,
                 Joint hand) {
  return (body.Pose(a).skeleton[hand] - body.Pose(b).skeleton[hand]).norm();
}

TEST(LimbSwap, CrossedEndsAreRecognisedInTheBodysOwnFrame) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArticulatedPose rest = FacingSensor(body);
  EXPECT_FALSE(LimbsCrossed(body, body.Pose(rest), kArms));
  EXPECT_FALSE(LimbsCrossed(body, body.Pose(rest), kLegs));
  // Turned away from the sensor: the arms still hang at their own sides.
  ArticulatedPose away = rest;
  away.root_rotation = Rz(kPi) * rest.root_rotation;
  EXPECT_FALSE(LimbsCrossed(body, body.Pose(away), kArms));

  // Forearms forward, the left hand reaching 10 cm to the right of the right hand: crossed.
  const ArticulatedPose forearms = ForearmsForward(body);
  const PosedBody3 posed = body.Pose(forearms);
  EXPECT_FALSE(LimbsCrossed(body, posed, kArms));
  const Eigen::Vector3d left_axis =
      posed.sensor_from_segment[static_cast<int>(S::kChest)].linear().col(1);
  const Eigen::Vector3d forward = 0.25 * rest.root_rotation.col(0);
  const ArticulatedPose arm_across = ReachLimb(
      body, forearms, Limb::kLeftArm, LimbEnd(body, posed, Limb::kRightArm) - 0.1 * left_axis);
  EXPECT_TRUE(LimbsCrossed(body, body.Pose(arm_across), kArms));
  EXPECT_FALSE(LimbsCrossed(body, body.Pose(arm_across), kLegs));
  // The left foot stepped across in front of the right one.
  const ArticulatedPose leg_across =
      ReachLimb(body, rest, Limb::kLeftLeg,
                LimbEnd(body, posed, Limb::kRightLeg) + forward - 0.1 * left_axis);
  EXPECT_TRUE(LimbsCrossed(body, body.Pose(leg_across), kLegs));
  // Both hands at one point in front of the chest: level, not crossed.
  const Eigen::Vector3d front = posed.skeleton[Joint::kTorso] + forward;
  const ArticulatedPose joined =
      ReachLimb(body, ReachLimb(body, rest, Limb::kLeftArm, front), Limb::kRightArm, front);
  const PosedBody3 j = body.Pose(joined);
  ASSERT_LT((LimbEnd(body, j, Limb::kLeftArm) - LimbEnd(body, j, Limb::kRightArm)).norm(), 1e-6);
  EXPECT_FALSE(LimbsCrossed(body, j, kArms));
  // The margin: the left hand 2 cm to the right of the right one is crossed by more than 1 cm,
  // not by more than 3.
  const ArticulatedPose past = ReachLimb(body, joined, Limb::kLeftArm, front - 0.02 * left_axis);
  EXPECT_TRUE(LimbsCrossed(body, body.Pose(past), kArms, 0.01));
  EXPECT_FALSE(LimbsCrossed(body, body.Pose(past), kArms, 0.03));
}

TEST(LimbSwap, SwappedLimbsReachEachOthersEnds) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  ArticulatedPose pose = ForearmsForward(body);
  pose.local[static_cast<int>(S::kLeftUpperArm)] = Rx(0.2) * Ry(-0.3);  // out to the left
  const PosedBody3 before = body.Pose(pose);
  const ArticulatedPose swapped = SwappedLimbs(body, pose, kArms);
  const PosedBody3 after = body.Pose(swapped);
  // Both ends are within the other arm's reach (the shoulders lie 37 cm apart, the reach
  // from shoulder to fingertip 64 cm), so ReachLimb places them exactly.
  EXPECT_LT((LimbEnd(body, after, Limb::kLeftArm) - LimbEnd(body, before, Limb::kRightArm)).norm(),
            1e-6);
  EXPECT_LT((LimbEnd(body, after, Limb::kRightArm) - LimbEnd(body, before, Limb::kLeftArm)).norm(),
            1e-6);
  EXPECT_TRUE(LimbsCrossed(body, after, kArms));
  // Nothing else moves.
  for (const Joint j : {Joint::kHead, Joint::kNeck, Joint::kLeftShoulder, Joint::kRightShoulder,
                        Joint::kLeftFoot, Joint::kRightFoot})
    EXPECT_LT((after.skeleton[j] - before.skeleton[j]).norm(), 1e-12);
}

TEST(LimbSwap, TheFitFromTheSwapUndoesArmsThatTookEachOthersPoints) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArticulatedPose truth = ForearmsForward(body);
  const BodyObservation obs = PointsObservation(RenderBodyPoints(body, truth));
  // The arms crossed, each hand on the other's: the model's left arm reaches across the chest
  // for the right forearm's points, the right arm for the left's.
  const ArticulatedPose crossed = SwappedLimbs(body, truth, kArms);
  ASSERT_TRUE(LimbsCrossed(body, body.Pose(crossed), kArms));
  const BodyFitResult local = FitBody(body, crossed, obs, PointsOnly());
  // The local fit keeps them crossed: each arm is held by the points it took.
  EXPECT_TRUE(LimbsCrossed(body, local.posed, kArms));
  EXPECT_GT(HandError(body, local.pose, truth, Joint::kLeftHand), 0.2);
  EXPECT_GT(HandError(body, local.pose, truth, Joint::kRightHand), 0.2);

  // From the swap, each hand starts on its own forearm's end; the fit converges on exact data
  // (bound: 2 cm, well within a forearm's radius), and costs clearly less than the crossed
  // fit (the tracker's margin is 5 %).
  const BodyFitResult swapped =
      FitBody(body, SwappedLimbs(body, local.pose, kArms), obs, PointsOnly());
  EXPECT_FALSE(LimbsCrossed(body, swapped.posed, kArms));
  EXPECT_LT(HandError(body, swapped.pose, truth, Joint::kLeftHand), 0.02);
  EXPECT_LT(HandError(body, swapped.pose, truth, Joint::kRightHand), 0.02);
  EXPECT_LT(swapped.cost, 0.95 * local.cost);
}

TEST(LimbSwap, ArmsCrossedByTheSubjectStayCrossed) {
  // The subject crosses its arms in front of the chest; fitted there, the swap's fit costs more,
  // so the tracker keeps the crossed arms.
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArticulatedPose truth = SwappedLimbs(body, ForearmsForward(body), kArms);
  const BodyObservation obs = PointsObservation(RenderBodyPoints(body, truth));
  const BodyFitResult at_truth = FitBody(body, truth, obs, PointsOnly());
  ASSERT_TRUE(LimbsCrossed(body, at_truth.posed, kArms));
  const BodyFitResult swapped =
      FitBody(body, SwappedLimbs(body, at_truth.pose, kArms), obs, PointsOnly());
  EXPECT_GT(swapped.cost, at_truth.cost);
}

// The walk's arms as the tracker met them: the subject swung the right forearm up in front
// faster than the fit followed (`previous`, the prediction, still has it hanging), and the fit
// reached across with the left arm, swung back at the subject's side, for the right forearm's
// points, while the right arm, without data, slid behind the back (`crossed`).
struct ArmTakenAcross {
  ArticulatedPose truth, previous, crossed;
};
ArmTakenAcross TakeArmAcross(const ArticulatedBody& body) {
  ArmTakenAcross a;
  a.truth = ForearmsForward(body);
  a.truth.local[static_cast<int>(S::kLeftUpperArm)] = Ry(0.5);  // swung back
  a.truth.hinge_angle[static_cast<int>(S::kLeftForearm)] = 0.2;
  a.previous = a.truth;
  a.previous.local[static_cast<int>(S::kRightUpperArm)] = Eigen::Matrix3d::Identity();
  a.previous.hinge_angle[static_cast<int>(S::kRightForearm)] = 0.1;
  const PosedBody3 truth = body.Pose(a.truth);
  const Eigen::Isometry3d& pelvis = truth.sensor_from_segment[static_cast<int>(S::kPelvis)];
  // 25 cm behind the waist (x is forward), 10 cm to its left (y).
  const Eigen::Vector3d behind_the_back =
      truth.skeleton[Joint::kWaist] - 0.25 * pelvis.linear().col(0) + 0.1 * pelvis.linear().col(1);
  a.crossed = ReachLimb(
      body, ReachLimb(body, a.previous, Limb::kLeftArm, LimbEnd(body, truth, Limb::kRightArm)),
      Limb::kRightArm, behind_the_back);
  return a;
}

TEST(LimbSwap, ReturnedLimbTakesThePreviousAnglesAndTheOtherReachesTheData) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArmTakenAcross a = TakeArmAcross(body);
  ASSERT_FALSE(LimbsCrossed(body, body.Pose(a.previous), kArms));
  ASSERT_TRUE(LimbsCrossed(body, body.Pose(a.crossed), kArms));
  const ArticulatedPose returned = ReturnedLimb(body, a.crossed, a.previous, kArms, Limb::kLeftArm);
  // The left arm's angles are the previous pose's, exactly.
  const int upper = static_cast<int>(S::kLeftUpperArm), lower = static_cast<int>(S::kLeftForearm);
  EXPECT_LT((returned.local[upper] - a.previous.local[upper]).norm(), 1e-12);
  EXPECT_EQ(returned.hinge_angle[lower], a.previous.hinge_angle[lower]);
  // The right arm ends where the left one ended: its own end in the truth, within its reach,
  // so ReachLimb places it exactly.
  const PosedBody3 before = body.Pose(a.crossed);
  const PosedBody3 posed = body.Pose(returned);
  EXPECT_LT((LimbEnd(body, posed, Limb::kRightArm) - LimbEnd(body, before, Limb::kLeftArm)).norm(),
            1e-6);
  EXPECT_FALSE(LimbsCrossed(body, posed, kArms));
  for (const Joint j : {Joint::kHead, Joint::kNeck, Joint::kLeftShoulder, Joint::kRightShoulder,
                        Joint::kLeftFoot, Joint::kRightFoot})
    EXPECT_LT((posed.skeleton[j] - before.skeleton[j]).norm(), 1e-12);
  // The taker must be one of the pair.
  EXPECT_THROW(ReturnedLimb(body, a.crossed, a.previous, kArms, Limb::kLeftLeg), CheckError);
}

TEST(LimbSwap, TheFitFromTheReturnedLimbUndoesAnArmTakenAcross) {
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  const ArmTakenAcross a = TakeArmAcross(body);
  const BodyObservation obs = PointsObservation(RenderBodyPoints(body, a.truth));
  const BodyFitResult local = FitBody(body, a.crossed, obs, PointsOnly());
  ASSERT_TRUE(LimbsCrossed(body, local.posed, kArms));
  EXPECT_GT(HandError(body, local.pose, a.truth, Joint::kLeftHand), 0.2);
  // The swap moves the left arm to where the fit left the right one, behind the back: a guess.
  // Its fit leaves the left hand there (measured: 20 cm off, bound 10).
  const BodyFitResult swapped =
      FitBody(body, SwappedLimbs(body, local.pose, kArms), obs, PointsOnly());
  const BodyFitResult returned = FitBody(
      body, ReturnedLimb(body, local.pose, a.previous, kArms, Limb::kLeftArm), obs, PointsOnly());
  EXPECT_GT(HandError(body, swapped.pose, a.truth, Joint::kLeftHand), 0.1);
  // From the returned left arm, the right arm starts on its own forearm's points and the left
  // one on its own; the fit converges on exact data (bound 2 cm, as the swap's test above) and
  // costs clearly less than the crossed fit and the swap's (the tracker's margin is 5 %).
  EXPECT_FALSE(LimbsCrossed(body, returned.posed, kArms));
  EXPECT_LT(HandError(body, returned.pose, a.truth, Joint::kLeftHand), 0.02);
  EXPECT_LT(HandError(body, returned.pose, a.truth, Joint::kRightHand), 0.02);
  EXPECT_LT(returned.cost, 0.95 * local.cost);
  EXPECT_LT(returned.cost, 0.95 * swapped.cost);
}

TEST(LimbSwap, TurnedAroundFacesBackOnTheSameLimbEnds) {
  // Facing the sensor with the left arm out sideways and the left knee bent: turned around,
  // the body faces away, its waist where it was, and each limb ends where the opposite one
  // ended. The spine is straight, so the turned shoulders and hips lie exactly where the
  // opposite ones were and every end is in reach (ReachLimb places it exactly).
  const ArticulatedBody body(BodyShape::FromHeight(1.75));
  ArticulatedPose pose = FacingSensor(body);
  pose.local[static_cast<int>(S::kLeftUpperArm)] = Rx(-1.2);
  pose.local[static_cast<int>(S::kLeftThigh)] = Ry(0.5);
  pose.hinge_angle[static_cast<int>(S::kLeftShin)] = 0.9;
  const Eigen::Vector3d up(0, -1, 0);
  const PosedBody3 before = body.Pose(pose);
  const PosedBody3 after = body.Pose(TurnedAround(body, pose, up));
  const auto forward = [&](const PosedBody3& p) {
    return p.sensor_from_segment[static_cast<int>(S::kPelvis)].linear().col(0);
  };
  EXPECT_NEAR(forward(after).dot(forward(before)), -1.0, 1e-9);
  EXPECT_LT((after.skeleton[Joint::kWaist] - before.skeleton[Joint::kWaist]).norm(), 1e-12);
  const std::pair<Limb, Limb> opposite[] = {{Limb::kLeftArm, Limb::kRightArm},
                                            {Limb::kRightArm, Limb::kLeftArm},
                                            {Limb::kLeftLeg, Limb::kRightLeg},
                                            {Limb::kRightLeg, Limb::kLeftLeg}};
  for (const auto& [limb, other] : opposite)
    EXPECT_LT((LimbEnd(body, after, limb) - LimbEnd(body, before, other)).norm(), 1e-6)
        << static_cast<int>(limb);
  for (const auto& [joint, other] : {std::pair{Joint::kLeftShoulder, Joint::kRightShoulder},
                                     {Joint::kLeftHip, Joint::kRightHip}})
    EXPECT_LT((after.skeleton[joint] - before.skeleton[other]).norm(), 1e-9);

  // Without an up there is no turn: the limbs are swapped in place, as SwappedLimbs does.
  const PosedBody3 unturned = body.Pose(TurnedAround(body, pose, Eigen::Vector3d::Zero()));
  const PosedBody3 swapped = body.Pose(SwappedLimbs(body, SwappedLimbs(body, pose, kArms), kLegs));
  EXPECT_NEAR(forward(unturned).dot(forward(before)), 1.0, 1e-9);
  for (int j = 0; j < kJointCount; ++j)
    EXPECT_LT((unturned.skeleton.position[j] - swapped.skeleton.position[j]).norm(), 1e-12) << j;
}

}  // namespace
}  // namespace reenact::capture
