#include "capture-client/tracker/head_size.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/error/check.h"

namespace reenact::capture {

void HeadSizeOptions::Check() const {
  REENACT_CHECK(slice_m > 0 && band_m > slice_m, "need band_m > slice_m > 0");
  REENACT_CHECK(neck_ratio > 0 && neck_ratio < 1, "neck_ratio must lie in (0, 1)");
  REENACT_CHECK(min_slice_points >= 2, "min_slice_points must be >= 2");
}

std::optional<HeadSize> MeasureHeadSize(const PersonBlob& blob, double camera_fy,
                                        const HeadSizeOptions& options) {
  options.Check();
  REENACT_CHECK(camera_fy > 0 && std::isfinite(camera_fy), "focal length must be positive");
  if (blob.status != DetectStatus::kOk || !blob.floor_in_sensor || blob.points.empty())
    return std::nullopt;
  const Plane3& floor = *blob.floor_in_sensor;
  const Eigen::Vector3d up = floor.normal.normalized();
  std::vector<double> height(blob.points.size());
  for (size_t i = 0; i < blob.points.size(); ++i) height[i] = floor.SignedDistance(blob.points[i]);
  const double top = *std::max_element(height.begin(), height.end());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  int n = 0;
  for (size_t i = 0; i < blob.points.size(); ++i)
    if (height[i] >= top - options.band_m) centroid += blob.points[i], ++n;
  centroid /= n;
  const Eigen::Vector3d across = up.cross(centroid - up * up.dot(centroid));
  if (across.norm() < 1e-6 * centroid.norm() || centroid.z() <= 0) return std::nullopt;
  const Eigen::Vector3d u_axis = across.normalized();

  const double grid_m = blob.grid_step_px * centroid.z() / camera_fy;
  const double slice_m = std::max(options.slice_m, 2 * grid_m);
  const int slices = static_cast<int>(std::ceil(options.band_m / slice_m));
  std::vector<double> lo(slices, std::numeric_limits<double>::infinity());
  std::vector<double> hi(slices, -std::numeric_limits<double>::infinity());
  std::vector<int> count(slices, 0);
  for (size_t i = 0; i < blob.points.size(); ++i) {
    const double below = top - height[i];
    if (below >= options.band_m) continue;
    const int k = std::min(slices - 1, static_cast<int>(below / slice_m));
    const double u = u_axis.dot(blob.points[i]);
    lo[k] = std::min(lo[k], u);
    hi[k] = std::max(hi[k], u);
    ++count[k];
  }
  double widest = 0;
  int neck = -1;
  for (int k = 0; k < slices && neck < 0; ++k) {
    if (count[k] < options.min_slice_points) continue;
    const double width = hi[k] - lo[k];
    if (width < options.neck_ratio * widest) neck = k;
    widest = std::max(widest, width);
  }
  if (neck < 0) return std::nullopt;
  // The head down to the neck must lie inside the image: a head cut by its edge reads short.
  if (blob.pixels.size() == blob.points.size() && blob.mask.width > 0 && blob.mask.height > 0)
    for (size_t i = 0; i < blob.points.size(); ++i) {
      const Eigen::Vector2i& px = blob.pixels[i];
      const bool on_border = px.x() <= 0 || px.y() <= 0 || px.x() >= blob.mask.width - 1 ||
                             px.y() >= blob.mask.height - 1;
      if (on_border && top - height[i] < (neck + 1) * slice_m) return std::nullopt;
    }
  return HeadSize{.half_width_m = 0.5 * widest, .neck_below_top_m = (neck + 0.5) * slice_m};
}

}  // namespace reenact::capture
