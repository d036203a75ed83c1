#pragma once
// Test and benchmark support: exact ray casting of the side surfaces of posed cylinders into
// a depth image (mm) and a subject mask, independent of the code under test. Each cylinder
// is only cast over its image bounding box, so a 640x480 frame takes milliseconds.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"

namespace reenact::testing {

// cam must be undistorted; cylinders in its frame (x right, y down, z forward, metres).
inline void RayCastCylinders(const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders,
                             const PinholeCamera& cam, ImageDepthMm& depth, ImageGray8& mask) {
  depth = ImageDepthMm(cam.width, cam.height, 1, 0);
  mask = ImageGray8(cam.width, cam.height, 1, 0);
  Image<double> range(cam.width, cam.height, 1, std::numeric_limits<double>::infinity());
  for (const auto& c : cylinders) {
    if (!c) continue;
    // Image bounding box: both ends projected, padded by the radius seen at the nearest end.
    int x0 = 0, y0 = 0, x1 = cam.width - 1, y1 = cam.height - 1;
    const double z_near = std::min(c->a.z(), c->b.z()) - c->radius;
    if (z_near > 1e-3) {
      const auto pa = cam.Project(c->a), pb = cam.Project(c->b);
      const double pad = c->radius * std::max(cam.fx, cam.fy) / z_near + 2;
      x0 = std::max(0, static_cast<int>(std::floor(std::min(pa->x(), pb->x()) - pad)));
      x1 = std::min(cam.width - 1, static_cast<int>(std::ceil(std::max(pa->x(), pb->x()) + pad)));
      y0 = std::max(0, static_cast<int>(std::floor(std::min(pa->y(), pb->y()) - pad)));
      y1 = std::min(cam.height - 1, static_cast<int>(std::ceil(std::max(pa->y(), pb->y()) + pad)));
    }
    const Eigen::Vector3d u = (c->b - c->a).normalized();
    const Eigen::Vector3d ap = -c->a - (-c->a).dot(u) * u;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector3d d = cam.Unproject({double(x), double(y)}, 1.0).normalized();
        // |(t d - a) - ((t d - a).u) u|^2 = r^2, solved for the ray parameter t.
        const Eigen::Vector3d dp = d - d.dot(u) * u;
        const double qa = dp.squaredNorm(), qb = 2 * dp.dot(ap),
                     qc = ap.squaredNorm() - c->radius * c->radius;
        const double disc = qb * qb - 4 * qa * qc;
        if (disc < 0 || qa < 1e-12) continue;
        const double t = (-qb - std::sqrt(disc)) / (2 * qa);
        const double h = (t * d - c->a).dot(u);
        if (t > 0 && h >= 0 && h <= c->Length() && t < range.at(x, y)) {
          range.at(x, y) = t;
          depth.at(x, y) = static_cast<uint16_t>(std::lround(t * d.z() * 1000));
          mask.at(x, y) = 255;
        }
      }
  }
}

}  // namespace reenact::testing
