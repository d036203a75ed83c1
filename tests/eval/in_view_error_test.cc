// The in-view split of `reenact-eval tracker` on constructed skeletons.
#include "tests/eval/in_view_error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace reenact::eval {
namespace {

const PinholeCamera kCamera = PinholeCamera::KinectLike();  // 640 x 480

// A truth with every joint 1.5 m ahead, joint j at pixel (100 + 25 j, 240): all in view.
Skeleton AllInView() {
  Skeleton s;
  for (int j = 0; j < kJointCount; ++j)
    s.Set(static_cast<Joint>(j), kCamera.Unproject(Eigen::Vector2d(100 + 25 * j, 240), 1.5));
  return s;
}

// The truth with the knees and feet below the image's lower edge (a close-up's).
Skeleton LegsBelowTheImage() {
  Skeleton s = AllInView();
  for (Joint j : {Joint::kLeftKnee, Joint::kRightKnee, Joint::kLeftFoot, Joint::kRightFoot})
    s.Set(j, kCamera.Unproject(Eigen::Vector2d(320, 700), 1.5));
  return s;
}

// `truth` with joint j moved by j centimetres along x, every joint reported.
Skeleton OffByJointIndexCm(const Skeleton& truth) {
  Skeleton e = truth;
  for (int j = 0; j < kJointCount; ++j) e.position[j].x() += 0.01 * j;
  return e;
}

TEST(InViewError, JointsInViewAreAheadAndInsideTheImage) {
  Skeleton s = AllInView();
  // Pixel coordinates a thousandth inside or outside the edges, against rounding.
  auto at = [](double u, double v, double z) { return kCamera.Unproject({u, v}, z); };
  s.Set(Joint::kHead, at(639.999, 0.001, 2.0));               // the last column, the first row
  s.Set(Joint::kNeck, at(640.001, 240, 2.0));                 // past the last column
  s.Set(Joint::kTorso, at(320, 480.001, 2.0));                // past the last row
  s.Set(Joint::kWaist, at(-0.001, 240, 2.0));                 // left of the first column
  s.Set(Joint::kLeftHand, Eigen::Vector3d(0, 0, 0.05));       // not ahead enough
  s.Set(Joint::kRightHand, Eigen::Vector3d(0.1, 0.1, -1.0));  // behind the sensor
  s.Set(Joint::kLeftElbow, at(320, 240, 0.06));               // just ahead
  s.confidence[Index(Joint::kRightElbow)] = 0;                // absent from the truth
  const std::array<bool, kJointCount> in_view = JointsInView(s, kCamera);
  for (int j = 0; j < kJointCount; ++j) {
    const Joint joint = static_cast<Joint>(j);
    const bool expected = joint != Joint::kNeck && joint != Joint::kTorso &&
                          joint != Joint::kWaist && joint != Joint::kLeftHand &&
                          joint != Joint::kRightHand && joint != Joint::kRightElbow;
    EXPECT_EQ(in_view[j], expected) << JointName(joint);
  }
}

TEST(InViewError, AllInViewAndReportedGivesTheSixteenJointError) {
  // Joint j off by j cm: the frame's mean error is (0 + 1 + ... + 15) / 16 = 7.5 cm.
  InViewErrorTable table;
  table.Add(OffByJointIndexCm(AllInView()), AllInView(), kCamera);
  const InViewErrorStats s = table.Stats();
  EXPECT_EQ(s.frames, 1);
  EXPECT_EQ(s.in_view, kJointCount);
  EXPECT_EQ(s.out_of_view, 0);
  EXPECT_NEAR(s.in_view_mpjpe_cm, 7.5, 1e-9);
  EXPECT_DOUBLE_EQ(s.in_view_reported_share, 1.0);
  EXPECT_DOUBLE_EQ(s.invented_share, 0.0);  // nothing out of view
}

TEST(InViewError, LegsReportedOutOfViewAreInventedAndLeftOutOfTheError) {
  // The knees and feet (joints 11, 12, 14, 15) out of view, reported anyway: all four
  // invented; the error is the other twelve joints' mean, (120 - 52) / 12 cm.
  const Skeleton truth = LegsBelowTheImage();
  Skeleton estimate = OffByJointIndexCm(truth);
  InViewErrorTable guessed;
  guessed.Add(estimate, truth, kCamera);
  InViewErrorStats s = guessed.Stats();
  EXPECT_EQ(s.in_view, 12);
  EXPECT_EQ(s.out_of_view, 4);
  EXPECT_EQ(s.out_of_view_reported, 4);
  EXPECT_DOUBLE_EQ(s.invented_share, 1.0);
  EXPECT_NEAR(s.in_view_mpjpe_cm, (120.0 - 52.0) / 12, 1e-9);
  // Flagged not seen (confidence 0), and one foot reported: a quarter invented. The left
  // hand (joint 6), in view, not reported either: 11 of 12 in-view joints reported, and the
  // error over those 11, (68 - 6) / 11 cm.
  for (Joint j : {Joint::kLeftKnee, Joint::kRightKnee, Joint::kLeftFoot})
    estimate.confidence[Index(j)] = 0;
  estimate.confidence[Index(Joint::kLeftHand)] = 0;
  InViewErrorTable flagged;
  flagged.Add(estimate, truth, kCamera);
  s = flagged.Stats();
  EXPECT_EQ(s.out_of_view_reported, 1);
  EXPECT_DOUBLE_EQ(s.invented_share, 0.25);
  EXPECT_EQ(s.in_view_reported, 11);
  EXPECT_DOUBLE_EQ(s.in_view_reported_share, 11.0 / 12);
  EXPECT_NEAR(s.in_view_mpjpe_cm, (68.0 - 6.0) / 11, 1e-9);
}

TEST(InViewError, FramesCountEquallyAndSharesPoolTheJoints) {
  // Frame 1: all in view, 2 cm off each (mean 2 cm, 16 joints). Frame 2: legs out of view,
  // flagged, the twelve in view 5 cm off (mean 5 cm): the mean of the frames' means is 3.5 cm
  // (pooling the joints would give (32 + 60) / 28 = 3.29). Frame 3: nothing reported, no
  // error to add, its twelve in-view joints unreported.
  InViewErrorTable table;
  Skeleton e1 = AllInView();
  for (auto& p : e1.position) p.y() += 0.02;
  table.Add(e1, AllInView(), kCamera);
  const Skeleton truth2 = LegsBelowTheImage();
  Skeleton e2 = truth2;
  for (auto& p : e2.position) p.z() += 0.05;
  for (Joint j : {Joint::kLeftKnee, Joint::kRightKnee, Joint::kLeftFoot, Joint::kRightFoot})
    e2.confidence[Index(j)] = 0;
  table.Add(e2, truth2, kCamera);
  table.Add(Skeleton(), truth2, kCamera);
  const InViewErrorStats s = table.Stats();
  EXPECT_EQ(s.frames, 3);
  EXPECT_NEAR(s.in_view_mpjpe_cm, 3.5, 1e-9);
  EXPECT_EQ(s.in_view, 16 + 12 + 12);
  EXPECT_EQ(s.in_view_reported, 16 + 12);
  EXPECT_DOUBLE_EQ(s.in_view_reported_share, 28.0 / 40);
  EXPECT_EQ(s.out_of_view, 8);
  EXPECT_DOUBLE_EQ(s.invented_share, 0.0);
}

TEST(InViewError, NothingAddedIsZeroNotNaN) {
  const InViewErrorStats s = InViewErrorTable().Stats();
  EXPECT_EQ(s.frames, 0);
  EXPECT_EQ(s.in_view_mpjpe_cm, 0);
  EXPECT_EQ(s.in_view_reported_share, 0);
  EXPECT_EQ(s.invented_share, 0);
  // A truth without joints: nothing in view, nothing out of view.
  InViewErrorTable empty;
  empty.Add(Skeleton(), Skeleton(), kCamera);
  const InViewErrorStats e = empty.Stats();
  EXPECT_EQ(e.in_view + e.out_of_view, 0);
  EXPECT_FALSE(std::isnan(e.in_view_mpjpe_cm));
}

}  // namespace
}  // namespace reenact::eval
