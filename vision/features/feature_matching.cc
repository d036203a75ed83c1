#include "vision/features/feature_matching.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "common/error/check.h"

namespace reenact::vision {

void MatchOptions::Check() const {
  REENACT_CHECK(std::isfinite(radius_px) && radius_px > 0, "radius_px must be > 0");
  REENACT_CHECK(max_distance >= 0 && max_distance <= 256, "max_distance in [0, 256]");
  REENACT_CHECK(ratio > 0 && ratio <= 1, "ratio in (0, 1]");
  REENACT_CHECK(std::isfinite(scale_factor) && scale_factor > 1, "scale_factor must be > 1");
}

KeypointGrid::KeypointGrid(const FrameFeatures& features, int width, int height, int cell_px)
    : cell_(cell_px) {
  REENACT_CHECK(width > 0 && height > 0 && cell_px > 0, "bad grid size");
  cols_ = (width + cell_ - 1) / cell_;
  rows_ = (height + cell_ - 1) / cell_;
  const size_t n = features.keypoints.size();
  std::vector<int> cell_of(n);
  cell_start_.assign(static_cast<size_t>(cols_) * rows_ + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    const int cx = std::clamp(static_cast<int>(features.keypoints[i].pt.x) / cell_, 0, cols_ - 1);
    const int cy = std::clamp(static_cast<int>(features.keypoints[i].pt.y) / cell_, 0, rows_ - 1);
    cell_of[i] = cy * cols_ + cx;
    ++cell_start_[cell_of[i] + 1];
  }
  for (size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  index_.resize(n);
  x_.resize(n);
  y_.resize(n);
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (size_t i = 0; i < n; ++i) {
    const int e = fill[cell_of[i]]++;
    index_[e] = static_cast<int>(i);
    x_[e] = features.keypoints[i].pt.x;
    y_[e] = features.keypoints[i].pt.y;
  }
}

void KeypointGrid::Query(double x, double y, double radius, std::vector<int>& out) const {
  out.clear();
  if (!std::isfinite(x) || !std::isfinite(y) || !(radius > 0)) return;
  const int x0 = std::max(0, static_cast<int>(std::floor((x - radius) / cell_)));
  const int x1 = std::min(cols_ - 1, static_cast<int>(std::floor((x + radius) / cell_)));
  const int y0 = std::max(0, static_cast<int>(std::floor((y - radius) / cell_)));
  const int y1 = std::min(rows_ - 1, static_cast<int>(std::floor((y + radius) / cell_)));
  const double r2 = radius * radius;
  for (int cy = y0; cy <= y1; ++cy) {
    // The cells of one row are contiguous entries.
    const int begin = cell_start_[static_cast<size_t>(cy) * cols_ + x0];
    const int end = cell_start_[static_cast<size_t>(cy) * cols_ + x1 + 1];
    for (int e = begin; e < end; ++e) {
      const double dx = x_[e] - x, dy = y_[e] - y;
      if (dx * dx + dy * dy <= r2) out.push_back(index_[e]);
    }
  }
}

namespace {

// Keeps, per keypoint, the candidate match with the smallest distance.
std::vector<FeatureMatch> OnePerKeypoint(std::vector<FeatureMatch> matches, size_t keypoints) {
  std::vector<int> best(keypoints, -1);
  for (size_t m = 0; m < matches.size(); ++m) {
    int& b = best[matches[m].keypoint];
    if (b < 0 || matches[m].distance < matches[b].distance) b = static_cast<int>(m);
  }
  std::vector<FeatureMatch> out;
  for (int b : best) {
    if (b >= 0) out.push_back(matches[b]);
  }
  return out;
}

}  // namespace

std::vector<FeatureMatch> MatchByProjection(const std::vector<MatchCandidate>& candidates,
                                            const FrameFeatures& features, const KeypointGrid& grid,
                                            const Eigen::Isometry3d& sensor_from_world,
                                            const PinholeCamera& camera,
                                            const MatchOptions& options, std::vector<char>* in_view,
                                            MatchStats* stats) {
  options.Check();
  if (in_view != nullptr) in_view->assign(candidates.size(), 0);
  std::vector<FeatureMatch> matches;
  std::vector<int> nearby;
  int64_t num_in_view = 0, comparisons = 0;
  for (size_t c = 0; c < candidates.size(); ++c) {
    const MatchCandidate& cand = candidates[c];
    const Eigen::Vector3d pc = sensor_from_world * cand.point_in_world;
    if (!(pc.z() > 0.05)) continue;
    const std::optional<Eigen::Vector2d> px = camera.Project(pc);
    if (!px || px->x() < 0 || px->y() < 0 || px->x() > camera.width - 1 ||
        px->y() > camera.height - 1) {
      continue;
    }
    if (in_view != nullptr) (*in_view)[c] = 1;
    ++num_in_view;
    const bool any_level = cand.predicted_octave < 0;
    const double radius = options.radius_px *
                          (any_level ? 1.0 : std::pow(options.scale_factor, cand.predicted_octave));
    grid.Query(px->x(), px->y(), radius, nearby);
    int best = std::numeric_limits<int>::max(), second = std::numeric_limits<int>::max();
    int best_keypoint = -1;
    for (int k : nearby) {
      const int octave = features.keypoints[k].octave;
      if (!any_level && (octave < cand.predicted_octave - 1 || octave > cand.predicted_octave + 1))
        continue;
      const int d = DescriptorDistance(cand.descriptor, features.Descriptor(k));
      ++comparisons;
      if (d < best) {
        second = best;
        best = d;
        best_keypoint = k;
      } else if (d < second) {
        second = d;
      }
    }
    if (best_keypoint < 0 || best > options.max_distance) continue;
    if (second != std::numeric_limits<int>::max() && best >= options.ratio * second) continue;
    matches.push_back({cand.id, best_keypoint, best});
  }
  if (stats != nullptr) {
    stats->projected += static_cast<int64_t>(candidates.size());
    stats->in_view += num_in_view;
    stats->comparisons += comparisons;
  }
  return OnePerKeypoint(std::move(matches), features.size());
}

std::vector<FeatureMatch> MatchByDescriptor(const std::vector<MatchCandidate>& candidates,
                                            const FrameFeatures& features,
                                            const MatchOptions& options) {
  options.Check();
  std::vector<FeatureMatch> matches;
  for (size_t k = 0; k < features.size(); ++k) {
    const uint8_t* desc = features.Descriptor(k);
    int best = std::numeric_limits<int>::max(), second = std::numeric_limits<int>::max();
    int best_id = -1;
    for (const MatchCandidate& cand : candidates) {
      const int d = DescriptorDistance(cand.descriptor, desc);
      if (d < best) {
        second = best;
        best = d;
        best_id = cand.id;
      } else if (d < second) {
        second = d;
      }
    }
    if (best_id < 0 || best > options.max_distance) continue;
    if (second != std::numeric_limits<int>::max() && best >= options.ratio * second) continue;
    matches.push_back({best_id, static_cast<int>(k), best});
  }
  return matches;
}

}  // namespace reenact::vision
