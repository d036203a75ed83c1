#pragma once
// Pinhole camera with Brown-Conrady distortion (OpenCV's k1 k2 p1 p2 k3 model, as Kinect
// and TUM RGB-D intrinsics are given). Camera frame as OpenCV: x right, y down, z forward,
// metres. Pixel centres at integer coordinates (OpenCV convention).
//
//   x' = X/Z, y' = Y/Z, r^2 = x'^2 + y'^2
//   x'' = x'(1 + k1 r^2 + k2 r^4 + k3 r^6) + 2 p1 x'y' + p2 (r^2 + 2x'^2)
//   y'' = y'(1 + k1 r^2 + k2 r^4 + k3 r^6) + p1 (r^2 + 2y'^2) + 2 p2 x'y'
//   u = fx x'' + cx, v = fy y'' + cy

#include <optional>

#include <Eigen/Core>

namespace reenact {

struct Distortion {
  double k1 = 0, k2 = 0, p1 = 0, p2 = 0, k3 = 0;
  bool IsZero() const { return k1 == 0 && k2 == 0 && p1 == 0 && p2 == 0 && k3 == 0; }
};

struct PinholeCamera {
  int width = 0;   // pixels
  int height = 0;  // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels
  Distortion distortion;

  // Throws CheckError unless width, height, fx, fy > 0 and every value is finite.
  void Check() const;

  // Kinect v1 / TUM RGB-D Freiburg 1 colour intrinsics at 640x480, without distortion.
  static PinholeCamera KinectLike();

  // Pixel of a point in this camera's frame; nullopt if the point is not in front of the
  // camera (Z <= min_depth). The pixel may lie outside the image.
  std::optional<Eigen::Vector2d> Project(const Eigen::Vector3d& point_in_camera,
                                         double min_depth = 1e-6) const;

  // Point at depth Z (metres, along the optical axis) seen at a pixel; undistorts
  // iteratively when distortion is set.
  Eigen::Vector3d Unproject(const Eigen::Vector2d& pixel, double depth) const;

  // Normalised image coordinates (x', y') of a pixel, undistorted.
  Eigen::Vector2d Undistort(const Eigen::Vector2d& pixel) const;

  // The same camera seen through a crop window whose top-left pixel is (x0, y0).
  PinholeCamera Cropped(int x0, int y0, int crop_width, int crop_height) const;

  // 3x3 intrinsic matrix K.
  Eigen::Matrix3d K() const;
};

}  // namespace reenact
