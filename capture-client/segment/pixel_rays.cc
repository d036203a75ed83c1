#include "capture-client/segment/pixel_rays.h"

namespace reenact::capture {

PixelRays::PixelRays(const PinholeCamera& camera) : width_(camera.width), height_(camera.height) {
  camera.Check();
  rays_.resize(static_cast<size_t>(width_) * height_);
  const bool plain = camera.distortion.IsZero();
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const Eigen::Vector2d r =
          plain ? Eigen::Vector2d((x - camera.cx) / camera.fx, (y - camera.cy) / camera.fy)
                : camera.Undistort(Eigen::Vector2d(x, y));
      rays_[static_cast<size_t>(y) * width_ + x] = r;
    }
  }
}

}  // namespace reenact::capture
