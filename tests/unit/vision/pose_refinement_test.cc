#include <gtest/gtest.h>

#include <random>

#include "vision/pose/pose_refinement.h"
#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact::vision {
namespace {

constexpr double kF = 525;

Eigen::Isometry3d TruePose() {
  Eigen::Isometry3d sensor_from_world = Eigen::Isometry3d::Identity();
  sensor_from_world.linear() = ExpSo3({-0.1, 0.25, 0.05});
  sensor_from_world.translation() = Eigen::Vector3d(0.2, 0.1, -0.3);
  return sensor_from_world;
}

// Points 1.5-3.5 m in front of the true camera, seen with pixel noise and (optionally) depth.
std::vector<PointObservation> Observe(int n, double pixel_noise, bool depth, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g(0, 1);
  std::vector<PointObservation> out;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d camera(u(rng), 0.7 * u(rng), 2.5 + u(rng));
    PointObservation o;
    o.point_in_world = TruePose().inverse() * camera;
    o.observation.normalized =
        camera.head<2>() / camera.z() + pixel_noise / kF * Eigen::Vector2d(g(rng), g(rng));
    o.observation.depth_m = depth ? camera.z() : 0;
    out.push_back(o);
  }
  return out;
}

Eigen::Isometry3d Perturbed() {
  Eigen::Matrix<double, 6, 1> d;
  d << 0.05, -0.04, 0.03, 0.03, -0.02, 0.04;  // 7 cm, about 3 degrees
  return ApplyPoseUpdate(d, TruePose());
}

double PoseError(const Eigen::Isometry3d& a) {
  const Eigen::Isometry3d d = a * TruePose().inverse();
  return d.translation().norm() + RotationAngle(d.linear());
}

TEST(SlamPoseRefinement, ExactObservationsConvergeToTheTruth) {
  for (bool depth : {true, false}) {
    const auto r = RefinePose(Perturbed(), Observe(50, 0, depth, 1), kF, kF, ObservationNoise{},
                              PoseRefinementOptions{2, 20});
    EXPECT_LT(PoseError(r.sensor_from_world), 1e-7) << depth;
    EXPECT_EQ(r.num_inliers, 50);
  }
}

TEST(SlamPoseRefinement, OutliersAreFlaggedAndIgnored) {
  auto obs = Observe(100, 0.5, true, 2);
  for (size_t i = 0; i < obs.size(); i += 5) obs[i].observation.normalized.y() += 30 / kF;
  const auto r = RefinePose(Perturbed(), obs, kF, kF, ObservationNoise{});
  // 0.5 px noise on 80 good points: well under a millimetre / milliradian.
  EXPECT_LT(PoseError(r.sensor_from_world), 2e-3);
  for (size_t i = 0; i < obs.size(); ++i) EXPECT_EQ(r.inlier[i] != 0, i % 5 != 0) << i;
  EXPECT_EQ(r.num_inliers, 80);
}

TEST(SlamPoseRefinement, TooFewObservationsKeepTheInitialPose) {
  const auto obs = Observe(2, 0, true, 3);
  const auto r = RefinePose(Perturbed(), obs, kF, kF, ObservationNoise{});
  EXPECT_TRUE(r.sensor_from_world.isApprox(Perturbed()));
  EXPECT_EQ(r.inlier.size(), 2u);
  const auto none = RefinePose(Perturbed(), {}, kF, kF, ObservationNoise{});
  EXPECT_EQ(none.num_inliers, 0);
}

TEST(SlamPoseRefinement, NonFiniteStartIsDefinedNotNaN) {
  Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
  bad.translation().x() = std::nan("");
  const auto r = RefinePose(bad, Observe(20, 0, true, 4), kF, kF, ObservationNoise{});
  EXPECT_EQ(r.num_inliers, 0);
  for (char f : r.inlier) EXPECT_FALSE(f);
}

TEST(SlamPoseRefinement, BadArgumentsAreBugs) {
  EXPECT_THROW(RefinePose(TruePose(), {}, 0, kF, ObservationNoise{}), CheckError);
  EXPECT_THROW(RefinePose(TruePose(), {}, kF, kF, ObservationNoise{}, PoseRefinementOptions{0, 1}),
               CheckError);
}

}  // namespace
}  // namespace reenact::vision
