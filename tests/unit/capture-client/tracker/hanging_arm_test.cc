// An arm the fit has lost, started again from hanging (hanging_arm.h), on ray-cast capsule
// bodies seen by the Kinect-like camera (silhouette, depth and points, as the detector gives
// them): the truth's own capsules, so the data are exact.
#include "capture-client/tracker/hanging_arm.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "capture-client/tracker/extremity_pose.h"
#include "common/error/check.h"
#include "tests/unit/capture-client/tracker/capsule_body_scene.h"

namespace reenact::capture {
namespace {

using tracker_test::FacingSensor;
using tracker_test::SceneBlob;
using tracker_test::SceneCapsule;

constexpr int kRightUpperArm = static_cast<int>(BodySegment::kRightUpperArm);
constexpr int kRightForearm = static_cast<int>(BodySegment::kRightForearm);

const ArticulatedBody& Body() {
  static const ArticulatedBody body(BodyShape::FromHeight(1.75));
  return body;
}

// The observation of the body posed as `truth` (every 2nd pixel, as SceneBlob).
BodyObservation Seen(const ArticulatedPose& truth) {
  const PosedBody3 posed = Body().Pose(truth);
  std::vector<SceneCapsule> figure;
  for (const BodyCapsule& c : Body().capsules()) {
    const Eigen::Isometry3d& t = posed.sensor_from_segment[static_cast<int>(c.segment)];
    figure.push_back({t * c.a, t * c.b, c.radius});
  }
  const PersonBlob blob = SceneBlob(figure);
  return MakeObservation(PinholeCamera::KinectLike(), blob.grid_step_px, blob.mask, blob.depth_m,
                         blob.points, blob.pixels, 1);
}

double HandError(const ArticulatedPose& truth, const BodyFitResult& fit) {
  return (fit.posed.skeleton[Joint::kRightHand] - Body().Pose(truth).skeleton[Joint::kRightHand])
      .norm();
}

// The right hand behind the back below the waist, where the trunk hides the forearm.
ArticulatedPose BehindTheBack(const ArticulatedPose& pose) {
  return ReachLimb(Body(), pose, Limb::kRightArm,
                   Body().Pose(pose).skeleton[Joint::kWaist] + Eigen::Vector3d(0, 0.15, 0.25));
}

// Standing at 3 m turned side-on, its right side to the sensor (a quarter turn about the
// body's up from facing it), the right arm swung forward by 0.35 rad as in a walk: it hangs in
// front of the hip.
ArticulatedPose SideOnArmSwung() {
  ArticulatedPose pose = FacingSensor(Body());
  pose.root_rotation = pose.root_rotation * tracker_test::Rz(-std::acos(0.0));
  pose.local[kRightUpperArm] = ExpRotation(Eigen::Vector3d(0, -0.35, 0));
  return pose;
}

TEST(HangingArm, AnArmLostBehindTheBackIsFoundHangingInFrontOfTheHip) {
  // The data show the right arm hanging in front of the hip; the fit starts with it behind the
  // back, as a track that lost it while hidden. Its points lie within outlier_m of the trunk's
  // and thigh's capsules, so the local fit does not reach them (measured: hand 18 cm off, the
  // arm without support). Started hanging, the fit finds it (measured 0.8 cm, cost 0.008
  // against 0.154); bound: the data are exact and the forward swing starts 0.05 rad from the
  // truth's, so the hand comes within 3 cm.
  const ArticulatedPose truth = SideOnArmSwung();
  const BodyObservation seen = Seen(truth);
  const BodyFitOptions fo;
  const BodyFitResult lost = FitBody(Body(), BehindTheBack(truth), seen, fo);
  ASSERT_GT(HandError(truth, lost), 0.15);
  ASSERT_LT(lost.support[kRightUpperArm] + lost.support[kRightForearm],
            0.2 * (lost.expected_support[kRightUpperArm] + lost.expected_support[kRightForearm]));
  const BodyFitResult found = HangUnsupportedArms(Body(), lost, seen, fo, {});
  EXPECT_LT(HandError(truth, found), 0.03);
  EXPECT_LT(found.cost, 0.9 * lost.cost);
  // Off (min_support 0): the fit as it was.
  HangingArmOptions off;
  off.min_support = 0;
  EXPECT_EQ(HangUnsupportedArms(Body(), lost, seen, fo, {}, off).posed.skeleton.position,
            lost.posed.skeleton.position);
}

TEST(HangingArm, AnArmTheDataHideStaysWhereItIs) {
  // The truth has the right arm behind the back, facing the sensor: the trunk hides it, and a
  // hanging arm would stand beside the trunk where the silhouette shows nothing. The fit from
  // the truth has no support for the arm, so hanging starts are fitted, but none is taken.
  const ArticulatedPose truth = BehindTheBack(FacingSensor(Body()));
  const BodyObservation seen = Seen(truth);
  const BodyFitOptions fo;
  const BodyFitResult fit = FitBody(Body(), truth, seen, fo);
  ASSERT_LT(fit.support[kRightUpperArm] + fit.support[kRightForearm],
            0.2 * (fit.expected_support[kRightUpperArm] + fit.expected_support[kRightForearm]));
  const BodyFitResult kept = HangUnsupportedArms(Body(), fit, seen, fo, {});
  EXPECT_EQ(kept.posed.skeleton.position, fit.posed.skeleton.position);
}

TEST(HangingArm, ASupportedArmIsNotTried) {
  // Arms held out sideways, in view: both arms are supported, nothing is tried, even where a
  // hanging start would fit (min_support 1 tries every arm with less than all its expected
  // support; the held-out arm then stays, as hanging costs more).
  ArticulatedPose out = FacingSensor(Body());
  out.local[static_cast<int>(BodySegment::kLeftUpperArm)] = tracker_test::Rx(std::acos(0.0));
  out.local[kRightUpperArm] = tracker_test::Rx(-std::acos(0.0));
  const BodyObservation seen = Seen(out);
  const BodyFitOptions fo;
  const BodyFitResult fit = FitBody(Body(), out, seen, fo);
  EXPECT_EQ(HangUnsupportedArms(Body(), fit, seen, fo, {}).posed.skeleton.position,
            fit.posed.skeleton.position);
  HangingArmOptions every;
  every.min_support = 1;
  EXPECT_LT(HandError(out, HangUnsupportedArms(Body(), fit, seen, fo, {}, every)), 0.03);
}

TEST(HangingArm, StartsHangFromTheShoulderAndBadInputIsRefused) {
  // Straight down (swing 0): the upper arm's local rotation is the rest's (hanging along the
  // chest's down axis), the elbow bent by elbow_rad; the swings turn it about the left axis.
  const ArticulatedPose pose = BehindTheBack(FacingSensor(Body()));
  const HangingArmOptions o;
  const auto starts = HangingArmStarts(pose, Limb::kRightArm, {}, o);
  ASSERT_EQ(starts.size(), 3u);
  EXPECT_TRUE(starts[1].local[kRightUpperArm].isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  EXPECT_DOUBLE_EQ(starts[1].hinge_angle[kRightForearm], o.elbow_rad);
  const double turned = Eigen::AngleAxisd(starts[0].local[kRightUpperArm].transpose() *
                                          starts[2].local[kRightUpperArm])
                            .angle();
  EXPECT_NEAR(turned, 2 * o.swing_rad, 1e-9);
  // The rest of the body is the pose's.
  EXPECT_TRUE(starts[1].root_rotation.isApprox(pose.root_rotation, 1e-12));
  EXPECT_TRUE(starts[1].local[static_cast<int>(BodySegment::kLeftUpperArm)].isApprox(
      pose.local[static_cast<int>(BodySegment::kLeftUpperArm)], 1e-12));
  EXPECT_THROW(HangingArmStarts(pose, Limb::kLeftLeg, {}, o), CheckError);
  EXPECT_THROW(HangingArmOptions{.min_support = 1.5}.Check(), CheckError);
  EXPECT_THROW(HangingArmOptions{.gain = 1}.Check(), CheckError);
  EXPECT_THROW(HangingArmOptions{.max_other_move_m = 0}.Check(), CheckError);
  // An observation without points: no support expected or found, the fit kept.
  const BodyFitResult none = FitBody(Body(), pose, tracker_test::PointsObservation({}), {});
  EXPECT_EQ(HangUnsupportedArms(Body(), none, tracker_test::PointsObservation({}), {}, {})
                .posed.skeleton.position,
            none.posed.skeleton.position);
}

}  // namespace
}  // namespace reenact::capture
