#include "viewer-client/reloc/pose_smoother.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/error/check.h"
#include "vision/pose/observation_model.h"

namespace reenact::viewer {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// viewer_from_world of a camera moving at constant velocity: frame k = U(k * xi) T0.
Eigen::Isometry3d Truth(int k) {
  Vector6 xi;
  xi << 0.004, 0.001, -0.002, 0.001, 0.004, 0.0;  // 4.6 mm and 0.24 degrees per frame
  return vision::ApplyPoseUpdate(k * xi, Eigen::Isometry3d::Identity());
}

// Measurements whose error has sigma 2 cm along one direction (x translation) and 1 mm / 0.01
// rad elsewhere, with the matching information matrix.
struct Noisy {
  Eigen::Isometry3d pose;
  Matrix6 information;
};
Noisy Measure(int k, std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  Vector6 sigma;
  sigma << 0.02, 0.001, 0.001, 0.0002, 0.0002, 0.0002;
  Vector6 error;
  for (int i = 0; i < 6; ++i) error(i) = sigma(i) * g(rng);
  return {vision::ApplyPoseUpdate(error, Truth(k)),
          Matrix6(sigma.cwiseInverse().cwiseAbs2().asDiagonal())};
}

TEST(PoseSmoother, WeakDirectionGetsItsNoiseAveragedAway) {
  // The steady state of a constant-velocity Kalman filter with acceleration sigma 5 mm per
  // frame^2 and measurement sigma 2 cm (the Riccati recursion of this model, iterated to
  // convergence) keeps 0.71 of the measurement's standard deviation: bound 0.8. Directions
  // the frames pin down (1 mm) keep that accuracy (bound 1.2 mm).
  std::mt19937_64 rng(3);
  PoseSmoother smoother;
  double raw = 0, smoothed = 0, strong = 0;
  int n = 0;
  for (int k = 0; k < 300; ++k) {
    const Noisy m = Measure(k, rng);
    const Eigen::Isometry3d out = smoother.Update(m.pose, m.information);
    if (k < 30) continue;  // settling
    raw += std::pow(PoseDelta(Truth(k), m.pose)(0), 2);
    const Vector6 e = PoseDelta(Truth(k), out);
    smoothed += e(0) * e(0);
    strong += e(1) * e(1);
    ++n;
  }
  EXPECT_LT(std::sqrt(smoothed / n), 0.8 * std::sqrt(raw / n));
  EXPECT_LT(std::sqrt(strong / n), 0.0012);
}

TEST(PoseSmoother, FirstMeasurementIsTakenAndMotionIsPredicted) {
  PoseSmoother smoother;
  EXPECT_FALSE(smoother.Predict().has_value());
  const Matrix6 precise = 1e8 * Matrix6::Identity();
  const Eigen::Isometry3d first = smoother.Update(Truth(0), precise);
  EXPECT_TRUE(first.isApprox(Truth(0)));
  EXPECT_TRUE(smoother.restarted());
  for (int k = 1; k < 5; ++k) smoother.Update(Truth(k), precise);
  EXPECT_FALSE(smoother.restarted());
  // Exact measurements of a constant velocity: the prediction is the next frame.
  EXPECT_LT(PoseDelta(Truth(5), *smoother.Predict()).norm(), 1e-4);
  smoother.Reset();
  EXPECT_FALSE(smoother.Predict().has_value());
}

TEST(PoseSmoother, AJumpRestartsAtTheMeasurement) {
  PoseSmoother smoother;
  const Matrix6 precise = 1e6 * Matrix6::Identity();
  for (int k = 0; k < 5; ++k) smoother.Update(Truth(k), precise);
  Eigen::Isometry3d jumped = Truth(5);
  jumped.translation() += Eigen::Vector3d(0.5, 0, 0);  // half a metre in one frame
  const Eigen::Isometry3d out = smoother.Update(jumped, precise);
  EXPECT_TRUE(smoother.restarted());
  EXPECT_TRUE(out.isApprox(jumped));
}

TEST(PoseSmoother, DegenerateInputsGiveDefinedPoses) {
  PoseSmoother smoother;
  // No information at all (a frame that pins nothing down): finite, near the measurement.
  const Eigen::Isometry3d first = smoother.Update(Truth(0), Matrix6::Zero());
  EXPECT_TRUE(first.matrix().allFinite());
  const Eigen::Isometry3d second = smoother.Update(Truth(1), Matrix6::Zero());
  EXPECT_TRUE(second.matrix().allFinite());
  // A non-finite measurement changes nothing and returns the prediction.
  Eigen::Isometry3d bad = Truth(2);
  bad.translation().x() = std::numeric_limits<double>::quiet_NaN();
  const auto predicted = smoother.Predict();
  const Eigen::Isometry3d out = smoother.Update(bad, Matrix6::Identity());
  EXPECT_TRUE(out.isApprox(*predicted));
  Matrix6 nan_info = Matrix6::Identity();
  nan_info(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(smoother.Update(Truth(2), nan_info).matrix().allFinite());
}

TEST(PoseSmoother, DeltaInvertsTheUpdate) {
  Vector6 d;
  d << 0.1, -0.2, 0.05, 0.3, -0.1, 0.2;
  const Eigen::Isometry3d a = Truth(7);
  const Eigen::Isometry3d b = vision::ApplyPoseUpdate(d, a);
  EXPECT_LT((PoseDelta(a, b) - d).norm(), 1e-12);
  EXPECT_LT(PoseDelta(a, a).norm(), 1e-12);
}

TEST(PoseSmoother, BadOptionsAreBugs) {
  PoseSmootherOptions o;
  o.acceleration_m = 0;
  EXPECT_THROW(PoseSmoother{o}, CheckError);
  o = {};
  o.acceleration_deg = -1;
  EXPECT_THROW(PoseSmoother{o}, CheckError);
  o = {};
  o.gate_chi2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(PoseSmoother{o}, CheckError);
}

}  // namespace
}  // namespace reenact::viewer
