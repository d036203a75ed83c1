#include "common/model/extension_fit.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error/check.h"
#include "common/estimate/median.h"

namespace reenact {
namespace {

// Step along the 3D axis used to find the projected axis's direction and scale, metres.
constexpr double kAxisStepM = 0.01;

bool Inside(const ImageGray8& image, int x, int y) {
  return x >= 0 && y >= 0 && x < image.width && y < image.height;
}

}  // namespace

void ExtensionFitOptions::Check() const {
  REENACT_CHECK(std::isfinite(min_fill) && min_fill > 0 && min_fill <= 1,
                "min_fill must be in (0, 1]");
  REENACT_CHECK(std::isfinite(depth_tolerance_m) && depth_tolerance_m >= 0,
                "depth_tolerance_m must be finite and >= 0");
  REENACT_CHECK(std::isfinite(max_ratio) && max_ratio >= 0, "max_ratio must be finite and >= 0");
  REENACT_CHECK(std::isfinite(min_axis_scale) && min_axis_scale > 0 && min_axis_scale <= 1,
                "min_axis_scale must be in (0, 1]");
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0,
                "depth_scale_m must be finite and > 0");
}

bool IsExtendedPart(BodyPart part) {
  switch (part) {
    case BodyPart::kHead:
    case BodyPart::kLeftForearm:
    case BodyPart::kRightForearm:
    case BodyPart::kLeftShin:
    case BodyPart::kRightShin:
      return true;
    default:
      return false;
  }
}

std::optional<double> MeasureExtension(const ExtensionFitFrame& frame, BodyPart part,
                                       const RadiusRatios& ratios,
                                       const ExtensionFitOptions& options) {
  options.Check();
  REENACT_CHECK(frame.skeleton_in_sensor && frame.camera && frame.mask && frame.depth,
                "extension fit frame needs a skeleton, camera, mask and depth");
  const Skeleton& skeleton = *frame.skeleton_in_sensor;
  const PinholeCamera& camera = *frame.camera;
  const ImageGray8& mask = *frame.mask;
  const ImageDepthMm& depth = *frame.depth;
  camera.Check();
  REENACT_CHECK(mask.channels == 1 && mask.width == camera.width && mask.height == camera.height,
                "mask must be 1-channel of the camera's size");
  REENACT_CHECK(depth.empty() || (depth.channels == 1 && depth.width == mask.width &&
                                  depth.height == mask.height),
                "depth must be empty or 1-channel of the mask's size");
  const double ratio = ratios[Index(part)];
  REENACT_CHECK(std::isfinite(ratio) && ratio >= 0, "radius ratio must be finite and >= 0");

  if (!skeleton.HasPart(part)) return std::nullopt;
  const auto [ja, jb] = PartJoints(part);
  const Joint end = EndJoint(part);
  const Eigen::Vector3d d = skeleton[end];
  const Eigen::Vector3d q = skeleton[end == ja ? jb : ja];
  const double bone = (d - q).norm();
  if (!(bone >= kMinBoneLength)) return std::nullopt;
  const Eigen::Vector3d u = (d - q) / bone;
  const double radius = bone * ratio;
  // The walk follows the cylinder's front generator line (the surface line nearest the
  // camera), whose end is where the drawn cylinder's silhouette ends: the joint's own pixel
  // lies inside the silhouette by a perspective offset of up to a few pixels.
  Eigen::Vector3d facing = -d - (-d).dot(u) * u;
  facing = facing.norm() > 1e-9 ? Eigen::Vector3d(facing.normalized()) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d front = d + radius * facing;
  const auto d_px = camera.Project(front);
  const auto step_px = camera.Project(front + kAxisStepM * u);
  if (!camera.Project(d) || !d_px || !step_px) return std::nullopt;
  const Eigen::Vector2d delta = *step_px - *d_px;
  const double scale = delta.norm() / kAxisStepM;  // J, pixels per metre along the axis
  const double f = 0.5 * (camera.fx + camera.fy);
  if (!(scale >= options.min_axis_scale * f / d.z())) return std::nullopt;
  const Eigen::Vector2d dir = delta.normalized();
  const Eigen::Vector2d normal(-dir.y(), dir.x());
  const int half_band = static_cast<int>(std::floor(f * radius / d.z()));
  const int dx = static_cast<int>(std::lround(d_px->x())),
            dy = static_cast<int>(std::lround(d_px->y()));
  if (!Inside(mask, dx, dy) || mask.at(dx, dy) < 128) return std::nullopt;  // joint off the mask
  const int max_steps = static_cast<int>(std::ceil(options.max_ratio * bone * scale)) + 1;

  int passed = 0;
  for (int t = 1; t <= max_steps; ++t) {
    const Eigen::Vector2d centre = *d_px + t * dir;
    if (!Inside(mask, static_cast<int>(std::lround(centre.x())),
                static_cast<int>(std::lround(centre.y()))))
      return std::nullopt;  // the subject may go on past the image border
    const double expected_z = front.z() + (t / scale) * u.z();
    int hits = 0, samples = 0;
    for (int k = -half_band; k <= half_band; ++k) {
      const Eigen::Vector2d p = centre + k * normal;
      const int x = static_cast<int>(std::lround(p.x())), y = static_cast<int>(std::lround(p.y()));
      ++samples;
      if (!Inside(mask, x, y) || mask.at(x, y) < 128) continue;
      if (!depth.empty() && depth.at(x, y) > 0 &&
          std::abs(depth.at(x, y) * options.depth_scale_m - expected_z) >
              options.depth_tolerance_m + radius)
        continue;
      ++hits;
    }
    if (hits < options.min_fill * samples) break;
    passed = t;
  }
  return passed > 0 ? (passed + 0.5) / scale : 0.0;
}

ExtensionFitResult FitPartExtensions(std::span<const ExtensionFitFrame> frames,
                                     const RadiusRatios& ratios,
                                     const ExtensionFitOptions& options) {
  options.Check();
  ExtensionFitResult result;
  for (int p = 0; p < kBodyPartCount; ++p) {
    const BodyPart part = static_cast<BodyPart>(p);
    if (!IsExtendedPart(part)) continue;
    std::vector<double> ratio_of_bone;
    for (const ExtensionFitFrame& frame : frames) {
      const auto metres = MeasureExtension(frame, part, ratios, options);
      if (!metres) continue;
      const auto [ja, jb] = PartJoints(part);
      const Skeleton& s = *frame.skeleton_in_sensor;
      ratio_of_bone.push_back(*metres / (s[ja] - s[jb]).norm());
    }
    result.frames_measured[p] = static_cast<int>(ratio_of_bone.size());
    if (ratio_of_bone.empty()) continue;
    result.fitted[p] = true;
    result.extension[p] = std::clamp(Median(std::move(ratio_of_bone)), 0.0, options.max_ratio);
  }
  return result;
}

}  // namespace reenact
