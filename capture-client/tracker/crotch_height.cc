#include "capture-client/tracker/crotch_height.h"

#include <cmath>

#include "common/error/check.h"

namespace reenact::capture {

void CrotchHeightOptions::Check() const {
  REENACT_CHECK(step_m > 0 && depth_tolerance_m > 0, "step_m, depth_tolerance_m must be > 0");
  REENACT_CHECK(min_gap_m >= 0 && max_height_m > min_gap_m, "need 0 <= min_gap_m < max_height_m");
}

namespace {

// The first hit up the vertical line from the floor point `base` (see crotch_height.h).
std::optional<double> GapTop(const PersonBlob& blob, const PinholeCamera& camera,
                             const Eigen::Vector3d& base, const Eigen::Vector3d& up,
                             const CrotchHeightOptions& options) {
  const int steps = static_cast<int>(options.max_height_m / options.step_m);
  for (int i = 1; i <= steps; ++i) {
    const double height = i * options.step_m;
    const Eigen::Vector3d q = base + height * up;
    const auto px = camera.Project(q);
    if (!px) return std::nullopt;
    const int gx = static_cast<int>(std::lround(px->x() / blob.grid_step_px));
    const int gy = static_cast<int>(std::lround(px->y() / blob.grid_step_px));
    if (gx < 0 || gy < 0 || gx >= blob.mask.width || gy >= blob.mask.height) continue;
    if (blob.mask.at(gx, gy) == 0) continue;
    const double z = blob.depth_m.at(gx, gy);
    if (z <= 0) continue;
    if (height < options.min_gap_m || z < q.z() - options.depth_tolerance_m) return std::nullopt;
    if (z > q.z() + options.depth_tolerance_m) continue;  // a surface behind the line
    return height;
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> MeasureCrotchHeight(const PersonBlob& blob, const PinholeCamera& camera,
                                          const Eigen::Vector3d& left_ankle,
                                          const Eigen::Vector3d& right_ankle,
                                          const CrotchHeightOptions& options) {
  options.Check();
  if (blob.status != DetectStatus::kOk || !blob.floor_in_sensor || blob.grid_step_px < 1 ||
      blob.mask.width == 0 || blob.depth_m.width != blob.mask.width ||
      blob.depth_m.height != blob.mask.height || !left_ankle.allFinite() ||
      !right_ankle.allFinite())
    return std::nullopt;
  const Plane3& floor = *blob.floor_in_sensor;
  const Eigen::Vector3d up = floor.normal.normalized();
  std::optional<double> top;
  for (const double f : {0.3, 0.4, 0.5, 0.6, 0.7}) {
    const Eigen::Vector3d p = left_ankle + f * (right_ankle - left_ankle);
    const auto h = GapTop(blob, camera, p - up * floor.SignedDistance(p), up, options);
    if (h && (!top || *h > *top)) top = h;
  }
  return top;
}

}  // namespace reenact::capture
