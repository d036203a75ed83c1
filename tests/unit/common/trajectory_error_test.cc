// ATE: RMSE of positions after rigid or similarity alignment; timestamp association.
#include "common/align/trajectory_error.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact {
namespace {

std::vector<Eigen::Vector3d> Circle(int n) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i)
    out.push_back({2 * std::cos(0.3 * i), 2 * std::sin(0.3 * i), 0.05 * i});
  return out;
}

TEST(TrajectoryError, RigidlyMovedCopyHasZeroError) {
  const auto truth = Circle(30);
  const Sim3 est_from_truth(1, *Theta({1, 2, 3}, 0.8), {5, -1, 2});
  std::vector<Eigen::Vector3d> est;
  for (const auto& p : truth) est.push_back(est_from_truth * p);
  const TrajectoryErrorResult r = AbsoluteTrajectoryError(truth, est);
  ASSERT_TRUE(r.ok());
  EXPECT_LT(r.ate_rmse_m, 1e-13);
  EXPECT_LT(r.max_m, 1e-13);
  EXPECT_LT((r.truth_from_estimate.rotation - est_from_truth.rotation.transpose()).norm(), 1e-13);
  EXPECT_EQ(r.errors_m.size(), 30u);
}

TEST(TrajectoryError, KnownErrorWhereNoAlignmentHelps) {
  // Truth: (+-1, 0, 0), (0, +-1, 0). Estimate: +d z for the first pair, -d z for the second.
  // The errors have zero mean and sum_i t_i e_i^T = 0, so Sigma is symmetric PSD and the
  // best rigid alignment is the identity: every error is d, ATE = d.
  const double d = 0.03;
  const std::vector<Eigen::Vector3d> truth = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  const std::vector<Eigen::Vector3d> est = {{1, 0, d}, {-1, 0, d}, {0, 1, -d}, {0, -1, -d}};
  const TrajectoryErrorResult r = AbsoluteTrajectoryError(truth, est);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r.ate_rmse_m, d, 1e-15);
  EXPECT_NEAR(r.mean_m, d, 1e-15);
  EXPECT_NEAR(r.median_m, d, 1e-15);
  EXPECT_NEAR(r.max_m, d, 1e-15);
}

TEST(TrajectoryError, SimilarityAlignmentRemovesScale) {
  const auto truth = Circle(20);
  const Sim3 est_from_truth(0.25, *Theta({0, 0, 1}, 1.0), {1, 2, 3});  // monocular scale
  std::vector<Eigen::Vector3d> est;
  for (const auto& p : truth) est.push_back(est_from_truth * p);
  TrajectoryErrorOptions sim;
  sim.alignment = TrajectoryAlignment::kSimilarity;
  const TrajectoryErrorResult s = AbsoluteTrajectoryError(truth, est, sim);
  ASSERT_TRUE(s.ok());
  EXPECT_LT(s.ate_rmse_m, 1e-13);
  EXPECT_NEAR(s.truth_from_estimate.scale, 4, 1e-12);
  const TrajectoryErrorResult rigid = AbsoluteTrajectoryError(truth, est);
  ASSERT_TRUE(rigid.ok());
  EXPECT_GT(rigid.ate_rmse_m, 0.5);  // a quarter-size copy cannot be aligned rigidly
}

TEST(TrajectoryError, StraightLineTrajectoryIsAccepted) {
  std::vector<Eigen::Vector3d> truth, est;
  for (int i = 0; i < 10; ++i) {
    truth.push_back(Eigen::Vector3d(0.1 * i, 0, 1));
    est.push_back(Eigen::Vector3d(3, 0.1 * i, 0));
  }
  const TrajectoryErrorResult r = AbsoluteTrajectoryError(truth, est);
  ASSERT_TRUE(r.ok());
  EXPECT_LT(r.ate_rmse_m, 1e-14);
}

TEST(TrajectoryError, PosesCompareTheirTranslations) {
  const auto truth_positions = Circle(10);
  std::vector<Eigen::Isometry3d> truth, est;
  for (size_t i = 0; i < truth_positions.size(); ++i) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.translation() = truth_positions[i];
    truth.push_back(t);
    t.linear() = *Theta({1, 0, 0}, 0.1 * static_cast<double>(i));  // orientation is ignored
    t.translation() += Eigen::Vector3d(0, 0, i % 2 ? 0.01 : -0.01);
    est.push_back(t);
  }
  const TrajectoryErrorResult r = AbsoluteTrajectoryError(truth, est);
  ASSERT_TRUE(r.ok());
  EXPECT_GT(r.ate_rmse_m, 0);
  EXPECT_LE(r.ate_rmse_m, 0.01 + 1e-12);  // the identity alignment already gives 0.01
}

TEST(TrajectoryError, TooFewOrDegeneratePosesFail) {
  const std::vector<Eigen::Vector3d> two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(AbsoluteTrajectoryError(two, two).failure, UmeyamaFailure::kTooFewPoints);
  const std::vector<Eigen::Vector3d> still(5, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(AbsoluteTrajectoryError(Circle(5), still).failure, UmeyamaFailure::kCoincidentPoints);
  EXPECT_THROW(AbsoluteTrajectoryError(Circle(5), Circle(6)), CheckError);
}

TEST(TrajectoryError, AssociateByTimestampPairsClosestFirst) {
  const std::vector<double> truth = {0.0, 0.1, 0.2, 0.3, 0.4};
  // 0.105 and 0.11 both want truth 0.1: the closer (0.105) wins; 0.11 is then 0.09 from 0.2
  // (too far for 0.02); 0.29 pairs with 0.3; 0.6 has no partner.
  const std::vector<double> est = {0.005, 0.105, 0.11, 0.29, 0.6};
  const auto pairs = AssociateByTimestamp(truth, est, 0.02);
  const std::vector<std::pair<size_t, size_t>> expected = {{0, 0}, {1, 1}, {3, 3}};
  EXPECT_EQ(pairs, expected);
  EXPECT_TRUE(AssociateByTimestamp({}, est, 0.02).empty());
  EXPECT_THROW(AssociateByTimestamp({0.2, 0.1}, est, 0.02), CheckError);
  EXPECT_THROW(AssociateByTimestamp(truth, est, -1), CheckError);
}

}  // namespace
}  // namespace reenact
