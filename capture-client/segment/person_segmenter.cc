#include "capture-client/segment/person_segmenter.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "capture-client/segment/body_bound.h"
#include "capture-client/segment/mask_fill.h"
#include "capture-client/segment/region_grow.h"
#include "common/error/check.h"

namespace reenact::capture {
namespace {

Status CheckInputs(const ImageDepthMm& depth, const PinholeCamera& camera, const Skeleton& skeleton,
                   const SegmentFrameGeometry& geometry) {
  if (depth.channels != 1 || depth.width != camera.width || depth.height != camera.height ||
      depth.data.size() != static_cast<size_t>(camera.width) * camera.height)
    return MakeError("invalid_argument",
                     "person segmentation: the depth image is " + std::to_string(depth.width) +
                         "x" + std::to_string(depth.height) + " with " +
                         std::to_string(depth.channels) + " channel(s), the depth camera " +
                         std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                         " with 1: register depth to the camera the segmenter was made for");
  bool any = false;
  for (int j = 0; j < kJointCount; ++j) {
    if (!skeleton.Has(static_cast<Joint>(j))) continue;
    any = true;
    if (!skeleton.position[j].allFinite() || !std::isfinite(skeleton.confidence[j]))
      return MakeError("invalid_argument",
                       "person segmentation: joint " +
                           std::string(JointName(static_cast<Joint>(j))) +
                           " is not a finite position: mark it missing (confidence 0) instead");
  }
  if (!any)
    return MakeError("invalid_argument",
                     "person segmentation: no skeleton (no joint present): the mask is grown "
                     "from the skeleton, so give a skeleton source for this frame");
  if (geometry.world_up && (!geometry.world_up->allFinite() || !(geometry.world_up->norm() > 1e-9)))
    return MakeError("invalid_argument",
                     "person segmentation: world_up must be a finite, non-zero direction");
  if (geometry.world_from_sensor && !geometry.world_from_sensor->matrix().allFinite())
    return MakeError("invalid_argument", "person segmentation: world_from_sensor is not finite");
  return {};
}

// The body's up axis in the sensor frame from the trunk (waist or torso to neck or head);
// the camera's up (-y) when the trunk is missing.
Eigen::Vector3d SkeletonUp(const Skeleton& s) {
  for (Joint top : {Joint::kNeck, Joint::kHead})
    for (Joint bottom : {Joint::kWaist, Joint::kTorso}) {
      if (!s.Has(top) || !s.Has(bottom)) continue;
      const Eigen::Vector3d axis = s[top] - s[bottom];
      if (axis.norm() > 1e-3) return axis.normalized();
    }
  return -Eigen::Vector3d::UnitY();
}

}  // namespace

std::string_view SegmentStatusName(SegmentStatus status) {
  switch (status) {
    case SegmentStatus::kOk:
      return "ok";
    case SegmentStatus::kNoDepth:
      return "no_depth";
    case SegmentStatus::kSkeletonBehindCamera:
      return "skeleton_behind_camera";
    case SegmentStatus::kSkeletonOutsideImage:
      return "skeleton_outside_image";
    case SegmentStatus::kNoSeeds:
      return "no_seeds";
  }
  return "unknown";
}

PersonSegmenter::PersonSegmenter(const PinholeCamera& depth_camera, double depth_scale_m,
                                 const PersonSegmentOptions& options)
    : camera_(depth_camera),
      depth_scale_m_(depth_scale_m),
      options_(options),
      rays_((depth_camera.Check(), depth_camera)) {
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0,
                "depth_scale_m must be positive and finite");
  options_.Check();
}

std::optional<Plane3> PersonSegmenter::UpdateFloor(const ImageDepthMm& depth,
                                                   const Skeleton& skeleton,
                                                   const SegmentFrameGeometry& geometry,
                                                   bool* refitted) {
  const auto& pose = geometry.world_from_sensor;
  std::optional<Plane3> cached;
  if (floor_ && (!floor_->in_world || pose))
    cached = floor_->in_world ? floor_->plane.Transformed(pose->inverse()) : floor_->plane;

  Eigen::Vector3d up;
  if (cached)
    up = cached->normal;
  else if (geometry.world_up && pose)
    up = (pose->linear().transpose() * *geometry.world_up).normalized();
  else
    up = SkeletonUp(skeleton);

  const auto guess = GuessFloor(skeleton, up);
  if (!guess) return std::nullopt;
  std::vector<Eigen::Vector3d> candidates;
  const int stride = options_.floor_sample_stride_px;
  for (int y = stride / 2; y < depth.height; y += stride)
    for (int x = stride / 2; x < depth.width; x += stride) {
      const double z = depth.at(x, y) * depth_scale_m_;
      if (z <= 0 || z < options_.min_depth_m || z > options_.max_depth_m) continue;
      const Eigen::Vector3d p = rays_.Point(x, y, z);
      if (IsFloorCandidate(p, up, *guess, options_)) candidates.push_back(p);
    }

  if (cached) {
    const bool checkable = static_cast<int>(candidates.size()) >= options_.floor_min_inliers;
    if (!checkable) return cached;  // too little floor in view to disprove the cached plane
    const FloorFit score = ScoreFloorPlane(*cached, candidates, options_);
    if (score.inliers >= options_.floor_min_inliers &&
        score.inlier_ratio >= options_.floor_min_inlier_ratio &&
        score.inlier_ratio >= options_.floor_keep_ratio * floor_->inlier_ratio)
      return cached;
  }
  const auto fit = FitFloorPlane(candidates, up, options_);
  if (!fit) {
    floor_.reset();
    return std::nullopt;
  }
  *refitted = true;
  floor_ = CachedFloor{pose ? fit->plane.Transformed(*pose) : fit->plane, pose.has_value(),
                       fit->inlier_ratio};
  return fit->plane;
}

Expected<PersonSegmentation> PersonSegmenter::Segment(const ImageDepthMm& depth,
                                                      const Skeleton& skeleton,
                                                      const SegmentFrameGeometry& geometry) {
  if (Status s = CheckInputs(depth, camera_, skeleton, geometry); !s.ok()) return s.error();
  PersonSegmentation out;
  out.mask = ImageGray8(depth.width, depth.height, 1, 0);

  const bool any_reading = std::any_of(depth.data.begin(), depth.data.end(), [&](uint16_t d) {
    const double z = d * depth_scale_m_;
    return d != 0 && z >= options_.min_depth_m && z <= options_.max_depth_m;
  });
  if (!any_reading) {
    out.status = SegmentStatus::kNoDepth;
    return out;
  }
  const BodyBound bound(skeleton, camera_, options_.body_margin_m);
  if (bound.behind_camera()) {
    out.status = SegmentStatus::kSkeletonBehindCamera;
    return out;
  }
  if (options_.remove_floor)
    out.floor_in_sensor = UpdateFloor(depth, skeleton, geometry, &out.floor_refitted);

  const BodyPixelTest test(depth, depth_scale_m_, rays_, bound, out.floor_in_sensor, options_);
  const SeedResult seeds = BoneSeeds(test, camera_);
  out.seed_pixels = static_cast<int>(seeds.pixels.size());
  if (seeds.samples_in_image == 0) {
    out.status = SegmentStatus::kSkeletonOutsideImage;
    return out;
  }
  if (seeds.pixels.empty()) {
    out.status = SegmentStatus::kNoSeeds;
    return out;
  }
  PixelRect box;
  const int grown = GrowRegion(test, seeds.pixels, &out.mask, &box, &state_);

  out.filled_pixels = FillDepthHoles([&](int x, int y) { return test.Depth(x, y); },
                                     options_.max_hole_run_px, box, &out.mask);
  out.filled_pixels +=
      FillEnclosedHoles([&](int x, int y) { return test.Depth(x, y); },
                        [&](int x, int y, double z) { return test.OnFloor(x, y, z); },
                        options_.depth_step, options_.hole_person_ratio, box, &out.mask);
  out.mask_pixels = grown + out.filled_pixels;
  return out;
}

Expected<PersonSegmentation> PersonSegmenter::SegmentFrame(
    const SensorFrame& frame, const std::optional<Eigen::Vector3d>& world_up) {
  if (!frame.skeleton_in_world)
    return MakeError("invalid_argument",
                     "person segmentation: the frame has no skeleton: the mask is grown from the "
                     "skeleton, so give a skeleton source");
  if (!frame.world_from_sensor)
    return MakeError("invalid_argument",
                     "person segmentation: the frame's skeleton is in the world frame but the "
                     "frame has no sensor pose (world_from_sensor): track the sensor first");
  if (!frame.world_from_sensor->matrix().allFinite())
    return MakeError("invalid_argument", "person segmentation: world_from_sensor is not finite");
  const Skeleton in_sensor =
      frame.skeleton_in_world->Transformed(frame.world_from_sensor->inverse());
  return Segment(frame.depth, in_sensor, {frame.world_from_sensor, world_up});
}

}  // namespace reenact::capture
