#pragma once
// Test support: ray casting of posed cylinders that carry a PartShape (cylinder_model.h:
// elliptic rings, semi-axes linear in t between rings, closed at both ends) into a depth image
// (mm) and a subject mask, independent of the code under test. Each pixel's ray is marched
// through the shape's bounding cylinder in 1 mm steps and the first entry refined by
// bisection; a ray that stays inside the solid for less than a step is missed, which only
// happens within about 1e-5 m of a silhouette edge (chord c = 1 mm of a radius >= 0.02 m
// misses by c^2 / 8r), far below a pixel.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "common/model/cylinder_model.h"

namespace reenact::testing {

namespace shaped_detail {

inline double Lerp(const std::array<double, kShapeRings>& rings, double t) {
  const double x = std::clamp(t, 0.0, 1.0) * (kShapeRings - 1);
  const int k = std::min(kShapeRings - 2, static_cast<int>(x));
  return rings[k] + (x - k) * (rings[k + 1] - rings[k]);
}

}  // namespace shaped_detail

// cam must be undistorted; cylinders in its frame (x right, y down, z forward, metres).
inline void RayCastShapedCylinders(
    const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders, const PinholeCamera& cam,
    ImageDepthMm& depth, ImageGray8& mask) {
  using shaped_detail::Lerp;
  constexpr double kStep = 0.001;
  depth = ImageDepthMm(cam.width, cam.height, 1, 0);
  mask = ImageGray8(cam.width, cam.height, 1, 0);
  Image<double> range(cam.width, cam.height, 1, std::numeric_limits<double>::infinity());
  for (const auto& c : cylinders) {
    if (!c) continue;
    const double length = c->Length();
    const Eigen::Vector3d z_hat = (c->b - c->a) / length;
    Eigen::Vector3d x_hat;
    if (c->width_direction) {
      x_hat = *c->width_direction;
    } else {
      const Eigen::Vector3d helper =
          std::abs(z_hat.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
      x_hat = z_hat.cross(helper).normalized();
    }
    const Eigen::Vector3d y_hat = z_hat.cross(x_hat);
    double bound = 0;
    for (int k = 0; k < kShapeRings; ++k)
      bound = std::max({bound, c->shape.width[k], c->shape.depth[k]});
    bound *= c->radius;

    // Image bounding box of the bounding cylinder's corners.
    int x0 = 0, y0 = 0, x1 = cam.width - 1, y1 = cam.height - 1;
    bool all_front = true;
    double u_min = 1e300, u_max = -1e300, v_min = 1e300, v_max = -1e300;
    for (const Eigen::Vector3d& end : {c->a, c->b})
      for (int sx : {-1, 1})
        for (int sy : {-1, 1}) {
          const auto px = cam.Project(end + bound * (sx * x_hat + sy * y_hat), 1e-3);
          if (!px) {
            all_front = false;
            continue;
          }
          u_min = std::min(u_min, px->x());
          u_max = std::max(u_max, px->x());
          v_min = std::min(v_min, px->y());
          v_max = std::max(v_max, px->y());
        }
    if (all_front) {
      x0 = std::max(0, static_cast<int>(std::floor(u_min)) - 2);
      x1 = std::min(cam.width - 1, static_cast<int>(std::ceil(u_max)) + 2);
      y0 = std::max(0, static_cast<int>(std::floor(v_min)) - 2);
      y1 = std::min(cam.height - 1, static_cast<int>(std::ceil(v_max)) + 2);
    }

    // Local coordinates of the ray point s d: (x, y, h) = ((s d - a).x_hat, ..., ...).
    const auto inside = [&](const Eigen::Vector3d& d, double s) {
      const Eigen::Vector3d rel = s * d - c->a;
      const double h = rel.dot(z_hat);
      if (h < 0 || h > length) return false;
      const double t = h / length;
      const double w = Lerp(c->shape.width, t) * c->radius;
      const double e = Lerp(c->shape.depth, t) * c->radius;
      const double x = rel.dot(x_hat) / w, y = rel.dot(y_hat) / e;
      return x * x + y * y <= 1;
    };

    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector3d d = cam.Unproject({double(x), double(y)}, 1.0).normalized();
        // Ray interval inside the bounding cylinder (radius `bound` about the axis) and the
        // slab 0 <= h <= length.
        const Eigen::Vector3d ap = -c->a - (-c->a).dot(z_hat) * z_hat;
        const Eigen::Vector3d dp = d - d.dot(z_hat) * z_hat;
        const double qa = dp.squaredNorm(), qb = 2 * dp.dot(ap),
                     qc = ap.squaredNorm() - bound * bound;
        double s_lo = 0, s_hi = 100;
        if (qa > 1e-12) {
          const double disc = qb * qb - 4 * qa * qc;
          if (disc < 0) continue;
          s_lo = std::max(s_lo, (-qb - std::sqrt(disc)) / (2 * qa));
          s_hi = std::min(s_hi, (-qb + std::sqrt(disc)) / (2 * qa));
        } else if (qc > 0) {
          continue;
        }
        const double dz = d.dot(z_hat), h0 = (-c->a).dot(z_hat);  // h(s) = h0 + s dz
        if (std::abs(dz) > 1e-12) {
          const double sa = -h0 / dz, sb = (length - h0) / dz;
          s_lo = std::max(s_lo, std::min(sa, sb));
          s_hi = std::min(s_hi, std::max(sa, sb));
        } else if (h0 < 0 || h0 > length) {
          continue;
        }
        if (s_hi <= s_lo) continue;
        double prev = s_lo;
        std::optional<double> hit;
        if (inside(d, s_lo)) hit = s_lo;
        for (double s = s_lo + kStep; !hit && s < s_hi + kStep; s += kStep) {
          const double sc = std::min(s, s_hi);
          if (inside(d, sc)) {
            double lo = prev, hi = sc;
            for (int i = 0; i < 30; ++i) {
              const double mid = 0.5 * (lo + hi);
              (inside(d, mid) ? hi : lo) = mid;
            }
            hit = hi;
          }
          prev = sc;
        }
        if (!hit || !(*hit > 0) || *hit >= range.at(x, y)) continue;
        range.at(x, y) = *hit;
        depth.at(x, y) = static_cast<uint16_t>(std::lround(*hit * d.z() * 1000));
        mask.at(x, y) = 255;
      }
  }
}

}  // namespace reenact::testing
