// The limbs table of `reenact-eval tracker` against constructed label images and skeletons.
#include "tests/eval/limb_visibility_table.h"

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::eval {
namespace {

// Every joint present at depth z, spread sideways so that no two coincide.
Skeleton AtDepth(double z) {
  Skeleton s;
  for (int j = 0; j < kJointCount; ++j)
    s.Set(static_cast<Joint>(j), Eigen::Vector3d(0.1 * j, 0, z));
  return s;
}

// Part areas with only the left arm's upper arm showing `left_arm` square metres and every
// leg part 1.
std::array<double, kBodyPartCount> Areas(double left_arm) {
  std::array<double, kBodyPartCount> a{};
  a[Index(BodyPart::kLeftUpperArm)] = left_arm;
  for (BodyPart p :
       {BodyPart::kLeftThigh, BodyPart::kLeftShin, BodyPart::kRightThigh, BodyPart::kRightShin})
    a[Index(p)] = 1;
  return a;
}

TEST(VisiblePartAreas, EachPixelCoversItsAreaAtThePartsDepth) {
  const PinholeCamera camera = PinholeCamera::KinectLike();
  ImageLabel8 labels(camera.width, camera.height, 1, 0);
  for (int y = 100; y < 120; ++y)
    for (int x = 200; x < 210; ++x) labels.at(x, y) = PartLabel(BodyPart::kLeftForearm);
  for (int x = 0; x < 7; ++x) labels.at(x, 0) = PartLabel(BodyPart::kHead);
  labels.at(1, 1) = 200;  // not a part: left out
  Skeleton truth = AtDepth(2.0);
  truth.Set(Joint::kLeftElbow, {0, 0, 1.5});
  truth.Set(Joint::kLeftHand, {0, 0, 2.5});  // the forearm's middle at 2 m
  truth.Set(Joint::kHead, {0, 0, -1});
  truth.Set(Joint::kNeck, {0, 0, 0.5});  // the head's middle behind the sensor
  const auto area = VisiblePartAreas(labels, truth, camera);
  // 200 pixels, each (2 / fx) (2 / fy) square metres at 2 m.
  EXPECT_NEAR(area[Index(BodyPart::kLeftForearm)], 200 * (2 / camera.fx) * (2 / camera.fy), 1e-12);
  EXPECT_EQ(area[Index(BodyPart::kHead)], 0.0);
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (p == Index(BodyPart::kLeftForearm)) continue;
    EXPECT_EQ(area[p], 0.0) << p;
  }
}

TEST(VisiblePartAreas, LabelsOfAnotherSizeAreABug) {
  const PinholeCamera camera = PinholeCamera::KinectLike();
  EXPECT_THROW(VisiblePartAreas(ImageLabel8(320, 240, 1, 0), AtDepth(2), camera), CheckError);
}

TEST(LimbVisibilityTable, FramesBelowAQuarterOfTheLargestAreaAreHidden) {
  // The left arm shows 1, 1, 0.2 and 0.25 square metres: the third frame below a quarter of
  // the largest (hidden), the fourth at it (in view). Its hand is 2 cm off in view and 40 cm
  // off hidden, its elbow 1 and 30 cm.
  LimbVisibilityTable table;
  const Skeleton truth = AtDepth(3);
  const double areas[] = {1, 1, 0.2, 0.25};
  for (const double a : areas) {
    Skeleton estimate = truth;
    const bool hidden = a < 0.25;
    estimate[Joint::kLeftHand] += Eigen::Vector3d(hidden ? 0.4 : 0.02, 0, 0);
    estimate[Joint::kLeftElbow] += Eigen::Vector3d(0, hidden ? 0.3 : 0.01, 0);
    table.Add(Areas(a), estimate, truth);
  }
  const auto stats = table.Stats();
  const LimbVisibilityStats& l = stats[0];
  EXPECT_EQ(l.in_view, 3);
  EXPECT_EQ(l.hidden, 1);
  EXPECT_NEAR(l.in_view_end_cm, 2, 1e-9);
  EXPECT_NEAR(l.hidden_end_cm, 40, 1e-9);
  EXPECT_NEAR(l.in_view_middle_cm, 1, 1e-9);
  EXPECT_NEAR(l.hidden_middle_cm, 30, 1e-9);
  // The right arm shows nothing on any frame: hidden throughout, its joints exact.
  EXPECT_EQ(stats[1].in_view, 0);
  EXPECT_EQ(stats[1].hidden, 4);
  EXPECT_EQ(stats[1].hidden_end_cm, 0.0);
  // The legs show the same area on every frame: in view throughout.
  EXPECT_EQ(stats[2].in_view, 4);
  EXPECT_EQ(stats[3].hidden, 0);
  EXPECT_EQ(EvalLimbName(0), "l_arm");
  EXPECT_EQ(EvalLimbName(3), "r_leg");
  EXPECT_THROW(EvalLimbName(4), CheckError);
}

TEST(LimbVisibilityTable, MissingJointsCountTheFrameButNotTheirError) {
  LimbVisibilityTable table;
  const Skeleton truth = AtDepth(3);
  Skeleton estimate = truth;
  estimate[Joint::kLeftHand] += Eigen::Vector3d(0.1, 0, 0);
  table.Add(Areas(1), estimate, truth);
  estimate.confidence[Index(Joint::kLeftHand)] = 0;  // missing: its position must not count
  estimate[Joint::kLeftHand] += Eigen::Vector3d(5, 0, 0);
  table.Add(Areas(1), estimate, truth);
  const LimbVisibilityStats l = table.Stats()[0];
  EXPECT_EQ(l.in_view, 2);
  EXPECT_NEAR(l.in_view_end_cm, 10, 1e-9);
}

TEST(LimbVisibilityTable, AnEmptyTableReadsZero) {
  for (const LimbVisibilityStats& s : LimbVisibilityTable().Stats()) {
    EXPECT_EQ(s.in_view + s.hidden, 0);
    EXPECT_EQ(s.in_view_end_cm + s.hidden_end_cm + s.in_view_middle_cm + s.hidden_middle_cm, 0.0);
  }
}

}  // namespace
}  // namespace reenact::eval
