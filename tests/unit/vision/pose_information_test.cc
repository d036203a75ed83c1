// The information matrix of a refined pose against the scatter of the pose itself: for
// Gaussian keypoint noise of the sigma the refinement assumes, the covariance of the estimate
// is the inverse information (least squares, to first order).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "common/geometry/rotation.h"
#include "vision/pose/pose_refinement.h"

namespace reenact::vision {
namespace {

constexpr double kF = 525;

TEST(PoseInformation, InverseInformationIsTheCovarianceOfTheEstimate) {
  // 60 points 2-6 m away, seen without depth, with 1 px keypoint noise (the noise model's
  // sigma); 300 trials.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g(0, 1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 60; ++i) points.emplace_back(1.5 * u(rng), 1.0 * u(rng), 4 + 2 * u(rng));
  ObservationNoise noise;
  noise.pixel_sigma_px = 1.0;
  const Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  Eigen::Matrix<double, 6, 6> scatter = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  constexpr int kTrials = 300;
  for (int t = 0; t < kTrials; ++t) {
    std::vector<PointObservation> obs;
    for (const Eigen::Vector3d& p : points) {
      PointObservation o;
      o.point_in_world = p;
      o.observation.normalized = p.head<2>() / p.z() + Eigen::Vector2d(g(rng), g(rng)) / kF;
      obs.push_back(o);
    }
    const PoseRefinementResult r =
        RefinePose(truth, obs, kF, kF, noise, PoseRefinementOptions{1, 20});
    ASSERT_GE(r.num_inliers, 50);
    // delta of the estimate from the truth in the update's parametrisation.
    Eigen::Matrix<double, 6, 1> d;
    const Eigen::AngleAxisd aa(r.sensor_from_world.linear() * truth.linear().transpose());
    d.head<3>() = r.sensor_from_world.translation() -
                  r.sensor_from_world.linear() * truth.linear().transpose() * truth.translation();
    d.tail<3>() = aa.axis() * aa.angle();
    scatter += d * d.transpose() / kTrials;
    information += r.information / kTrials;
  }
  const Eigen::Matrix<double, 6, 6> predicted = information.inverse();
  // Per-direction variances within 35% (300 samples: the sample variance's own spread is
  // about 8%; the information averages over trials that drop a few points as outliers), and
  // the weakest direction (a sideways shift traded against a turn) found by both.
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(scatter(i, i) / predicted(i, i), 1.0, 0.35) << i;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> weak(predicted);
  const Eigen::Matrix<double, 6, 1> direction = weak.eigenvectors().col(5);
  const double along = direction.dot(scatter * direction);
  EXPECT_NEAR(along / weak.eigenvalues()(5), 1.0, 0.35);
}

TEST(PoseInformation, TooFewInliersGiveNoInformation) {
  std::vector<PointObservation> obs(2);
  obs[0].point_in_world = {0, 0, 3};
  obs[1].point_in_world = {1, 0, 3};
  obs[1].observation.normalized = {1.0 / 3, 0};
  const PoseRefinementResult r =
      RefinePose(Eigen::Isometry3d::Identity(), obs, kF, kF, ObservationNoise{});
  EXPECT_TRUE(r.information.isZero());
}

}  // namespace
}  // namespace reenact::vision
