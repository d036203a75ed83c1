#include "capture-client/source/synthetic_source.h"

#include <cmath>
#include <filesystem>

#include "capture-client/source/source_argument.h"

namespace reenact::capture {

SyntheticSource::SyntheticSource(SyntheticScene scene, SensorInfo info)
    : scene_(std::move(scene)), info_(std::move(info)) {}

Expected<std::unique_ptr<FrameSource>> SyntheticSource::OpenSpec(std::string_view argument) {
  Expected<SourceArgument> arg =
      ParseSourceArgument("synthetic", argument, {"body", "body_height"});
  if (!arg.ok()) return arg.error();
  if (arg->path.empty())
    return MakeError("usage",
                     "--source synthetic:SCENARIO needs a scenario name, e.g. "
                     "synthetic:turn-and-kick");
  SyntheticBodySpec body;
  if (const auto it = arg->options.find("body");
      it != arg->options.end() && it->second != "procedural")
    body.gltf_path = it->second;
  if (const auto it = arg->options.find("body_height"); it != arg->options.end()) {
    char* end = nullptr;
    body.height_m = std::strtod(it->second.c_str(), &end);
    if (it->second.empty() || *end != '\0' || !std::isfinite(body.height_m) || body.height_m <= 0 ||
        body.height_m >= 10)
      return MakeError("usage", "synthetic: body_height=" + it->second +
                                    " must be a height in metres in (0, 10)");
    if (!body.skinned())
      return MakeError("usage",
                       "synthetic: body_height needs body=FILE.glb (the procedural "
                       "body has a fixed size)");
  }
  return Open(arg->path, 1, body);
}

Expected<std::unique_ptr<FrameSource>> SyntheticSource::Open(std::string_view scenario,
                                                             uint64_t seed,
                                                             const SyntheticBodySpec& body) {
  auto scene = SyntheticScene::Create(scenario, seed, body);
  if (!scene.ok()) return scene.error();
  SensorInfo info;
  info.description =
      "synthetic:" + std::string(scenario) + " (seed " + std::to_string(seed) +
      (body.skinned() ? ", body " + std::filesystem::path(body.gltf_path).filename().string()
                      : std::string()) +
      ")";
  info.color_camera = scene->sensor_camera();
  info.depth_camera = scene->sensor_camera();
  info.depth_scale_m = 0.001;
  info.frame_rate_hz = scene->frame_rate_hz();
  info.frame_count = scene->frame_count();
  info.world_up = scene->world_up();
  // The Kinect-like noise model's 1.65 mm at 1 m (depth_noise.h: noise and quantisation),
  // doubled for keypoints that straddle depth edges; rendering without noise is no worse.
  info.depth_sigma_1m_m = 0.003;
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
