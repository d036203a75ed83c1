#include "capture-client/source/synthetic_source.h"

namespace reenact::capture {

SyntheticSource::SyntheticSource(SyntheticScene scene, SensorInfo info)
    : scene_(std::move(scene)), info_(std::move(info)) {}

Expected<std::unique_ptr<FrameSource>> SyntheticSource::Open(std::string_view scenario,
                                                             uint64_t seed) {
  auto scene = SyntheticScene::Create(scenario, seed);
  if (!scene.ok()) return scene.error();
  SensorInfo info;
  info.description = "synthetic:" + std::string(scenario) + " (seed " + std::to_string(seed) + ")";
  info.color_camera = scene->sensor_camera();
  info.depth_camera = scene->sensor_camera();
  info.depth_scale_m = 0.001;
  info.frame_rate_hz = scene->frame_rate_hz();
  info.frame_count = scene->frame_count();
  info.world_up = scene->world_up();
  return std::unique_ptr<FrameSource>(new SyntheticSource(std::move(scene).value(), info));
}

Expected<std::optional<SensorFrame>> SyntheticSource::Next() {
  if (next_ >= scene_.frame_count()) return std::optional<SensorFrame>();
  const int n = next_++;
  SyntheticView view = scene_.RenderSensor(n);
  SensorFrame frame;
  frame.timestamp_s = n / scene_.frame_rate_hz();
  frame.color = std::move(view.color);
  frame.depth = std::move(view.depth);
  frame.person_mask = std::move(view.mask);
  frame.world_from_sensor = scene_.world_from_sensor(n);
  frame.skeleton_in_world = scene_.skeleton_in_world(n);
  return std::optional<SensorFrame>(std::move(frame));
}

}  // namespace reenact::capture
