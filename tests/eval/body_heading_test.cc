// The heading error of body_heading.h on skeletons built from the tracker's rest pose (body
// frame: x forward, y left, z up), turned by known angles: the truth is the construction.
#include "tests/eval/body_heading.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "capture-client/tracker/articulated_body.h"

namespace reenact::eval {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180;

Skeleton Rest() { return capture::BodyShape::FromHeight(1.7).RestSkeleton(); }

// The skeleton turned by `rotation` about the origin, then moved by `shift`.
Skeleton Moved(const Skeleton& s, const Eigen::Matrix3d& rotation,
               const Eigen::Vector3d& shift = Eigen::Vector3d::Zero()) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation;
  t.translation() = shift;
  return s.Transformed(t);
}

Eigen::Matrix3d About(const Eigen::Vector3d& axis, double deg) {
  return Eigen::AngleAxisd(deg * kRadPerDeg, axis.normalized()).toRotationMatrix();
}

TEST(BodyHeading, TheRestPoseFacesForward) {
  const auto f = BodyForward(Rest());
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->x(), 1, 1e-9);
  EXPECT_NEAR(f->norm(), 1, 1e-12);
}

TEST(BodyHeading, ErrorIsTheTurnAboutUp) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Skeleton truth = Rest();
  for (const double deg : {0.0, 10.0, 45.0, 90.0, 135.0, 179.0, -30.0, -120.0}) {
    const auto e = HeadingErrorDeg(Moved(truth, About(up, deg), {0.3, -1, 2}), truth, up);
    ASSERT_TRUE(e) << deg;
    EXPECT_NEAR(*e, std::abs(deg), 1e-9) << deg;
  }
  // Symmetric, and whatever frame both are in (the sensor frame's up here along -y).
  const Eigen::Matrix3d sensor_from_body = About({1, 0, 0}, 90);
  const Eigen::Vector3d sensor_up = sensor_from_body * up;
  const Skeleton a = Moved(truth, sensor_from_body);
  const Skeleton b = Moved(truth, sensor_from_body * About(up, 70));
  EXPECT_NEAR(*HeadingErrorDeg(a, b, sensor_up), 70, 1e-9);
  EXPECT_NEAR(*HeadingErrorDeg(b, a, 3 * sensor_up), 70, 1e-9);  // up need not be unit
}

TEST(BodyHeading, LeaningDoesNotCountOnlyTurning) {
  // Bent forward 40 degrees (about the body's left axis) and turned 30: the floor sees 30.
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Skeleton truth = Rest();
  const Skeleton leaning = Moved(truth, About(up, 30) * About({0, 1, 0}, 40));
  EXPECT_NEAR(*HeadingErrorDeg(leaning, truth, up), 30, 1e-9);
}

TEST(BodyHeading, DegenerateBodiesHaveNoHeading) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Skeleton truth = Rest();
  // Shoulders at one point.
  Skeleton narrow = truth;
  narrow[Joint::kLeftShoulder] = narrow[Joint::kRightShoulder];
  EXPECT_FALSE(BodyForward(narrow));
  EXPECT_FALSE(HeadingErrorDeg(narrow, truth, up));
  EXPECT_FALSE(HeadingErrorDeg(truth, narrow, up));
  // No spine: the neck at the waist.
  Skeleton folded = truth;
  folded[Joint::kNeck] = folded[Joint::kWaist];
  EXPECT_FALSE(BodyForward(folded));
  // The shoulder line along the spine.
  Skeleton sideways = truth;
  sideways[Joint::kLeftShoulder] = sideways[Joint::kNeck];
  sideways[Joint::kRightShoulder] = sideways[Joint::kWaist];
  EXPECT_FALSE(BodyForward(sideways));
  // Lying face up: the forward is up, no heading on the floor.
  EXPECT_FALSE(HeadingErrorDeg(Moved(truth, About({0, 1, 0}, -90)), truth, up));
  // A zero up.
  EXPECT_FALSE(HeadingErrorDeg(truth, truth, Eigen::Vector3d::Zero()));
  // An everyday body against itself: 0, never NaN.
  const auto same = HeadingErrorDeg(truth, truth, up);
  ASSERT_TRUE(same);
  EXPECT_EQ(*same, 0);
}

}  // namespace
}  // namespace reenact::eval
