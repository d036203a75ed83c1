#include "viewer-client/play/reenactment.h"

#include <algorithm>

#include "common/error/check.h"
#include "common/texture/texture_mapping.h"

namespace reenact::viewer {
namespace {

// Distinct flat colours for bare cylinders, one per part.
Eigen::Vector3f PartColor(int part) {
  static const float kHues[kBodyPartCount][3] = {
      {0.90f, 0.75f, 0.60f}, {0.25f, 0.45f, 0.80f}, {0.20f, 0.35f, 0.70f}, {0.85f, 0.40f, 0.35f},
      {0.95f, 0.60f, 0.45f}, {0.40f, 0.75f, 0.40f}, {0.55f, 0.85f, 0.50f}, {0.55f, 0.45f, 0.75f},
      {0.70f, 0.60f, 0.90f}, {0.85f, 0.75f, 0.30f}, {0.95f, 0.85f, 0.45f}};
  return {kHues[part][0], kHues[part][1], kHues[part][2]};
}

}  // namespace

Reenactment::Reenactment(proto::ClipManifest manifest, std::vector<proto::ClipFrame> frames,
                         const ReenactmentOptions& options)
    : options_(options), manifest_(std::move(manifest)), frames_(std::move(frames)) {
  options_.Check();
  REENACT_CHECK(static_cast<int64_t>(frames_.size()) == manifest_.frame_count,
                "frame count disagrees with the manifest");
  usable_ = std::make_unique<bool[]>(frames_.size());
  for (size_t n = 0; n < frames_.size(); ++n) {
    const proto::ClipFrame& f = frames_[n];
    skeletons_in_sensor_.push_back(f.skeleton_in_world.Transformed(f.world_from_sensor.inverse()));
    usable_[n] = std::any_of(f.mask.data.begin(), f.mask.data.end(), [](uint8_t v) { return v > 127; });
  }
  for (int64_t n : manifest_.flagged_skeleton_frames)
    if (n >= 0 && n < manifest_.frame_count) usable_[n] = false;
  texture_index_ =
      TextureIndex(skeletons_in_sensor_, std::span<const bool>(usable_.get(), frames_.size()));

  std::vector<Skeleton> in_world;
  std::vector<double> times;
  std::unique_ptr<bool[]> flagged = std::make_unique<bool[]>(frames_.size());
  for (size_t n = 0; n < frames_.size(); ++n) {
    in_world.push_back(frames_[n].skeleton_in_world);
    times.push_back(frames_[n].timestamp_s);
    flagged[n] = false;
  }
  for (int64_t n : manifest_.flagged_skeleton_frames)
    if (n >= 0 && n < manifest_.frame_count) flagged[n] = true;
  steady_in_world_ = SteadySkeletonTrack(
      in_world, times, std::span<const bool>(flagged.get(), frames_.size()), options_.steady);
}

Eigen::Vector3d Reenactment::SubjectCentre() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int count = 0;
  for (const proto::ClipFrame& f : frames_)
    if (f.skeleton_in_world.Has(Joint::kWaist)) {
      sum += f.skeleton_in_world[Joint::kWaist];
      ++count;
    }
  return count ? Eigen::Vector3d(sum / count) : Eigen::Vector3d::Zero();
}

StoredTexture Reenactment::Texture(int n) const {
  const proto::ClipFrame& f = frames_.at(n);
  return {f.color, f.mask,
          manifest_.color_camera.Cropped(f.crop_x, f.crop_y, f.color.width, f.color.height)};
}

ReenactedFrame Reenactment::Build(int k, const PinholeCamera& viewer_camera,
                                  const Eigen::Isometry3d& viewer_from_world,
                                  const std::function<int(int)>& texture_for_frame) const {
  REENACT_CHECK(k >= 0 && k < frame_count(), "output frame out of range");
  return BuildPosed(k, options_.steady_motion ? steady_in_world_[k] : frames_[k].skeleton_in_world,
                    viewer_camera, viewer_from_world, texture_for_frame);
}

ReenactedFrame Reenactment::BuildPosed(int k, const Skeleton& skeleton_in_world,
                                       const PinholeCamera& viewer_camera,
                                       const Eigen::Isometry3d& viewer_from_world,
                                       const std::function<int(int)>& texture_for_frame) const {
  REENACT_CHECK(k >= 0 && k < frame_count(), "output frame out of range");
  ReenactedFrame out;
  out.clip_frame = k;
  out.draw.camera = viewer_camera;
  const Skeleton viewer_skeleton = skeleton_in_world.Transformed(viewer_from_world);

  const auto ranked = texture_index_.Rank(viewer_skeleton);
  const int n_bar = ranked.empty() ? -1 : ranked.front().frame;
  out.texture_frame = n_bar;
  const int texture = n_bar < 0 ? -1 : texture_for_frame(n_bar);

  const auto cylinders = PoseCylinders(viewer_skeleton, manifest_.radius_ratio);
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!cylinders[p]) continue;
    CylinderDraw draw;
    draw.a = cylinders[p]->a;
    draw.b = cylinders[p]->b;
    draw.radius = cylinders[p]->radius;
    draw.color = PartColor(p);
    if (n_bar >= 0) {
      const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
      const Skeleton& stored = skeletons_in_sensor_[n_bar];
      if (stored.HasPart(static_cast<BodyPart>(p))) {
        if (auto m = StoredFromViewerMapping(draw.a, draw.b, stored[ja], stored[jb])) {
          draw.stored_from_viewer = *m;
          draw.texture = texture;
        }
      }
    }
    out.draw.cylinders.push_back(draw);
    out.cylinder_parts.push_back(static_cast<BodyPart>(p));
  }
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
    if (viewer_skeleton.HasPart(static_cast<BodyPart>(p)))
      out.draw.bones.emplace_back(viewer_skeleton[ja], viewer_skeleton[jb]);
  }
  return out;
}

}  // namespace reenact::viewer
