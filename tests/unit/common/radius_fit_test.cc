#include "common/model/radius_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/unit/common/cylinder_raycast.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::RayCastCylinders;
using testing::StandingPerson;

TEST(RadiusFit, RecoversRadiusRatiosOfRayCastCylinders) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const Skeleton s = StandingPerson(2.5, 0.0, /*arms_out=*/true);
  RadiusRatios truth = DefaultRadiusRatios();
  truth[Index(BodyPart::kLeftUpperArm)] = 0.2;
  truth[Index(BodyPart::kRightForearm)] = 0.1;
  ImageDepthMm depth;
  ImageGray8 mask;
  RayCastCylinders(PoseCylinders(s, truth), cam, depth, mask);

  const RadiusFitResult fit = FitRadiusRatios(s, cam, depth, mask);
  // Limbs held apart from the body must be recovered within 10% (pixel quantisation of a
  // ~15-25 pixel wide band and the slices' spread); the torso and head overlap neighbours at
  // their ends, so they get 20%.
  for (BodyPart p : {BodyPart::kLeftUpperArm, BodyPart::kLeftForearm, BodyPart::kRightUpperArm,
                     BodyPart::kRightForearm, BodyPart::kLeftShin, BodyPart::kRightShin}) {
    ASSERT_TRUE(fit.fitted[Index(p)]) << PartName(p);
    EXPECT_NEAR(fit.radius_ratio[Index(p)], truth[Index(p)], 0.1 * truth[Index(p)]) << PartName(p);
  }
  for (BodyPart p : {BodyPart::kHead, BodyPart::kUpperTorso}) {
    ASSERT_TRUE(fit.fitted[Index(p)]) << PartName(p);
    EXPECT_NEAR(fit.radius_ratio[Index(p)], truth[Index(p)], 0.2 * truth[Index(p)]) << PartName(p);
  }
}

TEST(RadiusFit, EmptyMaskKeepsDefaults) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const RadiusFitResult fit = FitRadiusRatios(
      StandingPerson(2.5, 0, true), cam, ImageDepthMm(640, 480, 1, 0), ImageGray8(640, 480, 1, 0));
  EXPECT_EQ(fit.fitted_count(), 0);
  EXPECT_EQ(fit.radius_ratio, DefaultRadiusRatios());
}

TEST(RadiusFit, SkeletonBehindCameraKeepsDefaults) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const RadiusFitResult fit =
      FitRadiusRatios(StandingPerson(-2.5, 0, true), cam, ImageDepthMm(640, 480, 1, 1000),
                      ImageGray8(640, 480, 1, 255));
  EXPECT_EQ(fit.fitted_count(), 0);
}

TEST(CylinderModel, ZeroLengthBoneAndMissingJointAreNotPosed) {
  Skeleton s = StandingPerson(2.5, 0, true);
  s.Set(Joint::kLeftElbow, s[Joint::kLeftShoulder]);
  s.confidence[Index(Joint::kRightHand)] = 0;
  const auto cylinders = PoseCylinders(s, DefaultRadiusRatios());
  EXPECT_FALSE(cylinders[Index(BodyPart::kLeftUpperArm)]);
  EXPECT_FALSE(cylinders[Index(BodyPart::kRightForearm)]);
  ASSERT_TRUE(cylinders[Index(BodyPart::kLeftForearm)]);
  EXPECT_NEAR(cylinders[Index(BodyPart::kLeftForearm)]->radius,
              cylinders[Index(BodyPart::kLeftForearm)]->Length() *
                  DefaultRadiusRatios()[Index(BodyPart::kLeftForearm)],
              1e-12);
}

}  // namespace
}  // namespace reenact

namespace reenact {
namespace {

TEST(CylinderModel, SubMillimetreBonesArePosedAndEveryJointMissingPosesNothing) {
  Skeleton s = testing::StandingPerson(2.5, 0, true);
  s.Set(Joint::kLeftHand, s[Joint::kLeftElbow] + Eigen::Vector3d(0.0005, 0, 0));  // 0.5 mm
  const auto cylinders = PoseCylinders(s, DefaultRadiusRatios());
  ASSERT_TRUE(cylinders[Index(BodyPart::kLeftForearm)]);
  EXPECT_NEAR(cylinders[Index(BodyPart::kLeftForearm)]->Length(), 0.0005, 1e-12);
  EXPECT_TRUE(std::isfinite(cylinders[Index(BodyPart::kLeftForearm)]->radius));
  for (const auto& c : PoseCylinders(Skeleton{}, DefaultRadiusRatios())) EXPECT_FALSE(c);
}

TEST(RadiusFit, DepthHolesInsideTheMaskAreIgnored) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const Skeleton s = testing::StandingPerson(2.5, 0.0, true);
  const RadiusRatios truth = DefaultRadiusRatios();
  ImageDepthMm depth;
  ImageGray8 mask;
  RayCastCylinders(PoseCylinders(s, truth), cam, depth, mask);
  // Every third row of depth readings lost, as at a Kinect's dark or shiny patches.
  for (int y = 0; y < depth.height; y += 3)
    for (int x = 0; x < depth.width; ++x) depth.at(x, y) = 0;
  const RadiusFitResult fit = FitRadiusRatios(s, cam, depth, mask);
  // The silhouette is whole, so the fit of the free limbs keeps the 10% of the hole-free case.
  for (BodyPart p : {BodyPart::kLeftUpperArm, BodyPart::kLeftForearm, BodyPart::kRightUpperArm,
                     BodyPart::kRightForearm, BodyPart::kLeftShin, BodyPart::kRightShin}) {
    ASSERT_TRUE(fit.fitted[Index(p)]) << PartName(p);
    EXPECT_NEAR(fit.radius_ratio[Index(p)], truth[Index(p)], 0.1 * truth[Index(p)]) << PartName(p);
  }
}

}  // namespace
}  // namespace reenact
