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

// The height map's factor: the node values at the nodes, linear between them, periodic in
// the angle (any multiple of 2 pi, negative angles), 1 without a surface.
TEST(PartSurface, FactorIsPeriodicAndLinearBetweenTheNodes) {
  PartSurface s;
  EXPECT_EQ(s.FactorAt(2, 1.0), 1.0);
  s.angles = 4;
  s.radial[2] = {1.2, 0.8, 1.4, 0.6};
  const double quarter = std::acos(-1.0) / 2;
  EXPECT_NEAR(s.FactorAt(2, 0), 1.2, 1e-12);
  EXPECT_NEAR(s.FactorAt(2, quarter), 0.8, 1e-12);
  EXPECT_NEAR(s.FactorAt(2, 0.5 * quarter), 1.0, 1e-12);
  EXPECT_NEAR(s.FactorAt(2, 3.5 * quarter), 0.9, 1e-12);  // between the last node and the first
  EXPECT_NEAR(s.FactorAt(2, -0.5 * quarter), 0.9, 1e-12);
  EXPECT_NEAR(s.FactorAt(2, 2 * quarter + 8 * quarter), 1.4, 1e-9);
}

TEST(PartShape, IsValidRejectsBadRingsSurfacesAndCaps) {
  EXPECT_TRUE(PartShape{}.IsValid());
  PartShape bad_ring;
  bad_ring.depth[3] = 0;
  EXPECT_FALSE(bad_ring.IsValid());
  PartShape bad_angles;
  bad_angles.surface.angles = 2;
  EXPECT_FALSE(bad_angles.IsValid());
  bad_angles.surface.angles = kMaxSurfaceAngles + 1;
  EXPECT_FALSE(bad_angles.IsValid());
  PartShape bad_factor;
  bad_factor.surface.angles = 4;
  for (auto& ring : bad_factor.surface.radial) ring.fill(1.0);
  EXPECT_TRUE(bad_factor.IsValid());
  bad_factor.surface.radial[1][3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(bad_factor.IsValid());
  PartShape bad_cap;
  bad_cap.cap_depth[1] = -0.1;
  EXPECT_FALSE(bad_cap.IsValid());
}

// The body-fixed reference: the torso's is its width direction; every other part's is unit and
// orthogonal to its axis, the head's forward (towards the camera for a person facing it), and
// it turns with the person.
TEST(PartReferenceDirection, FixedToTheBodyUnitAndOrthogonalToTheAxis) {
  const Skeleton facing = StandingPerson(2.0, 0, false);
  EXPECT_EQ(PartReferenceDirection(facing, BodyPart::kUpperTorso),
            PartWidthDirection(facing, BodyPart::kUpperTorso));
  const auto head = PartReferenceDirection(facing, BodyPart::kHead);
  ASSERT_TRUE(head.has_value());
  EXPECT_LT(head->z(), -0.99);  // forward: towards the camera at the origin
  const double yaw = 0.7;
  const Skeleton turned = StandingPerson(2.0, yaw, false);
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto part = static_cast<BodyPart>(p);
    const auto d = PartReferenceDirection(facing, part), e = PartReferenceDirection(turned, part);
    ASSERT_TRUE(d.has_value() && e.has_value()) << PartName(part);
    const auto [ja, jb] = PartJoints(part);
    EXPECT_NEAR(d->norm(), 1, 1e-12);
    EXPECT_NEAR(d->dot((facing[jb] - facing[ja]).normalized()), 0, 1e-9);
    const Eigen::Matrix3d rot =
        Eigen::AngleAxisd(yaw, -Eigen::Vector3d::UnitY()).toRotationMatrix();
    EXPECT_NEAR((rot * *d - *e).norm(), 0, 1e-9) << PartName(part);
  }
}

// Degenerate: a missing joint, or a limb along its reference direction (the left arm pointing
// back and across the body), give none; PoseCylinder then drops the part's surface.
TEST(PartReferenceDirection, NoneForMissingJointsOrALimbAlongIt) {
  Skeleton s = StandingPerson(2.0, 0, false);
  Skeleton missing = s;
  missing.confidence[Index(Joint::kNeck)] = 0;
  EXPECT_FALSE(PartReferenceDirection(missing, BodyPart::kLeftForearm).has_value());
  const Eigen::Vector3d across = (s[Joint::kLeftShoulder] - s[Joint::kRightShoulder]).normalized();
  const Eigen::Vector3d forward =
      across.cross(s[Joint::kNeck] - s[Joint::kWaist]).normalized();
  s.Set(Joint::kLeftHand, s[Joint::kLeftElbow] + 0.25 * (-forward - across).normalized());
  EXPECT_FALSE(PartReferenceDirection(s, BodyPart::kLeftForearm).has_value());
  PartShapes shapes{};
  shapes[Index(BodyPart::kLeftForearm)].surface.angles = 4;
  for (auto& ring : shapes[Index(BodyPart::kLeftForearm)].surface.radial) ring.fill(1.2);
  const auto c = PoseCylinder(s, BodyPart::kLeftForearm, DefaultRadiusRatios(), {}, shapes);
  ASSERT_TRUE(c.has_value());
  EXPECT_TRUE(c->shape.surface.IsEmpty());
  EXPECT_FALSE(c->width_direction.has_value());
}

// A part with a surface is posed in its reference frame; a rounded end is as deep as its end
// ring's mean radius, as a fraction of the drawn axis; an invalid surface is refused.
TEST(PoseCylinder, SurfacesTakeTheReferenceFrameAndRoundedEndsTheirDepth) {
  const Skeleton s = StandingPerson(2.0, 0.3, false);
  PartShapes shapes{};
  PartShape& thigh = shapes[Index(BodyPart::kLeftThigh)];
  thigh.surface.angles = 8;
  for (auto& ring : thigh.surface.radial) ring.fill(1.1);
  thigh.width = {1.2, 1.2, 1.2, 1.2, 1.5};
  thigh.depth = {1.0, 1.0, 1.0, 1.0, 0.6};
  thigh.round_end = {true, true};
  const auto c = PoseCylinder(s, BodyPart::kLeftThigh, DefaultRadiusRatios(), {}, shapes);
  ASSERT_TRUE(c.has_value());
  ASSERT_TRUE(c->width_direction.has_value());
  EXPECT_NEAR((*c->width_direction - *PartReferenceDirection(s, BodyPart::kLeftThigh)).norm(), 0,
              1e-12);
  EXPECT_NEAR(c->shape.cap_depth[0], c->radius * std::sqrt(1.2 * 1.0) / c->Length(), 1e-12);
  EXPECT_NEAR(c->shape.cap_depth[1], c->radius * std::sqrt(1.5 * 0.6) / c->Length(), 1e-12);
  thigh.surface.radial[2][5] = -1;
  EXPECT_THROW(PoseCylinder(s, BodyPart::kLeftThigh, DefaultRadiusRatios(), {}, shapes),
               CheckError);
}

}  // namespace
}  // namespace reenact
