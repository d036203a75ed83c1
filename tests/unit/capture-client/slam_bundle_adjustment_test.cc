#include <gtest/gtest.h>

#include <random>

#include "capture-client/slam/local_bundle_adjustment.h"
#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact::capture::slam {
namespace {

constexpr double kF = 525;

// Cameras on an arc looking at points spread over a 2 m x 1.5 m x 1 m box 2-3 m away.
struct Scene {
  std::vector<Eigen::Isometry3d> sensor_from_world;
  std::vector<Eigen::Vector3d> points;
};

Scene MakeScene(int cameras, int points, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Scene s;
  for (int c = 0; c < cameras; ++c) {
    Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d::Identity();
    world_from_sensor.linear() = ExpSo3(Eigen::Vector3d(0.02 * c, 0.05 * c, 0.01 * c));
    world_from_sensor.translation() = Eigen::Vector3d(0.1 * c, 0.02 * c, 0.03 * c);
    s.sensor_from_world.push_back(world_from_sensor.inverse());
  }
  for (int p = 0; p < points; ++p) s.points.emplace_back(u(rng), 0.75 * u(rng), 2.5 + 0.5 * u(rng));
  return s;
}

BundleProblem Observe(const Scene& s, bool with_depth, double pixel_noise, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, 1);
  BundleProblem p;
  p.sensor_from_world = s.sensor_from_world;
  p.camera_fixed.assign(s.sensor_from_world.size(), 0);
  p.camera_fixed[0] = 1;
  p.points_in_world = s.points;
  for (size_t c = 0; c < s.sensor_from_world.size(); ++c) {
    for (size_t i = 0; i < s.points.size(); ++i) {
      const Eigen::Vector3d pc = s.sensor_from_world[c] * s.points[i];
      BundleProblem::Observation o;
      o.camera = static_cast<int>(c);
      o.point = static_cast<int>(i);
      o.keypoint.normalized =
          pc.head<2>() / pc.z() + Eigen::Vector2d(n(rng), n(rng)) * pixel_noise / kF;
      o.keypoint.depth_m = with_depth ? pc.z() : 0;
      p.observations.push_back(o);
    }
  }
  return p;
}

double MaxPoseError(const BundleProblem& p, const Scene& s) {
  double e = 0;
  for (size_t c = 0; c < s.sensor_from_world.size(); ++c) {
    const Eigen::Isometry3d d = p.sensor_from_world[c] * s.sensor_from_world[c].inverse();
    e = std::max({e, d.translation().norm(), RotationAngle(d.linear())});
  }
  return e;
}

void Perturb(BundleProblem& p, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, 1);
  for (size_t c = 0; c < p.sensor_from_world.size(); ++c) {
    if (p.camera_fixed[c]) continue;
    Eigen::Matrix<double, 6, 1> d;
    for (int k = 0; k < 3; ++k) d(k) = 0.02 * n(rng);  // 2 cm
    for (int k = 3; k < 6; ++k) d(k) = 0.01 * n(rng);  // about 0.6 degrees
    p.sensor_from_world[c] = ApplyPoseUpdate(d, p.sensor_from_world[c]);
  }
  for (auto& x : p.points_in_world) x += 0.02 * Eigen::Vector3d(n(rng), n(rng), n(rng));
}

TEST(SlamBundleAdjustment, ExactObservationsRecoverTheTruth) {
  const Scene s = MakeScene(4, 60, 1);
  BundleProblem p = Observe(s, true, 0, 2);
  Perturb(p, 3);
  ASSERT_GT(MaxPoseError(p, s), 0.01);
  const BundleResult r = SolveBundle(p, kF, kF, ObservationNoise{}, BundleOptions{2, 20});
  EXPECT_LT(r.final_cost, 1e-6 * r.initial_cost);
  EXPECT_LT(MaxPoseError(p, s), 1e-5);
  for (size_t i = 0; i < s.points.size(); ++i)
    EXPECT_LT((p.points_in_world[i] - s.points[i]).norm(), 1e-5) << i;
  for (char inlier : r.inlier) EXPECT_TRUE(inlier);
}

TEST(SlamBundleAdjustment, WithoutDepthTheFixedCameraAndPointsStillDetermineTheRest) {
  // Two fixed cameras fix the scale that reprojections alone cannot.
  const Scene s = MakeScene(4, 60, 4);
  BundleProblem p = Observe(s, false, 0, 5);
  p.camera_fixed[1] = 1;
  Perturb(p, 6);
  SolveBundle(p, kF, kF, ObservationNoise{}, BundleOptions{2, 30});
  EXPECT_LT(MaxPoseError(p, s), 1e-4);
}

TEST(SlamBundleAdjustment, NoisyObservationsStayNearTheTruthAndOutliersAreFlagged) {
  const Scene s = MakeScene(5, 120, 7);
  BundleProblem p = Observe(s, true, 1.0, 8);
  // Wrong matches: in camera c, every point i with i % 10 == c is seen 40 pixels off (a
  // different point per camera, so no single 3D point explains them).
  std::vector<size_t> wrong;
  for (size_t i = 0; i < p.observations.size(); ++i) {
    const auto& o = p.observations[i];
    if (o.point % 10 != o.camera) continue;
    p.observations[i].keypoint.normalized.x() += 40 / kF;
    wrong.push_back(i);
  }
  Perturb(p, 9);
  ObservationNoise noise;  // what the data has: 1 px keypoints, exact depth
  noise.pixel_sigma_px = 1;
  noise.depth_sigma_1m_m = 0.001;
  const BundleResult r = SolveBundle(p, kF, kF, noise, BundleOptions{3, 10});
  // Noise-limited precision: a sideways shift t of a camera with the compensating turn
  // t / 2.5 m moves a point at 2 m by only f t (1/2 - 1/2.5) = 0.1 f t pixels, so 1 px of
  // noise on 120 points leaves t about 1 / (0.1 f sqrt(120)) = 2 mm per axis. The bound is
  // five times that (the worst of four cameras and three axes), far below the 2 cm start.
  EXPECT_LT(MaxPoseError(p, s), 0.01);
  for (size_t i : wrong) EXPECT_FALSE(r.inlier[i]) << i;
  int inliers = 0;
  for (char f : r.inlier) inliers += f;
  EXPECT_GT(inliers, 0.85 * static_cast<double>(p.observations.size()));
}

TEST(SlamBundleAdjustment, NeedsAFixedCamera) {
  const Scene s = MakeScene(2, 10, 1);
  BundleProblem p = Observe(s, true, 0, 2);
  p.camera_fixed.assign(2, 0);
  EXPECT_THROW(SolveBundle(p, kF, kF, ObservationNoise{}), CheckError);
}

TEST(SlamBundleAdjustment, BadIndicesAndOptionsAreBugs) {
  const Scene s = MakeScene(2, 10, 1);
  BundleProblem p = Observe(s, true, 0, 2);
  p.observations[0].point = 99;
  EXPECT_THROW(SolveBundle(p, kF, kF, ObservationNoise{}), CheckError);
  p = Observe(s, true, 0, 2);
  EXPECT_THROW(SolveBundle(p, kF, kF, ObservationNoise{}, BundleOptions{0, 5}), CheckError);
  EXPECT_THROW(SolveBundle(p, 0, kF, ObservationNoise{}), CheckError);
}

TEST(SlamBundleAdjustment, PointsBehindACameraDoNotBreakIt) {
  const Scene s = MakeScene(3, 30, 1);
  BundleProblem p = Observe(s, true, 0, 2);
  p.points_in_world[0] = Eigen::Vector3d(0, 0, -5);  // behind every camera
  const BundleResult r = SolveBundle(p, kF, kF, ObservationNoise{});
  for (const auto& pose : p.sensor_from_world) EXPECT_TRUE(pose.matrix().allFinite());
  for (const auto& x : p.points_in_world) EXPECT_TRUE(x.allFinite());
  EXPECT_FALSE(r.inlier[0]);
}

}  // namespace
}  // namespace reenact::capture::slam
