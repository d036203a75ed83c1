#include "common/texture/part_coverage.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "common/error/check.h"
#include "common/render/cylinder_mesh.h"
#include "common/texture/texture_mapping.h"

namespace reenact {
namespace {

bool Visible(const Eigen::Vector3d& point, int label, const PinholeCamera& camera,
             const ImageGray8& mask, const ImageLabel8& part_labels, const Image<float>& depth_m,
             double depth_tolerance_m) {
  if (!(point.z() > 0)) return false;
  const double u = camera.fx * point.x() / point.z() + camera.cx;
  const double v = camera.fy * point.y() / point.z() + camera.cy;
  if (!(u >= -0.5 && u <= camera.width - 0.5 && v >= -0.5 && v <= camera.height - 0.5))
    return false;
  const int x = std::clamp(static_cast<int>(std::floor(u + 0.5)), 0, camera.width - 1);
  const int y = std::clamp(static_cast<int>(std::floor(v + 0.5)), 0, camera.height - 1);
  if (mask.at(x, y) < 128 || part_labels.at(x, y) != label) return false;
  if (depth_m.empty()) return true;
  const double d = depth_m.at(x, y);
  return d == 0 || std::abs(d - point.z()) <= depth_tolerance_m;
}

PartCoverage CoverageOfPart(const Cylinder& c, int label, const PinholeCamera& camera,
                            const ImageGray8& mask, const ImageLabel8& part_labels,
                            const Image<float>& depth_m, double depth_tolerance_m) {
  const Eigen::Vector3d axis = c.b - c.a;
  const std::optional<Eigen::Vector3d> f = FacingDirection(c.a, c.b);
  if (!f || !(axis.norm() >= kMinBoneLength)) return 0;
  const Eigen::Vector3d u = axis.normalized();
  const Eigen::Vector3d side = u.cross(*f);
  const Eigen::Matrix4d frame = ViewerFromUnitCylinder(c);
  const Eigen::Vector3d x_hat = frame.col(0).head<3>().normalized();
  const Eigen::Vector3d y_hat = frame.col(1).head<3>().normalized();
  PartCoverage coverage = 0;
  for (int i = 0; i < kCoverageAngles; ++i) {
    const double theta = std::numbers::pi * ((i + 0.5) / kCoverageAngles - 0.5);
    const Eigen::Vector3d d = std::cos(theta) * *f + std::sin(theta) * side;
    for (int j = 0; j < kCoverageHeights; ++j) {
      const double t = (j + 0.5) / kCoverageHeights;
      const double across = d.dot(x_hat) / RingValueAt(c.shape.width, t);
      const double along = d.dot(y_hat) / RingValueAt(c.shape.depth, t);
      const double rho = c.radius / std::sqrt(across * across + along * along);
      const Eigen::Vector3d point = c.a + t * axis + rho * d;
      if (Visible(point, label, camera, mask, part_labels, depth_m, depth_tolerance_m))
        coverage |= PartCoverage{1} << (i * kCoverageHeights + j);
    }
  }
  return coverage;
}

}  // namespace

PartCoverages CoverageOfFrame(const std::array<std::optional<Cylinder>, kBodyPartCount>& cylinders,
                              const PinholeCamera& camera, const ImageGray8& mask,
                              const ImageLabel8& part_labels, const Image<float>& depth_m,
                              double depth_tolerance_m) {
  camera.Check();
  const auto camera_sized = [&camera](const auto& image) {
    return image.channels == 1 && image.width == camera.width && image.height == camera.height;
  };
  REENACT_CHECK(camera_sized(mask) && camera_sized(part_labels),
                "coverage: mask and part labels must be 1-channel of the camera's size");
  REENACT_CHECK(depth_m.empty() || camera_sized(depth_m),
                "coverage: depth must be empty or 1-channel of the camera's size");
  REENACT_CHECK(std::isfinite(depth_tolerance_m) && depth_tolerance_m >= 0,
                "coverage: depth_tolerance_m must be finite and >= 0");
  PartCoverages out{};
  for (int p = 0; p < kBodyPartCount; ++p)
    if (cylinders[p])
      out[p] = CoverageOfPart(*cylinders[p], PartLabel(static_cast<BodyPart>(p)), camera, mask,
                              part_labels, depth_m, depth_tolerance_m);
  return out;
}

int CoveredCells(PartCoverage coverage) { return std::popcount(coverage); }

}  // namespace reenact
