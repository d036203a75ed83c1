#include "capture-client/source/clip_source.h"

#include <algorithm>
#include <cmath>

namespace reenact::capture {
namespace {

// Copies `crop` into `full` with its top-left pixel at (x0, y0).
template <typename T>
void Place(const Image<T>& crop, int x0, int y0, Image<T>& full) {
  for (int y = 0; y < crop.height; ++y)
    std::copy_n(&crop.at(0, y), static_cast<size_t>(crop.width) * crop.channels,
                &full.at(x0, y0 + y));
}

}  // namespace

ClipSource::ClipSource(proto::ClipDirectory clip) : clip_(std::move(clip)) {}

Expected<std::unique_ptr<FrameSource>> ClipSource::Open(const std::filesystem::path& dir) {
  auto clip = proto::ReadClipDirectory(dir);
  if (!clip.ok())
    return MakeError(clip.error().code, "clip:" + dir.string() + ": " + clip.error().message);
  std::unique_ptr<ClipSource> source(new ClipSource(std::move(clip).value()));
  const proto::ClipManifest& m = source->clip_.manifest();
  SensorInfo& info = source->info_;
  info.description = "clip:" + dir.string() + " (" + std::to_string(m.frame_count) + " frames" +
                     (m.title.empty() ? "" : ", \"" + m.title + "\"") + ")";
  info.color_camera = m.color_camera;
  info.depth_camera = m.depth_camera;
  info.depth_scale_m = 0.001;
  info.frame_rate_hz = m.frame_rate_hz;
  info.frame_count = static_cast<int>(m.frame_count);
  info.world_up = m.world_up;
  return std::unique_ptr<FrameSource>(std::move(source));
}

Expected<std::optional<SensorFrame>> ClipSource::Next() {
  const proto::ClipManifest& m = clip_.manifest();
  if (next_ >= m.frame_count) return std::optional<SensorFrame>();
  const int64_t index = next_;
  auto stored = clip_.ReadFrame(index);
  if (!stored.ok())
    return MakeError(stored.error().code, "clip:" + clip_.path().string() + " frame " +
                                              std::to_string(index) + ": " +
                                              stored.error().message);
  const int w = m.color_camera.width, h = m.color_camera.height;
  const proto::ClipFrame& f = *stored;
  if (f.crop_x + f.color.width > w || f.crop_y + f.color.height > h)
    return MakeError(
        "corrupt", "clip:" + clip_.path().string() + " frame " + std::to_string(index) +
                       ": its crop (" + std::to_string(f.color.width) + "x" +
                       std::to_string(f.color.height) + " at " + std::to_string(f.crop_x) + "," +
                       std::to_string(f.crop_y) + ") lies outside the " + std::to_string(w) + "x" +
                       std::to_string(h) + " frame of its manifest");
  SensorFrame frame;
  frame.timestamp_s = f.timestamp_s;
  frame.color = ImageRgb8(w, h, 3);
  frame.depth = ImageDepthMm(w, h, 1);
  ImageGray8 mask(w, h, 1);
  Place(f.color, f.crop_x, f.crop_y, frame.color);
  Place(f.mask, f.crop_x, f.crop_y, mask);
  if (m.depth_scale_m == 0.001) {
    Place(f.depth, f.crop_x, f.crop_y, frame.depth);
  } else {
    ImageDepthMm mm(f.depth.width, f.depth.height, 1);
    const double to_mm = m.depth_scale_m / 0.001;
    std::transform(f.depth.data.begin(), f.depth.data.end(), mm.data.begin(), [&](uint16_t d) {
      return static_cast<uint16_t>(std::min(65535.0, std::round(d * to_mm)));
    });
    Place(mm, f.crop_x, f.crop_y, frame.depth);
  }
  frame.world_from_sensor = f.world_from_sensor;
  frame.skeleton_in_world = f.skeleton_in_world;
  frame.person_mask = std::move(mask);
  ++next_;
  return std::optional<SensorFrame>(std::move(frame));
}

}  // namespace reenact::capture
