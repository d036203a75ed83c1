#include <gtest/gtest.h>

#include <random>

#include "vision/pose/pnp_estimator.h"
#include "common/estimate/ransac.h"
#include "common/geometry/rotation.h"

namespace reenact::vision {
namespace {

Eigen::Isometry3d TruePose() {
  Eigen::Isometry3d sensor_from_world = Eigen::Isometry3d::Identity();
  sensor_from_world.linear() = ExpSo3({0.2, -0.3, 0.1});
  sensor_from_world.translation() = Eigen::Vector3d(0.1, -0.2, 0.4);
  return sensor_from_world;
}

std::vector<PnpEstimator::Sample> Samples(const Eigen::Isometry3d& sensor_from_world, int n,
                                          uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<PnpEstimator::Sample> out;
  while (static_cast<int>(out.size()) < n) {
    const Eigen::Vector3d camera(u(rng), 0.7 * u(rng), 2.5 + u(rng));
    PnpEstimator::Sample s;
    s.point_in_world = sensor_from_world.inverse() * camera;
    s.normalized = camera.head<2>() / camera.z();
    out.push_back(s);
  }
  return out;
}

double PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d d = a * b.inverse();
  return d.translation().norm() + RotationAngle(d.linear());
}

TEST(SlamPnp, ThreePointsGiveTheTruePoseAmongTheirSolutions) {
  const PnpEstimator e{525, 525};
  const auto samples = Samples(TruePose(), 3, 1);
  const auto models = e.Estimate(samples);
  ASSERT_FALSE(models.empty());
  ASSERT_LE(models.size(), 4u);
  double best = 1e9;
  for (const auto& m : models) best = std::min(best, PoseError(m, TruePose()));
  EXPECT_LT(best, 1e-6);
}

TEST(SlamPnp, ManyPointsGiveTheTruePose) {
  const PnpEstimator e{525, 525};
  const auto models = e.Estimate(Samples(TruePose(), 40, 2));
  ASSERT_EQ(models.size(), 1u);
  EXPECT_LT(PoseError(models[0], TruePose()), 1e-6);
}

TEST(SlamPnp, ResidualsArePixelsAndInfiniteBehindTheCamera) {
  const PnpEstimator e{500, 400};
  PnpEstimator::Sample s;
  s.point_in_world = {0, 0, 2};
  s.normalized = {3.0 / 500, 4.0 / 400};  // 3 px right, 4 px down of the projection
  PnpEstimator::Sample behind;
  behind.point_in_world = {0, 0, -2};
  const auto r = e.Residuals(Eigen::Isometry3d::Identity(), {s, behind});
  EXPECT_NEAR(r[0], 5.0, 1e-9);
  EXPECT_TRUE(std::isinf(r[1]));
}

TEST(SlamPnp, DegenerateSamplesGiveNoModelAndNoCrash) {
  const PnpEstimator e{525, 525};
  std::vector<PnpEstimator::Sample> same(3);
  for (auto& s : same) s.point_in_world = {0, 0, 2};
  for (const auto& m : e.Estimate(same)) EXPECT_TRUE(m.matrix().allFinite());
  std::vector<PnpEstimator::Sample> nan(3);
  nan[0].point_in_world = {std::nan(""), 0, 1};
  EXPECT_TRUE(e.Estimate(nan).empty());
  EXPECT_TRUE(e.Estimate({}).empty());
}

TEST(SlamPnp, RansacFindsThePoseAmongOutliers) {
  auto samples = Samples(TruePose(), 100, 3);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (size_t i = 0; i < samples.size(); i += 3) samples[i].normalized = {u(rng), u(rng)};
  RansacOptions o;
  o.max_error = 2;
  o.seed = 5;
  const auto r = Ransac(PnpEstimator{525, 525}, samples, o);
  ASSERT_TRUE(r.success);
  EXPECT_LT(PoseError(r.model, TruePose()), 1e-4);
  for (size_t i : r.inliers) EXPECT_NE(i % 3, 0u) << i;
  EXPECT_EQ(r.inliers.size(), 66u);  // every sample whose keypoint was not replaced
}

}  // namespace
}  // namespace reenact::vision
