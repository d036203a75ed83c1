// Depth image to camera-frame points: holes, masks, image borders, distortion, depth scale.
#include "common/geometry/depth_points.h"

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact {
namespace {

// 40x30 camera with the principal point on pixel (20, 15) and f = 50 px.
PinholeCamera SmallCamera() {
  PinholeCamera c;
  c.width = 40;
  c.height = 30;
  c.fx = 50;
  c.fy = 50;
  c.cx = 20;
  c.cy = 15;
  return c;
}

TEST(DepthPoints, PlaneWithHolesBackProjectsByThePinholeFormula) {
  const PinholeCamera cam = SmallCamera();
  ImageDepthMm depth(40, 30, 1, 2000);  // a wall 2 m away
  depth.at(3, 4) = 0;
  depth.at(0, 0) = 0;
  depth.at(39, 29) = 0;
  const DepthPoints pts = DepthToPoints(depth, cam);
  ASSERT_EQ(pts.points_in_camera.size(), 40u * 30u - 3u);
  ASSERT_EQ(pts.pixels.size(), pts.points_in_camera.size());
  for (size_t i = 0; i < pts.pixels.size(); ++i) {
    const Eigen::Vector2i px = pts.pixels[i];
    EXPECT_NE(depth.at(px.x(), px.y()), 0);
    // X = (x - cx) / fx * Z, Y = (y - cy) / fy * Z, Z = 2.
    const Eigen::Vector3d expected((px.x() - 20) / 50.0 * 2, (px.y() - 15) / 50.0 * 2, 2);
    EXPECT_LT((pts.points_in_camera[i] - expected).norm(), 1e-15);
  }
  EXPECT_EQ(pts.pixels.front(), Eigen::Vector2i(1, 0));  // row-major, (0, 0) is a hole
}

TEST(DepthPoints, MaskSelectsPixels) {
  const PinholeCamera cam = SmallCamera();
  ImageDepthMm depth(40, 30, 1, 1500);
  depth.at(11, 10) = 0;
  ImageGray8 mask(40, 30, 1, 0);
  for (int y = 10; y < 12; ++y)
    for (int x = 10; x < 13; ++x) mask.at(x, y) = 255;
  const DepthPoints pts = DepthToPoints(depth, cam, {}, &mask);
  ASSERT_EQ(pts.pixels.size(), 5u);  // 6 masked pixels, one of them a hole
  for (const auto& px : pts.pixels) EXPECT_EQ(mask.at(px.x(), px.y()), 255);
}

TEST(DepthPoints, DepthScaleRangeAndStride) {
  const PinholeCamera cam = SmallCamera();
  ImageDepthMm depth(40, 30, 1, 10000);
  depth.at(20, 15) = 20000;
  DepthPointsOptions tum;
  tum.depth_scale_m = 0.0002;  // TUM: 5000 units per metre
  const auto centre = BackProjectPixel(depth, cam, 20, 15, tum);
  ASSERT_TRUE(centre);
  EXPECT_LT((*centre - Eigen::Vector3d(0, 0, 4)).norm(), 1e-15);
  tum.max_depth_m = 3;
  EXPECT_FALSE(BackProjectPixel(depth, cam, 20, 15, tum));
  EXPECT_EQ(DepthToPoints(depth, cam, tum).pixels.size(), 40u * 30u - 1u);
  tum.min_depth_m = 2.5;
  EXPECT_EQ(DepthToPoints(depth, cam, tum).pixels.size(), 0u);
  DepthPointsOptions strided;
  strided.stride = 4;  // x in {0, 4, .., 36}, y in {0, 4, .., 28}
  EXPECT_EQ(DepthToPoints(depth, cam, strided).pixels.size(), 10u * 8u);
}

TEST(DepthPoints, BorderPixelsAndOutsideOrHolePixels) {
  const PinholeCamera cam = SmallCamera();
  ImageDepthMm depth(40, 30, 1, 1000);
  depth.at(5, 5) = 0;
  const auto corner = BackProjectPixel(depth, cam, 39, 29);
  ASSERT_TRUE(corner);
  EXPECT_LT((*corner - Eigen::Vector3d(19 / 50.0, 14 / 50.0, 1)).norm(), 1e-15);
  ASSERT_TRUE(BackProjectPixel(depth, cam, 0, 0));
  EXPECT_FALSE(BackProjectPixel(depth, cam, 5, 5));   // hole
  EXPECT_FALSE(BackProjectPixel(depth, cam, -1, 0));  // outside
  EXPECT_FALSE(BackProjectPixel(depth, cam, 40, 0));
  EXPECT_FALSE(BackProjectPixel(depth, cam, 0, 30));
}

TEST(DepthPoints, ProjectionBehindOnPlaneAndAtTheBorder) {
  const PinholeCamera cam = SmallCamera();
  EXPECT_FALSE(cam.Project({0.1, 0.1, 0}));   // on the camera plane
  EXPECT_FALSE(cam.Project({0.1, 0.1, -2}));  // behind
  // Border pixel centres project exactly; a point beyond the border gives a pixel outside.
  EXPECT_LT((*cam.Project({-0.4, -0.3, 1}) - Eigen::Vector2d(0, 0)).norm(), 1e-12);
  EXPECT_LT((*cam.Project({19 / 50.0, 14 / 50.0, 1}) - Eigen::Vector2d(39, 29)).norm(), 1e-12);
  const auto outside = cam.Project({1, 0, 1});
  ASSERT_TRUE(outside);
  EXPECT_GT(outside->x(), cam.width);
}

TEST(DepthPoints, DistortedCameraPointsProjectBackToTheirPixels) {
  PinholeCamera cam = SmallCamera();
  cam.distortion = {0.2624, -0.9531, -0.0054, 0.0026, 1.1633};  // TUM Freiburg 1
  ImageDepthMm depth(40, 30, 1, 1800);
  const DepthPoints pts = DepthToPoints(depth, cam);
  ASSERT_EQ(pts.pixels.size(), 40u * 30u);
  for (size_t i = 0; i < pts.pixels.size(); ++i) {
    EXPECT_NEAR(pts.points_in_camera[i].z(), 1.8, 1e-15);
    const auto px = cam.Project(pts.points_in_camera[i]);
    ASSERT_TRUE(px);
    EXPECT_LT((*px - pts.pixels[i].cast<double>()).norm(), 1e-6);
  }
}

TEST(DepthPoints, BadInputIsACheckError) {
  const PinholeCamera cam = SmallCamera();
  EXPECT_THROW(DepthToPoints(ImageDepthMm(20, 30), cam), CheckError);  // size mismatch
  ImageDepthMm depth(40, 30, 1, 1000);
  ImageGray8 small_mask(10, 10);
  EXPECT_THROW(DepthToPoints(depth, cam, {}, &small_mask), CheckError);
  DepthPointsOptions bad;
  bad.depth_scale_m = 0;
  EXPECT_THROW(DepthToPoints(depth, cam, bad), CheckError);
  bad = {};
  bad.stride = 0;
  EXPECT_THROW(BackProjectPixel(depth, cam, 1, 1, bad), CheckError);
  bad = {};
  bad.min_depth_m = 5;
  bad.max_depth_m = 1;
  EXPECT_THROW(DepthToPoints(depth, cam, bad), CheckError);
}

}  // namespace
}  // namespace reenact
