#include "tests/eval/calibration_aligned_error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

namespace reenact::eval {
namespace {

using Eigen::Vector3d;

// A body in a frame with z up, x the subject's left to its right, y forward (the body frame
// of joint_error_table.h is then the identity). Arms held out to the sides (the calibration
// pose) or hanging down.
Skeleton Body(bool arms_out) {
  Skeleton s;
  s.Set(Joint::kHead, {0, 0, 1.7});
  s.Set(Joint::kNeck, {0, 0, 1.5});
  s.Set(Joint::kTorso, {0, 0, 1.3});
  s.Set(Joint::kWaist, {0, 0, 1.0});
  for (double side : {-1.0, 1.0}) {
    const bool left = side < 0;
    const Vector3d shoulder(0.2 * side, 0, 1.45);
    const Vector3d elbow_dir = arms_out ? Vector3d(side, 0, 0) : Vector3d(0, 0, -1);
    s.Set(left ? Joint::kLeftShoulder : Joint::kRightShoulder, shoulder);
    s.Set(left ? Joint::kLeftElbow : Joint::kRightElbow, shoulder + 0.3 * elbow_dir);
    s.Set(left ? Joint::kLeftHand : Joint::kRightHand, shoulder + 0.55 * elbow_dir);
    s.Set(left ? Joint::kLeftHip : Joint::kRightHip, {0.1 * side, 0, 0.95});
    s.Set(left ? Joint::kLeftKnee : Joint::kRightKnee, {0.1 * side, 0, 0.5});
    s.Set(left ? Joint::kLeftFoot : Joint::kRightFoot, {0.1 * side, 0, 0.08});
  }
  return s;
}

Skeleton Moved(const Skeleton& s, const Eigen::Isometry3d& g) { return s.Transformed(g); }

double MaxJointDistance(const Skeleton& a, const Skeleton& b) {
  double d = 0;
  for (int j = 0; j < kJointCount; ++j) d = std::max(d, (a.position[j] - b.position[j]).norm());
  return d;
}

TEST(CalibrationAlignment, ARigidMotionCarriesEveryOffset) {
  const Skeleton estimate = Body(true);
  Skeleton truth = estimate;
  for (int j = 0; j < kJointCount; ++j)  // offsets up to 10 cm, a different one per joint
    truth.position[j] += 0.1 * Vector3d(std::sin(j + 1.0), std::cos(3.0 * j), std::sin(5.0 * j));
  const auto alignment = CalibrationAlignment::FromCalibrationFrame(estimate, truth);
  ASSERT_TRUE(alignment);
  EXPECT_LT(MaxJointDistance(alignment->Aligned(estimate), truth), 1e-12);

  const Eigen::Isometry3d g = Eigen::Translation3d(0.4, -1.2, 2.5) *
                              Eigen::AngleAxisd(1.2, Vector3d(0.3, -0.5, 0.8).normalized());
  EXPECT_GT(MaxJointDistance(Moved(estimate, g), Moved(truth, g)), 0.05);
  EXPECT_LT(MaxJointDistance(alignment->Aligned(Moved(estimate, g)), Moved(truth, g)), 1e-12);
}

TEST(CalibrationAlignment, OffsetsTurnWithTheLimbsAsTheySwing) {
  // Calibration frame: arms out. The rig puts the right hand 3 cm beyond the tracker's, along
  // the forearm; the right elbow 2 cm above it (the top of the arm held out); both hips 10 cm
  // lower; the right shoulder 5 cm nearer the mid-line.
  const Skeleton out = Body(true);
  Skeleton out_truth = out;
  out_truth[Joint::kRightHand] += Vector3d(0.03, 0, 0);
  out_truth[Joint::kRightElbow] += Vector3d(0, 0, 0.02);
  out_truth[Joint::kLeftHip] += Vector3d(0, 0, -0.10);
  out_truth[Joint::kRightHip] += Vector3d(0, 0, -0.10);
  out_truth[Joint::kRightShoulder] += Vector3d(-0.05, 0, 0);
  const auto alignment = CalibrationAlignment::FromCalibrationFrame(out, out_truth);
  ASSERT_TRUE(alignment);

  // Later: arms hanging, the body turned a quarter turn about up and moved. Lowering the
  // right arm (a turn about forward) takes its top to its outer side (+x), and the hand's
  // offset along the forearm to below it; the trunk's offsets keep their body-frame
  // directions.
  const Eigen::Isometry3d g =
      Eigen::Translation3d(1.0, 2.0, 0.0) * Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ());
  const Skeleton down = Body(false);
  Skeleton down_truth = down;
  down_truth[Joint::kRightHand] += Vector3d(0, 0, -0.03);
  down_truth[Joint::kRightElbow] += Vector3d(0.02, 0, 0);
  down_truth[Joint::kLeftHip] += Vector3d(0, 0, -0.10);
  down_truth[Joint::kRightHip] += Vector3d(0, 0, -0.10);
  down_truth[Joint::kRightShoulder] += Vector3d(-0.05, 0, 0);
  const Skeleton aligned = alignment->Aligned(Moved(down, g));
  EXPECT_LT(MaxJointDistance(aligned, Moved(down_truth, g)), 1e-12);
}

TEST(CalibrationAlignment, SegmentFramesAreRotationsWithTheBoneAtTheRestDirection) {
  Skeleton s = Body(true);
  s[Joint::kLeftHand] = s[Joint::kLeftElbow] + Vector3d(0.1, -0.2, 0.15);  // any direction
  s[Joint::kRightElbow] = s[Joint::kRightShoulder] + Vector3d(0, 0, 0.3);  // straight up
  for (Joint j : {Joint::kLeftHand, Joint::kRightElbow, Joint::kLeftKnee, Joint::kNeck}) {
    const auto f = SegmentFrame(s, j);
    ASSERT_TRUE(f) << JointName(j);
    EXPECT_LT((f->transpose() * *f - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(f->determinant(), 1.0, 1e-12);
  }
  // A limb's frame takes the rest direction (-z of the body frame) onto its bone.
  const Vector3d hand_bone = (s[Joint::kLeftHand] - s[Joint::kLeftElbow]).normalized();
  EXPECT_LT((-SegmentFrame(s, Joint::kLeftHand)->col(2) - hand_bone).norm(), 1e-12);
  EXPECT_LT((-SegmentFrame(s, Joint::kRightElbow)->col(2) - Vector3d::UnitZ()).norm(), 1e-12);
  // A trunk joint's frame is the body frame (the identity here).
  EXPECT_LT((*SegmentFrame(s, Joint::kWaist) - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(CalibrationAlignment, DegenerateSkeletonsGiveNoAlignmentAndNoNaN) {
  const Skeleton body = Body(true);
  Skeleton missing = body;
  missing.confidence[Index(Joint::kLeftKnee)] = 0;
  EXPECT_FALSE(CalibrationAlignment::FromCalibrationFrame(body, missing));  // truth
  EXPECT_FALSE(CalibrationAlignment::FromCalibrationFrame(missing, body));  // estimate
  EXPECT_FALSE(SegmentFrame(missing, Joint::kLeftKnee));
  EXPECT_FALSE(SegmentFrame(missing, Joint::kLeftFoot));  // its parent is missing

  Skeleton zero_bone = body;  // the hand at the elbow
  zero_bone[Joint::kRightHand] = zero_bone[Joint::kRightElbow];
  EXPECT_FALSE(SegmentFrame(zero_bone, Joint::kRightHand));
  EXPECT_FALSE(CalibrationAlignment::FromCalibrationFrame(zero_bone, body));

  Skeleton folded = body;  // the neck at the waist: no body frame
  folded[Joint::kNeck] = folded[Joint::kWaist];
  EXPECT_FALSE(SegmentFrame(folded, Joint::kWaist));
  EXPECT_FALSE(CalibrationAlignment::FromCalibrationFrame(folded, body));

  // An alignment applied to a degenerate frame moves only the joints it can place.
  Skeleton truth = body;
  for (Eigen::Vector3d& p : truth.position) p += Vector3d(0, 0, 0.05);
  const auto alignment = CalibrationAlignment::FromCalibrationFrame(body, truth);
  ASSERT_TRUE(alignment);
  const Skeleton a = alignment->Aligned(zero_bone);
  for (const Eigen::Vector3d& p : a.position) EXPECT_TRUE(p.allFinite());
  EXPECT_EQ(a[Joint::kRightHand], zero_bone[Joint::kRightHand]);
  EXPECT_LT((a[Joint::kWaist] - truth[Joint::kWaist]).norm(), 1e-12);
  const Skeleton b = alignment->Aligned(folded);
  for (int j = 0; j < kJointCount; ++j) EXPECT_EQ(b.position[j], folded.position[j]);
}

}  // namespace
}  // namespace reenact::eval
