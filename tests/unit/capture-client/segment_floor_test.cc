// The floor plane of the person segmentation: RANSAC estimator, floor guess from the skeleton,
// fits against constructed point sets with walls, furniture tops and noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "capture-client/segment/floor_plane.h"
#include "common/estimate/ransac.h"
#include "common/geometry/pinhole_camera.h"
#include "common/geometry/rotation.h"

namespace reenact::capture {
namespace {

static_assert(RansacEstimator<FloorPlaneEstimator>);

// A sensor 1.3 m above the floor looking down by tilt_deg (OpenCV axes: y down; the level
// frame has y along gravity, the floor at y = 1.3).
struct SensorTilt {
  Eigen::Matrix3d sensor_from_level;
  Eigen::Vector3d up;   // sensor frame
  double floor_offset;  // up . p on the floor
};

SensorTilt MakeSetup(double tilt_deg) {
  SensorTilt s;
  s.sensor_from_level =
      Eigen::AngleAxisd(tilt_deg * std::numbers::pi / 180, Eigen::Vector3d::UnitX())
          .toRotationMatrix();
  s.up = s.sensor_from_level * -Eigen::Vector3d::UnitY();
  s.floor_offset = -1.3;
  return s;
}

// Level-frame point (x right, y down, z ahead) -> sensor frame.
Eigen::Vector3d ToSensor(const SensorTilt& s, double x, double y, double z) {
  return s.sensor_from_level * Eigen::Vector3d(x, y, z);
}

TEST(FloorPlaneEstimator, ThreePointsGiveTheirPlaneWithTheNormalUp) {
  FloorPlaneEstimator e;
  const auto models = e.Estimate({{0, 1, 2}, {1, 1, 3}, {-1, 1, 4}});
  ASSERT_EQ(models.size(), 1u);
  EXPECT_NEAR(models[0].normal.dot(-Eigen::Vector3d::UnitY()), 1.0, 1e-12);
  EXPECT_NEAR(models[0].offset, -1.0, 1e-12);
  const auto r = e.Residuals(models[0], {{0, 1, 2}, {0, 0.9, 2}});
  EXPECT_NEAR(r[0], 0, 1e-12);
  // 10 cm off; the noise across the plane at z = 2, |n . p| = 0.9: 1 cm + 5 mm * 2 * 0.9.
  EXPECT_NEAR(r[1], 0.1 / (0.01 + 0.005 * 2 * 0.9), 1e-12);
}

TEST(FloorPlaneEstimator, CollinearDrawsAndWallsGiveNoModel) {
  FloorPlaneEstimator e;
  EXPECT_TRUE(e.Estimate({{0, 1, 2}, {0, 1, 3}, {0, 1, 4}}).empty());
  EXPECT_TRUE(e.Estimate({{0, 0, 2}, {0, 0, 2}, {1, 1, 2}}).empty());
  // A wall facing the sensor (z = 4) and a side wall (x = 2).
  EXPECT_TRUE(e.Estimate({{0, 0, 4}, {1, 0, 4}, {0, 1, 4}}).empty());
  EXPECT_TRUE(e.Estimate({{2, 0, 3}, {2, 1, 3}, {2, 0, 4}}).empty());
}

TEST(Plane3, TransformedKeepsThePointsOnIt) {
  const Plane3 plane{Eigen::Vector3d(0.1, -0.9, 0.2).normalized(), 0.7};
  Eigen::Isometry3d b_from_a = Eigen::Isometry3d::Identity();
  b_from_a.linear() = ExpSo3(Eigen::Vector3d(0.3, -0.2, 0.5));
  b_from_a.translation() = Eigen::Vector3d(1, 2, -3);
  const Plane3 in_b = plane.Transformed(b_from_a);
  for (const Eigen::Vector3d& t : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1)}) {
    const Eigen::Vector3d on = plane.normal * plane.offset + t.cross(plane.normal);
    EXPECT_NEAR(plane.SignedDistance(on), 0, 1e-12);
    EXPECT_NEAR(in_b.SignedDistance(b_from_a * on), 0, 1e-12);
    EXPECT_NEAR(in_b.SignedDistance(b_from_a * (on + 0.5 * plane.normal)), 0.5, 1e-12);
  }
}

TEST(GuessFloor, FromTheLowestLegJoint) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  Skeleton s;
  s.Set(Joint::kWaist, {0, 0, 1.0});
  s.Set(Joint::kLeftFoot, {0.1, 0, 0.08});
  s.Set(Joint::kRightFoot, {0.3, 0.4, 0.7});  // kicking
  const auto guess = GuessFloor(s, up);
  ASSERT_TRUE(guess);
  EXPECT_NEAR(guess->height, 0.0, 1e-12);
  EXPECT_NEAR((guess->under_feet - Eigen::Vector3d(0.2, 0.2, 0)).norm(), 0, 1e-12);
  Skeleton waist_only;
  waist_only.Set(Joint::kWaist, {0, 0, 1.0});
  EXPECT_NEAR(GuessFloor(waist_only, up)->height, 0.05, 1e-12);
  Skeleton head_only;
  head_only.Set(Joint::kHead, {0, 0, 1.6});
  EXPECT_FALSE(GuessFloor(head_only, up).has_value());
}

struct PointScene {
  std::vector<Eigen::Vector3d> points;
  FloorGuess guess;
};

// What a Kinect-like sensor tilted by tilt_deg sees, cast through every 4th pixel: the floor
// 1.3 m below the sensor, a wall 4.2 m ahead, the 25 cm high top of a box beside the person
// (x 0.6-1.1 m, 2.6-3.1 m ahead), with axial noise sigma = 1.425 mm z^2. Only floor
// candidates (as the segmenter selects them, around a person's feet 3 m ahead) are kept.
PointScene MakeScene(const SensorTilt& s, const PersonSegmentOptions& options, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0, 1);
  const PinholeCamera camera = PinholeCamera::KinectLike();
  PointScene scene;
  scene.guess.height = s.floor_offset + 0.01;  // a slightly wrong guess
  scene.guess.under_feet = ToSensor(s, 0, 1.3 - 0.01, 3.0);
  for (int y = 2; y < camera.height; y += 4)
    for (int x = 2; x < camera.width; x += 4) {
      const Eigen::Vector3d ray =  // level frame
          s.sensor_from_level.transpose() *
          Eigen::Vector3d((x - camera.cx) / camera.fx, (y - camera.cy) / camera.fy, 1);
      double t = 4.2 / ray.z();                         // the wall
      if (ray.y() > 0) t = std::min(t, 1.3 / ray.y());  // the floor
      if (ray.y() > 0) {
        const double tb = 1.05 / ray.y();
        const Eigen::Vector3d hit = tb * ray;
        if (hit.x() > 0.6 && hit.x() < 1.1 && hit.z() > 2.6 && hit.z() < 3.1) t = std::min(t, tb);
      }
      const Eigen::Vector3d p = s.sensor_from_level * (t * ray);
      const double sigma = 1.425e-3 * p.z() * p.z();
      const Eigen::Vector3d noisy = p * (1 + sigma * n(rng) / p.z());
      if (IsFloorCandidate(noisy, s.up, scene.guess, options)) scene.points.push_back(noisy);
    }
  return scene;
}

TEST(FitFloorPlane, FindsTheFloorAmongWallAndFurniture) {
  const PersonSegmentOptions options;
  for (double tilt : {7.0, 15.0, 25.0}) {
    const SensorTilt s = MakeSetup(tilt);
    const PointScene scene = MakeScene(s, options, 3);
    const auto fit = FitFloorPlane(scene.points, s.up, options);
    ASSERT_GT(scene.points.size(), 1000u);
    ASSERT_TRUE(fit) << tilt;
    // Within 0.5 degrees and, under the feet, within 5 mm (the noise across the floor there
    // is ~5 mm per point; hundreds of points average it down, the foot of the wall 1.2 m
    // behind the feet pulls a little).
    EXPECT_GT(fit->plane.normal.dot(s.up), std::cos(0.5 * std::numbers::pi / 180)) << tilt;
    const Eigen::Vector3d feet_on_floor = ToSensor(s, 0, 1.3, 3.0);
    EXPECT_NEAR(fit->plane.SignedDistance(feet_on_floor), 0, 0.005) << tilt;
    EXPECT_EQ(fit->candidates, static_cast<int>(scene.points.size()));
    EXPECT_GT(fit->inlier_ratio, 0.5);
    // The same points score the same against the fitted plane.
    const FloorFit score = ScoreFloorPlane(fit->plane, scene.points, options);
    EXPECT_EQ(score.inliers, fit->inliers);
  }
}

TEST(FitFloorPlane, ANormalBeyondTheTiltLimitIsNoFloor) {
  // The body's up axis 50 degrees off the floor normal (a lying or wrongly tracked body).
  PersonSegmentOptions options;
  const SensorTilt s = MakeSetup(10);
  const PointScene scene = MakeScene(s, options, 5);
  const Eigen::Vector3d wrong_up =
      Eigen::AngleAxisd(50 * std::numbers::pi / 180, Eigen::Vector3d::UnitZ()) * s.up;
  EXPECT_FALSE(FitFloorPlane(scene.points, wrong_up, options).has_value());
  options.floor_max_tilt_deg = 60;
  EXPECT_TRUE(FitFloorPlane(scene.points, wrong_up, options).has_value());
}

TEST(FitFloorPlane, TooFewCandidatesIsNoFloor) {
  const PersonSegmentOptions options;
  const SensorTilt s = MakeSetup(0);
  std::vector<Eigen::Vector3d> few;
  for (int i = 0; i < options.floor_min_inliers - 1; ++i)
    few.push_back(ToSensor(s, 0.01 * i, 1.3, 2 + 0.013 * (i % 17)));
  EXPECT_FALSE(FitFloorPlane(few, s.up, options).has_value());
  EXPECT_FALSE(FitFloorPlane({}, s.up, options).has_value());
}

TEST(OnOrUnderFloor, ClearanceShrinksAtGrazingViews) {
  const Plane3 floor{-Eigen::Vector3d::UnitY(), -1.3};  // y = 1.3, up = -y
  const DepthTolerance clearance{0.008, 0.005};
  // 1 m ahead, height h: 8 mm + 5 mm * 1 * (1.3 - h) = 1.44 cm at h = 1.3 cm.
  EXPECT_TRUE(OnOrUnderFloor(floor, {0, 1.3 - 0.013, 1}, clearance));
  EXPECT_FALSE(OnOrUnderFloor(floor, {0, 1.3 - 0.016, 1}, clearance));
  // 3 m ahead (a grazing view): 8 mm + 5 mm * 3 * (1.3 - h) = 2.71 cm at h = 2.5 cm.
  EXPECT_TRUE(OnOrUnderFloor(floor, {0, 1.3 - 0.025, 3}, clearance));
  EXPECT_FALSE(OnOrUnderFloor(floor, {0, 1.3 - 0.029, 3}, clearance));
  EXPECT_TRUE(OnOrUnderFloor(floor, {0, 1.5, 3}, clearance));  // under the floor
}

}  // namespace
}  // namespace reenact::capture
