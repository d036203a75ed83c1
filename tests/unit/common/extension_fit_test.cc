#include "common/model/extension_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/error/check.h"
#include "tests/unit/common/cylinder_raycast.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::RayCastCylinders;
using testing::StandingPerson;

PartExtensions Truth() {
  PartExtensions e{};
  e[Index(BodyPart::kHead)] = 0.4;
  e[Index(BodyPart::kLeftForearm)] = 0.3;
  e[Index(BodyPart::kRightForearm)] = 0.2;
  e[Index(BodyPart::kLeftShin)] = 0.15;
  e[Index(BodyPart::kRightShin)] = 0.2;
  return e;
}

struct Scene {
  PinholeCamera camera = PinholeCamera::KinectLike();
  Skeleton skeleton = StandingPerson(2.5, 0.0, /*arms_out=*/true);
  ImageDepthMm depth;
  ImageGray8 mask;
  ExtensionFitFrame Frame() const { return {&skeleton, &camera, &mask, &depth}; }
};

Scene MakeScene(const PartExtensions& truth) {
  Scene s;
  RayCastCylinders(PoseCylinders(s.skeleton, DefaultRadiusRatios(), truth), s.camera, s.depth,
                   s.mask);
  return s;
}

TEST(PoseCylinder, ExtendsPastTheEndJointKeepingTheRadius) {
  const Skeleton s = StandingPerson(2.5, 0.0, true);
  const RadiusRatios ratios = DefaultRadiusRatios();
  const auto plain = PoseCylinders(s, ratios);
  const auto extended = PoseCylinders(s, ratios, Truth());
  for (int p = 0; p < kBodyPartCount; ++p) {
    ASSERT_TRUE(plain[p] && extended[p]);
    const BodyPart part = static_cast<BodyPart>(p);
    const auto [ja, jb] = PartJoints(part);
    const double bone = (s[ja] - s[jb]).norm();
    EXPECT_NEAR(extended[p]->radius, plain[p]->radius, 1e-12);
    EXPECT_NEAR(extended[p]->Length(), bone * (1 + Truth()[p]), 1e-12);
    // The joint that is not the end joint stays where it was.
    const bool head = part == BodyPart::kHead;
    EXPECT_NEAR(((head ? extended[p]->b : extended[p]->a) - s[head ? jb : ja]).norm(), 0, 1e-12);
  }
  // The head grows upwards (past the head joint, -y), the left shin downwards (past the foot).
  EXPECT_LT(extended[Index(BodyPart::kHead)]->a.y(), s[Joint::kHead].y() - 0.07);
  EXPECT_GT(extended[Index(BodyPart::kLeftShin)]->b.y(), s[Joint::kLeftFoot].y() + 0.06);
}

TEST(PoseCylinder, NoExtensionsIsTheThesisCylinder) {
  const Skeleton s = StandingPerson(2.5, 0.3, false);
  const auto plain = PoseCylinders(s, DefaultRadiusRatios(), PartExtensions{});
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
    EXPECT_EQ(plain[p]->a, s[ja]);
    EXPECT_EQ(plain[p]->b, s[jb]);
  }
}

TEST(PoseCylinder, RejectsNegativeOrNonFiniteExtension) {
  const Skeleton s = StandingPerson(2.5, 0.0, true);
  PartExtensions e{};
  e[Index(BodyPart::kLeftShin)] = -0.1;
  EXPECT_THROW(PoseCylinders(s, DefaultRadiusRatios(), e), CheckError);
  e[Index(BodyPart::kLeftShin)] = std::nan("");
  EXPECT_THROW(PoseCylinders(s, DefaultRadiusRatios(), e), CheckError);
}

TEST(ExtensionFit, RecoversTheExtensionsOfRayCastCylinders) {
  const Scene scene = MakeScene(Truth());
  const ExtensionFitFrame frame = scene.Frame();
  const ExtensionFitResult fit = FitPartExtensions({&frame, 1}, DefaultRadiusRatios());
  for (int p = 0; p < kBodyPartCount; ++p) {
    const BodyPart part = static_cast<BodyPart>(p);
    if (!IsExtendedPart(part)) {
      EXPECT_FALSE(fit.fitted[p]) << PartName(part);
      EXPECT_EQ(fit.extension[p], 0.0) << PartName(part);
      continue;
    }
    ASSERT_TRUE(fit.fitted[p]) << PartName(part);
    EXPECT_EQ(fit.frames_measured[p], 1);
    // Within 2 pixels at 2.5 m (f = 525: 9.5 mm) over bones of 0.2-0.45 m.
    const auto [ja, jb] = PartJoints(part);
    const double bone = (scene.skeleton[ja] - scene.skeleton[jb]).norm();
    EXPECT_NEAR(fit.extension[p], Truth()[p], 0.0095 / bone) << PartName(part);
  }
}

TEST(ExtensionFit, ThesisCylindersMeasureNoExtension) {
  const Scene scene = MakeScene(PartExtensions{});
  const ExtensionFitFrame frame = scene.Frame();
  const ExtensionFitResult fit = FitPartExtensions({&frame, 1}, DefaultRadiusRatios());
  for (int p = 0; p < kBodyPartCount; ++p) EXPECT_LT(fit.extension[p], 0.03) << p;
}

TEST(ExtensionFit, SubjectFarBehindTheEndIsNotThePart) {
  // A wall of subject pixels 0.6 m behind the body below the feet and around the head (as a
  // hand in front of the torso): the depth test stops the walk at the part's own end.
  Scene scene = MakeScene(Truth());
  for (int y = 0; y < scene.camera.height; ++y)
    for (int x = 0; x < scene.camera.width; ++x)
      if (scene.mask.at(x, y) < 128) {
        scene.mask.at(x, y) = 255;
        scene.depth.at(x, y) = 3100;
      }
  const ExtensionFitFrame frame = scene.Frame();
  const ExtensionFitResult fit = FitPartExtensions({&frame, 1}, DefaultRadiusRatios());
  for (BodyPart part : {BodyPart::kHead, BodyPart::kLeftShin, BodyPart::kRightForearm}) {
    const auto [ja, jb] = PartJoints(part);
    const double bone = (scene.skeleton[ja] - scene.skeleton[jb]).norm();
    EXPECT_NEAR(fit.extension[Index(part)], Truth()[Index(part)], 0.0095 / bone) << PartName(part);
  }
}

TEST(ExtensionFit, MedianOverFramesAndClamped) {
  PartExtensions small{}, large{};
  small[Index(BodyPart::kLeftShin)] = 0.1;
  large[Index(BodyPart::kLeftShin)] = 0.2;
  const Scene a = MakeScene(small), b = MakeScene(large), c = MakeScene(large);
  const ExtensionFitFrame frames[] = {a.Frame(), b.Frame(), c.Frame()};
  const auto fit = FitPartExtensions(frames, DefaultRadiusRatios());
  const double bone = (a.skeleton[Joint::kLeftKnee] - a.skeleton[Joint::kLeftFoot]).norm();
  EXPECT_EQ(fit.frames_measured[Index(BodyPart::kLeftShin)], 3);
  EXPECT_NEAR(fit.extension[Index(BodyPart::kLeftShin)], 0.2, 0.0095 / bone);
  const auto clamped = FitPartExtensions(frames, DefaultRadiusRatios(), {.max_ratio = 0.15});
  EXPECT_DOUBLE_EQ(clamped.extension[Index(BodyPart::kLeftShin)], 0.15);
}

TEST(ExtensionFit, EmptyMaskMeasuresNothing) {
  Scene scene = MakeScene(Truth());
  scene.mask = ImageGray8(scene.camera.width, scene.camera.height, 1, 0);
  const ExtensionFitFrame frame = scene.Frame();
  const auto fit = FitPartExtensions({&frame, 1}, DefaultRadiusRatios());
  for (int p = 0; p < kBodyPartCount; ++p) {
    EXPECT_FALSE(fit.fitted[p]);
    EXPECT_EQ(fit.extension[p], 0.0);
  }
}

TEST(ExtensionFit, NoFramesFitsNothing) {
  const auto fit = FitPartExtensions({}, DefaultRadiusRatios());
  for (int p = 0; p < kBodyPartCount; ++p) EXPECT_FALSE(fit.fitted[p]);
}

TEST(ExtensionFit, JointBehindTheCameraMeasuresNothing) {
  Scene scene = MakeScene(Truth());
  scene.skeleton.Set(Joint::kLeftFoot, Eigen::Vector3d(0.1, 0.9, -0.5));
  EXPECT_FALSE(MeasureExtension(scene.Frame(), BodyPart::kLeftShin, DefaultRadiusRatios()));
  // The others still measure.
  EXPECT_TRUE(MeasureExtension(scene.Frame(), BodyPart::kRightShin, DefaultRadiusRatios()));
}

TEST(ExtensionFit, ZeroLengthBoneOrMissingJointMeasuresNothing) {
  Scene scene = MakeScene(Truth());
  scene.skeleton.Set(Joint::kLeftHand, scene.skeleton[Joint::kLeftElbow]);
  EXPECT_FALSE(MeasureExtension(scene.Frame(), BodyPart::kLeftForearm, DefaultRadiusRatios()));
  scene.skeleton.confidence[Index(Joint::kHead)] = 0;
  EXPECT_FALSE(MeasureExtension(scene.Frame(), BodyPart::kHead, DefaultRadiusRatios()));
}

TEST(ExtensionFit, AxisPointingAtTheCameraMeasuresNothing) {
  Scene scene = MakeScene(Truth());
  // The left forearm points straight at the camera centre.
  const Eigen::Vector3d elbow = scene.skeleton[Joint::kLeftElbow];
  scene.skeleton.Set(Joint::kLeftHand, elbow - 0.3 * elbow.normalized());
  EXPECT_FALSE(MeasureExtension(scene.Frame(), BodyPart::kLeftForearm, DefaultRadiusRatios()));
}

TEST(ExtensionFit, RejectsBadOptionsAndMismatchedImages) {
  const Scene scene = MakeScene(Truth());
  EXPECT_THROW(
      MeasureExtension(scene.Frame(), BodyPart::kHead, DefaultRadiusRatios(), {.min_fill = 0}),
      CheckError);
  EXPECT_THROW(
      MeasureExtension(scene.Frame(), BodyPart::kHead, DefaultRadiusRatios(), {.max_ratio = -1}),
      CheckError);
  const ImageGray8 small(10, 10, 1, 255);
  ExtensionFitFrame frame = scene.Frame();
  frame.mask = &small;
  EXPECT_THROW(MeasureExtension(frame, BodyPart::kHead, DefaultRadiusRatios()), CheckError);
  frame = scene.Frame();
  frame.camera = nullptr;
  EXPECT_THROW(MeasureExtension(frame, BodyPart::kHead, DefaultRadiusRatios()), CheckError);
}

}  // namespace
}  // namespace reenact
