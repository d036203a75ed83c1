#include "common/model/part_pixel_assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace reenact {

std::optional<ProjectedPartAxis> ProjectPartAxis(const Eigen::Vector3d& a_in_camera,
                                                 const Eigen::Vector3d& b_in_camera,
                                                 const PinholeCamera& camera,
                                                 double min_length_px) {
  const auto pa = camera.Project(a_in_camera);
  const auto pb = camera.Project(b_in_camera);
  if (!pa || !pb) return std::nullopt;
  ProjectedPartAxis axis;
  axis.a = *pa;
  axis.b = *pb;
  axis.length_px = (*pb - *pa).norm();
  if (!(axis.length_px >= min_length_px) || !(axis.length_px > 0)) return std::nullopt;
  axis.dir = (*pb - *pa) / axis.length_px;
  axis.normal = Eigen::Vector2d(-axis.dir.y(), axis.dir.x());
  return axis;
}

std::optional<PartPixelAssignment> AssignPixelToPart(const Eigen::Vector2d& pixel,
                                                     const ProjectedPartAxes& axes,
                                                     double depth_m) {
  PartPixelAssignment best;
  double best_distance = std::numeric_limits<double>::max();
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!axes[p]) continue;
    const ProjectedPartAxis& axis = *axes[p];
    const Eigen::Vector2d from_a = pixel - axis.a;
    const double along = from_a.dot(axis.dir);
    if (along < -axis.end_band_a_px || along > axis.length_px + axis.end_band_b_px) continue;
    const double t = std::clamp(along / axis.length_px, 0.0, 1.0);
    const double offset = from_a.dot(axis.normal);
    double distance =
        std::abs(offset) / ((1 - t) * axis.distance_unit_a + t * axis.distance_unit_b);
    if (depth_m > 0 && axis.radius_m > 0 && axis.depth_a_m > 0 && axis.depth_b_m > 0) {
      const double z = 1 / ((1 - t) / axis.depth_a_m + t / axis.depth_b_m);
      const double behind = (depth_m - z) / axis.radius_m;
      distance = behind <= 0 ? std::abs(std::hypot(distance, behind) - 1)
                             : std::hypot(std::abs(distance - 1), behind);
    }
    if (distance < best_distance) {
      best_distance = distance;
      best = {p, t, offset};
    }
  }
  if (best.part < 0) return std::nullopt;
  return best;
}

}  // namespace reenact
