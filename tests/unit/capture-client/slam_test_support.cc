#include "tests/unit/capture-client/slam_test_support.h"

#include <filesystem>
#include <map>
#include <mutex>

#include "capture-client/source/tum_source.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture::slam::test_input {

std::string TumRpyDir() { return std::string(REENACT_SHARED_DATA_DIR) + "/tum-fr1-rpy-head"; }

Sequence LoadTum(const std::string& dir, int max_frames) {
  Sequence s;
  if (!std::filesystem::is_directory(dir)) return s;
  TumSourceOptions options;
  options.undistort = TumSourceOptions::Undistort::kNone;
  auto source = TumSource::Open(dir, options);
  if (!source.ok()) return s;
  s.camera = (*source)->info().color_camera;
  s.depth_scale_m = (*source)->info().depth_scale_m;
  for (int i = 0; i < max_frames; ++i) {
    auto next = (*source)->Next();
    if (!next.ok() || !next->has_value()) break;
    Frame f;
    f.timestamp_s = (*next)->timestamp_s;
    f.color = std::move((*next)->color);
    f.depth = std::move((*next)->depth);
    if (static_cast<size_t>(i) < (*source)->ground_truth().size())
      f.truth_world_from_sensor = (*source)->ground_truth()[i];
    s.frames.push_back(std::move(f));
  }
  return s;
}

const SyntheticScene& WalkHandheldScene() {
  static const SyntheticScene scene = SyntheticScene::Create("walk-handheld", 1).value();
  return scene;
}

const Sequence& WalkHandheld(int count, int step) {
  static std::mutex mutex;
  static std::map<std::pair<int, int>, Sequence> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find({count, step});
  if (it != cache.end()) return it->second;
  const SyntheticScene& scene = WalkHandheldScene();
  Sequence s;
  s.camera = scene.sensor_camera();
  s.depth_scale_m = 0.001;
  SyntheticRenderOptions render;
  render.depth_noise = true;
  for (int i = 0; i < count && i * step < scene.frame_count(); ++i) {
    const int k = i * step;
    SyntheticView view = scene.RenderSensor(k, render);
    Frame f;
    f.timestamp_s = k / scene.frame_rate_hz();
    f.color = std::move(view.color);
    f.depth = std::move(view.depth);
    f.mask = std::move(view.mask);
    f.truth_world_from_sensor = scene.world_from_sensor(k);
    s.frames.push_back(std::move(f));
  }
  return cache.emplace(std::make_pair(count, step), std::move(s)).first->second;
}

}  // namespace reenact::capture::slam::test_input
