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

// The recorder's state across the source frames.
struct Recording {
  Recording(const RecordOptions& options, const SensorInfo& info)
      : options(options),
        info(info),
        map_builder(options.map),
        segmenter(info.depth_camera, info.depth_scale_m, options.segment),
        world_up(info.world_up) {}

  const RecordOptions& options;
  const SensorInfo& info;
  StoredFrames stored;
  BackgroundMapBuilder map_builder;
  std::vector<VirtualViewKeyframe> virtual_keyframes;
  PersonSegmenter segmenter;
  std::optional<slam::RgbdSlam> slam;
  std::optional<Eigen::Vector3d> world_up;
  RecordSummary summary;
};

// At the first frame, chooses between the source's poses and SLAM; later frames must then
// keep the source's poses.
Status ChoosePoseSource(Recording& r, const SensorFrame& f, int index) {
  if (index == 0) {
    r.summary.slam_poses = r.options.poses == PoseSource::kSlam || !f.world_from_sensor;
    if (r.summary.slam_poses)
      r.slam.emplace(r.info.color_camera, r.info.depth_scale_m,
                     SlamOptionsFor(r.options, r.info, f));
    if (r.summary.slam_poses && f.world_from_sensor)
      r.world_up = r.info.world_up;
    else if (r.summary.slam_poses)
      r.world_up.reset();
  } else if (!r.summary.slam_poses && !f.world_from_sensor) {
    return MakeError("corrupt", FrameName(index, r.info) +
                                    " has no sensor pose although the frames before it had");
  }
  return {};
}

// The frame's skeleton in the sensor frame, given the pose known before tracking it.
Expected<std::optional<Skeleton>> FrameSkeleton(Recording& r, const SensorFrame& f, int index) {
  const auto skeleton_start = Clock::now();
  const FramePoseHint pose = r.slam ? FramePoseHint{r.slam->PredictedWorldFromSensor(), r.world_up}
                                    : FramePoseHint{f.world_from_sensor, r.info.world_up};
  auto skeleton = SkeletonInSensor(f, r.info, index, r.options, pose);
  if (!skeleton.ok()) return skeleton.error();
  r.summary.stage_times.tracker_ms.push_back(r.options.frame_skeletons ? MsSince(skeleton_start)
                                                                       : 0.0);
  return skeleton;
}

// Our segmentation of a frame whose source gives no person mask; none without a skeleton.
struct Segmented {
  std::optional<ImageGray8> mask;
  std::optional<Plane3> floor_in_sensor;
};

Expected<Segmented> SegmentUnmasked(Recording& r, const SensorFrame& f,
                                    const std::optional<Skeleton>& skeleton) {
  const auto segment_start = Clock::now();
  Segmented segmented;
  if (!f.person_mask && skeleton) {
    SegmentFrameGeometry geometry;
    if (!r.summary.slam_poses) geometry = {f.world_from_sensor, r.info.world_up};
    auto segmentation = r.segmenter.Segment(f.depth, *skeleton, geometry);
    if (!segmentation.ok()) return segmentation.error();
    segmented.mask = std::move(segmentation->mask);
    segmented.floor_in_sensor = segmentation->floor_in_sensor;
    ++r.summary.segmented_frames;
  }
  r.summary.stage_times.segment_ms.push_back(f.person_mask || !skeleton ? 0.0
                                                                        : MsSince(segment_start));
  return segmented;
}

// The frame's sensor pose: the source's, or SLAM's tracking of the frame with the person
// masked out.
Expected<std::optional<Eigen::Isometry3d>> FramePose(Recording& r, const SensorFrame& f,
                                                     const ImageGray8* person_mask) {
  std::optional<Eigen::Isometry3d> world_from_sensor = f.world_from_sensor;
  const auto slam_start = Clock::now();
  if (r.slam) {
    auto tracked = r.slam->Track(f.timestamp_s, f.color, f.depth, person_mask);
    if (!tracked.ok()) return tracked.error();
    world_from_sensor = tracked->world_from_sensor;
    r.summary.slam_keyframes += tracked->keyframe;
    r.summary.slam_fallback_frames += tracked->status == slam::SlamStatus::kOdometryFallback;
    r.summary.slam_relocalised_frames += tracked->status == slam::SlamStatus::kRelocalised;
  }
  r.summary.stage_times.slam_ms.push_back(r.slam ? MsSince(slam_start) : 0.0);
  return world_from_sensor;
}

// Crops the frame to the subject, encodes it and keeps it with its skeleton.
void StoreFrame(Recording& r, const SensorFrame& f, const Skeleton& skeleton_in_sensor,
                const Eigen::Isometry3d& world_from_sensor, const ImageGray8& mask) {
  const CropRect crop = SubjectCrop(mask, r.options.crop_margin_px);
  proto::ClipFrame frame;
  frame.timestamp_s = f.timestamp_s;
  frame.world_from_sensor = world_from_sensor;
  frame.skeleton_in_world = skeleton_in_sensor.Transformed(world_from_sensor);
  frame.crop_x = crop.x;
  frame.crop_y = crop.y;
  frame.color = Crop(f.color, crop);
  frame.depth = Crop(f.depth, crop);
  frame.mask = Crop(mask, crop);
  r.stored.encoded.push_back(proto::EncodeFrame(frame, r.options.codec));
  r.summary.frame_bytes += r.stored.encoded.back().size();
  r.stored.skeletons_in_sensor.push_back(skeleton_in_sensor);
  r.stored.has_subject.push_back(std::any_of(frame.mask.data.begin(), frame.mask.data.end(),
                                             [](uint8_t v) { return v > 127; }));
}

// A stored frame's share of the map: a keyframe of the map builder (with the source's poses)
// and a keyframe of virtual views around the subject.
void AddToMap(Recording& r, const SensorFrame& f, int index, const Skeleton& skeleton_in_sensor,
              const Eigen::Isometry3d& world_from_sensor, const ImageGray8& mask) {
  if (!r.slam && index % r.options.keyframe_interval == 0)
    r.map_builder.AddKeyframe(f.color, f.depth, r.info.depth_scale_m, mask, r.info.color_camera,
                              world_from_sensor);
  const auto pivot = SubjectPivot(skeleton_in_sensor, world_from_sensor);
  if (pivot && (r.stored.encoded.size() - 1) % r.options.virtual_views.keyframe_interval == 0 &&
      static_cast<int>(r.virtual_keyframes.size()) < r.options.virtual_views.max_keyframes) {
    r.virtual_keyframes.push_back({f.color, f.depth, mask, world_from_sensor, *pivot});
  }
}

// One source frame: its skeleton, person mask and pose, then stored when it has both a pose
// and a skeleton.
Status RecordFrame(Recording& r, const SensorFrame& f, int index) {
  RecordStageTimes& times = r.summary.stage_times;
  if (Status sizes = CheckFrameSizes(f, r.info, index); !sizes.ok()) return sizes.error();
  if (Status poses = ChoosePoseSource(r, f, index); !poses.ok()) return poses.error();
  auto skeleton = FrameSkeleton(r, f, index);
  if (!skeleton.ok()) return skeleton.error();

  // The person mask: the source's, else segmented (SLAM needs it before it tracks).
  auto segmented = SegmentUnmasked(r, f, *skeleton);
  if (!segmented.ok()) return segmented.error();
  const ImageGray8* person_mask = f.person_mask     ? &*f.person_mask
                                  : segmented->mask ? &*segmented->mask
                                                    : nullptr;
  auto world_from_sensor = FramePose(r, f, person_mask);
  if (!world_from_sensor.ok()) return world_from_sensor.error();

  // Without a known up, the first floor that segmentation finds under a posed frame gives it.
  if (!r.world_up && segmented->floor_in_sensor && *world_from_sensor)
    r.world_up = ((*world_from_sensor)->linear() * segmented->floor_in_sensor->normal).normalized();

  if (!*world_from_sensor || !*skeleton) {
    r.summary.frames_without_skeleton += !*skeleton;
    r.summary.frames_without_pose += *skeleton && !*world_from_sensor;
    times.encode_ms.push_back(0);
    times.map_ms.push_back(0);
    return {};
  }

  const auto encode_start = Clock::now();
  if (!person_mask) person_mask = &segmented->mask.emplace(f.color.width, f.color.height, 1, 0);
  StoreFrame(r, f, **skeleton, **world_from_sensor, *person_mask);
  times.encode_ms.push_back(MsSince(encode_start));

  const auto map_start = Clock::now();
  AddToMap(r, f, index, **skeleton, **world_from_sensor, *person_mask);
  times.map_ms.push_back(r.slam ? 0.0 : MsSince(map_start));
  return {};
}

proto::ClipManifest ManifestOf(const Recording& r) {
  proto::ClipManifest manifest;
  manifest.title = r.options.title;
  manifest.author = r.options.author;
  manifest.capture_time = NowIso8601Utc();
  manifest.color_camera = r.info.color_camera;
  manifest.depth_camera = r.info.depth_camera;
  manifest.depth_scale_m = r.info.depth_scale_m;
  // Unknown up (no floor seen): the first stored frame's camera -y, right for a level sensor.
  manifest.world_up = r.world_up.value_or(Eigen::Vector3d(0, -1, 0));
  manifest.frame_count = r.summary.frames;
  manifest.frame_rate_hz = r.info.frame_rate_hz;
  manifest.radius_ratio = DefaultRadiusRatios();
  return manifest;
}

// Builds the cylinder model from the stored frames into the manifest's radius ratios and
// representative frame.
void BuildModel(Recording& r, proto::ClipManifest& manifest) {
  // Frames without a subject or with an inconsistent skeleton (bone lengths off the clip's
  // medians, left and right swapped) stay out of the model; the inconsistent ones are flagged
  // for the viewer. std::vector<bool> has no contiguous storage to view as a span.
  const StoredFrames& stored = r.stored;
  const SensorInfo& info = r.info;
  const SkeletonConsistency consistency = CheckSkeletonConsistency(stored.skeletons_in_sensor);
  const auto usable = std::make_unique<bool[]>(stored.has_subject.size());
  for (size_t n = 0; n < stored.has_subject.size(); ++n) {
    usable[n] = stored.has_subject[n] && consistency.frames[n].usable;
    if (!consistency.frames[n].usable) {
      ++r.summary.inconsistent_skeletons;
      manifest.flagged_skeleton_frames.push_back(static_cast<int64_t>(n));
    }
  }
  ModelBuildOptions model_options = r.options.model;
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
    r.summary.representative_frame = *model.representative_frame;
  }
  r.summary.fitted_parts = model.fitted_count();
}

// Finishes the map and writes the clip directory.
Status WriteClip(Recording& r, proto::ClipManifest& manifest,
                 const std::filesystem::path& out_dir) {
  proto::ClipMap map = AddVirtualViews(
      r.slam ? r.slam->ExportClipMap() : std::move(r.map_builder).Finish(), r.virtual_keyframes,
      r.info.depth_scale_m, r.info.color_camera, manifest.world_up, r.options.virtual_views,
      r.options.map, &r.summary.virtual_view_points);
  auto map_bytes = proto::EncodeMap(map, proto::MapCodecOptions{});
  if (!map_bytes.ok()) return map_bytes.error();
  manifest.map.point_count = static_cast<int64_t>(map.points.size());
  proto::FillPartHashes(manifest, r.stored.encoded, *map_bytes);
  if (Status written = proto::WriteClipDirectory(out_dir, manifest, r.stored.encoded, *map_bytes);
      !written.ok())
    return written.error();
  r.summary.map_bytes = map_bytes->size();
  r.summary.map_points = map.points.size();
  return {};
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

Status CheckRecordableSource(const SensorInfo& info) {
  if (info.has_color) return {};
  return MakeError("unsupported",
                   "cannot record a clip from " + info.description +
                       ": it has no colour images, and a clip needs colour (viewers texture "
                       "the model and the frames from it); record from a source with colour: "
                       "synthetic:, oni:, openni, tum:, clip:, or rgbd:DIR with colour images in "
                       "DIR/rgb/ or DIR/color/ (tracking and evaluation work without colour)");
}

Expected<RecordSummary> RecordClip(FrameSource& source, const std::filesystem::path& out_dir,
                                   const RecordOptions& options) {
  options.Check();
  const auto start = Clock::now();
  const SensorInfo& info = source.info();
  if (Status recordable = CheckRecordableSource(info); !recordable.ok()) return recordable.error();
  if (std::error_code ec; std::filesystem::exists(out_dir, ec))
    return MakeError("already_exists",
                     out_dir.string() + " already exists; remove it or choose another --out");

  Recording r(options, info);
  RecordSummary& summary = r.summary;
  while (options.max_frames < 0 || summary.source_frames < options.max_frames) {
    auto read_start = Clock::now();
    auto next = source.Next();
    if (!next.ok()) return next.error();
    if (!next->has_value()) break;
    const int index = summary.source_frames++;
    summary.stage_times.source_ms.push_back(MsSince(read_start));
    if (Status recorded = RecordFrame(r, **next, index); !recorded.ok()) return recorded.error();
  }
  if (summary.source_frames == 0)
    return MakeError("empty", "the source " + info.description + " yielded no frames");
  if (r.stored.encoded.empty()) return NothingStored(summary, info);
  summary.frames = static_cast<int>(r.stored.encoded.size());

  proto::ClipManifest manifest = ManifestOf(r);
  const auto model_start = Clock::now();
  BuildModel(r, manifest);
  summary.stage_times.model_ms = MsSince(model_start);

  const auto write_start = Clock::now();
  if (Status written = WriteClip(r, manifest, out_dir); !written.ok()) return written.error();
  summary.stage_times.write_ms = MsSince(write_start);
  summary.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return std::move(summary);
}

}  // namespace reenact::capture
