#include "common/geometry/depth_points.h"

#include <cmath>

#include "common/error/check.h"

namespace reenact {
namespace {

void CheckInputs(const ImageDepthMm& depth, const PinholeCamera& camera,
                 const DepthPointsOptions& options) {
  options.Check();
  camera.Check();
  REENACT_CHECK(depth.channels == 1, "depth image must have 1 channel");
  REENACT_CHECK(depth.width == camera.width && depth.height == camera.height,
                "depth image size must match the camera");
}

std::optional<Eigen::Vector3d> PointAt(const ImageDepthMm& depth, const PinholeCamera& camera,
                                       int x, int y, const DepthPointsOptions& options) {
  const uint16_t d = depth.at(x, y);
  if (d == 0) return std::nullopt;
  const double z = d * options.depth_scale_m;
  if (z < options.min_depth_m || z > options.max_depth_m) return std::nullopt;
  return camera.Unproject(Eigen::Vector2d(x, y), z);
}

}  // namespace

void DepthPointsOptions::Check() const {
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0,
                "depth_scale_m must be positive and finite");
  REENACT_CHECK(min_depth_m >= 0 && min_depth_m <= max_depth_m,
                "need 0 <= min_depth_m <= max_depth_m");
  REENACT_CHECK(stride >= 1, "stride must be >= 1");
}

DepthPoints DepthToPoints(const ImageDepthMm& depth, const PinholeCamera& camera,
                          const DepthPointsOptions& options, const ImageGray8* mask) {
  CheckInputs(depth, camera, options);
  if (mask != nullptr) {
    REENACT_CHECK(mask->channels == 1, "mask must have 1 channel");
    REENACT_CHECK(mask->width == depth.width && mask->height == depth.height,
                  "mask size must match the depth image");
  }
  DepthPoints out;
  for (int y = 0; y < depth.height; y += options.stride) {
    for (int x = 0; x < depth.width; x += options.stride) {
      if (mask != nullptr && mask->at(x, y) == 0) continue;
      const auto p = PointAt(depth, camera, x, y, options);
      if (!p) continue;
      out.points_in_camera.push_back(*p);
      out.pixels.emplace_back(x, y);
    }
  }
  return out;
}

std::optional<Eigen::Vector3d> BackProjectPixel(const ImageDepthMm& depth,
                                                const PinholeCamera& camera, int x, int y,
                                                const DepthPointsOptions& options) {
  CheckInputs(depth, camera, options);
  if (!depth.Contains(x, y)) return std::nullopt;
  return PointAt(depth, camera, x, y, options);
}

}  // namespace reenact
