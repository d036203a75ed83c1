#include <gtest/gtest.h>

#include <cmath>

#include "vision/pose/observation_model.h"
#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact::vision {
namespace {

constexpr double kFx = 520, kFy = 515;

KeypointObservation Obs(double x, double y, double depth, int octave = 0) {
  KeypointObservation o;
  o.normalized = {x, y};
  o.depth_m = depth;
  o.octave = octave;
  return o;
}

TEST(SlamObservationModel, ResidualIsZeroAtTheMeasurementAndWhitened) {
  const ObservationNoise noise;
  const Eigen::Vector3d p(0.2, -0.1, 1.5);
  const auto r0 = EvaluateObservation(p, Obs(0.2 / 1.5, -0.1 / 1.5, 1.5), kFx, kFy, noise);
  ASSERT_TRUE(r0.valid);
  EXPECT_EQ(r0.dof, 3);
  EXPECT_LT(r0.r.norm(), 1e-12);
  // One pixel to the right at level 2: sigma is pixel_sigma * 1.2^2.
  const auto r1 =
      EvaluateObservation(p, Obs(0.2 / 1.5 - 1 / kFx, -0.1 / 1.5, 0, 2), kFx, kFy, noise);
  EXPECT_EQ(r1.dof, 2);
  EXPECT_NEAR(r1.r(0), 1 / (noise.pixel_sigma_px * 1.44), 1e-9);
  EXPECT_EQ(r1.r(2), 0);
  // Depth 3 cm short at 1.5 m: sigma_d = depth_sigma_1m_m * 1.5^2.
  const auto r2 = EvaluateObservation(p, Obs(0.2 / 1.5, -0.1 / 1.5, 1.47), kFx, kFy, noise);
  EXPECT_NEAR(r2.r(2), 0.03 / (noise.depth_sigma_1m_m * 1.47 * 1.47), 1e-9);
}

TEST(SlamObservationModel, JacobianMatchesFiniteDifferences) {
  const ObservationNoise noise;
  const Eigen::Vector3d p(0.3, 0.2, 2.0);
  const KeypointObservation o = Obs(0.1, 0.12, 2.1, 1);
  const auto r = EvaluateObservation(p, o, kFx, kFy, noise);
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(k) = 1e-6;
    const Eigen::Vector3d numeric = (EvaluateObservation(p + d, o, kFx, kFy, noise).r -
                                     EvaluateObservation(p - d, o, kFx, kFy, noise).r) /
                                    2e-6;
    EXPECT_LT((numeric - r.d_r_d_point.col(k)).norm(), 1e-4 * (1 + numeric.norm())) << k;
  }
}

TEST(SlamObservationModel, PoseJacobianMatchesTheLeftUpdate) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = ExpSo3({0.1, -0.2, 0.05});
  pose.translation() = Eigen::Vector3d(0.3, 0.1, -0.2);
  const Eigen::Vector3d world(0.5, 0.4, 2.5);
  const Eigen::Matrix<double, 3, 6> j = PointJacobianWrtPose(pose * world);
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 6, 1> d = Eigen::Matrix<double, 6, 1>::Zero();
    d(k) = 1e-7;
    const Eigen::Vector3d numeric =
        (ApplyPoseUpdate(d, pose) * world - ApplyPoseUpdate(-d, pose) * world) / 2e-7;
    EXPECT_LT((numeric - j.col(k)).norm(), 1e-6) << k;
  }
}

TEST(SlamObservationModel, PointsBehindTheCameraAreInvalidNotNaN) {
  const auto r = EvaluateObservation({0, 0, -1}, Obs(0, 0, 1), kFx, kFy, ObservationNoise{});
  EXPECT_FALSE(r.valid);
  EXPECT_FALSE(r.IsInlier());
  EXPECT_TRUE(r.r.allFinite());
  EXPECT_FALSE(EvaluateObservation({0, 0, 0}, Obs(0, 0, 0), kFx, kFy, ObservationNoise{}).valid);
}

TEST(SlamObservationModel, HuberIsQuadraticInsideAndLinearOutside) {
  ObservationResidual r;
  r.valid = true;
  r.dof = 2;
  const double delta = std::sqrt(kChi2Dof2);
  r.r = {0.5 * delta, 0, 0};
  EXPECT_DOUBLE_EQ(r.HuberWeight(), 1);
  EXPECT_DOUBLE_EQ(r.HuberCost(), 0.5 * 0.25 * delta * delta);
  EXPECT_TRUE(r.IsInlier());
  r.r = {4 * delta, 0, 0};
  EXPECT_DOUBLE_EQ(r.HuberWeight(), 0.25);
  EXPECT_DOUBLE_EQ(r.HuberCost(), delta * (4 * delta - 0.5 * delta));
  EXPECT_FALSE(r.IsInlier());
}

TEST(SlamObservationModel, OptionsOutOfRangeAreRefused) {
  ObservationNoise n;
  n.pixel_sigma_px = 0;
  EXPECT_THROW(n.Check(), CheckError);
  n = {};
  n.scale_factor = 1;
  EXPECT_THROW(n.Check(), CheckError);
  n = {};
  n.depth_sigma_1m_m = std::nan("");
  EXPECT_THROW(n.Check(), CheckError);
  EXPECT_NO_THROW(ObservationNoise{}.Check());
}

}  // namespace
}  // namespace reenact::vision
