#include "viewer-client/render/gl_projection.h"

#include <random>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact::viewer {
namespace {

// The GL pipeline written out from the OpenGL specification: perspective divide, viewport
// transform to window coordinates (pixel x spans [x, x + 1], centre x + 0.5), then the
// renderer's row flip (output row = h - 1 - GL row), back to OpenCV's integer centres.
Eigen::Vector2d OpenCvPixelFromGl(const Eigen::Matrix4d& projection, const PinholeCamera& cam,
                                  const Eigen::Vector3d& p) {
  const Eigen::Vector4d clip = projection * p.homogeneous();
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  const double window_x = (ndc.x() + 1) / 2 * cam.width;
  const double window_y = (ndc.y() + 1) / 2 * cam.height;
  return {window_x - 0.5, cam.height - window_y - 0.5};
}

TEST(ProjectionMatrix, MapsPointsToThePixelsPinholeProjectNames) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> xy(-2, 2), z(0.2, 20);
  for (const PinholeCamera& cam :
       {PinholeCamera::KinectLike(), PinholeCamera{160, 120, 200, 190, 80.3, 60.7, {}},
        PinholeCamera{33, 77, 50, 50, 3.0, 70.0, {}}}) {
    const Eigen::Matrix4d projection = GlProjectionFromPinhole(cam);
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d p(xy(rng), xy(rng), z(rng));
      const Eigen::Vector2d expected = *cam.Project(p);
      const Eigen::Vector2d gl = OpenCvPixelFromGl(projection, cam, p);
      EXPECT_NEAR(gl.x(), expected.x(), 1e-9);
      EXPECT_NEAR(gl.y(), expected.y(), 1e-9);
    }
  }
}

TEST(ProjectionMatrix, DepthRunsFromNearToFarAndGrowsWithDistance) {
  const PinholeCamera cam = PinholeCamera::KinectLike();
  const Eigen::Matrix4d projection = GlProjectionFromPinhole(cam, 0.05, 50.0);
  auto ndc_z = [&](double z) {
    const Eigen::Vector4d clip = projection * Eigen::Vector4d(0.1, -0.2, z, 1);
    return clip.z() / clip.w();
  };
  EXPECT_NEAR(ndc_z(0.05), -1.0, 1e-12);
  EXPECT_NEAR(ndc_z(50.0), 1.0, 1e-12);
  EXPECT_LT(ndc_z(1.0), ndc_z(1.01));
  EXPECT_GT(projection.row(3).dot(Eigen::Vector4d(0, 0, 3, 1)), 0);  // clip w = Z
}

TEST(ProjectionMatrix, RejectsBadClipPlanesAndCameras) {
  EXPECT_THROW(GlProjectionFromPinhole(PinholeCamera::KinectLike(), 1.0, 0.5), CheckError);
  EXPECT_THROW(GlProjectionFromPinhole(PinholeCamera{}, 0.05, 50), CheckError);
}

}  // namespace
}  // namespace reenact::viewer
