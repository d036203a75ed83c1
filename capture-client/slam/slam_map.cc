#include "capture-client/slam/slam_map.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "capture-client/slam/vision_names.h"
#include "common/error/check.h"

namespace reenact::capture::slam {

void MapExportOptions::Check() const {
  REENACT_CHECK(min_observations >= 1, "min_observations must be >= 1");
  REENACT_CHECK(min_found_ratio >= 0 && min_found_ratio <= 1, "min_found_ratio in [0, 1]");
}

int SlamMap::AddKeyframe(Keyframe keyframe) {
  REENACT_CHECK(keyframe.descriptors.rows == static_cast<int>(keyframe.observations.size()),
                "one descriptor per keypoint");
  keyframe.point_ids.assign(keyframe.observations.size(), -1);
  keyframes_.push_back(std::move(keyframe));
  return static_cast<int>(keyframes_.size()) - 1;
}

int SlamMap::AddPoint(const Eigen::Vector3d& position_in_world, int keyframe_id, int keypoint) {
  Keyframe& kf = keyframes_.at(keyframe_id);
  REENACT_CHECK(kf.point_ids.at(keypoint) < 0, "keypoint already observes a point");
  MapPoint p;
  p.position_in_world = position_in_world;
  std::memcpy(p.descriptor.data(), kf.descriptors.ptr<uint8_t>(keypoint), 32);
  p.observations.emplace_back(keyframe_id, keypoint);
  p.created_by_keyframe = keyframe_id;
  p.reference_distance_m = std::max(1e-3, (position_in_world - kf.CentreInWorld()).norm());
  p.reference_octave = kf.observations[keypoint].octave;
  points_.push_back(p);
  const int id = static_cast<int>(points_.size()) - 1;
  kf.point_ids[keypoint] = id;
  return id;
}

void SlamMap::AddObservation(int point_id, int keyframe_id, int keypoint) {
  MapPoint& p = points_.at(point_id);
  Keyframe& kf = keyframes_.at(keyframe_id);
  if (p.bad || kf.point_ids.at(keypoint) >= 0) return;
  for (const auto& [k, i] : p.observations) {
    if (k == keyframe_id) return;
  }
  p.observations.emplace_back(keyframe_id, keypoint);
  kf.point_ids[keypoint] = point_id;
}

void SlamMap::RemoveObservation(int point_id, int keyframe_id) {
  MapPoint& p = points_.at(point_id);
  for (size_t o = 0; o < p.observations.size(); ++o) {
    if (p.observations[o].first != keyframe_id) continue;
    keyframes_.at(keyframe_id).point_ids.at(p.observations[o].second) = -1;
    p.observations.erase(p.observations.begin() + static_cast<std::ptrdiff_t>(o));
    break;
  }
  if (p.observations.empty()) p.bad = true;
}

void SlamMap::CullPoint(int point_id) {
  MapPoint& p = points_.at(point_id);
  for (const auto& [k, i] : p.observations) keyframes_.at(k).point_ids.at(i) = -1;
  p.observations.clear();
  p.bad = true;
}

void SlamMap::UpdateDescriptor(int point_id) {
  MapPoint& p = points_.at(point_id);
  const size_t n = p.observations.size();
  if (n < 2) return;
  std::vector<const uint8_t*> d;
  d.reserve(n);
  for (const auto& [k, i] : p.observations) d.push_back(keyframes_[k].descriptors.ptr<uint8_t>(i));
  size_t best = 0;
  int best_median = 1 << 30;
  std::vector<int> dist(n);
  for (size_t a = 0; a < n; ++a) {
    for (size_t b = 0; b < n; ++b) dist[b] = DescriptorDistance(d[a], d[b]);
    std::nth_element(dist.begin(), dist.begin() + static_cast<std::ptrdiff_t>((n - 1) / 2),
                     dist.end());
    const int median = dist[(n - 1) / 2];
    if (median < best_median) {
      best_median = median;
      best = a;
    }
  }
  std::memcpy(p.descriptor.data(), d[best], 32);
}

int SlamMap::PredictOctave(int point_id, double distance_m, double scale_factor,
                           int num_levels) const {
  const MapPoint& p = points_.at(point_id);
  if (!(distance_m > 0)) return p.reference_octave;
  const double level =
      p.reference_octave + std::log(p.reference_distance_m / distance_m) / std::log(scale_factor);
  return std::clamp(static_cast<int>(std::lround(level)), 0, num_levels - 1);
}

int SlamMap::good_point_count() const {
  int n = 0;
  for (const MapPoint& p : points_) n += !p.bad;
  return n;
}

proto::ClipMap SlamMap::ExportClipMap(const MapExportOptions& options) const {
  options.Check();
  proto::ClipMap out;
  for (const MapPoint& p : points_) {
    if (p.bad || static_cast<int>(p.observations.size()) < options.min_observations ||
        p.FoundRatio() < options.min_found_ratio || !p.position_in_world.allFinite()) {
      continue;
    }
    proto::MapPoint mp;
    mp.position_in_world = p.position_in_world;
    mp.descriptor = p.descriptor;
    mp.observations = static_cast<uint32_t>(p.observations.size());
    out.points.push_back(mp);
  }
  return out;
}

}  // namespace reenact::capture::slam
