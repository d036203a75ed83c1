// Sim3: x_in_b = s R x_in_a + t, composition, inverse and 4x4 conversion.
#include "common/geometry/similarity3.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact {
namespace {

constexpr double kPi = std::numbers::pi;

Sim3 Example(double s, const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& t) {
  return Sim3(s, *Theta(axis, angle), t);
}

TEST(Sim3, AppliesScaleRotationTranslationInThatOrder) {
  // 90 degrees about z takes e_x to e_y; scale 2; then shift by e_x: (1, 2, 0).
  const Sim3 b_from_a = Example(2, {0, 0, 1}, kPi / 2, {1, 0, 0});
  EXPECT_LT((b_from_a * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(1, 2, 0)).norm(), 1e-15);
  EXPECT_EQ(Sim3::Identity() * Eigen::Vector3d(4, 5, 6), Eigen::Vector3d(4, 5, 6));
}

TEST(Sim3, CompositionAppliesRightThenLeft) {
  const Sim3 b_from_a = Example(0.5, {1, 2, 3}, 0.4, {1, -2, 0.5});
  const Sim3 c_from_b = Example(3, {-1, 0, 2}, 2.1, {0.1, 4, -3});
  const Sim3 c_from_a = c_from_b * b_from_a;
  for (const Eigen::Vector3d& x :
       {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, -1, 2), Eigen::Vector3d(-3, 0.2, 7)})
    EXPECT_LT((c_from_a * x - c_from_b * (b_from_a * x)).norm(), 1e-13);
  EXPECT_NEAR(c_from_a.scale, 1.5, 1e-15);
}

TEST(Sim3, InverseUndoes) {
  const Sim3 b_from_a = Example(1e3, {0.3, -1, 0.2}, -2.9, {5, 6, -7});
  const Sim3 a_from_b = b_from_a.Inverse();
  const Eigen::Vector3d x(0.25, -8, 3);
  EXPECT_LT((a_from_b * (b_from_a * x) - x).norm(), 1e-12);
  const Sim3 id = a_from_b * b_from_a;
  EXPECT_NEAR(id.scale, 1, 1e-15);
  EXPECT_LT((id.rotation - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LT(id.translation.norm(), 1e-14);
}

TEST(Sim3, MatrixRoundTrip) {
  const Sim3 b_from_a = Example(1e-3, {1, 1, 0}, 1.3, {0.5, 0, -2});
  const Eigen::Matrix4d m = b_from_a.ToMatrix();
  const Eigen::Vector3d x(1, 2, 3);
  EXPECT_LT(((m * x.homogeneous()).head<3>() - b_from_a * x).norm(), 1e-15);
  const auto back = Sim3::FromMatrix(m);
  ASSERT_TRUE(back);
  EXPECT_NEAR(back->scale, 1e-3, 1e-18);
  EXPECT_LT((back->rotation - b_from_a.rotation).norm(), 1e-14);
  EXPECT_EQ(back->translation, b_from_a.translation);
}

TEST(Sim3, FromMatrixRejectsNonSimilarities) {
  Eigen::Matrix4d shear = Eigen::Matrix4d::Identity();
  shear(0, 1) = 0.1;
  EXPECT_FALSE(Sim3::FromMatrix(shear));
  Eigen::Matrix4d mirror = Eigen::Matrix4d::Identity();
  mirror(2, 2) = -1;
  EXPECT_FALSE(Sim3::FromMatrix(mirror));
  Eigen::Matrix4d projective = Eigen::Matrix4d::Identity();
  projective(3, 0) = 0.5;
  EXPECT_FALSE(Sim3::FromMatrix(projective));
  Eigen::Matrix4d nan = Eigen::Matrix4d::Identity();
  nan(0, 3) = std::nan("");
  EXPECT_FALSE(Sim3::FromMatrix(nan));
  EXPECT_FALSE(Sim3::FromMatrix(Eigen::Matrix4d::Zero()));
}

TEST(Sim3, IsometryRoundTrip) {
  Eigen::Isometry3d iso = Eigen::Isometry3d::Identity();
  iso.linear() = *Theta({0, 1, 0}, 0.8);
  iso.translation() = Eigen::Vector3d(1, 2, 3);
  const Sim3 s = Sim3::FromIsometry(iso);
  const Eigen::Vector3d x(-1, 0.5, 2);
  EXPECT_LT((s * x - iso * x).norm(), 1e-15);
  EXPECT_LT((s.RigidPart().matrix() - iso.matrix()).norm(), 1e-15);
}

TEST(Sim3, CheckRejectsBadScaleAndRotation) {
  EXPECT_NO_THROW(Example(2, {1, 0, 0}, 1, {0, 0, 0}).Check());
  EXPECT_THROW(Sim3(0, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()).Check(), CheckError);
  EXPECT_THROW(Sim3(1, 2 * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()).Check(),
               CheckError);
  EXPECT_THROW(Sim3(1, -Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()).Check(), CheckError);
}

}  // namespace
}  // namespace reenact
