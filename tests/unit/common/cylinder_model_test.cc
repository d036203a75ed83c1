#include "common/model/cylinder_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/error/check.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::StandingPerson;

constexpr BodyPart kUpper = BodyPart::kUpperTorso;
constexpr BodyPart kLower = BodyPart::kLowerTorso;

// The person's left, by construction of StandingPerson: its local +x turned by the yaw about
// -y.
Eigen::Vector3d LeftOf(double yaw) {
  return Eigen::AngleAxisd(yaw, -Eigen::Vector3d::UnitY()).toRotationMatrix() *
         Eigen::Vector3d::UnitX();
}

PartShape Elliptic() {
  PartShape shape;
  shape.width = {1.2, 1.3, 1.4, 1.3, 1.2};
  shape.depth = {0.7, 0.75, 0.8, 0.75, 0.7};
  return shape;
}

PartShape Tapered() {
  PartShape shape;
  shape.width = shape.depth = {1.2, 1.1, 1.0, 0.9, 0.8};
  return shape;
}

TEST(PartShape, DefaultIsTheCylinderAndCircularMeansEqualRings) {
  EXPECT_TRUE(PartShape{}.IsCylinder());
  EXPECT_TRUE(PartShape{}.IsCircular());
  EXPECT_FALSE(Tapered().IsCylinder());
  EXPECT_TRUE(Tapered().IsCircular());
  EXPECT_FALSE(Elliptic().IsCylinder());
  EXPECT_FALSE(Elliptic().IsCircular());
}

TEST(PartWidthDirection, TorsoWidthRunsFromTheRightToTheLeftShoulderAndHip) {
  for (double yaw : {0.0, 0.4, -1.2}) {
    const Skeleton s = StandingPerson(2.5, yaw, /*arms_out=*/true);
    for (BodyPart part : {kUpper, kLower}) {
      const auto w = PartWidthDirection(s, part);
      ASSERT_TRUE(w) << yaw;
      EXPECT_NEAR((*w - LeftOf(yaw)).norm(), 0, 1e-12) << yaw;
    }
  }
}

TEST(PartWidthDirection, IsMadeOrthogonalToTheAxis) {
  Skeleton s = StandingPerson(2.5, 0.0, false);
  // Left shoulder 0.1 m higher: the shoulder line (0.4, -0.1, 0) loses its component along the
  // vertical axis (neck -> torso along +y), leaving +x.
  s.Set(Joint::kLeftShoulder, s[Joint::kLeftShoulder] + Eigen::Vector3d(0, -0.1, 0));
  const auto w = PartWidthDirection(s, kUpper);
  ASSERT_TRUE(w);
  EXPECT_NEAR((*w - Eigen::Vector3d::UnitX()).norm(), 0, 1e-12);
}

TEST(PartWidthDirection, NoneForLimbsAndHeadMissingJointsAndShouldersAlongTheAxis) {
  const Skeleton s = StandingPerson(2.5, 0.0, true);
  for (BodyPart part : {BodyPart::kHead, BodyPart::kLeftUpperArm, BodyPart::kRightShin})
    EXPECT_FALSE(PartWidthDirection(s, part));

  Skeleton missing = s;
  missing.confidence[Index(Joint::kLeftShoulder)] = 0;
  EXPECT_FALSE(PartWidthDirection(missing, kUpper));
  EXPECT_TRUE(PartWidthDirection(missing, kLower));

  Skeleton along = s;  // both shoulders on the neck -> torso line
  along.Set(Joint::kLeftShoulder, s[Joint::kNeck] + Eigen::Vector3d(0, -0.1, 0));
  along.Set(Joint::kRightShoulder, s[Joint::kNeck] + Eigen::Vector3d(0, 0.1, 0));
  EXPECT_FALSE(PartWidthDirection(along, kUpper));

  Skeleton coincident = s;  // left and right hip at one point
  coincident.Set(Joint::kLeftHip, s[Joint::kRightHip]);
  EXPECT_FALSE(PartWidthDirection(coincident, kLower));
}

TEST(PoseCylinder, DefaultShapesAreTheThesisCylinder) {
  const Skeleton s = StandingPerson(2.5, 0.3, false);
  const RadiusRatios ratios = DefaultRadiusRatios();
  const auto cylinders = PoseCylinders(s, ratios);
  for (int p = 0; p < kBodyPartCount; ++p) {
    ASSERT_TRUE(cylinders[p]);
    const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
    EXPECT_EQ(cylinders[p]->a, s[ja]);
    EXPECT_EQ(cylinders[p]->b, s[jb]);
    EXPECT_DOUBLE_EQ(cylinders[p]->radius, (s[ja] - s[jb]).norm() * ratios[p]);
    EXPECT_TRUE(cylinders[p]->shape.IsCylinder());
    EXPECT_FALSE(cylinders[p]->width_direction);
  }
}

TEST(PoseCylinder, CarriesTheShapeAndGivesEllipticTorsosTheirWidthDirection) {
  const double yaw = 0.4;
  const Skeleton s = StandingPerson(2.5, yaw, true);
  PartShapes shapes{};
  shapes[Index(kUpper)] = Elliptic();
  shapes[Index(kLower)] = Elliptic();
  shapes[Index(BodyPart::kLeftThigh)] = Tapered();
  const auto plain = PoseCylinders(s, DefaultRadiusRatios());
  const auto shaped = PoseCylinders(s, DefaultRadiusRatios(), {}, shapes);
  for (int p = 0; p < kBodyPartCount; ++p) {
    ASSERT_TRUE(shaped[p]);
    EXPECT_EQ(shaped[p]->a, plain[p]->a);  // the shape changes neither axis nor radius
    EXPECT_EQ(shaped[p]->b, plain[p]->b);
    EXPECT_EQ(shaped[p]->radius, plain[p]->radius);
    EXPECT_EQ(shaped[p]->shape.width, shapes[p].width);
    EXPECT_EQ(shaped[p]->shape.depth, shapes[p].depth);
  }
  for (BodyPart part : {kUpper, kLower}) {
    const auto& w = shaped[Index(part)]->width_direction;
    ASSERT_TRUE(w);
    EXPECT_NEAR((*w - LeftOf(yaw)).norm(), 0, 1e-12);
  }
  // Circular (tapered) parts need no width direction.
  EXPECT_FALSE(shaped[Index(BodyPart::kLeftThigh)]->width_direction);
}

TEST(PoseCylinder, EllipticPartWithoutWidthDirectionIsDrawnCircularOfTheSameArea) {
  Skeleton s = StandingPerson(2.5, 0.0, true);
  s.confidence[Index(Joint::kRightShoulder)] = 0;  // the upper torso is still posed
  PartShapes shapes{};
  shapes[Index(kUpper)] = Elliptic();
  shapes[Index(BodyPart::kHead)] = Elliptic();  // not a torso: no width direction ever
  const auto cylinders = PoseCylinders(s, DefaultRadiusRatios(), {}, shapes);
  for (BodyPart part : {kUpper, BodyPart::kHead}) {
    const auto& c = cylinders[Index(part)];
    ASSERT_TRUE(c);
    EXPECT_FALSE(c->width_direction);
    EXPECT_TRUE(c->shape.IsCircular());
    for (int k = 0; k < kShapeRings; ++k) {
      const double area_ratio = Elliptic().width[k] * Elliptic().depth[k];
      EXPECT_NEAR(c->shape.width[k] * c->shape.depth[k], area_ratio, 1e-12);
      EXPECT_NEAR(c->shape.width[k], std::sqrt(area_ratio), 1e-12);
    }
  }
}

TEST(PoseCylinder, RejectsNonFiniteOrNonPositiveShapeValues) {
  const Skeleton s = StandingPerson(2.5, 0.0, true);
  for (double bad : {0.0, -0.5, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    PartShapes shapes{};
    shapes[Index(BodyPart::kLeftShin)].width[2] = bad;
    EXPECT_THROW(PoseCylinders(s, DefaultRadiusRatios(), {}, shapes), CheckError) << bad;
    shapes = PartShapes{};
    shapes[Index(kLower)].depth[4] = bad;
    EXPECT_THROW(PoseCylinder(s, kLower, DefaultRadiusRatios(), {}, shapes), CheckError) << bad;
  }
}

}  // namespace
}  // namespace reenact
