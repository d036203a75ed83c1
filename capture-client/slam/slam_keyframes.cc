#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "capture-client/slam/local_bundle_adjustment.h"
#include "capture-client/slam/slam_state.h"
#include "common/geometry/rotation.h"

namespace reenact::capture::slam {
namespace {

void LocalBundleAdjustment(RgbdSlam::State& s) {
  auto& kfs = s.map.keyframes();
  auto& points = s.map.points();
  const int n = static_cast<int>(kfs.size());
  const int first_free = std::max(1, n - s.options.bundle_window_keyframes);
  if (first_free >= n) return;  // only the first keyframe: nothing to adjust

  BundleProblem problem;
  std::unordered_map<int, int> camera_of;  // keyframe id -> camera index
  auto add_camera = [&](int k, bool fixed) {
    auto [it, inserted] = camera_of.emplace(k, static_cast<int>(problem.sensor_from_world.size()));
    if (inserted) {
      problem.sensor_from_world.push_back(kfs[k].sensor_from_world);
      problem.camera_fixed.push_back(fixed ? 1 : 0);
    }
    return it->second;
  };
  for (int k = first_free; k < n; ++k) add_camera(k, false);

  std::vector<int> point_ids;
  s.stamp.resize(points.size(), 0);
  ++s.stamp_value;
  for (int k = first_free; k < n; ++k) {
    for (int id : kfs[k].point_ids) {
      if (id < 0 || points[id].bad || s.stamp[id] == s.stamp_value) continue;
      s.stamp[id] = s.stamp_value;
      point_ids.push_back(id);
    }
  }
  std::vector<std::pair<int, int>> observation_keys;  // (point id, keyframe id) per observation
  for (size_t p = 0; p < point_ids.size(); ++p) {
    const MapPoint& mp = points[point_ids[p]];
    problem.points_in_world.push_back(mp.position_in_world);
    for (const auto& [k, i] : mp.observations) {
      const int camera = add_camera(k, k < first_free);
      problem.observations.push_back({camera, static_cast<int>(p), kfs[k].observations[i]});
      observation_keys.emplace_back(point_ids[p], k);
    }
  }
  if (std::none_of(problem.camera_fixed.begin(), problem.camera_fixed.end(),
                   [](char f) { return f != 0; })) {
    problem.camera_fixed[0] = 1;  // no older observer: hold the oldest window keyframe
  }
  const BundleResult result =
      SolveBundle(problem, s.camera.fx, s.camera.fy, s.options.noise, s.options.bundle_adjustment);
  for (const auto& [k, c] : camera_of) {
    if (!problem.camera_fixed[c]) kfs[k].sensor_from_world = problem.sensor_from_world[c];
  }
  for (size_t p = 0; p < point_ids.size(); ++p) {
    points[point_ids[p]].position_in_world = problem.points_in_world[p];
  }
  for (size_t o = 0; o < result.inlier.size(); ++o) {
    if (!result.inlier[o])
      s.map.RemoveObservation(observation_keys[o].first, observation_keys[o].second);
  }
}

void CullPoints(RgbdSlam::State& s) {
  const int target =
      static_cast<int>(s.map.keyframes().size()) - 1 - s.options.cull_after_keyframes;
  if (target < 0) return;
  const std::vector<int> ids = s.map.keyframes()[target].point_ids;
  for (int id : ids) {
    if (id < 0) continue;
    const MapPoint& p = s.map.points()[id];
    if (p.bad || p.created_by_keyframe != target) continue;
    if (p.FoundRatio() < s.options.cull_min_found_ratio) s.map.CullPoint(id);
  }
}

}  // namespace

bool NeedKeyframe(const RgbdSlam::State& s, const Eigen::Isometry3d& sensor_from_world,
                  int inliers) {
  if (s.last_keyframe < 0) return true;
  if (s.frames_since_keyframe >= s.options.max_frames_between_keyframes) return true;
  const Keyframe& kf = s.map.keyframes()[s.last_keyframe];
  // The last keyframe's points that were seen again (all of them while it is the only one).
  const size_t min_observations = s.map.keyframes().size() > 1 ? 2 : 1;
  int reference = 0;
  for (int id : kf.point_ids) {
    reference += id >= 0 && !s.map.points()[id].bad &&
                 s.map.points()[id].observations.size() >= min_observations;
  }
  if (inliers < s.options.keyframe_min_tracked_ratio * reference) return true;
  const Eigen::Isometry3d motion = sensor_from_world * kf.sensor_from_world.inverse();
  if (motion.translation().norm() > s.options.keyframe_translation_m) return true;
  return RotationAngle(motion.linear()) * 180 / std::numbers::pi > s.options.keyframe_rotation_deg;
}

int InsertKeyframe(RgbdSlam::State& s, int frame_index, double timestamp_s,
                   const FrameFeatures& features, const Eigen::Isometry3d& sensor_from_world,
                   const std::vector<FeatureMatch>& inliers, int max_new_points) {
  Keyframe kf;
  kf.frame_index = frame_index;
  kf.timestamp_s = timestamp_s;
  kf.sensor_from_world = sensor_from_world;
  kf.observations = features.observations;
  kf.descriptors = features.descriptors.clone();
  const int id = s.map.AddKeyframe(std::move(kf));
  for (const FeatureMatch& m : inliers) {
    s.map.AddObservation(m.id, id, m.keypoint);
    s.map.UpdateDescriptor(m.id);
  }
  std::vector<int> fresh;
  for (size_t i = 0; i < features.size(); ++i) {
    if (features.observations[i].depth_m > 0 && s.map.keyframes()[id].point_ids[i] < 0)
      fresh.push_back(static_cast<int>(i));
  }
  std::stable_sort(fresh.begin(), fresh.end(), [&](int a, int b) {
    return features.observations[a].depth_m < features.observations[b].depth_m;
  });
  if (static_cast<int>(fresh.size()) > max_new_points) fresh.resize(max_new_points);
  const Eigen::Isometry3d world_from_sensor = sensor_from_world.inverse();
  for (int i : fresh) s.map.AddPoint(world_from_sensor * features.points_in_camera[i], id, i);

  s.last_keyframe = id;
  s.frames_since_keyframe = 0;
  if (s.options.local_bundle_adjustment) LocalBundleAdjustment(s);
  CullPoints(s);
  return id;
}

}  // namespace reenact::capture::slam
