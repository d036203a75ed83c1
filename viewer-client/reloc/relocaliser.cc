#include "viewer-client/reloc/relocaliser.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

#include "common/error/check.h"
#include "common/estimate/ransac.h"
#include "common/geometry/voxel_key.h"
#include "vision/pose/pnp_estimator.h"

namespace reenact::viewer {
namespace {

// Map points closer than this are one place seen in several views.
constexpr double kSamePointRadiusM = 0.02;
// Nearest descriptors looked at for a second best of another place.
constexpr int kNearestDescriptors = 6;

// Per point, the index of the first point within radius_m of it (itself when none is).
std::vector<int> GroupNearbyPoints(const proto::ClipMap& map, double radius_m) {
  std::unordered_multimap<int64_t, int> cells;
  std::vector<int> group(map.points.size());
  for (size_t i = 0; i < map.points.size(); ++i) {
    const Eigen::Vector3d& p = map.points[i].position_in_world;
    const Eigen::Vector3i cell = VoxelCell(p, radius_m);
    group[i] = static_cast<int>(i);
    for (int dx = -1; dx <= 1 && group[i] == static_cast<int>(i); ++dx)
      for (int dy = -1; dy <= 1 && group[i] == static_cast<int>(i); ++dy)
        for (int dz = -1; dz <= 1 && group[i] == static_cast<int>(i); ++dz) {
          auto [lo, hi] = cells.equal_range(VoxelKey(cell + Eigen::Vector3i(dx, dy, dz)));
          for (auto it = lo; it != hi; ++it) {
            if ((map.points[it->second].position_in_world - p).norm() <= radius_m) {
              group[i] = group[it->second];
              break;
            }
          }
        }
    cells.emplace(VoxelKey(cell), static_cast<int>(i));
  }
  return group;
}

}  // namespace

std::string_view RelocStatusName(RelocStatus status) {
  switch (status) {
    case RelocStatus::kRelocalised:
      return "relocalised";
    case RelocStatus::kTracked:
      return "tracked";
    case RelocStatus::kLost:
      return "lost";
  }
  return "lost";
}

void RelocaliserOptions::Check() const {
  features.Check();
  smoothing.Check();
  REENACT_CHECK(min_map_points >= 4, "min_map_points must be >= 4");
  REENACT_CHECK(reloc_max_distance >= 0 && reloc_max_distance <= 256,
                "reloc_max_distance must be in [0, 256]");
  REENACT_CHECK(reloc_ratio > 0 && reloc_ratio <= 1, "reloc_ratio must be in (0, 1]");
  REENACT_CHECK(std::isfinite(ransac_max_error_px) && ransac_max_error_px > 0,
                "ransac_max_error_px must be > 0");
  REENACT_CHECK(ransac_max_iterations >= 1 && ransac_max_iterations <= 100000,
                "ransac_max_iterations must be in [1, 100000]");
  REENACT_CHECK(reloc_min_inliers >= 4, "reloc_min_inliers must be >= 4");
  REENACT_CHECK(std::isfinite(search_radius_px) && search_radius_px > 0,
                "search_radius_px must be > 0");
  REENACT_CHECK(std::isfinite(wide_search_radius_px) && wide_search_radius_px >= search_radius_px,
                "wide_search_radius_px must be >= search_radius_px");
  REENACT_CHECK(track_max_distance >= 0 && track_max_distance <= 256,
                "track_max_distance must be in [0, 256]");
  REENACT_CHECK(track_ratio > 0 && track_ratio <= 1, "track_ratio must be in (0, 1]");
  REENACT_CHECK(track_min_inliers >= 4, "track_min_inliers must be >= 4");
  noise.Check();
  refinement.Check();
}

Expected<Relocaliser> Relocaliser::Create(proto::ClipMap map, const PinholeCamera& camera,
                                          const RelocaliserOptions& options) {
  options.Check();
  if (map.points.empty()) {
    return MakeError("invalid_argument",
                     "the clip's map is empty: it cannot be relocalised against; record the clip "
                     "again with the textured background in view");
  }
  if (static_cast<int>(map.points.size()) < options.min_map_points) {
    return MakeError(
        "invalid_argument",
        "the clip's map is too small to relocalise: " + std::to_string(map.points.size()) +
            " points, at least " + std::to_string(options.min_map_points) +
            " are needed; record the clip again with more textured background in "
            "view");
  }
  try {
    camera.Check();
  } catch (const CheckError& e) {
    return MakeError("invalid_argument", std::string("invalid viewer camera: ") + e.what());
  }
  return Relocaliser(std::move(map), camera, options);
}

Relocaliser::Relocaliser(proto::ClipMap map, const PinholeCamera& camera,
                         const RelocaliserOptions& options)
    : map_(std::move(map)),
      camera_(camera),
      options_(options),
      no_depth_(camera.width, camera.height, 1, 0),
      smoother_(options.smoothing) {
  candidates_.reserve(map_.points.size());
  for (size_t i = 0; i < map_.points.size(); ++i) {
    vision::MatchCandidate c;
    c.id = static_cast<int>(i);
    c.point_in_world = map_.points[i].position_in_world;
    c.descriptor = map_.points[i].descriptor.data();
    candidates_.push_back(c);
  }
  map_descriptors_ = cv::Mat(static_cast<int>(map_.points.size()), 32, CV_8UC1);
  for (size_t i = 0; i < map_.points.size(); ++i) {
    std::copy(map_.points[i].descriptor.begin(), map_.points[i].descriptor.end(),
              map_descriptors_.ptr<uint8_t>(static_cast<int>(i)));
  }
  matcher_ = cv::BFMatcher::create(cv::NORM_HAMMING);
  point_group_ = GroupNearbyPoints(map_, kSamePointRadiusM);
}

void Relocaliser::Reset() {
  last_.reset();
  before_last_.reset();
  smoother_.Reset();
}

Expected<RelocFrameResult> Relocaliser::ProcessFrame(const ImageRgb8& image) {
  if (image.empty() || image.channels != 3) {
    return MakeError("invalid_argument", "the viewer frame is empty or not RGB (3 channels)");
  }
  const cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.data.data()));
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_RGB2GRAY);
  return ProcessFrame(gray);
}

Expected<RelocFrameResult> Relocaliser::ProcessFrame(const cv::Mat& image) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = vision::CpuMs();
  if (image.empty()) return MakeError("invalid_argument", "the viewer frame is empty");
  if (image.cols != camera_.width || image.rows != camera_.height) {
    return MakeError("invalid_argument",
                     "the viewer frame is " + std::to_string(image.cols) + "x" +
                         std::to_string(image.rows) + " but the camera calibration is for " +
                         std::to_string(camera_.width) + "x" + std::to_string(camera_.height) +
                         "; use the calibration of this camera at this resolution");
  }
  cv::Mat gray;
  if (image.type() == CV_8UC1) {
    gray = image;
  } else if (image.type() == CV_8UC3) {
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  } else {
    return MakeError("invalid_argument",
                     "the viewer frame must be 8-bit grey or 8-bit BGR (OpenCV type " +
                         std::to_string(image.type()) + " given)");
  }
  ++frames_;
  RelocFrameResult result;
  RelocStageTimes& cpu = result.cpu;
  double t = vision::CpuMs();
  const vision::FrameFeatures features = vision::ExtractOrbFeatures(
      gray, no_depth_, 0.001, nullptr, camera_, options_.features, &cpu.orb);
  cpu.features_ms = vision::CpuMs() - t;
  t = vision::CpuMs();
  const vision::KeypointGrid grid(features, camera_.width, camera_.height);
  cpu.grid_ms = vision::CpuMs() - t;

  result.features = static_cast<int>(features.size());
  std::optional<Estimate> estimate;
  if (last_) {
    const Eigen::Isometry3d predicted =
        before_last_ ? Eigen::Isometry3d((*last_) * before_last_->inverse() * (*last_)) : *last_;
    Estimate tracked = TrackFrom(predicted, features, grid, cpu);
    if (tracked.inliers >= options_.track_min_inliers) {
      estimate = tracked;
      result.status = RelocStatus::kTracked;
    }
  }
  if (!estimate) {
    estimate = Relocalise(features, grid, result.reason, cpu);
    if (estimate) result.status = RelocStatus::kRelocalised;
  }
  if (estimate) {
    // The search follows the frames' own poses (a smoothed prediction lags behind fast
    // turns); what the user sees is smoothed.
    before_last_ = last_;
    last_ = estimate->viewer_from_world;
    if (options_.smooth) {
      t = vision::CpuMs();
      if (result.status == RelocStatus::kRelocalised) smoother_.Reset();
      estimate->viewer_from_world =
          smoother_.Update(estimate->viewer_from_world, estimate->information);
      cpu.smooth_ms = vision::CpuMs() - t;
    }
    result.viewer_from_world = estimate->viewer_from_world;
    result.matches = estimate->matches;
    result.inliers = estimate->inliers;
  } else {
    result.status = RelocStatus::kLost;
    Reset();
  }
  cpu.total_ms = vision::CpuMs() - cpu_start;
  result.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

Relocaliser::Estimate Relocaliser::Refine(const Eigen::Isometry3d& start,
                                          const vision::FrameFeatures& features,
                                          const std::vector<vision::FeatureMatch>& matches,
                                          RelocStageTimes& cpu) const {
  const double t = vision::CpuMs();
  std::vector<vision::PointObservation> observations;
  observations.reserve(matches.size());
  for (const vision::FeatureMatch& m : matches) {
    observations.push_back(
        {map_.points[m.id].position_in_world, features.observations[m.keypoint]});
  }
  const vision::PoseRefinementResult refined = vision::RefinePose(
      start, observations, camera_.fx, camera_.fy, options_.noise, options_.refinement);
  cpu.refine_ms += vision::CpuMs() - t;
  return {refined.sensor_from_world, static_cast<int>(matches.size()), refined.num_inliers,
          refined.information};
}

Relocaliser::Estimate Relocaliser::TrackFrom(const Eigen::Isometry3d& predicted,
                                             const vision::FrameFeatures& features,
                                             const vision::KeypointGrid& grid,
                                             RelocStageTimes& cpu) const {
  vision::MatchOptions match;
  match.max_distance = options_.track_max_distance;
  match.ratio = options_.track_ratio;
  match.scale_factor = options_.features.scale_factor;
  match.radius_px = options_.search_radius_px;
  double t = vision::CpuMs();
  std::vector<vision::FeatureMatch> matches = vision::MatchByProjection(
      candidates_, features, grid, predicted, camera_, match, nullptr, &cpu.matching);
  if (static_cast<int>(matches.size()) < 2 * options_.track_min_inliers) {
    match.radius_px = options_.wide_search_radius_px;
    std::vector<vision::FeatureMatch> wide = vision::MatchByProjection(
        candidates_, features, grid, predicted, camera_, match, nullptr, &cpu.matching);
    if (wide.size() > matches.size()) matches = std::move(wide);
  }
  cpu.match_ms += vision::CpuMs() - t;
  Estimate first = Refine(predicted, features, matches, cpu);
  if (first.inliers < options_.track_min_inliers) return first;
  // A tighter search at the refined pose: more matches, fewer wrong ones.
  match.radius_px = 0.3 * options_.search_radius_px;
  t = vision::CpuMs();
  const std::vector<vision::FeatureMatch> again = vision::MatchByProjection(
      candidates_, features, grid, first.viewer_from_world, camera_, match, nullptr, &cpu.matching);
  cpu.match_ms += vision::CpuMs() - t;
  Estimate second = Refine(first.viewer_from_world, features, again, cpu);
  return second.inliers >= first.inliers ? second : first;
}

std::optional<Relocaliser::Estimate> Relocaliser::Relocalise(const vision::FrameFeatures& features,
                                                             const vision::KeypointGrid& grid,
                                                             std::string& reason,
                                                             RelocStageTimes& cpu) {
  const double t = vision::CpuMs();
  if (features.size() == 0) {
    reason = "no features in the frame (too dark, blurred or textureless)";
    return std::nullopt;
  }
  // The nearest map descriptors of every keypoint (OpenCV's vectorised Hamming search,
  // several times faster than vision::MatchByDescriptor on maps of thousands). The second
  // best is the nearest descriptor of another place: a point the map holds in several views
  // (capture-client/map/virtual_views.h) does not compete with itself.
  std::vector<std::vector<cv::DMatch>> nearest;
  matcher_->knnMatch(features.descriptors, map_descriptors_, nearest, kNearestDescriptors);
  std::vector<vision::FeatureMatch> matches;
  for (const std::vector<cv::DMatch>& n : nearest) {
    if (n.empty() || n[0].distance > options_.reloc_max_distance) continue;
    const int place = point_group_[n[0].trainIdx];
    const auto other = std::find_if(n.begin() + 1, n.end(), [&](const cv::DMatch& m) {
      return point_group_[m.trainIdx] != place;
    });
    if (other != n.end() && n[0].distance >= options_.reloc_ratio * other->distance) continue;
    matches.push_back({n[0].trainIdx, n[0].queryIdx, static_cast<int>(n[0].distance)});
  }
  if (static_cast<int>(matches.size()) < options_.reloc_min_inliers) {
    reason = "too few matches with the map (" + std::to_string(matches.size()) + " of " +
             std::to_string(options_.reloc_min_inliers) + " needed)";
    return std::nullopt;
  }
  std::vector<vision::PnpEstimator::Sample> samples;
  samples.reserve(matches.size());
  for (const vision::FeatureMatch& m : matches) {
    samples.push_back(
        {map_.points[m.id].position_in_world, features.observations[m.keypoint].normalized});
  }
  RansacOptions ransac;
  ransac.max_error = options_.ransac_max_error_px;
  ransac.max_iterations = options_.ransac_max_iterations;
  ransac.min_iterations = std::min(20, options_.ransac_max_iterations);
  ransac.seed = options_.seed + frames_;
  const vision::PnpEstimator estimator{camera_.fx, camera_.fy};
  const RansacResult<Eigen::Isometry3d> found = Ransac(estimator, samples, ransac);
  if (!found.success || static_cast<int>(found.inliers.size()) < options_.reloc_min_inliers) {
    reason = "no pose agrees with enough matches (" + std::to_string(found.inliers.size()) +
             " inliers of " + std::to_string(options_.reloc_min_inliers) + " needed)";
    return std::nullopt;
  }
  std::vector<vision::FeatureMatch> inlier_matches;
  inlier_matches.reserve(found.inliers.size());
  for (size_t i : found.inliers) inlier_matches.push_back(matches[i]);
  cpu.relocalise_ms += vision::CpuMs() - t;
  const Estimate refined = Refine(found.model, features, inlier_matches, cpu);
  // Confirm with guided matching over the whole map, as tracking would.
  Estimate confirmed = TrackFrom(refined.viewer_from_world, features, grid, cpu);
  if (confirmed.inliers < options_.reloc_min_inliers) {
    reason = "the pose found is not confirmed by the map (" + std::to_string(confirmed.inliers) +
             " inliers of " + std::to_string(options_.reloc_min_inliers) + " needed)";
    return std::nullopt;
  }
  return confirmed;
}

}  // namespace reenact::viewer
