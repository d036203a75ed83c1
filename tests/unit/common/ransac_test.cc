// Generic RANSAC: line and plane fits and a Umeyama estimator, each with gross outliers.
#include "common/estimate/ransac.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "common/align/umeyama_estimator.h"
#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact {
namespace {

// Hyperplane n . x = c in D dimensions (a line for D = 2, a plane for D = 3), fitted by total
// least squares: n is the eigenvector of the scatter matrix with the smallest eigenvalue.
template <int D>
struct HyperplaneEstimator {
  using Sample = Eigen::Matrix<double, D, 1>;
  struct Model {
    Sample normal = Sample::UnitX();
    double offset = 0;
  };
  static constexpr int kMinSampleSize = D;

  std::vector<Model> Estimate(const std::vector<Sample>& samples) const {
    Sample mean = Sample::Zero();
    for (const auto& s : samples) mean += s;
    mean /= static_cast<double>(samples.size());
    Eigen::Matrix<double, D, D> scatter = Eigen::Matrix<double, D, D>::Zero();
    for (const auto& s : samples) scatter += (s - mean) * (s - mean).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> eig(scatter);
    // Degenerate: the points do not span a hyperplane (second-smallest eigenvalue ~ 0).
    if (!(eig.eigenvalues()(1) > 1e-12 * eig.eigenvalues()(D - 1))) return {};
    const Sample n = eig.eigenvectors().col(0);
    return {Model{n, n.dot(mean)}};
  }
  std::vector<double> Residuals(const Model& m, const std::vector<Sample>& samples) const {
    std::vector<double> r;
    for (const auto& s : samples) r.push_back(std::abs(m.normal.dot(s) - m.offset));
    return r;
  }
};
using LineEstimator = HyperplaneEstimator<2>;
using PlaneEstimator = HyperplaneEstimator<3>;

static_assert(RansacEstimator<LineEstimator>);
static_assert(RansacEstimator<PlaneEstimator>);
static_assert(RansacEstimator<UmeyamaEstimator>);
static_assert(!RansacEstimator<int>);

// An estimator that never produces a model.
struct NeverEstimator {
  using Sample = double;
  using Model = double;
  static constexpr int kMinSampleSize = 1;
  std::vector<double> Estimate(const std::vector<double>&) const { return {}; }
  std::vector<double> Residuals(const double&, const std::vector<double>& s) const {
    return std::vector<double>(s.size(), 0);
  }
};

// 100 points on y = 0.5 x + 1 (exact) and 60 outliers at least 0.5 from it; first the
// inliers, then the outliers, so the true inlier set is {0..99}.
std::vector<Eigen::Vector2d> LineData(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-10, 10);
  std::vector<Eigen::Vector2d> data;
  for (int i = 0; i < 100; ++i) {
    const double x = u(rng);
    data.push_back({x, 0.5 * x + 1});
  }
  while (data.size() < 160) {
    const Eigen::Vector2d p(u(rng), u(rng));
    if (std::abs(p.y() - 0.5 * p.x() - 1) / std::sqrt(1.25) > 0.5) data.push_back(p);
  }
  return data;
}

std::vector<size_t> Range(size_t n) {
  std::vector<size_t> r(n);
  for (size_t i = 0; i < n; ++i) r[i] = i;
  return r;
}

TEST(Ransac, LineFitFindsExactlyTheInliers) {
  RansacOptions options;
  options.max_error = 0.01;
  const auto data = LineData(1);
  const auto result = Ransac(LineEstimator{}, data, options);
  ASSERT_TRUE(result.success);
  EXPECT_EQ(result.inliers, Range(100));
  EXPECT_NEAR(result.inlier_ratio, 100.0 / 160.0, 1e-15);
  // The line y = 0.5 x + 1 has normal (-0.5, 1) / sqrt(1.25) (up to sign), offset 1 / sqrt(1.25).
  const Eigen::Vector2d n = Eigen::Vector2d(-0.5, 1).normalized();
  const double sign = result.model.normal.dot(n) > 0 ? 1 : -1;
  EXPECT_LT((sign * result.model.normal - n).norm(), 1e-12);
  EXPECT_NEAR(sign * result.model.offset, 1 / std::sqrt(1.25), 1e-12);
  // Adaptive: w = 0.625, m = 2, p = 0.99 needs ceil(log 0.01 / log(1 - 0.390625)) = 10
  // trials once the true line is found; far fewer than the 10000 allowed.
  EXPECT_LE(result.num_trials, 200);
  EXPECT_GE(result.num_trials, 10);
}

TEST(Ransac, DeterministicForASeed) {
  RansacOptions options;
  options.max_error = 0.01;
  options.seed = 42;
  const auto data = LineData(2);
  const auto a = Ransac(LineEstimator{}, data, options);
  const auto b = Ransac(LineEstimator{}, data, options);
  EXPECT_EQ(a.num_trials, b.num_trials);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.model.normal, b.model.normal);
  options.seed = 43;
  const auto c = Ransac(LineEstimator{}, data, options);
  EXPECT_EQ(c.inliers, a.inliers);  // another seed, same consensus
}

TEST(Ransac, RequiredTrialsFormula) {
  RansacOptions options;  // confidence 0.99
  // log(0.01) / log(0.75) = 16.008: 17 trials.
  EXPECT_EQ(RansacRequiredTrials(0.5, 2, options), 17);
  EXPECT_EQ(RansacRequiredTrials(1.0, 3, options), 0);
  EXPECT_EQ(RansacRequiredTrials(0.0, 3, options), options.max_iterations);
  EXPECT_EQ(RansacRequiredTrials(1e-3, 8, options), options.max_iterations);  // w^m underflows
  options.min_iterations = 30;
  EXPECT_EQ(RansacRequiredTrials(0.5, 2, options), 30);
}

TEST(Ransac, AllInliersStopsAfterMinIterations) {
  std::vector<Eigen::Vector2d> data;
  for (int i = 0; i < 20; ++i) data.push_back({i, 2.0 * i});
  RansacOptions options;
  options.max_error = 1e-9;
  EXPECT_EQ(Ransac(LineEstimator{}, data, options).num_trials, 1);
  options.min_iterations = 5;
  const auto r = Ransac(LineEstimator{}, data, options);
  EXPECT_EQ(r.num_trials, 5);
  EXPECT_EQ(r.inliers.size(), 20u);
}

TEST(Ransac, PlaneFitWithNoiseAndLocalOptimisation) {
  // Plane z = 0.2 x - 0.1 y + 3 with noise of std 0.002 (within max_error 0.01 at 5 std),
  // plus 50% outliers at least 0.5 away.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  std::normal_distribution<double> noise(0, 0.002);
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, -1).normalized();
  const double c = -3 / Eigen::Vector3d(0.2, -0.1, -1).norm();
  std::vector<Eigen::Vector3d> data;
  for (int i = 0; i < 200; ++i) {
    const double x = u(rng), y = u(rng);
    data.push_back({x, y, 0.2 * x - 0.1 * y + 3 + noise(rng)});
  }
  while (data.size() < 400) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng) + 3);
    if (std::abs(n.dot(p) - c) > 0.5) data.push_back(p);
  }
  RansacOptions options;
  options.max_error = 0.01;
  options.local_optimization_rounds = 3;
  options.final_refit = true;
  const auto r = Ransac(PlaneEstimator{}, data, options);
  ASSERT_TRUE(r.success);
  EXPECT_EQ(r.inliers, Range(200));
  const double sign = r.model.normal.dot(n) > 0 ? 1 : -1;
  // Least squares over 200 points with z-noise 0.002 over a 10 m square: the normal's
  // tilt has std ~ 0.002 / (sqrt(200) * 2.9 m) ~ 5e-5; 1e-3 is a > 10 std bound.
  EXPECT_LT((sign * r.model.normal - n).norm(), 1e-3);
  EXPECT_NEAR(sign * r.model.offset, c, 1e-3);
}

TEST(Ransac, UmeyamaEstimatorWithOutliers) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-2, 2);
  const Sim3 truth(1.7, *Theta({0.3, 1, -0.2}, 2.4), {10, -3, 4});
  std::vector<UmeyamaEstimator::Sample> data;
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector3d a(u(rng), u(rng), u(rng));
    data.push_back({a, truth * a});
  }
  while (data.size() < 100) {  // 40% wrong matches, at least 0.5 m off
    const Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng) + 10, u(rng) - 3, u(rng) + 4);
    if ((b - truth * a).norm() > 0.5) data.push_back({a, b});
  }
  RansacOptions options;
  options.max_error = 1e-6;
  options.final_refit = true;
  const auto r = Ransac(UmeyamaEstimator{}, data, options);
  ASSERT_TRUE(r.success);
  EXPECT_EQ(r.inliers, Range(60));
  EXPECT_NEAR(r.model.scale, 1.7, 1e-12);
  EXPECT_LT(RotationAngle(r.model.rotation * truth.rotation.transpose()), 1e-12);
  EXPECT_LT((r.model.translation - truth.translation).norm(), 1e-11);
}

TEST(Ransac, NoModelOrTooLittleData) {
  RansacOptions options;
  options.max_iterations = 50;
  const auto none = Ransac(NeverEstimator{}, std::vector<double>{1, 2, 3}, options);
  EXPECT_FALSE(none.success);
  EXPECT_EQ(none.num_trials, 50);
  const auto small = Ransac(LineEstimator{}, std::vector<Eigen::Vector2d>{{0, 0}}, options);
  EXPECT_FALSE(small.success);
  EXPECT_EQ(small.num_trials, 0);
}

TEST(Ransac, BadOptionsAreACheckError) {
  const auto data = LineData(5);
  RansacOptions bad;
  bad.confidence = 1;
  EXPECT_THROW(Ransac(LineEstimator{}, data, bad), CheckError);
  bad = {};
  bad.max_error = 0;
  EXPECT_THROW(Ransac(LineEstimator{}, data, bad), CheckError);
  bad = {};
  bad.min_iterations = 10;
  bad.max_iterations = 5;
  EXPECT_THROW(Ransac(LineEstimator{}, data, bad), CheckError);
}

}  // namespace
}  // namespace reenact
