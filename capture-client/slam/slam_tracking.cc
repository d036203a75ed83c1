#include <algorithm>
#include <map>

#include "capture-client/slam/slam_state.h"
#include "capture-client/slam/vision_names.h"
#include "common/estimate/ransac.h"

namespace reenact::capture::slam {
namespace {

std::vector<PointObservation> Observations(const RgbdSlam::State& s, const FrameFeatures& f,
                                           const std::vector<FeatureMatch>& matches) {
  std::vector<PointObservation> obs;
  obs.reserve(matches.size());
  for (const FeatureMatch& m : matches) {
    obs.push_back({s.map.points()[m.id].position_in_world, f.observations[m.keypoint]});
  }
  return obs;
}

// RANSAC PnP over the matches, then refinement from its pose (and from `prior` when given);
// the refined pose with the most inliers wins.
PoseEstimate SolvePose(const RgbdSlam::State& s, const FrameFeatures& f,
                       const std::vector<FeatureMatch>& matches,
                       const std::optional<Eigen::Isometry3d>& prior, int ransac_iterations) {
  PoseEstimate out;
  out.matches = static_cast<int>(matches.size());
  if (matches.size() < 3) return out;
  std::vector<PnpEstimator::Sample> samples;
  samples.reserve(matches.size());
  for (const FeatureMatch& m : matches) {
    samples.push_back(
        {s.map.points()[m.id].position_in_world, f.observations[m.keypoint].normalized});
  }
  RansacOptions ro;
  ro.max_error = s.options.ransac_max_error_px;
  ro.max_iterations = ransac_iterations;
  ro.min_iterations = std::min(20, ransac_iterations);
  ro.seed = s.options.seed + static_cast<uint64_t>(s.frames_seen);
  const PnpEstimator estimator{s.camera.fx, s.camera.fy};
  const RansacResult<Eigen::Isometry3d> ransac = Ransac(estimator, samples, ro);

  std::vector<Eigen::Isometry3d> starts;
  if (ransac.success) starts.push_back(ransac.model);
  if (prior) starts.push_back(*prior);
  const std::vector<PointObservation> obs = Observations(s, f, matches);
  int best = -1;
  for (const Eigen::Isometry3d& start : starts) {
    const PoseRefinementResult refined = RefinePose(start, obs, s.camera.fx, s.camera.fy,
                                                    s.options.noise, s.options.pose_refinement);
    if (refined.num_inliers <= best) continue;
    best = refined.num_inliers;
    out.sensor_from_world = refined.sensor_from_world;
    out.inliers.clear();
    for (size_t i = 0; i < matches.size(); ++i) {
      if (refined.inlier[i]) out.inliers.push_back(matches[i]);
    }
  }
  return out;
}

// The points of the local map: those of the keyframes sharing the most points with the
// previous frame, and of the newest keyframes.
std::vector<MatchCandidate> LocalMapCandidates(RgbdSlam::State& s,
                                               const Eigen::Isometry3d& sensor_from_world) {
  const auto& kfs = s.map.keyframes();
  const auto& points = s.map.points();
  std::map<int, int> shared;
  for (int id : s.last_inlier_points) {
    if (id < 0 || id >= static_cast<int>(points.size()) || points[id].bad) continue;
    for (const auto& [k, i] : points[id].observations) ++shared[k];
  }
  std::vector<std::pair<int, int>> ranked;  // (count, keyframe)
  for (const auto& [k, n] : shared) ranked.emplace_back(n, k);
  std::sort(ranked.begin(), ranked.end(), std::greater<>());
  std::vector<int> local;
  for (size_t i = 0;
       i < ranked.size() && static_cast<int>(local.size()) < s.options.local_keyframes; ++i) {
    local.push_back(ranked[i].second);
  }
  const int newest = static_cast<int>(kfs.size());
  for (int k = newest - 1; k >= std::max(0, newest - 3); --k) {
    if (std::find(local.begin(), local.end(), k) == local.end()) local.push_back(k);
  }

  s.stamp.resize(points.size(), 0);
  ++s.stamp_value;
  const Eigen::Vector3d centre = sensor_from_world.inverse().translation();
  std::vector<MatchCandidate> out;
  for (int k : local) {
    for (int id : kfs[k].point_ids) {
      if (id < 0 || points[id].bad || s.stamp[id] == s.stamp_value) continue;
      s.stamp[id] = s.stamp_value;
      MatchCandidate c;
      c.id = id;
      c.point_in_world = points[id].position_in_world;
      c.descriptor = points[id].descriptor.data();
      c.predicted_octave =
          s.map.PredictOctave(id, (c.point_in_world - centre).norm(),
                              s.options.features.scale_factor, s.options.features.num_levels);
      out.push_back(c);
    }
  }
  return out;
}

MatchOptions Matching(const RgbdSlam::State& s, double radius_px) {
  MatchOptions mo;
  mo.radius_px = radius_px;
  mo.max_distance = s.options.max_descriptor_distance;
  mo.ratio = s.options.match_ratio;
  mo.scale_factor = s.options.features.scale_factor;
  return mo;
}

}  // namespace

PoseEstimate TrackLocalMap(RgbdSlam::State& s, const FrameFeatures& features,
                           const Eigen::Isometry3d& predicted, int min_inliers) {
  const KeypointGrid grid(features, s.camera.width, s.camera.height);
  std::vector<MatchCandidate> candidates = LocalMapCandidates(s, predicted);
  std::vector<FeatureMatch> matches = MatchByProjection(
      candidates, features, grid, predicted, s.camera, Matching(s, s.options.search_radius_px));
  if (static_cast<int>(matches.size()) < 2 * min_inliers) {
    std::vector<FeatureMatch> wide =
        MatchByProjection(candidates, features, grid, predicted, s.camera,
                          Matching(s, s.options.wide_search_radius_px));
    if (wide.size() > matches.size()) matches = std::move(wide);
  }
  PoseEstimate est = SolvePose(s, features, matches, predicted, s.options.ransac_max_iterations);
  if (static_cast<int>(est.inliers.size()) < min_inliers) return est;

  // A tighter search at the refined pose finds the points the prediction missed.
  std::vector<char> in_view;
  const std::vector<FeatureMatch> again =
      MatchByProjection(candidates, features, grid, est.sensor_from_world, s.camera,
                        Matching(s, 0.5 * s.options.search_radius_px), &in_view);
  const PoseRefinementResult refined =
      RefinePose(est.sensor_from_world, Observations(s, features, again), s.camera.fx, s.camera.fy,
                 s.options.noise, s.options.pose_refinement);
  if (refined.num_inliers >= static_cast<int>(est.inliers.size())) {
    est.sensor_from_world = refined.sensor_from_world;
    est.matches = static_cast<int>(again.size());
    est.inliers.clear();
    for (size_t i = 0; i < again.size(); ++i) {
      if (refined.inlier[i]) est.inliers.push_back(again[i]);
    }
  }
  est.ok = static_cast<int>(est.inliers.size()) >= min_inliers;
  if (est.ok) {
    auto& points = s.map.points();
    for (size_t c = 0; c < candidates.size(); ++c) {
      if (in_view[c]) ++points[candidates[c].id].visible;
    }
    for (const FeatureMatch& m : est.inliers) ++points[m.id].found;
  }
  return est;
}

PoseEstimate Relocalise(RgbdSlam::State& s, const FrameFeatures& features) {
  const auto& points = s.map.points();
  std::vector<MatchCandidate> all;
  all.reserve(points.size());
  for (size_t id = 0; id < points.size(); ++id) {
    if (points[id].bad) continue;
    MatchCandidate c;
    c.id = static_cast<int>(id);
    c.point_in_world = points[id].position_in_world;
    c.descriptor = points[id].descriptor.data();
    all.push_back(c);
  }
  MatchOptions mo = Matching(s, s.options.search_radius_px);
  mo.max_distance = std::min(mo.max_distance, 64);
  mo.ratio = std::min(mo.ratio, 0.8);
  const std::vector<FeatureMatch> matches = MatchByDescriptor(all, features, mo);
  PoseEstimate est;
  est.matches = static_cast<int>(matches.size());
  if (est.matches < s.options.relocalisation_min_inliers) return est;
  est = SolvePose(s, features, matches, std::nullopt, s.options.relocalisation_ransac_iterations);
  if (static_cast<int>(est.inliers.size()) < s.options.relocalisation_min_inliers) {
    est.ok = false;
    return est;
  }
  s.last_inlier_points.clear();
  for (const FeatureMatch& m : est.inliers) s.last_inlier_points.push_back(m.id);
  PoseEstimate local =
      TrackLocalMap(s, features, est.sensor_from_world, s.options.relocalisation_min_inliers);
  if (!local.ok) {
    est.ok = false;
    return est;
  }
  return local;
}

}  // namespace reenact::capture::slam
