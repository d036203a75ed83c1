#include "viewer-client/play/orbit_camera.h"

#include <cmath>

#include <gtest/gtest.h>

#include "common/geometry/pinhole_camera.h"

namespace reenact::viewer {
namespace {

const Eigen::Vector3d kUp(0, 0, 1);

TEST(LookAt, TargetOnOpticalAxisAndUpIsImageUp) {
  const Eigen::Vector3d eye(0, -3, 1.3), target(0, 0, 1.0);
  const auto world_from_camera = LookAt(eye, target, kUp);
  ASSERT_TRUE(world_from_camera);
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const Eigen::Isometry3d camera_from_world = world_from_camera->inverse();
  const auto centre = cam.Project(camera_from_world * target);
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->x(), cam.cx, 1e-9);
  EXPECT_NEAR(centre->y(), cam.cy, 1e-9);
  // A point above the target appears higher in the image (smaller y).
  const auto above = cam.Project(camera_from_world * (target + 0.5 * kUp));
  ASSERT_TRUE(above);
  EXPECT_LT(above->y(), centre->y());
  // World +x (to the right when looking along +y with z up) appears to the right.
  const auto right = cam.Project(camera_from_world * (target + Eigen::Vector3d(0.5, 0, 0)));
  EXPECT_GT(right->x(), centre->x());
  EXPECT_NEAR(world_from_camera->linear().determinant(), 1.0, 1e-12);
}

TEST(LookAt, DegenerateInputsFail) {
  EXPECT_FALSE(LookAt({1, 1, 1}, {1, 1, 1}, kUp));
  EXPECT_FALSE(LookAt({0, 0, 3}, {0, 0, 1}, kUp));  // looking straight down the up axis
  EXPECT_FALSE(LookAt({0, -3, 1}, {0, 0, 1}, Eigen::Vector3d::Zero()));
}

TEST(OrbitCamera, TurnsAboutVerticalAxisKeepingDistanceAndHeight) {
  Eigen::Isometry3d world_from_sensor = *LookAt({0.3, -3.0, 1.4}, {0, 0, 1.0}, kUp);
  const Eigen::Vector3d centre(0, 0, 1.0);
  for (double angle : {45.0, 60.0, 180.0, -90.0}) {
    OrbitCameraOptions options;
    options.angle_deg = angle;
    const auto viewer = OrbitWorldFromViewer(world_from_sensor, centre, kUp, options);
    ASSERT_TRUE(viewer);
    const Eigen::Vector3d a = world_from_sensor.translation() - centre;
    const Eigen::Vector3d b = viewer->translation() - centre;
    EXPECT_NEAR(a.z(), b.z(), 1e-12);
    EXPECT_NEAR(a.head<2>().norm(), b.head<2>().norm(), 1e-12);
    const double turned = std::atan2(a.x() * b.y() - a.y() * b.x(), a.head<2>().dot(b.head<2>()));
    EXPECT_NEAR(std::remainder(turned * 180 / M_PI - angle, 360.0), 0.0, 1e-9) << angle;
  }
}

TEST(OrbitCamera, SensorOnTheVerticalAxisIsDegenerate) {
  const Eigen::Isometry3d above = Eigen::Translation3d(0, 0, 3) * Eigen::Isometry3d::Identity();
  EXPECT_FALSE(OrbitWorldFromViewer(above, {0, 0, 1}, kUp, {}));
}

}  // namespace
}  // namespace reenact::viewer
