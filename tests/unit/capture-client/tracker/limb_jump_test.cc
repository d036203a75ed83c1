// A limb that jumps out of its data (limb_jump.h), on the ray-cast capsule body's exact points.
#include "capture-client/tracker/limb_jump.h"

#include <gtest/gtest.h>

#include "capture-client/tracker/extremity_pose.h"
#include "common/error/check.h"
#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using S = BodySegment;
using tracker_test::FacingSensor;
using tracker_test::PointsObservation;
using tracker_test::RenderBodyPoints;

constexpr int kRightForearm = static_cast<int>(S::kRightForearm);

// A fit at `pose` as FitBody reports one: the posed body and each segment's support in obs.
// The expected support is set to the support of the pose the data show (`shown`), where the
// exact points cover every visible part: the area in view of each segment there.
BodyFitResult At(const ArticulatedBody& body, const ArticulatedPose& pose,
                 const ArticulatedPose& shown, const BodyObservation& obs) {
  const double inlier_m = BodyFitOptions{}.inlier_m;
  BodyFitResult r;
  r.pose = pose;
  r.posed = body.Pose(pose);
  r.support = SupportAt(body, r.posed, obs, inlier_m).support;
  const SegmentSupport in_view = SupportAt(body, body.Pose(shown), obs, inlier_m);
  for (int k = 0; k < kBodySegmentCount; ++k) r.expected_support[k] = in_view.support[k];
  return r;
}

double EndMove(const ArticulatedBody& body, const BodyFitResult& a, const BodyFitResult& b) {
  return (LimbEnd(body, a.posed, Limb::kRightArm) - LimbEnd(body, b.posed, Limb::kRightArm)).norm();
}

// Facing the sensor 3 m away, arms down, and the right arm swung up behind the head: the hand
// 25 cm above the head's top and 25 cm behind it, where the head hides the forearm.
struct ArmBehindTheHead {
  ArticulatedBody body{BodyShape::FromHeight(1.75)};
  ArticulatedPose down = FacingSensor(body);
  ArticulatedPose behind =
      ReachLimb(body, down, Limb::kRightArm,
                body.Pose(down).skeleton[Joint::kHead] + Eigen::Vector3d(0, -0.25, 0.25));
};

TEST(LimbJump, AnArmSwungBehindTheHeadJumpsOutOfItsData) {
  const ArmBehindTheHead s;
  const BodyObservation data = PointsObservation(RenderBodyPoints(s.body, s.down));
  const BodyFitResult own = At(s.body, s.down, s.down, data);
  const BodyFitResult behind = At(s.body, s.behind, s.down, data);
  const double move = EndMove(s.body, own, behind);
  ASSERT_GT(move, 0.6);
  ASSERT_GT(own.support[kRightForearm], 100);  // the forearm down is in view
  EXPECT_EQ(behind.support[kRightForearm], 0);
  EXPECT_EQ(LimbJumpedFromItsData(s.body, own, behind), Limb::kRightArm);
  // Not when it moved less than the limit.
  LimbJumpOptions far;
  far.max_move_m = move + 0.01;
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, own, behind, far));
  // Nor the other way: from behind the head to the arm's data.
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, behind, own));
  // Nothing moved.
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, own, own));
}

TEST(LimbJump, AForearmTheOwnFitHasOutOfViewIsNoJump) {
  // The data show the right hand behind the back, below the waist; the own fit has it there,
  // and the other fit behind the shoulder blades, 59 cm away and hidden as well: both fits
  // leave the forearm without points, and the data cannot tell them apart.
  const ArmBehindTheHead s;
  const PosedBody3 down = s.body.Pose(s.down);
  const ArticulatedPose low =
      ReachLimb(s.body, s.down, Limb::kRightArm,
                down.skeleton[Joint::kWaist] + Eigen::Vector3d(0, 0.15, 0.25));
  const ArticulatedPose blades = ReachLimb(
      s.body, s.down, Limb::kRightArm, down.skeleton[Joint::kNeck] + Eigen::Vector3d(0, 0.1, 0.3));
  const BodyObservation data = PointsObservation(RenderBodyPoints(s.body, low));
  const BodyFitResult own = At(s.body, low, low, data);
  const BodyFitResult other = At(s.body, blades, low, data);
  ASSERT_GT(EndMove(s.body, own, other), 0.5);
  ASSERT_EQ(own.support[kRightForearm], 0);
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, own, other));
}

TEST(LimbJump, TheOwnFitsForearmIsInViewAndTheOtherKeepsLessThanItsShare) {
  // The support counts as given, the arm swung behind the head as above. The own fit's forearm
  // has 100 points of 200 expected (in view at in_view_share 0.5); the other's 10 is a tenth
  // of them (not less), 9 is less.
  const ArmBehindTheHead s;
  const BodyObservation data = PointsObservation(RenderBodyPoints(s.body, s.down));
  BodyFitResult own = At(s.body, s.down, s.down, data), other = At(s.body, s.behind, s.down, data);
  own.support[kRightForearm] = 100;
  own.expected_support[kRightForearm] = 200;
  other.support[kRightForearm] = 10;
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, own, other));
  other.support[kRightForearm] = 9;
  EXPECT_EQ(LimbJumpedFromItsData(s.body, own, other), Limb::kRightArm);
  // 99 points of 200 expected: not in view.
  own.support[kRightForearm] = 99;
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, own, other));
  // Shares at their ends: in view at 0 with any point, a kept share of 0 never jumps, one of 1
  // jumps with any point lost.
  LimbJumpOptions o;
  o.in_view_share = 0;
  EXPECT_EQ(LimbJumpedFromItsData(s.body, own, other, o), Limb::kRightArm);
  o.kept_share = 0;
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, own, other, o));
  o.kept_share = 1;
  other.support[kRightForearm] = 98;
  EXPECT_EQ(LimbJumpedFromItsData(s.body, own, other, o), Limb::kRightArm);
}

TEST(LimbJump, ASwapOfTheArmsDataIsNoJump) {
  // The support counts as given, the right arm swung behind the head as above: the right
  // forearm loses its 100 points. When the left forearm takes at least half of them (here from
  // none), the arms' data were swapped, not left: no jump. Taking 49 is less than half.
  const ArmBehindTheHead s;
  const BodyObservation data = PointsObservation(RenderBodyPoints(s.body, s.down));
  BodyFitResult own = At(s.body, s.down, s.down, data), other = At(s.body, s.behind, s.down, data);
  constexpr int kLeftForearm = static_cast<int>(S::kLeftForearm);
  own.support[kRightForearm] = 100;
  own.expected_support[kRightForearm] = 150;
  own.support[kLeftForearm] = 0;
  other.support[kRightForearm] = 0;
  other.support[kLeftForearm] = 50;
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, own, other));
  other.support[kLeftForearm] = 49;
  EXPECT_EQ(LimbJumpedFromItsData(s.body, own, other), Limb::kRightArm);
  // The legs' pairs are their own: a left shin's gain does not excuse the right forearm.
  other.support[static_cast<int>(S::kLeftShin)] += 100;
  EXPECT_EQ(LimbJumpedFromItsData(s.body, own, other), Limb::kRightArm);
  // With swap_share 0, a fit in which the left forearm lost no points counts as swapped.
  LimbJumpOptions o;
  o.swap_share = 0;
  EXPECT_FALSE(LimbJumpedFromItsData(s.body, own, other, o));
}

TEST(LimbJump, BadOptionsAreABug) {
  const ArmBehindTheHead s;
  const BodyObservation data = PointsObservation(RenderBodyPoints(s.body, s.down));
  const BodyFitResult own = At(s.body, s.down, s.down, data);
  for (const auto& bad : {LimbJumpOptions{.max_move_m = 0}, LimbJumpOptions{.in_view_share = -0.1},
                          LimbJumpOptions{.kept_share = 1.5}, LimbJumpOptions{.swap_share = 2}}) {
    EXPECT_THROW(bad.Check(), CheckError);
    EXPECT_THROW(LimbJumpedFromItsData(s.body, own, own, bad), CheckError);
  }
}

}  // namespace
}  // namespace reenact::capture
