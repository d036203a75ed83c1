#include "common/geometry/pinhole_camera.h"

#include <cmath>

#include "common/error/check.h"

namespace reenact {
namespace {

Eigen::Vector2d Distort(const Distortion& d, const Eigen::Vector2d& n) {
  const double x = n.x(), y = n.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
  return {x * radial + 2 * d.p1 * x * y + d.p2 * (r2 + 2 * x * x),
          y * radial + d.p1 * (r2 + 2 * y * y) + 2 * d.p2 * x * y};
}

}  // namespace

void PinholeCamera::Check() const {
  REENACT_CHECK(width > 0 && height > 0, "camera size must be positive");
  REENACT_CHECK(std::isfinite(fx) && std::isfinite(fy) && fx > 0 && fy > 0,
                "focal lengths must be positive and finite");
  REENACT_CHECK(std::isfinite(cx) && std::isfinite(cy), "principal point must be finite");
  const Distortion& d = distortion;
  REENACT_CHECK(std::isfinite(d.k1) && std::isfinite(d.k2) && std::isfinite(d.p1) &&
                    std::isfinite(d.p2) && std::isfinite(d.k3),
                "distortion must be finite");
}

PinholeCamera PinholeCamera::KinectLike() {
  PinholeCamera c;
  c.width = 640;
  c.height = 480;
  c.fx = 517.3;
  c.fy = 516.5;
  c.cx = 318.6;
  c.cy = 255.3;
  return c;
}

std::optional<Eigen::Vector2d> PinholeCamera::Project(const Eigen::Vector3d& p,
                                                      double min_depth) const {
  if (!(p.z() > min_depth) || !p.allFinite()) return std::nullopt;
  Eigen::Vector2d n(p.x() / p.z(), p.y() / p.z());
  if (!distortion.IsZero()) n = Distort(distortion, n);
  return Eigen::Vector2d(fx * n.x() + cx, fy * n.y() + cy);
}

Eigen::Vector2d PinholeCamera::Undistort(const Eigen::Vector2d& pixel) const {
  const Eigen::Vector2d distorted((pixel.x() - cx) / fx, (pixel.y() - cy) / fy);
  if (distortion.IsZero()) return distorted;
  // Fixed-point iteration n <- distorted - (Distort(n) - n); converges for the moderate
  // distortion of depth cameras within the image.
  Eigen::Vector2d n = distorted;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector2d step = Distort(distortion, n) - distorted;
    n -= step;
    if (step.squaredNorm() < 1e-24) break;
  }
  return n;
}

Eigen::Vector3d PinholeCamera::Unproject(const Eigen::Vector2d& pixel, double depth) const {
  const Eigen::Vector2d n = Undistort(pixel);
  return {n.x() * depth, n.y() * depth, depth};
}

PinholeCamera PinholeCamera::Cropped(int x0, int y0, int crop_width, int crop_height) const {
  PinholeCamera c = *this;
  c.width = crop_width;
  c.height = crop_height;
  c.cx -= x0;
  c.cy -= y0;
  return c;
}

Eigen::Matrix3d PinholeCamera::K() const {
  Eigen::Matrix3d k;
  k << fx, 0, cx, 0, fy, cy, 0, 0, 1;
  return k;
}

}  // namespace reenact
