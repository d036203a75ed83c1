#include "capture-client/record/clip_recorder.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <memory>

#include "capture-client/segment/person_segmenter.h"
#include "capture-client/segment/skeleton_consistency.h"
#include "capture-client/slam/rgbd_slam.h"
#include "common/model/model_building.h"
#include "proto/clip/clip_directory.h"
#include "proto/clip/manifest.h"
#include "proto/clip/map_codec.h"

namespace reenact::capture {
namespace {

using Clock = std::chrono::steady_clock;

double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct CropRect {
  int x = 0, y = 0, width = 0, height = 0;
};

// Bounding box of the mask grown by margin and clamped to the image; a small empty crop at the
// origin when the subject is not in view.
CropRect SubjectCrop(const ImageGray8& mask, int margin) {
  int x0 = mask.width, y0 = mask.height, x1 = -1, y1 = -1;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y) > 127) {
        x0 = std::min(x0, x);
        y0 = std::min(y0, y);
        x1 = std::max(x1, x);
        y1 = std::max(y1, y);
      }
  if (x1 < 0) return {0, 0, std::min(8, mask.width), std::min(8, mask.height)};
  x0 = std::max(0, x0 - margin);
  y0 = std::max(0, y0 - margin);
  x1 = std::min(mask.width - 1, x1 + margin);
  y1 = std::min(mask.height - 1, y1 + margin);
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

template <typename T>
Image<T> Crop(const Image<T>& image, const CropRect& r) {
  Image<T> out(r.width, r.height, image.channels);
  for (int y = 0; y < r.height; ++y)
    std::copy_n(&image.at(r.x, r.y + y), static_cast<size_t>(r.width) * image.channels,
                &out.at(0, y));
  return out;
}

std::string NowIso8601Utc() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string FrameName(int index, const SensorInfo& info) {
  return "frame " + std::to_string(index) + " of " + info.description;
}

Status CheckFrameSizes(const SensorFrame& f, const SensorInfo& info, int index) {
  if (f.color.channels != 3 || f.color.empty() || f.depth.width != f.color.width ||
      f.depth.height != f.color.height ||
      (f.person_mask &&
       (f.person_mask->width != f.color.width || f.person_mask->height != f.color.height)))
    return MakeError("corrupt", FrameName(index, info) + ": colour, depth and mask sizes disagree");
  return {};
}

// The frame's skeleton in the sensor frame, from the lookup or the source.
Expected<std::optional<Skeleton>> SkeletonInSensor(const SensorFrame& f, const SensorInfo& info,
                                                   int index, const RecordOptions& options,
                                                   const FramePoseHint& pose) {
  if (options.frame_skeletons) {
    auto s = options.frame_skeletons(index, f, pose);
    if (!s.ok()) return s.error();
    const bool any_joint = *s && std::any_of((*s)->confidence.begin(), (*s)->confidence.end(),
                                             [](double c) { return c > 0; });
    return any_joint ? *s : std::nullopt;
  }
  if (options.skeletons) {
    std::optional<Skeleton> s = options.skeletons(index, f.timestamp_s);
    const bool any_joint = s && std::any_of(s->confidence.begin(), s->confidence.end(),
                                            [](double c) { return c > 0; });
    return any_joint ? s : std::nullopt;
  }
  if (!f.skeleton_in_world) return std::optional<Skeleton>();
  if (!f.world_from_sensor)
    return MakeError("unsupported", FrameName(index, info) +
                                        " has a world-frame skeleton but no sensor pose to "
                                        "place it; pass --skeleton with a sensor-frame track");
  return std::optional<Skeleton>(f.skeleton_in_world->Transformed(f.world_from_sensor->inverse()));
}

// The SLAM's options for this source: its rolling shutter, and the world anchored at the
// first frame's known pose.
slam::SlamOptions SlamOptionsFor(const RecordOptions& options, const SensorInfo& info,
                                 const SensorFrame& first) {
  slam::SlamOptions o = options.slam;
  o.readout_ratio = info.color_readout_ratio;
  if (info.depth_sigma_1m_m > 0) o.noise.depth_sigma_1m_m = info.depth_sigma_1m_m;
  if (first.world_from_sensor) o.initial_world_from_sensor = *first.world_from_sensor;
  return o;
}

// What the recorder keeps per stored frame until the model is built.
struct StoredFrames {
  std::vector<std::vector<uint8_t>> encoded;
  std::vector<Skeleton> skeletons_in_sensor;
  std::vector<bool> has_subject;
};

Error NothingStored(const RecordSummary& s, const SensorInfo& info) {
  if (s.source_frames == s.frames_without_skeleton)
    return MakeError("no_skeleton",
                     "none of the " + std::to_string(s.source_frames) + " frames of " +
                         info.description +
                         " has a skeleton; pass --skeleton json:FILE or kinect:FILE with a "
                         "skeleton track of the recording");
  return MakeError("no_pose", "SLAM found no sensor pose for any of the " +
                                  std::to_string(s.frames_without_pose) + " frames of " +
                                  info.description +
                                  " that have a skeleton (too few background features with "
                                  "depth: is the depth stream empty, or the view featureless?)");
}

}  // namespace

void RecordOptions::Check() const {
  REENACT_CHECK(max_frames == -1 || max_frames >= 1, "max_frames must be -1 or >= 1");
  REENACT_CHECK(crop_margin_px >= 0, "crop_margin_px must be >= 0");
  REENACT_CHECK(keyframe_interval >= 1, "keyframe_interval must be >= 1");
  codec.Check();
  map.Check();
  virtual_views.Check();
  model.Check();
  segment.Check();
  slam.Check();
}

Expected<RecordSummary> RecordClip(FrameSource& source, const std::filesystem::path& out_dir,
                                   const RecordOptions& options) {
  options.Check();
  const auto start = Clock::now();
  const SensorInfo& info = source.info();
  if (std::error_code ec; std::filesystem::exists(out_dir, ec))
    return MakeError("already_exists",
                     out_dir.string() + " already exists; remove it or choose another --out");

  StoredFrames stored;
  BackgroundMapBuilder map_builder(options.map);
  std::vector<VirtualViewKeyframe> virtual_keyframes;
  PersonSegmenter segmenter(info.depth_camera, info.depth_scale_m, options.segment);
  std::optional<slam::RgbdSlam> slam;
  std::optional<Eigen::Vector3d> world_up = info.world_up;
  RecordSummary summary;
  RecordStageTimes& times = summary.stage_times;

  while (options.max_frames < 0 || summary.source_frames < options.max_frames) {
    auto read_start = Clock::now();
    auto next = source.Next();
    if (!next.ok()) return next.error();
    if (!next->has_value()) break;
    const SensorFrame& f = **next;
    const int index = summary.source_frames++;
    times.source_ms.push_back(MsSince(read_start));
    if (Status sizes = CheckFrameSizes(f, info, index); !sizes.ok()) return sizes.error();

    if (index == 0) {
      summary.slam_poses = options.poses == PoseSource::kSlam || !f.world_from_sensor;
      if (summary.slam_poses)
        slam.emplace(info.color_camera, info.depth_scale_m, SlamOptionsFor(options, info, f));
      if (summary.slam_poses && f.world_from_sensor)
        world_up = info.world_up;
      else if (summary.slam_poses)
        world_up.reset();
    } else if (!summary.slam_poses && !f.world_from_sensor) {
      return MakeError("corrupt", FrameName(index, info) +
                                      " has no sensor pose although the frames before it had");
    }

    const auto skeleton_start = Clock::now();
    const FramePoseHint pose = slam ? FramePoseHint{slam->PredictedWorldFromSensor(), world_up}
                                    : FramePoseHint{f.world_from_sensor, info.world_up};
    auto skeleton = SkeletonInSensor(f, info, index, options, pose);
    if (!skeleton.ok()) return skeleton.error();
    times.tracker_ms.push_back(options.frame_skeletons ? MsSince(skeleton_start) : 0.0);

    // The person mask: the source's, else segmented (SLAM needs it before it tracks).
    const auto segment_start = Clock::now();
    std::optional<ImageGray8> segmented;
    std::optional<Plane3> floor_in_sensor;
    if (!f.person_mask && *skeleton) {
      SegmentFrameGeometry geometry;
      if (!summary.slam_poses) geometry = {f.world_from_sensor, info.world_up};
      auto segmentation = segmenter.Segment(f.depth, **skeleton, geometry);
      if (!segmentation.ok()) return segmentation.error();
      segmented = std::move(segmentation->mask);
      floor_in_sensor = segmentation->floor_in_sensor;
      ++summary.segmented_frames;
    }
    times.segment_ms.push_back(f.person_mask || !*skeleton ? 0.0 : MsSince(segment_start));
    const ImageGray8* person_mask = f.person_mask ? &*f.person_mask
                                    : segmented   ? &*segmented
                                                  : nullptr;

    std::optional<Eigen::Isometry3d> world_from_sensor = f.world_from_sensor;
    const auto slam_start = Clock::now();
    if (slam) {
      auto tracked = slam->Track(f.timestamp_s, f.color, f.depth, person_mask);
      if (!tracked.ok()) return tracked.error();
      world_from_sensor = tracked->world_from_sensor;
      summary.slam_keyframes += tracked->keyframe;
      summary.slam_fallback_frames += tracked->status == slam::SlamStatus::kOdometryFallback;
      summary.slam_relocalised_frames += tracked->status == slam::SlamStatus::kRelocalised;
    }
    times.slam_ms.push_back(slam ? MsSince(slam_start) : 0.0);

    // Without a known up, the first floor that segmentation finds under a posed frame gives it.
    if (!world_up && floor_in_sensor && world_from_sensor)
      world_up = (world_from_sensor->linear() * floor_in_sensor->normal).normalized();

    if (!world_from_sensor || !*skeleton) {
      summary.frames_without_skeleton += !*skeleton;
      summary.frames_without_pose += *skeleton && !world_from_sensor;
      times.encode_ms.push_back(0);
      times.map_ms.push_back(0);
      continue;
    }

    const auto encode_start = Clock::now();
    if (!person_mask) person_mask = &segmented.emplace(f.color.width, f.color.height, 1, 0);
    const ImageGray8& mask = *person_mask;
    const CropRect crop = SubjectCrop(mask, options.crop_margin_px);
    proto::ClipFrame frame;
    frame.timestamp_s = f.timestamp_s;
    frame.world_from_sensor = *world_from_sensor;
    frame.skeleton_in_world = (*skeleton)->Transformed(*world_from_sensor);
    frame.crop_x = crop.x;
    frame.crop_y = crop.y;
    frame.color = Crop(f.color, crop);
    frame.depth = Crop(f.depth, crop);
    frame.mask = Crop(mask, crop);
    stored.encoded.push_back(proto::EncodeFrame(frame, options.codec));
    summary.frame_bytes += stored.encoded.back().size();
    stored.skeletons_in_sensor.push_back(**skeleton);
    stored.has_subject.push_back(std::any_of(frame.mask.data.begin(), frame.mask.data.end(),
                                             [](uint8_t v) { return v > 127; }));
    times.encode_ms.push_back(MsSince(encode_start));

    const auto map_start = Clock::now();
    if (!slam && index % options.keyframe_interval == 0)
      map_builder.AddKeyframe(f.color, f.depth, info.depth_scale_m, mask, info.color_camera,
                              *world_from_sensor);
    const auto pivot = SubjectPivot(**skeleton, *world_from_sensor);
    if (pivot && (stored.encoded.size() - 1) % options.virtual_views.keyframe_interval == 0 &&
        static_cast<int>(virtual_keyframes.size()) < options.virtual_views.max_keyframes) {
      virtual_keyframes.push_back({f.color, f.depth, mask, *world_from_sensor, *pivot});
    }
    times.map_ms.push_back(slam ? 0.0 : MsSince(map_start));
  }
  if (summary.source_frames == 0)
    return MakeError("empty", "the source " + info.description + " yielded no frames");
  if (stored.encoded.empty()) return NothingStored(summary, info);
  summary.frames = static_cast<int>(stored.encoded.size());

  proto::ClipManifest manifest;
  manifest.title = options.title;
  manifest.author = options.author;
  manifest.capture_time = NowIso8601Utc();
  manifest.color_camera = info.color_camera;
  manifest.depth_camera = info.depth_camera;
  manifest.depth_scale_m = info.depth_scale_m;
  // Unknown up (no floor seen): the first stored frame's camera -y, right for a level sensor.
  manifest.world_up = world_up.value_or(Eigen::Vector3d(0, -1, 0));
  manifest.frame_count = summary.frames;
  manifest.frame_rate_hz = info.frame_rate_hz;
  manifest.radius_ratio = DefaultRadiusRatios();

  // Frames without a subject or with an inconsistent skeleton (bone lengths off the clip's
  // medians, left and right swapped) stay out of the model; the inconsistent ones are flagged
  // for the viewer. std::vector<bool> has no contiguous storage to view as a span.
  const auto model_start = Clock::now();
  const SkeletonConsistency consistency = CheckSkeletonConsistency(stored.skeletons_in_sensor);
  const auto usable = std::make_unique<bool[]>(stored.has_subject.size());
  for (size_t n = 0; n < stored.has_subject.size(); ++n) {
    usable[n] = stored.has_subject[n] && consistency.frames[n].usable;
    if (!consistency.frames[n].usable) {
      ++summary.inconsistent_skeletons;
      manifest.flagged_skeleton_frames.push_back(static_cast<int64_t>(n));
    }
  }
  ModelBuildOptions model_options = options.model;
  model_options.fit.depth_scale_m = info.depth_scale_m;
  const ModelBuildResult model = BuildCylinderModel(
      stored.skeletons_in_sensor,
      [&](int n) -> std::optional<ModelFrameImages> {
        auto frame = proto::DecodeFrame(stored.encoded[n]);
        if (!frame.ok()) return std::nullopt;
        return ModelFrameImages{info.color_camera.Cropped(frame->crop_x, frame->crop_y,
                                                          frame->color.width, frame->color.height),
                                std::move(frame->depth), std::move(frame->mask)};
      },
      model_options, std::span<const bool>(usable.get(), stored.has_subject.size()));
  for (int p = 0; p < kBodyPartCount; ++p)
    manifest.radius_ratio[p] = std::clamp(model.radius_ratio[p], 0.02, 2.0);
  if (model.representative_frame) {
    manifest.representative_frame = *model.representative_frame;
    summary.representative_frame = *model.representative_frame;
  }
  summary.fitted_parts = model.fitted_count();
  times.model_ms = MsSince(model_start);

  const auto write_start = Clock::now();
  proto::ClipMap map = AddVirtualViews(
      slam ? slam->ExportClipMap() : std::move(map_builder).Finish(), virtual_keyframes,
      info.depth_scale_m, info.color_camera, manifest.world_up, options.virtual_views,
      options.map, &summary.virtual_view_points);
  auto map_bytes = proto::EncodeMap(map, proto::MapCodecOptions{});
  if (!map_bytes.ok()) return map_bytes.error();
  manifest.map.point_count = static_cast<int64_t>(map.points.size());
  proto::FillPartHashes(manifest, stored.encoded, *map_bytes);
  if (Status written = proto::WriteClipDirectory(out_dir, manifest, stored.encoded, *map_bytes);
      !written.ok())
    return written.error();
  times.write_ms = MsSince(write_start);

  summary.map_bytes = map_bytes->size();
  summary.map_points = map.points.size();
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return summary;
}

}  // namespace reenact::capture
