#include "viewer-client/play/reenactment.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "common/error/check.h"
#include "common/model/cross_section_fit.h"
#include "common/model/extension_fit.h"
#include "common/texture/part_coverage.h"
#include "common/texture/texture_mapping.h"
#include "common/texture/visibility_maps.h"

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

// Bit Index(p) set where both joints of part p lie in front of the crop camera and project
// inside the crop: a part cut off at the crop's border would leave holes.
uint16_t PartsInsideCrop(const Skeleton& skeleton_in_sensor, const PinholeCamera& crop) {
  uint16_t mask = 0;
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
    if (!skeleton_in_sensor.HasPart(static_cast<BodyPart>(p))) continue;
    bool inside = true;
    for (Joint j : {ja, jb}) {
      const auto uv = crop.Project(skeleton_in_sensor[j]);
      inside = inside && uv && uv->x() >= -0.5 && uv->y() >= -0.5 && uv->x() <= crop.width - 0.5 &&
               uv->y() <= crop.height - 0.5;
    }
    if (inside) mask |= static_cast<uint16_t>(1u << p);
  }
  return mask;
}

// Frames the part extensions and cross-sections are fitted from: the representative frame (if
// usable) and up to `others` more usable frames spread evenly over the clip.
std::vector<int> ShapeFitFrames(int64_t representative, std::span<const bool> usable, int others) {
  std::vector<int> usable_frames;
  for (size_t n = 0; n < usable.size(); ++n)
    if (usable[n]) usable_frames.push_back(static_cast<int>(n));
  std::vector<int> out;
  if (representative >= 0 && representative < static_cast<int64_t>(usable.size()) &&
      usable[representative])
    out.push_back(static_cast<int>(representative));
  const int count = std::min<int>(others, static_cast<int>(usable_frames.size()));
  for (int i = 0; i < count; ++i) {
    const int n = usable_frames[(2 * i + 1) * usable_frames.size() / (2 * count)];
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  }
  return out;
}

}  // namespace

void TexturingOptions::Check() const {
  REENACT_CHECK(
      candidates >= 1 && candidates <= kMaxTextureCandidates,
      "texturing candidates must be in [1, " + std::to_string(kMaxTextureCandidates) + "]");
  REENACT_CHECK(selection == TextureSelection::kPerPart || candidates == 1,
                "whole-body selection takes exactly one candidate; use per-part selection for "
                "more");
  REENACT_CHECK(
      fallback_candidates >= 0 && candidates + fallback_candidates <= kMaxTextureCandidates,
      "texturing fallback candidates must be >= 0 and, with the ranked candidates, at "
      "most " +
          std::to_string(kMaxTextureCandidates));
  REENACT_CHECK(fallback_candidates == 0 ||
                    (selection == TextureSelection::kPerPart && mode != TexturingMode::kFirst),
                "fallback candidates need per-part selection and a visibility mode");
  REENACT_CHECK(hysteresis >= 0 && hysteresis < 1, "hysteresis must be in [0, 1)");
  REENACT_CHECK(std::isfinite(missing_joint_cost_m) && missing_joint_cost_m >= 0,
                "missing_joint_cost_m must be finite and >= 0");
}

Reenactment::Reenactment(proto::ClipManifest manifest, std::vector<proto::ClipFrame> frames,
                         const ReenactmentOptions& options)
    : options_(options), manifest_(std::move(manifest)), frames_(std::move(frames)) {
  options_.Check();
  REENACT_CHECK(static_cast<int64_t>(frames_.size()) == manifest_.frame_count,
                "frame count disagrees with the manifest");
  const std::unique_ptr<bool[]> flagged = FlaggedFrames();
  SteadyMotion(flagged.get());
  IndexFrames(flagged.get());
  FitShapes();
  FitLight();

  // The clip's own texturing's coverage now, so that the first frame drawn does not wait for it.
  if (options_.texturing.fallback_candidates > 0) CoverageIndexOf(options_.texturing.shape);
}

std::unique_ptr<bool[]> Reenactment::FlaggedFrames() const {
  std::unique_ptr<bool[]> flagged = std::make_unique<bool[]>(frames_.size());
  for (size_t n = 0; n < frames_.size(); ++n) flagged[n] = false;
  for (int64_t n : manifest_.flagged_skeleton_frames)
    if (n >= 0 && n < manifest_.frame_count) flagged[n] = true;
  return flagged;
}

void Reenactment::SteadyMotion(const bool* flagged) {
  std::vector<Skeleton> in_world;
  std::vector<double> times;
  for (size_t n = 0; n < frames_.size(); ++n) {
    in_world.push_back(frames_[n].skeleton_in_world);
    times.push_back(frames_[n].timestamp_s);
  }
  steady_in_world_ = SteadySkeletonTrack(
      in_world, times, std::span<const bool>(flagged, frames_.size()), options_.steady);
  if (options_.steady_motion)
    for (size_t n = 0; n < frames_.size(); ++n)
      if (!flagged[n]) frames_[n].skeleton_in_world = steady_in_world_[n];
}

void Reenactment::IndexFrames(const bool* flagged) {
  usable_ = std::make_unique<bool[]>(frames_.size());
  for (size_t n = 0; n < frames_.size(); ++n) {
    const proto::ClipFrame& f = frames_[n];
    skeletons_in_sensor_.push_back(f.skeleton_in_world.Transformed(f.world_from_sensor.inverse()));
    usable_[n] = !flagged[n] && std::any_of(f.mask.data.begin(), f.mask.data.end(),
                                            [](uint8_t v) { return v > 127; });
  }
  texture_index_ =
      TextureIndex(skeletons_in_sensor_, std::span<const bool>(usable_.get(), frames_.size()));
  part_allowed_.assign(frames_.size(), 0);
  for (size_t n = 0; n < frames_.size(); ++n)
    if (usable_[n]) {
      const proto::ClipFrame& f = frames_[n];
      part_allowed_[n] = PartsInsideCrop(
          skeletons_in_sensor_[n],
          manifest_.color_camera.Cropped(f.crop_x, f.crop_y, f.color.width, f.color.height));
    }
  part_index_ = PartTextureIndex(skeletons_in_sensor_, part_allowed_);
}

void Reenactment::FitShapes() {
  const auto fit_frames_of = [this](std::span<const int> indices,
                                    std::vector<PinholeCamera>& cameras) {
    cameras.clear();
    cameras.reserve(indices.size());
    std::vector<ExtensionFitFrame> fit_frames;
    for (int n : indices) {
      const proto::ClipFrame& f = frames_[n];
      cameras.push_back(
          manifest_.color_camera.Cropped(f.crop_x, f.crop_y, f.color.width, f.color.height));
      fit_frames.push_back({&skeletons_in_sensor_[n], &cameras.back(), &f.mask, &f.depth});
    }
    return fit_frames;
  };
  const std::span<const bool> usable(usable_.get(), frames_.size());
  std::vector<PinholeCamera> fit_cameras;
  part_extensions_ =
      FitPartExtensions(
          fit_frames_of(ShapeFitFrames(manifest_.representative_frame, usable, 8), fit_cameras),
          manifest_.radius_ratio, {.depth_scale_m = manifest_.depth_scale_m})
          .extension;
  const std::vector<ExtensionFitFrame> shape_frames =
      fit_frames_of(ShapeFitFrames(manifest_.representative_frame, usable, 24), fit_cameras);
  part_shapes_ = FitCrossSections(shape_frames, manifest_.radius_ratio, part_extensions_,
                                  {.depth_scale_m = manifest_.depth_scale_m})
                     .shape;
  SurfaceFitOptions surface_options;
  surface_options.depth_scale_m = manifest_.depth_scale_m;
  surface_fit_ = FitPartSurfaces(shape_frames, manifest_.radius_ratio, part_extensions_,
                                 part_shapes_, surface_options);
}

void Reenactment::FitLight() {
  const std::span<const bool> usable(usable_.get(), frames_.size());
  std::vector<LightSample> light_samples;
  for (int n : ShapeFitFrames(manifest_.representative_frame, usable, 24)) {
    const StoredTexture t = Texture(n, BodyShape::kProfiled);
    if (t.depth_m.empty()) continue;
    AppendLightSamples({.skeleton_in_sensor = &skeletons_in_sensor_[n],
                        .camera = &t.camera,
                        .color = &t.color,
                        .part_labels = &t.part_labels,
                        .depth_m = &t.depth_m,
                        .world_from_sensor = frames_[n].world_from_sensor.linear()},
                       {}, &light_samples);
  }
  subject_light_ = FitSubjectLight(light_samples);
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

std::pair<PartExtensions, PartShapes> Reenactment::ShapeOf(BodyShape shape) const {
  switch (shape) {
    case BodyShape::kCylinders: return {PartExtensions{}, PartShapes{}};
    case BodyShape::kExtended: return {part_extensions_, PartShapes{}};
    case BodyShape::kProfiled: return {part_extensions_, part_shapes_};
    case BodyShape::kSurface: return {part_extensions_, surface_fit_.shape};
  }
  return {PartExtensions{}, PartShapes{}};
}

StoredTexture Reenactment::Texture(int n) const { return Texture(n, options_.texturing.shape); }

PinholeCamera Reenactment::CropCamera(int n) const {
  const proto::ClipFrame& f = frames_.at(n);
  return manifest_.color_camera.Cropped(f.crop_x, f.crop_y, f.color.width, f.color.height);
}

VisibilityMaps Reenactment::VisibilityMapsOf(int n, BodyShape shape) const {
  const proto::ClipFrame& f = frames_.at(n);
  const auto [extensions, shapes] = ShapeOf(shape);
  return MakeVisibilityMaps(skeletons_in_sensor_.at(n), manifest_.radius_ratio, CropCamera(n),
                            f.mask, f.depth, manifest_.depth_scale_m, extensions, shapes);
}

StoredTexture Reenactment::Texture(int n, BodyShape shape) const {
  const proto::ClipFrame& f = frames_.at(n);
  const PinholeCamera camera = CropCamera(n);
  VisibilityMaps maps = VisibilityMapsOf(n, shape);
  Image<float> normals;
  if (subject_light_.found && !maps.depth_m.empty())
    normals = DepthNormalMap(maps.depth_m, maps.part_labels, camera);
  return {f.color,           f.mask, camera, std::move(maps.part_labels), std::move(maps.depth_m),
          std::move(normals)};
}

const PartTextureIndex& Reenactment::CoverageIndexOf(BodyShape shape) const {
  CoverageIndex& entry = (*coverage_index_)[static_cast<size_t>(shape)];
  std::call_once(entry.built, [&] {
    const auto [extensions, shapes] = ShapeOf(shape);
    std::vector<PartCoverages> coverage(frames_.size(), PartCoverages{});
    for (size_t n = 0; n < frames_.size(); ++n) {
      if (!part_allowed_[n]) continue;
      const int frame = static_cast<int>(n);
      const VisibilityMaps maps = VisibilityMapsOf(frame, shape);
      coverage[n] = CoverageOfFrame(
          PoseCylinders(skeletons_in_sensor_[n], manifest_.radius_ratio, extensions, shapes),
          CropCamera(frame), frames_[n].mask, maps.part_labels, maps.depth_m,
          kDefaultDepthToleranceM);
    }
    entry.index = PartTextureIndex(skeletons_in_sensor_, part_allowed_, coverage);
  });
  return entry.index;
}

ReenactedFrame Reenactment::Build(int k, const PinholeCamera& viewer_camera,
                                  const Eigen::Isometry3d& viewer_from_world,
                                  const std::function<int(int)>& texture_for_frame,
                                  PartSelectionHistory* history) const {
  REENACT_CHECK(k >= 0 && k < frame_count(), "output frame out of range");
  return BuildPosed(k, options_.steady_motion ? steady_in_world_[k] : frames_[k].skeleton_in_world,
                    viewer_camera, viewer_from_world, texture_for_frame, options_.texturing,
                    history);
}

ReenactedFrame Reenactment::BuildPosed(int k, const Skeleton& skeleton_in_world,
                                       const PinholeCamera& viewer_camera,
                                       const Eigen::Isometry3d& viewer_from_world,
                                       const std::function<int(int)>& texture_for_frame,
                                       const TexturingOptions& texturing,
                                       PartSelectionHistory* history) const {
  REENACT_CHECK(k >= 0 && k < frame_count(), "output frame out of range");
  texturing.Check();
  ReenactedFrame out;
  out.clip_frame = k;
  out.draw.camera = viewer_camera;
  const Skeleton viewer_skeleton = skeleton_in_world.Transformed(viewer_from_world);

  // Ranked stored frames (with weights) per part.
  PartCandidates chosen;
  if (texturing.selection == TextureSelection::kPerPart) {
    const PartTextureIndex& index =
        texturing.fallback_candidates > 0 ? CoverageIndexOf(texturing.shape) : part_index_;
    chosen = index.Select(viewer_skeleton,
                          {.top_k = texturing.candidates,
                           .missing_joint_cost_m = texturing.missing_joint_cost_m,
                           .hysteresis = texturing.hysteresis,
                           .fallback_k = texturing.fallback_candidates},
                          history);
    const auto& torso = chosen[Index(BodyPart::kUpperTorso)];
    out.texture_frame = torso.empty() ? -1 : torso.front().frame;
  } else {
    const auto ranked = texture_index_.Rank(
        viewer_skeleton, {.top_k = 1, .missing_joint_cost_m = texturing.missing_joint_cost_m});
    out.texture_frame = ranked.empty() ? -1 : ranked.front().frame;
    if (out.texture_frame >= 0)
      for (auto& part : chosen) part.push_back({out.texture_frame, ranked.front().cost, 1.0});
  }

  const bool relight = texturing.relight && subject_light_.found;
  if (relight) out.draw.subject_light = viewer_from_world.linear() * subject_light_.light;
  const auto [extensions, shapes] = ShapeOf(texturing.shape);
  const auto cylinders = PoseCylinders(viewer_skeleton, manifest_.radius_ratio, extensions, shapes);
  for (int p = 0; p < kBodyPartCount; ++p) {
    if (!cylinders[p]) continue;
    const BodyPart part = static_cast<BodyPart>(p);
    CylinderDraw draw;
    draw.a = cylinders[p]->a;
    draw.b = cylinders[p]->b;
    draw.radius = cylinders[p]->radius;
    draw.shape = cylinders[p]->shape;
    draw.width_direction = cylinders[p]->width_direction;
    draw.color = PartColor(p);
    draw.part = part;
    draw.texturing = texturing.mode;
    for (const PartCandidate& c : chosen[p]) {
      const auto stored =
          PoseCylinder(skeletons_in_sensor_[c.frame], part, manifest_.radius_ratio, extensions);
      if (!stored) continue;
      const auto m = StoredFromViewerMapping(draw.a, draw.b, stored->a, stored->b);
      if (!m) continue;
      const int texture = texture_for_frame(c.frame);
      if (texture < 0) continue;
      TextureCandidate candidate{texture, *m, c.weight};
      candidate.fallback = c.fallback;
      if (relight) {
        // stored_light = R^T L_stored, R the rotation of the similarity m (texturing.h).
        const Eigen::Matrix3d sr = m->topLeftCorner<3, 3>();
        const Eigen::Vector3d light_in_stored =
            frames_[c.frame].world_from_sensor.linear().transpose() * subject_light_.light;
        candidate.stored_light = sr.transpose() * light_in_stored / sr.col(0).norm();
      }
      draw.candidates.push_back(candidate);
    }
    out.draw.cylinders.push_back(draw);
    out.cylinder_parts.push_back(part);
  }
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto [ja, jb] = PartJoints(static_cast<BodyPart>(p));
    if (viewer_skeleton.HasPart(static_cast<BodyPart>(p)))
      out.draw.bones.emplace_back(viewer_skeleton[ja], viewer_skeleton[jb]);
  }
  return out;
}

}  // namespace reenact::viewer
