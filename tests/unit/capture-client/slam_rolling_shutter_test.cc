#include <gtest/gtest.h>

#include <random>

#include "capture-client/slam/rolling_shutter.h"
#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact::capture::slam {
namespace {

// A rolling-shutter image of points while the sensor turns by omega (rotation vector) per
// frame: row v sees the scene from the mid-frame sensor turned by Exp(a(v) omega), found by
// fixed-point iteration on the row (the row decides the time, the time the row).
struct Seen {
  Eigen::Vector3d point_in_mid;  // the point in the mid-frame sensor's frame
  double row = 0;
  Eigen::Vector2d normalized;  // where the rolling shutter saw it
};

Seen SeeWithRollingShutter(const Eigen::Vector3d& point_in_mid, const Eigen::Vector3d& omega,
                           double ratio, const PinholeCamera& camera) {
  Seen s;
  s.point_in_mid = point_in_mid;
  double row = camera.cy;
  for (int it = 0; it < 50; ++it) {
    const double a = (row - 0.5 * (camera.height - 1)) / camera.height * ratio;
    const Eigen::Vector3d in_row = ExpSo3(a * omega) * point_in_mid;
    s.normalized = in_row.head<2>() / in_row.z();
    row = camera.fy * s.normalized.y() + camera.cy;
  }
  s.row = row;
  return s;
}

FrameFeatures Features(const std::vector<Seen>& seen, const PinholeCamera& camera) {
  FrameFeatures f;
  for (const Seen& s : seen) {
    cv::KeyPoint kp;
    kp.pt = {static_cast<float>(camera.fx * s.normalized.x() + camera.cx),
             static_cast<float>(s.row)};
    f.keypoints.push_back(kp);
    KeypointObservation o;
    o.normalized = s.normalized;
    const double depth = 2.0;  // any reading: the compensation rotates its point too
    o.depth_m = depth;
    f.observations.push_back(o);
    f.points_in_camera.push_back(Eigen::Vector3d(s.normalized.x(), s.normalized.y(), 1) * depth);
  }
  f.descriptors = cv::Mat::zeros(static_cast<int>(seen.size()), 32, CV_8UC1);
  return f;
}

TEST(SlamRollingShutter, CompensationRestoresTheMidFrameViewOfATurningSensor) {
  PinholeCamera camera = PinholeCamera::KinectLike();
  const Eigen::Vector3d omega(0.01, 0.05, -0.02);  // about 3 degrees per frame
  const double ratio = 0.6;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Seen> seen;
  for (int i = 0; i < 50; ++i)
    seen.push_back(SeeWithRollingShutter({u(rng), 0.7 * u(rng), 2.5}, omega, ratio, camera));
  FrameFeatures f = Features(seen, camera);
  double before = 0;
  for (size_t i = 0; i < seen.size(); ++i) {
    const Eigen::Vector2d global = seen[i].point_in_mid.head<2>() / seen[i].point_in_mid.z();
    before = std::max(before, camera.fx * (f.observations[i].normalized - global).norm());
  }
  ASSERT_GT(before, 5);  // the rolling shutter moved keypoints by several pixels
  CompensateRollingShutter(ExpSo3(omega), ratio, camera.height, f);
  for (size_t i = 0; i < seen.size(); ++i) {
    const Eigen::Vector2d global = seen[i].point_in_mid.head<2>() / seen[i].point_in_mid.z();
    // Exact up to the keypoint's row, which is where the rolling shutter put it (the
    // compensation reads the time from the observed row, as it must).
    EXPECT_LT(camera.fx * (f.observations[i].normalized - global).norm(), 1e-6) << i;
    const Eigen::Vector3d& p = f.points_in_camera[i];
    EXPECT_LT((p.head<2>() / p.z() - f.observations[i].normalized).norm(), 1e-12);
    EXPECT_DOUBLE_EQ(f.observations[i].depth_m, p.z());
  }
}

TEST(SlamRollingShutter, GlobalShutterOrNoMotionChangesNothing) {
  const PinholeCamera camera = PinholeCamera::KinectLike();
  const std::vector<Seen> seen = {SeeWithRollingShutter({0.3, 0.4, 2}, {0, 0.05, 0}, 0.5, camera)};
  FrameFeatures f = Features(seen, camera);
  const Eigen::Vector2d n = f.observations[0].normalized;
  CompensateRollingShutter(ExpSo3({0, 0.05, 0}), 0, camera.height, f);
  EXPECT_EQ(f.observations[0].normalized, n);
  CompensateRollingShutter(Eigen::Matrix3d::Identity(), 0.5, camera.height, f);
  EXPECT_EQ(f.observations[0].normalized, n);
  EXPECT_THROW(CompensateRollingShutter(Eigen::Matrix3d::Identity(), 1.5, camera.height, f),
               CheckError);
}

}  // namespace
}  // namespace reenact::capture::slam
