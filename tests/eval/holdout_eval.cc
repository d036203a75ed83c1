#include "tests/eval/holdout_eval.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <tuple>

#include "capture-client/record/clip_recorder.h"
#include "capture-client/skeleton/skeleton_track_spec.h"
#include "capture-client/source/frame_source.h"
#include "capture-client/tracker/tracker_skeleton_source.h"
#include "proto/clip/clip_directory.h"
#include "tests/eval/holdout_frames.h"
#include "tests/eval/quality_methods.h"
#include "tests/eval/side_by_side.h"
#include "viewer-client/output/png_writer.h"
#include "viewer-client/play/reenactment.h"
#include "viewer-client/play/viewer_camera.h"
#include "viewer-client/render/renderer.h"

namespace reenact::eval {
namespace {

namespace fs = std::filesystem;

// A frame source over frames already read: frame i of `count` is frame_at(i).
class MemorySource : public capture::FrameSource {
 public:
  MemorySource(capture::SensorInfo info, int count,
               std::function<capture::SensorFrame(int)> frame_at)
      : info_(std::move(info)), count_(count), frame_at_(std::move(frame_at)) {
    info_.frame_count = count;
  }
  const capture::SensorInfo& info() const override { return info_; }
  Expected<std::optional<capture::SensorFrame>> Next() override {
    if (next_ >= count_) return std::optional<capture::SensorFrame>();
    return std::optional<capture::SensorFrame>(frame_at_(next_++));
  }

 private:
  capture::SensorInfo info_;
  int count_ = 0;
  std::function<capture::SensorFrame(int)> frame_at_;
  int next_ = 0;
};

struct SourceFrames {
  capture::SensorInfo info;
  std::vector<capture::SensorFrame> frames;
};

Expected<SourceFrames> ReadSource(const HoldoutOptions& options) {
  auto source = capture::OpenFrameSource(options.source);
  if (!source.ok()) return source.error();
  SourceFrames out{(*source)->info(), {}};
  if (!out.info.has_color)
    return MakeError("unsupported",
                     "holdout compares each held-out frame with its colour image, and " +
                         out.info.description +
                         " has none; use a source with colour: synthetic:SCENARIO, oni:FILE, "
                         "tum:DIR, clip:DIR, or rgbd:DIR with colour images in DIR/rgb/ or "
                         "DIR/color/");
  if (!out.info.color_camera.distortion.IsZero())
    return MakeError("unsupported",
                     out.info.description +
                         ": its colour camera has lens distortion, and the reenactment is "
                         "rendered through a pinhole camera; open the source with its colour "
                         "undistorted (e.g. tum:DIR?undistort=color, rgbd:DIR?undistort=both)");
  while (options.max_frames < 0 || static_cast<int>(out.frames.size()) < options.max_frames) {
    auto frame = (*source)->Next();
    if (!frame.ok()) return frame.error();
    if (!*frame) break;
    if ((*frame)->color.width != out.info.color_camera.width ||
        (*frame)->color.height != out.info.color_camera.height)
      return MakeError("corrupt", out.info.description + ": frame " +
                                      std::to_string(out.frames.size()) +
                                      "'s colour image is not the colour camera's size");
    out.frames.push_back(std::move(**frame));
  }
  return out;
}

// Source frame index of each stored clip frame, from the timestamps (the recorder stores the
// source's, written exactly). Error "internal" for a timestamp that is no source frame's.
Expected<std::vector<int>> SourceFrameOf(const std::vector<proto::ClipFrame>& clip,
                                         const std::vector<capture::SensorFrame>& source) {
  std::vector<int> out;
  size_t j = 0;
  for (const proto::ClipFrame& f : clip) {
    while (j < source.size() && source[j].timestamp_s < f.timestamp_s - 1e-9) ++j;
    if (j == source.size() || std::abs(source[j].timestamp_s - f.timestamp_s) > 1e-9)
      return MakeError("internal", "a recorded frame's timestamp " + std::to_string(f.timestamp_s) +
                                       " is no source frame's (or frames are out of order)");
    out.push_back(static_cast<int>(j++));
  }
  return out;
}

Expected<std::vector<proto::ClipFrame>> ReadFrames(const proto::ClipDirectory& clip) {
  std::vector<proto::ClipFrame> frames;
  for (int64_t n = 0; n < clip.manifest().frame_count; ++n) {
    auto frame = clip.ReadFrame(n);
    if (!frame.ok()) return frame.error();
    frames.push_back(std::move(frame).value());
  }
  return frames;
}

struct Recorded {
  proto::ClipManifest manifest;
  std::vector<proto::ClipFrame> frames;
  std::vector<int> source_frame;  // per stored frame
};

// Records the source into `dir` and reads the clip back.
Expected<Recorded> Record(capture::FrameSource& source, const capture::RecordOptions& options,
                          const std::vector<capture::SensorFrame>& source_frames,
                          const fs::path& dir) {
  auto recorded = capture::RecordClip(source, dir, options);
  if (!recorded.ok()) return recorded.error();
  auto clip = proto::ReadClipDirectory(dir);
  if (!clip.ok()) return clip.error();
  auto frames = ReadFrames(*clip);
  if (!frames.ok()) return frames.error();
  auto index = SourceFrameOf(*frames, source_frames);
  if (!index.ok()) return index.error();
  return Recorded{clip->manifest(), std::move(frames).value(), std::move(index).value()};
}

// Recording 1: every source frame, with the options' skeleton source and poses.
Expected<Recorded> RecordAll(const HoldoutOptions& options, const SourceFrames& source,
                             const fs::path& dir) {
  capture::RecordOptions record;
  record.poses = options.slam_poses ? capture::PoseSource::kSlam : capture::PoseSource::kAuto;
  std::optional<capture::SkeletonTrack> track;
  std::optional<capture::TrackerSkeletonSource> tracker;
  if (options.skeleton == "track") {
    tracker.emplace(source.info);
    record.frame_skeletons = tracker->Function();
  } else if (options.skeleton != "source") {
    auto loaded = capture::LoadSkeletonTrack(options.skeleton);
    if (!loaded.ok()) return loaded.error();
    track = std::move(loaded).value();
    record.skeletons = [&track](int64_t index, double timestamp_s) {
      return track->ForFrame(index, timestamp_s);
    };
  }
  MemorySource all(source.info, static_cast<int>(source.frames.size()),
                   [&source](int i) { return source.frames[i]; });
  auto recorded = Record(all, record, source.frames, dir);
  if (!recorded.ok() && tracker && tracker->stats().tracked == 0)
    return MakeError("tracking", "the depth tracker gave no skeleton on any of the " +
                                     std::to_string(source.frames.size()) + " frames of " +
                                     source.info.description + " (" + tracker->stats().Describe() +
                                     ")");
  if (!recorded.ok() && recorded.error().code == "no_skeleton" && !tracker)
    return MakeError("no_skeleton",
                     recorded.error().message + ", or --skeleton track for our depth tracker");
  return recorded;
}

// The full-size mask of a stored frame (its crop pasted at the crop position).
ImageGray8 FullMask(const proto::ClipFrame& f, int width, int height) {
  ImageGray8 mask(width, height, 1, 0);
  for (int y = 0; y < f.mask.height; ++y)
    for (int x = 0; x < f.mask.width; ++x) {
      const int fx = f.crop_x + x, fy = f.crop_y + y;
      if (fx < width && fy < height) mask.at(fx, fy) = f.mask.at(x, y);
    }
  return mask;
}

bool HasSubject(const ImageGray8& mask) {
  return std::any_of(mask.data.begin(), mask.data.end(), [](uint8_t v) { return v > 127; });
}

// The reenacted clip (see the header) and the source frame of each of its frames.
struct HoldoutClip {
  proto::ClipManifest manifest;
  std::vector<proto::ClipFrame> frames;
  std::vector<int> source_frame;
};

HoldoutClip MergeClips(const Recorded& all, const Recorded& kept,
                       const std::vector<bool>& excluded) {
  HoldoutClip out{kept.manifest, {}, {}};
  out.manifest.flagged_skeleton_frames.clear();
  std::map<int, int> kept_index;  // source frame -> recording 2's frame
  for (size_t n = 0; n < kept.source_frame.size(); ++n) kept_index[kept.source_frame[n]] = n;
  std::map<int64_t, bool> kept_flagged;
  for (int64_t n : kept.manifest.flagged_skeleton_frames) kept_flagged[n] = true;
  for (size_t n = 0; n < all.frames.size(); ++n) {
    const int i = all.source_frame[n];
    const int64_t merged = static_cast<int64_t>(out.frames.size());
    if (excluded[i]) {
      proto::ClipFrame f;
      f.timestamp_s = all.frames[n].timestamp_s;
      f.world_from_sensor = all.frames[n].world_from_sensor;
      f.skeleton_in_world = all.frames[n].skeleton_in_world;
      f.color = ImageRgb8(8, 8, 3, 0);
      f.depth = ImageDepthMm(8, 8, 1, 0);
      f.mask = ImageGray8(8, 8, 1, 0);
      out.frames.push_back(std::move(f));
    } else {
      const auto it = kept_index.find(i);
      if (it == kept_index.end()) continue;
      if (it->second == kept.manifest.representative_frame)
        out.manifest.representative_frame = merged;
      if (kept_flagged.count(it->second)) out.manifest.flagged_skeleton_frames.push_back(merged);
      out.frames.push_back(kept.frames[it->second]);
    }
    out.source_frame.push_back(i);
  }
  out.manifest.frame_count = static_cast<int64_t>(out.frames.size());
  return out;
}

// The reenacted clip as each method sees it, and the renderer's textures of its frames.
class Textures {
 public:
  Textures(const HoldoutClip& clip, viewer::Renderer& renderer)
      : plain_(clip.manifest, clip.frames), clip_(clip), renderer_(renderer) {}

  const viewer::Reenactment& ClipFor(bool steady) {
    if (!steady) return plain_;
    if (!steady_) {
      viewer::ReenactmentOptions options;
      options.steady_motion = true;
      steady_.emplace(clip_.manifest, clip_.frames, options);
    }
    return *steady_;
  }

  int TextureFor(int n, viewer::BodyShape shape, bool steady) {
    const auto key = std::make_tuple(n, shape, steady);
    auto it = texture_of_frame_.find(key);
    if (it != texture_of_frame_.end()) return it->second;
    return texture_of_frame_[key] = renderer_.UploadTexture(ClipFor(steady).Texture(n, shape));
  }

 private:
  viewer::Reenactment plain_;
  std::optional<viewer::Reenactment> steady_;
  const HoldoutClip& clip_;
  viewer::Renderer& renderer_;
  std::map<std::tuple<int, viewer::BodyShape, bool>, int> texture_of_frame_;
};

std::string ImageName(const std::string& method, int source_frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "_f%04d.png", source_frame);
  return method + name;
}

}  // namespace

void HoldoutOptions::Check() const {
  REENACT_CHECK(!source.empty(), "holdout needs a source");
  REENACT_CHECK(!skeleton.empty(), "the skeleton source must not be empty");
  REENACT_CHECK(every >= 1 && window >= 0, "every must be >= 1 and window >= 0");
  REENACT_CHECK(max_frames == -1 || max_frames >= 1, "max_frames must be -1 or >= 1");
  REENACT_CHECK(!methods.empty(), "need a method");
}

Expected<HoldoutRun> RunHoldout(const HoldoutOptions& options) {
  options.Check();
  auto found = FindQualityMethods(options.methods);
  if (!found.ok()) return found.error();
  const std::vector<const QualityMethod*>& methods = *found;
  auto source = ReadSource(options);
  if (!source.ok()) return source.error();
  HoldoutRun run;
  run.source = source->info.description;
  run.source_frames = static_cast<int>(source->frames.size());
  auto selection = SelectHeldOutFrames(run.source_frames, options.every, options.window);
  if (!selection.ok()) return selection.error();
  run.held_out = static_cast<int>(selection->held_out.size());
  run.excluded = run.source_frames - selection->kept;

  const fs::path dir =
      fs::temp_directory_path() / ("reenact-holdout-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  auto all = RecordAll(options, *source, dir / "all");
  if (!all.ok()) {
    fs::remove_all(dir);
    return all.error();
  }
  run.recorded_frames = static_cast<int>(all->frames.size());

  // Recording 2: the kept frames recording 1 stored, with its skeletons, masks and poses.
  std::vector<int> kept_stored;  // recording 1's frame of each
  for (size_t n = 0; n < all->frames.size(); ++n)
    if (!selection->excluded[all->source_frame[n]]) kept_stored.push_back(static_cast<int>(n));
  if (kept_stored.empty()) {
    fs::remove_all(dir);
    return MakeError(
        "usage",
        "--every " + std::to_string(options.every) + " --window " + std::to_string(options.window) +
            " leave no frame to texture from: " + "none of the " + std::to_string(selection->kept) +
            " frames outside the held-out windows was recorded (no skeleton or "
            "pose); give a larger --every or a smaller --window");
  }
  const int width = source->info.color_camera.width, height = source->info.color_camera.height;
  capture::SensorInfo kept_info = source->info;
  kept_info.world_up = all->manifest.world_up;
  MemorySource kept_source(kept_info, static_cast<int>(kept_stored.size()), [&](int j) {
    const proto::ClipFrame& stored = all->frames[kept_stored[j]];
    capture::SensorFrame f = source->frames[all->source_frame[kept_stored[j]]];
    f.world_from_sensor = stored.world_from_sensor;
    f.skeleton_in_world = stored.skeleton_in_world;
    f.person_mask = FullMask(stored, width, height);
    return f;
  });
  capture::RecordOptions record_kept;
  record_kept.poses = capture::PoseSource::kAuto;
  auto kept = Record(kept_source, record_kept, source->frames, dir / "kept");
  fs::remove_all(dir);
  if (!kept.ok()) return kept.error();
  run.kept = static_cast<int>(kept->frames.size());

  const HoldoutClip clip = MergeClips(*all, *kept, selection->excluded);
  std::vector<int> compared;  // clip frames of the held-out frames compared
  std::map<int, ImageGray8> truth_mask;
  for (int k : selection->held_out) {
    const auto it = std::find(clip.source_frame.begin(), clip.source_frame.end(), k);
    if (it == clip.source_frame.end()) {
      ++run.lost_held_out;
      continue;
    }
    const auto stored = std::find(all->source_frame.begin(), all->source_frame.end(), k);
    ImageGray8 mask = FullMask(all->frames[stored - all->source_frame.begin()], width, height);
    if (!HasSubject(mask)) {
      ++run.empty_mask_held_out;
      continue;
    }
    compared.push_back(static_cast<int>(it - clip.source_frame.begin()));
    truth_mask.emplace(k, std::move(mask));
  }
  run.compared = static_cast<int>(compared.size());
  if (compared.empty())
    return MakeError("no_frames", "none of the " + std::to_string(run.held_out) +
                                      " held-out frames has a skeleton, a sensor pose and a "
                                      "person in its mask (" +
                                      std::to_string(run.lost_held_out) +
                                      " without skeleton or pose, " +
                                      std::to_string(run.empty_mask_held_out) +
                                      " with an empty mask); nothing to compare");

  const PinholeCamera camera =
      viewer::ScaledViewerCamera(kept->manifest.color_camera, width, height);
  auto renderer = viewer::Renderer::CreateHeadless(width, height);
  if (!renderer.ok()) return renderer.error();
  run.gl_renderer = renderer->driver();
  if (!options.image_dir.empty()) {
    std::error_code ec;
    fs::create_directories(options.image_dir, ec);
    if (ec)
      return MakeError("io",
                       "cannot create the image folder " + options.image_dir + ": " + ec.message());
  }

  Textures textures(clip, *renderer);
  for (const QualityMethod* method : methods) {
    HoldoutRow row{method->name};
    PartSelectionHistory history;
    int psnr_frames = 0, textured = 0;
    for (int m : compared) {
      const int k = clip.source_frame[m];
      const Eigen::Isometry3d viewer_from_world = clip.frames[m].world_from_sensor.inverse();
      const viewer::ReenactedFrame frame = method->build(
          textures.ClipFor(method->steady), m, camera, viewer_from_world,
          [&](int n) { return textures.TextureFor(n, method->shape, method->steady); }, &history);
      const viewer::RenderedFrame rendered = renderer->Render(frame.draw);
      const capture::SensorFrame& truth = source->frames[k];
      HoldoutFrame f{
          method->name,
          k,
          frame.texture_frame >= 0 ? clip.source_frame[frame.texture_frame] : -1,
          CompareSubject(rendered.color, rendered.subject_mask, truth.color, truth_mask.at(k)),
          {}};
      if (!options.image_dir.empty()) {
        f.image_path = (fs::path(options.image_dir) / ImageName(method->name, k)).string();
        const Status written = viewer::WritePng(
            f.image_path,
            SideBySide(truth.color, truth_mask.at(k), rendered.color, rendered.subject_mask));
        if (!written.ok()) return written.error();
      }
      if (std::isfinite(f.comparison.psnr_db)) {
        row.psnr_db += f.comparison.psnr_db;
        ++psnr_frames;
      }
      row.ssim += f.comparison.ssim;
      row.iou += f.comparison.iou;
      row.colour_mae += f.comparison.colour_mae;
      if (f.texture_frame >= 0) {
        row.texture_gap += std::abs(f.texture_frame - k);
        ++textured;
      }
      ++row.n;
      run.frames.push_back(std::move(f));
    }
    if (psnr_frames) row.psnr_db /= psnr_frames;
    if (textured) row.texture_gap /= textured;
    for (double* mean : {&row.ssim, &row.iou, &row.colour_mae}) *mean /= row.n;
    run.rows.push_back(row);
  }
  return run;
}

}  // namespace reenact::eval
