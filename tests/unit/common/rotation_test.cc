// Rotations: Rodrigues (Eq. 8) and the minimal rotation between directions, at the
// degenerate cases (parallel, anti-parallel, tiny angles, dot products rounding past +-1).
#include "common/geometry/rotation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "common/error/check.h"

namespace reenact {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Vector3d RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Eigen::Vector3d v;
  do v = Eigen::Vector3d(g(rng), g(rng), g(rng));
  while (v.norm() < 1e-3);
  return v.normalized();
}

TEST(Rotation, ThetaQuarterTurnAboutZ) {
  const auto r = Theta({0, 0, 3}, kPi / 2);  // axis length does not matter
  ASSERT_TRUE(r);
  EXPECT_LT((*r * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  EXPECT_LT((*r * Eigen::Vector3d::UnitY() + Eigen::Vector3d::UnitX()).norm(), 1e-15);
  EXPECT_LT((*r * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
}

TEST(Rotation, ThetaRejectsZeroAxisAndNonFiniteInput) {
  EXPECT_FALSE(Theta(Eigen::Vector3d::Zero(), 0.3));
  EXPECT_FALSE(Theta({0, 0, 1}, std::nan("")));
  EXPECT_FALSE(Theta({0, std::numeric_limits<double>::infinity(), 1}, 0.1));
}

TEST(Rotation, ThetaAtOneNanoradianKeepsFullPrecision) {
  const double angle = 1e-9;
  const auto r = Theta({0, 0, 1}, angle);
  ASSERT_TRUE(r);
  // R e_x = (cos, sin, 0): sin(1e-9) = 1e-9 - 1.7e-28.
  EXPECT_NEAR((*r)(1, 0), angle, 1e-24);
  EXPECT_NEAR((*r)(0, 1), -angle, 1e-24);
  EXPECT_NEAR(RotationAngle(*r), angle, 1e-22);
  // The symmetric part 2 sin^2(angle/2) (n n^T - I) about a tilted axis: element (0,1) is
  // 2 sin^2(5e-10) n_x n_y = 5e-19 * 0.5 for n = (1, 1, 0)/sqrt(2), not rounded to 0.
  const auto tilted = Theta({1, 1, 0}, angle);
  ASSERT_TRUE(tilted);
  const Eigen::Matrix3d sym = 0.5 * (*tilted + tilted->transpose());
  EXPECT_NEAR(sym(0, 1), 2.5e-19, 1e-30);
}

TEST(Rotation, ExpSo3SeriesAgreesWithRodriguesAcrossTheSwitch) {
  EXPECT_EQ(ExpSo3(Eigen::Vector3d::Zero()), Eigen::Matrix3d::Identity());
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  for (double t : {1e-12, 1e-9, 0.99e-4, 1e-4, 1.01e-4, 1e-2, 1.0, 3.0}) {
    const Eigen::Matrix3d series_or_closed = ExpSo3(t * axis);
    // Independent evaluation by the textbook formula with sin and cos directly.
    const Eigen::Matrix3d k = Skew(axis);
    const Eigen::Matrix3d textbook =
        Eigen::Matrix3d::Identity() + std::sin(t) * k + (1 - std::cos(t)) * k * k;
    EXPECT_LT((series_or_closed - textbook).cwiseAbs().maxCoeff(), 1e-15) << t;
    EXPECT_NEAR(RotationAngle(series_or_closed), t, 1e-15 + 1e-12 * t) << t;
  }
  EXPECT_THROW(ExpSo3({std::nan(""), 0, 0}), CheckError);
}

TEST(Rotation, AngleBetweenUsesAtan2) {
  EXPECT_NEAR(*AngleBetween({1, 0, 0}, {0, 2, 0}), kPi / 2, 1e-15);
  EXPECT_NEAR(*AngleBetween({1, 0, 0}, {1, 1e-9, 0}), 1e-9, 1e-24);  // acos would give 0
  EXPECT_EQ(*AngleBetween({0, 0, 5}, {0, 0, -1}), kPi);
  EXPECT_FALSE(AngleBetween(Eigen::Vector3d::Zero(), {1, 0, 0}));
}

TEST(Rotation, BetweenGeneralVectors) {
  const Eigen::Vector3d u(1, 2, 3), v(-2, 0.5, 1);
  const auto r = RotationBetween(u, v);
  ASSERT_TRUE(r);
  EXPECT_LT((*r * u.normalized() - v.normalized()).norm(), 1e-15);
  // Minimal: the axis u x v is fixed and the angle is the angle between u and v.
  const Eigen::Vector3d axis = u.cross(v).normalized();
  EXPECT_LT((*r * axis - axis).norm(), 1e-15);
  EXPECT_NEAR(RotationAngle(*r), std::acos(u.normalized().dot(v.normalized())), 1e-14);
}

TEST(Rotation, BetweenParallelVectorsIsIdentity) {
  const auto r = RotationBetween({0.3, -1, 2}, {0.6, -2, 4});
  ASSERT_TRUE(r);
  EXPECT_LT((*r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Rotation, BetweenAntiParallelVectorsTurnsHalfAboutADeterministicAxis) {
  // u = e_x: smallest components y and z tie, the first (y) is used: axis e_x x e_y = e_z.
  const auto r = RotationBetween({2, 0, 0}, {-1, 0, 0});
  ASSERT_TRUE(r);
  EXPECT_LT((*r - Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix()).cwiseAbs().maxCoeff(),
            1e-15);
  // A general anti-parallel pair: R u = -u, angle pi, orthonormal, det +1, axis perpendicular.
  const Eigen::Vector3d u = Eigen::Vector3d(0.2, -0.7, 0.4).normalized();
  const auto q = RotationBetween(u, -3 * u);
  ASSERT_TRUE(q);
  EXPECT_LT((*q * u + u).norm(), 1e-15);
  EXPECT_NEAR(RotationAngle(*q), kPi, 1e-15);
  EXPECT_LT(OrthonormalityError(*q), 1e-15);
  EXPECT_NEAR(q->determinant(), 1, 1e-15);
  const Eigen::Vector3d axis = *AnyPerpendicular(u);
  EXPECT_NEAR(axis.dot(u), 0, 1e-16);
  EXPECT_LT((*q * axis - axis).norm(), 1e-15);
}

TEST(Rotation, BetweenNearlyAntiParallelVectorsStaysExact) {
  const Eigen::Vector3d u = Eigen::Vector3d(1, 2, -1).normalized();
  const Eigen::Vector3d w = *AnyPerpendicular(u);
  for (double eps : {1e-6, 1e-9, 1e-12, 1e-15}) {
    const Eigen::Vector3d v = (-u + eps * w).normalized();
    const auto r = RotationBetween(u, v);
    ASSERT_TRUE(r);
    // A few ulps (eps = 2.2e-16): no loss growing like 1 / |u x v|.
    EXPECT_LT((*r * u - v).norm(), 2e-15) << eps;
    EXPECT_LT(OrthonormalityError(*r), 4e-15);
  }
}

TEST(Rotation, BetweenVectorsOneNanoradianApart) {
  const auto r = RotationBetween({1, 0, 0}, {1, 1e-9, 0});
  ASSERT_TRUE(r);
  EXPECT_NEAR((*r)(1, 0), 1e-9, 1e-24);  // rotation about +z by 1e-9 rad
  EXPECT_NEAR((*r)(0, 1), -1e-9, 1e-24);
  EXPECT_NEAR(RotationAngle(*r), 1e-9, 1e-22);
}

TEST(Rotation, DotProductsRoundingPastOneGiveDefinedResults) {
  // Find unit vectors whose self dot product rounds above 1 (and so below -1 with -v).
  Eigen::Vector3d v;
  bool found = false;
  for (int i = 1; i < 1000 && !found; ++i) {
    v = Eigen::Vector3d(1, 0.001 * i, 0.37).normalized();
    found = v.dot(v) > 1;
  }
  ASSERT_TRUE(found) << "no unit vector with v.v > 1 found";
  EXPECT_EQ(*AngleBetween(v, v), 0);
  EXPECT_EQ(*AngleBetween(v, -v), kPi);
  const auto same = RotationBetween(v, v);
  const auto opposite = RotationBetween(v, -v);
  ASSERT_TRUE(same && opposite);
  EXPECT_TRUE(same->allFinite() && opposite->allFinite());
  EXPECT_LT((*same * v - v).norm(), 1e-15);
  EXPECT_LT((*opposite * v + v).norm(), 1e-15);
}

TEST(Rotation, BetweenZeroOrNonFiniteVectorsIsNullopt) {
  EXPECT_FALSE(RotationBetween(Eigen::Vector3d::Zero(), {1, 0, 0}));
  EXPECT_FALSE(RotationBetween({1, 0, 0}, Eigen::Vector3d::Zero()));
  EXPECT_FALSE(RotationBetween({std::nan(""), 0, 0}, {1, 0, 0}));
  EXPECT_FALSE(AnyPerpendicular(Eigen::Vector3d::Zero()));
}

TEST(Rotation, TinyButNonZeroVectorsStillWork) {
  const auto r = RotationBetween({1e-200, 0, 0}, {0, 1e-200, 0});
  ASSERT_TRUE(r);
  EXPECT_LT((*r * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-15);
}

// 10^5 random samples: every rotation is orthonormal to 1e-12 with det +1, and maps u onto v.
TEST(Rotation, RandomPropertyOrthonormalAndExact) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  double worst_orthonormal = 0, worst_map = 0, worst_angle = 0;
  for (int i = 0; i < 100000; ++i) {
    const Eigen::Vector3d u = RandomUnit(rng), v = RandomUnit(rng);
    const Eigen::Matrix3d r = *RotationBetween(u, v);
    worst_orthonormal = std::max(worst_orthonormal, OrthonormalityError(r));
    worst_map = std::max(worst_map, (r * u - v).norm());
    EXPECT_GT(r.determinant(), 0);
    const double a = angle(rng);
    const Eigen::Matrix3d t = *Theta(u, a);
    worst_orthonormal = std::max(worst_orthonormal, OrthonormalityError(t));
    worst_angle = std::max(worst_angle, std::abs(RotationAngle(t) - std::abs(a)));
  }
  EXPECT_LT(worst_orthonormal, 1e-12);
  EXPECT_LT(worst_map, 1e-12);
  // RotationAngle's atan2 form: error ~ eps / sin(angle) is not an issue, it is well
  // conditioned everywhere, so a few ulps of pi.
  EXPECT_LT(worst_angle, 1e-12);
}

TEST(Rotation, NearestRotationProjectsOntoSo3) {
  const Eigen::Matrix3d r = *Theta({1, 2, 3}, 0.7);
  Eigen::Matrix3d noisy = r;
  noisy(0, 1) += 1e-6;
  const Eigen::Matrix3d fixed = NearestRotation(noisy);
  EXPECT_LT(OrthonormalityError(fixed), 1e-14);
  EXPECT_LT((fixed - r).norm(), 1e-6);
  // A reflection is projected to a rotation (det +1).
  EXPECT_NEAR(NearestRotation(Eigen::Vector3d(1, 1, -1).asDiagonal().toDenseMatrix()).determinant(),
              1, 1e-15);
  EXPECT_THROW(NearestRotation(Eigen::Matrix3d::Constant(std::nan(""))), CheckError);
}

}  // namespace
}  // namespace reenact
