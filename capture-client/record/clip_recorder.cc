#include "capture-client/record/clip_recorder.h"

#include "capture-client/segment/person_segmenter.h"
#include "capture-client/segment/skeleton_consistency.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <memory>

#include "common/model/model_building.h"
#include "proto/clip/clip_directory.h"
#include "proto/clip/manifest.h"
#include "proto/clip/map_codec.h"

namespace reenact::capture {
namespace {

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

Status CheckFrameUsable(const SensorFrame& f, const SensorInfo& info, int index) {
  const std::string where = "frame " + std::to_string(index) + " of " + info.description;
  if (!f.world_from_sensor)
    return MakeError("unsupported", where + " has no sensor pose; this build records only "
                                            "sources that provide poses (SLAM arrives later)");
  if (!f.skeleton_in_world)
    return MakeError("unsupported", where + " has no skeleton; pass a source with skeletons");
  if (f.color.channels != 3 || f.color.empty() || f.depth.width != f.color.width ||
      f.depth.height != f.color.height ||
      (f.person_mask &&
       (f.person_mask->width != f.color.width || f.person_mask->height != f.color.height)))
    return MakeError("corrupt", where + ": colour, depth and mask sizes disagree");
  return {};
}

}  // namespace

void RecordOptions::Check() const {
  REENACT_CHECK(max_frames == -1 || max_frames >= 1, "max_frames must be -1 or >= 1");
  REENACT_CHECK(crop_margin_px >= 0, "crop_margin_px must be >= 0");
  REENACT_CHECK(keyframe_interval >= 1, "keyframe_interval must be >= 1");
  codec.Check();
  map.Check();
  model.Check();
  segment.Check();
}

Expected<RecordSummary> RecordClip(FrameSource& source, const std::filesystem::path& out_dir,
                                   const RecordOptions& options) {
  options.Check();
  const auto start = std::chrono::steady_clock::now();
  const SensorInfo& info = source.info();
  if (std::error_code ec; std::filesystem::exists(out_dir, ec))
    return MakeError("already_exists", out_dir.string() +
                                           " already exists; remove it or choose another --out");

  std::vector<std::vector<uint8_t>> encoded;
  std::vector<Skeleton> skeletons_in_sensor;
  std::vector<bool> has_subject;
  BackgroundMapBuilder map_builder(options.map);
  PersonSegmenter segmenter(info.depth_camera, info.depth_scale_m, options.segment);
  RecordSummary summary;

  while (options.max_frames < 0 || static_cast<int>(encoded.size()) < options.max_frames) {
    auto next = source.Next();
    if (!next.ok()) return next.error();
    if (!next->has_value()) break;
    const SensorFrame& f = **next;
    const int index = static_cast<int>(encoded.size());
    if (Status usable = CheckFrameUsable(f, info, index); !usable.ok()) return usable.error();
    // Sources without a person mask (real sensors) are segmented from depth and skeleton; a
    // frame where that finds nobody is kept without a subject.
    std::optional<ImageGray8> segmented;
    if (!f.person_mask) {
      auto segmentation = segmenter.SegmentFrame(f, info.world_up);
      if (!segmentation.ok()) return segmentation.error();
      segmented = std::move(segmentation->mask);
      ++summary.segmented_frames;
    }
    const ImageGray8& person_mask = f.person_mask ? *f.person_mask : *segmented;

    const CropRect crop = SubjectCrop(person_mask, options.crop_margin_px);
    proto::ClipFrame frame;
    frame.timestamp_s = f.timestamp_s;
    frame.world_from_sensor = *f.world_from_sensor;
    frame.skeleton_in_world = *f.skeleton_in_world;
    frame.crop_x = crop.x;
    frame.crop_y = crop.y;
    frame.color = Crop(f.color, crop);
    frame.depth = Crop(f.depth, crop);
    frame.mask = Crop(person_mask, crop);
    encoded.push_back(proto::EncodeFrame(frame, options.codec));
    summary.frame_bytes += encoded.back().size();
    skeletons_in_sensor.push_back(
        f.skeleton_in_world->Transformed(f.world_from_sensor->inverse()));
    has_subject.push_back(std::any_of(frame.mask.data.begin(), frame.mask.data.end(),
                                      [](uint8_t v) { return v > 127; }));
    if (index % options.keyframe_interval == 0)
      map_builder.AddKeyframe(f.color, f.depth, info.depth_scale_m, person_mask,
                              info.color_camera, *f.world_from_sensor);
  }
  if (encoded.empty())
    return MakeError("empty", "the source " + info.description + " yielded no frames");

  proto::ClipManifest manifest;
  manifest.title = options.title;
  manifest.author = options.author;
  manifest.capture_time = NowIso8601Utc();
  manifest.color_camera = info.color_camera;
  manifest.depth_camera = info.depth_camera;
  manifest.depth_scale_m = info.depth_scale_m;
  manifest.world_up = info.world_up.value_or(Eigen::Vector3d(0, -1, 0));
  manifest.frame_count = static_cast<int64_t>(encoded.size());
  manifest.frame_rate_hz = info.frame_rate_hz;
  manifest.radius_ratio = DefaultRadiusRatios();

  // Frames without a subject or with an inconsistent skeleton (bone lengths off the clip's
  // medians, left and right swapped) stay out of the model. std::vector<bool> has no
  // contiguous storage to view as a span.
  const SkeletonConsistency consistency = CheckSkeletonConsistency(skeletons_in_sensor);
  const auto usable = std::make_unique<bool[]>(has_subject.size());
  for (size_t n = 0; n < has_subject.size(); ++n) {
    usable[n] = has_subject[n] && consistency.frames[n].usable;
    summary.inconsistent_skeletons += !consistency.frames[n].usable;
  }
  ModelBuildOptions model_options = options.model;
  model_options.fit.depth_scale_m = info.depth_scale_m;
  const ModelBuildResult model = BuildCylinderModel(
      skeletons_in_sensor,
      [&](int n) -> std::optional<ModelFrameImages> {
        auto frame = proto::DecodeFrame(encoded[n]);
        if (!frame.ok()) return std::nullopt;
        return ModelFrameImages{info.color_camera.Cropped(frame->crop_x, frame->crop_y,
                                                          frame->color.width, frame->color.height),
                                std::move(frame->depth), std::move(frame->mask)};
      },
      model_options, std::span<const bool>(usable.get(), has_subject.size()));
  for (int p = 0; p < kBodyPartCount; ++p)
    manifest.radius_ratio[p] = std::clamp(model.radius_ratio[p], 0.02, 2.0);
  if (model.representative_frame) {
    manifest.representative_frame = *model.representative_frame;
    summary.representative_frame = *model.representative_frame;
  }
  summary.fitted_parts = model.fitted_count();

  proto::ClipMap map = std::move(map_builder).Finish();
  auto map_bytes = proto::EncodeMap(map, proto::MapCodecOptions{});
  if (!map_bytes.ok()) return map_bytes.error();
  manifest.map.point_count = static_cast<int64_t>(map.points.size());
  proto::FillPartHashes(manifest, encoded, *map_bytes);
  if (Status written = proto::WriteClipDirectory(out_dir, manifest, encoded, *map_bytes);
      !written.ok())
    return written.error();

  summary.frames = static_cast<int>(encoded.size());
  summary.map_bytes = map_bytes->size();
  summary.map_points = map.points.size();
  summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace reenact::capture
