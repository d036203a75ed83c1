#include "common/geometry/pinhole_camera.h"

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact {
namespace {

TEST(PinholeCamera, ProjectMatchesPinholeFormula) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const auto px = cam.Project({0.5, -0.25, 2.0});
  ASSERT_TRUE(px);
  EXPECT_NEAR(px->x(), 517.3 * 0.25 + 318.6, 1e-9);
  EXPECT_NEAR(px->y(), 516.5 * -0.125 + 255.3, 1e-9);
}

TEST(PinholeCamera, PointsBehindOrOnTheCameraDoNotProject) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  EXPECT_FALSE(cam.Project({0, 0, 0}));
  EXPECT_FALSE(cam.Project({1, 1, -1}));
  EXPECT_FALSE(cam.Project({0, 0, std::nan("")}));
}

TEST(PinholeCamera, UnprojectInvertsProjectWithDistortion) {
  PinholeCamera cam = PinholeCamera::KinectLike();
  cam.distortion = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};  // TUM Freiburg 1
  for (double x : {-0.6, 0.0, 0.7})
    for (double y : {-0.4, 0.1, 0.45}) {
      const Eigen::Vector3d p(x, y, 1.7);
      const auto px = cam.Project(p);
      ASSERT_TRUE(px);
      EXPECT_LT((cam.Unproject(*px, 1.7) - p).norm(), 1e-6) << x << " " << y;
    }
}

TEST(PinholeCamera, CropShiftsPrincipalPoint) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const PinholeCamera crop = cam.Cropped(100, 50, 200, 300);
  const Eigen::Vector3d p(0.1, 0.2, 3.0);
  EXPECT_NEAR((*cam.Project(p) - *crop.Project(p) - Eigen::Vector2d(100, 50)).norm(), 0, 1e-9);
}

TEST(PinholeCamera, CheckRejectsNonPositiveFocalLength) {
  PinholeCamera cam = PinholeCamera::KinectLike();
  cam.fx = 0;
  EXPECT_THROW(cam.Check(), CheckError);
}

}  // namespace
}  // namespace reenact
