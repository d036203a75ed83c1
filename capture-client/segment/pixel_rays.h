#pragma once
// Per-pixel viewing rays of a camera, computed once: the undistorted normalised coordinates
// (x', y') of every pixel centre, so that the point at depth z seen at pixel (x, y) is
// z * (x', y', 1) in the camera frame (OpenCV axes, metres). Undistortion is iterative
// (PinholeCamera::Undistort); the table spares doing it per frame.

#include <Eigen/Core>
#include <vector>

#include "common/geometry/pinhole_camera.h"

namespace reenact::capture {

class PixelRays {
 public:
  // Precondition (CHECK): a valid camera.
  explicit PixelRays(const PinholeCamera& camera);

  int width() const { return width_; }
  int height() const { return height_; }
  // Precondition: 0 <= x < width, 0 <= y < height (not checked: inner loops).
  Eigen::Vector3d Point(int x, int y, double z) const {
    const Eigen::Vector2d& r = rays_[static_cast<size_t>(y) * width_ + x];
    return {z * r.x(), z * r.y(), z};
  }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<Eigen::Vector2d> rays_;
};

}  // namespace reenact::capture
