#include "common/model/radius_fit.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "common/error/check.h"
#include "common/estimate/median.h"
#include "common/model/part_pixel_assignment.h"

namespace reenact {

void RadiusFitOptions::Check() const {
  REENACT_CHECK(slices >= 1, "slices must be >= 1");
  REENACT_CHECK(min_pixels_per_slice >= 1, "min_pixels_per_slice must be >= 1");
  REENACT_CHECK(min_slices >= 1, "min_slices must be >= 1");
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0, "depth_scale_m must be > 0");
}

int RadiusFitResult::fitted_count() const {
  return static_cast<int>(std::count(fitted.begin(), fitted.end(), true));
}

RadiusFitResult FitRadiusRatios(const Skeleton& skeleton, const PinholeCamera& camera,
                                const ImageDepthMm& depth, const ImageGray8& mask,
                                const RadiusFitOptions& options) {
  options.Check();
  camera.Check();
  REENACT_CHECK(depth.width == mask.width && depth.height == mask.height,
                "depth and mask must have the same size");

  RadiusFitResult result;
  result.radius_ratio = DefaultRadiusRatios();

  ProjectedPartAxes axes;
  std::array<double, kBodyPartCount> length_m{};
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto part = static_cast<BodyPart>(p);
    if (!skeleton.HasPart(part)) continue;
    const auto [ja, jb] = PartJoints(part);
    length_m[p] = (skeleton[jb] - skeleton[ja]).norm();
    if (length_m[p] < kMinBoneLength) continue;
    axes[p] = ProjectPartAxis(skeleton[ja], skeleton[jb], camera, 2.0);
  }

  // Pixel counts per part and slice; depths per part.
  const int slices = options.slices;
  std::vector<std::vector<int>> slice_count(kBodyPartCount, std::vector<int>(slices, 0));
  std::vector<std::vector<double>> part_depths(kBodyPartCount);

  for (int y = 0; y < mask.height; ++y) {
    for (int x = 0; x < mask.width; ++x) {
      if (mask.at(x, y) < 128) continue;
      const auto assigned = AssignPixelToPart(Eigen::Vector2d(x, y), axes);
      if (!assigned) continue;
      const int best = assigned->part;
      const double best_t = assigned->t;
      ++result.pixel_count[best];
      if (depth.at(x, y) != 0) part_depths[best].push_back(depth.at(x, y) * options.depth_scale_m);
      if (best_t < 0.1 || best_t > 0.9) continue;
      const int s = std::min(slices - 1, static_cast<int>((best_t - 0.1) / 0.8 * slices));
      ++slice_count[best][s];
    }
  }

  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!axes[p]) continue;
    const ProjectedPartAxis& ax = *axes[p];
    const double slice_length_px = 0.8 * ax.length_px / slices;
    std::vector<double> widths;
    for (int s = 0; s < slices; ++s)
      if (slice_count[p][s] >= options.min_pixels_per_slice)
        widths.push_back(slice_count[p][s] / slice_length_px);
    if (static_cast<int>(widths.size()) < options.min_slices || part_depths[p].empty()) continue;
    // Focal length across the axis: the normal's components weigh fx and fy.
    const double f = std::hypot(ax.normal.x() * camera.fx, ax.normal.y() * camera.fy);
    // The silhouette's half width is r f / (z + r) for a cylinder whose nearest surface lies
    // at depth z, so r = w z / (2 f - w).
    const double w = UpperMedian(widths);
    if (!(2 * f - w > 0)) continue;
    const double radius = w * UpperMedian(part_depths[p]) / (2 * f - w);
    result.radius_ratio[p] = radius / length_m[p];
    result.fitted[p] = true;
  }
  return result;
}

}  // namespace reenact
