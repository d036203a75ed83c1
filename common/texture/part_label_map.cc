#include "common/texture/part_label_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error/check.h"

namespace reenact {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Smallest t > 0 at which the ray t d (from the origin) meets the closed cylinder; +inf if
// none.
double RayCylinderHit(const Eigen::Vector3d& d, const Cylinder& c) {
  const Eigen::Vector3d axis = c.b - c.a;
  const double length = axis.norm();
  if (!(length > 0)) return kInf;
  const Eigen::Vector3d n = axis / length;
  const double r2 = c.radius * c.radius;
  double best = kInf;
  // Side: |(t d - a)_perp|^2 = r^2 with 0 <= (t d - a) . n <= length.
  const Eigen::Vector3d d_perp = d - d.dot(n) * n;
  const Eigen::Vector3d a_perp = c.a - c.a.dot(n) * n;
  const double qa = d_perp.squaredNorm(), qb = -2 * d_perp.dot(a_perp),
               qc = a_perp.squaredNorm() - r2;
  if (qa > 1e-18) {
    const double disc = qb * qb - 4 * qa * qc;
    if (disc >= 0) {
      const double root = std::sqrt(disc);
      for (double t : {(-qb - root) / (2 * qa), (-qb + root) / (2 * qa)}) {
        if (!(t > 0) || t >= best) continue;
        const double s = (t * d - c.a).dot(n);
        if (s >= 0 && s <= length) best = t;
      }
    }
  }
  // Caps: planes through a and b with normal n.
  const double dn = d.dot(n);
  if (std::abs(dn) > 1e-18)
    for (const Eigen::Vector3d* centre : {&c.a, &c.b}) {
      const double t = centre->dot(n) / dn;
      if (t > 0 && t < best && (t * d - *centre).squaredNorm() <= r2) best = t;
    }
  return best;
}

// A cylinder's axis projected into the image, clipped to z >= kLabelMapNearZ.
struct ProjectedAxis {
  Eigen::Vector2d p0, p1;     // pixels
  double rho0 = 0, rho1 = 0;  // projected radius at each end, pixels
};

std::optional<ProjectedAxis> ProjectAxis(const Cylinder& c, const PinholeCamera& camera) {
  Eigen::Vector3d a = c.a, b = c.b;
  if (a.z() < kLabelMapNearZ && b.z() < kLabelMapNearZ) return std::nullopt;
  if (a.z() < kLabelMapNearZ || b.z() < kLabelMapNearZ) {
    const double s = (kLabelMapNearZ - a.z()) / (b.z() - a.z());
    const Eigen::Vector3d cut = a + s * (b - a);
    (a.z() < kLabelMapNearZ ? a : b) = cut;
  }
  const auto project = [&camera](const Eigen::Vector3d& p) {
    return Eigen::Vector2d(camera.fx * p.x() / p.z() + camera.cx,
                           camera.fy * p.y() / p.z() + camera.cy);
  };
  return ProjectedAxis{project(a), project(b), camera.fx * c.radius / a.z(),
                       camera.fx * c.radius / b.z()};
}

// Pixel box (inclusive) that holds the cylinder's image: the projection of its axis-aligned
// 3D bounding box, grown by a pixel; the whole image where that box reaches z < near.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool Contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

PixelBox ImageBox(const Cylinder& c, const PinholeCamera& camera) {
  const Eigen::Vector3d lo = c.a.cwiseMin(c.b).array() - c.radius;
  const Eigen::Vector3d hi = c.a.cwiseMax(c.b).array() + c.radius;
  if (hi.z() <= 0) return {};  // wholly behind: never hit
  if (lo.z() < kLabelMapNearZ) return {0, 0, camera.width - 1, camera.height - 1};
  double u0 = kInf, v0 = kInf, u1 = -kInf, v1 = -kInf;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y(),
                            corner & 4 ? hi.z() : lo.z());
    const double u = camera.fx * p.x() / p.z() + camera.cx;
    const double v = camera.fy * p.y() / p.z() + camera.cy;
    u0 = std::min(u0, u);
    u1 = std::max(u1, u);
    v0 = std::min(v0, v);
    v1 = std::max(v1, v);
  }
  const auto clamp_to = [](double value, int size) {
    return static_cast<int>(std::clamp(value, -1.0, static_cast<double>(size)));
  };
  return {clamp_to(std::floor(u0) - 1, camera.width), clamp_to(std::floor(v0) - 1, camera.height),
          clamp_to(std::ceil(u1) + 1, camera.width), clamp_to(std::ceil(v1) + 1, camera.height)};
}

double CapsuleDistance(const ProjectedAxis& axis, const Eigen::Vector2d& pixel) {
  const Eigen::Vector2d e = axis.p1 - axis.p0;
  const double e2 = e.squaredNorm();
  const double s = e2 > 0 ? std::clamp((pixel - axis.p0).dot(e) / e2, 0.0, 1.0) : 0.0;
  return (pixel - (axis.p0 + s * e)).norm() - ((1 - s) * axis.rho0 + s * axis.rho1);
}

}  // namespace

ImageLabel8 RenderPartLabelMap(const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders,
                               const PinholeCamera& camera, const ImageGray8& mask) {
  camera.Check();
  REENACT_CHECK(mask.channels == 1 && mask.width == camera.width && mask.height == camera.height,
                "part label map: the mask must be single-channel of the camera's size");
  std::array<std::optional<ProjectedAxis>, kBodyPartCount> axes;
  std::array<PixelBox, kBodyPartCount> boxes;
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!cylinders[p]) continue;
    const Cylinder& c = *cylinders[p];
    REENACT_CHECK(c.a.allFinite() && c.b.allFinite() && std::isfinite(c.radius) && c.radius > 0,
                  "part label map: cylinders must be finite with a positive radius");
    if (c.Length() > 0) {
      axes[p] = ProjectAxis(c, camera);
      boxes[p] = ImageBox(c, camera);
    }
  }
  ImageLabel8 labels(camera.width, camera.height, 1, kBackgroundLabel);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      if (mask.at(x, y) < 128) continue;
      const Eigen::Vector3d d((x - camera.cx) / camera.fx, (y - camera.cy) / camera.fy, 1.0);
      int best = -1;
      double best_t = kInf;
      for (int p = 0; p < kBodyPartCount; ++p) {
        if (!boxes[p].Contains(x, y)) continue;
        const double t = RayCylinderHit(d, *cylinders[p]);
        if (t < best_t) {
          best_t = t;
          best = p;
        }
      }
      if (best < 0) {
        double best_distance = kInf;
        for (int p = 0; p < kBodyPartCount; ++p) {
          if (!axes[p]) continue;
          const double distance = CapsuleDistance(*axes[p], Eigen::Vector2d(x, y));
          if (distance < best_distance) {
            best_distance = distance;
            best = p;
          }
        }
      }
      if (best >= 0) labels.at(x, y) = static_cast<uint8_t>(PartLabel(static_cast<BodyPart>(best)));
    }
  return labels;
}

ImageLabel8 PartLabelMapOfFrame(const Skeleton& skeleton_in_sensor, const RadiusRatios& ratios,
                                const PinholeCamera& crop_camera, const ImageGray8& mask,
                                const PartExtensions& extensions) {
  return RenderPartLabelMap(PoseCylinders(skeleton_in_sensor, ratios, extensions), crop_camera,
                            mask);
}

}  // namespace reenact
