#include "vision/features/orb_features.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error/check.h"
#include "vision/features/depth_plane_fit.h"

namespace reenact::vision {

void OrbFeatureOptions::Check() const {
  REENACT_CHECK(num_features >= 1, "num_features must be >= 1");
  REENACT_CHECK(scale_factor > 1 && scale_factor <= 2, "scale_factor must be in (1, 2]");
  REENACT_CHECK(num_levels >= 1 && num_levels <= 16, "num_levels must be in [1, 16]");
  REENACT_CHECK(fast_threshold >= 1 && fast_threshold <= 255, "fast_threshold in [1, 255]");
  REENACT_CHECK(std::isfinite(candidate_factor) && candidate_factor >= 1,
                "candidate_factor must be >= 1");
  REENACT_CHECK(grid_cell_px >= 8, "grid_cell_px must be >= 8");
  REENACT_CHECK(mask_dilation_px >= 0, "mask_dilation_px must be >= 0");
  REENACT_CHECK(min_depth_m > 0 && max_depth_m > min_depth_m && std::isfinite(max_depth_m),
                "need 0 < min_depth_m < max_depth_m");
  REENACT_CHECK(depth_edge_ratio > 0 && depth_edge_ratio < 1, "depth_edge_ratio in (0, 1)");
  REENACT_CHECK(depth_edge_radius_px >= 0 && depth_edge_radius_px <= 16,
                "depth_edge_radius_px in [0, 16]");
  REENACT_CHECK(depth_fit_radius_px >= 0 && depth_fit_radius_px <= 16,
                "depth_fit_radius_px in [0, 16]");
}

int FrameFeatures::CountWithDepth() const {
  int n = 0;
  for (const KeypointObservation& o : observations) n += o.depth_m > 0;
  return n;
}

int DescriptorDistance(const uint8_t* a, const uint8_t* b) {
  int d = 0;
  for (int i = 0; i < 32; i += 8) {
    uint64_t x, y;
    std::memcpy(&x, a + i, 8);
    std::memcpy(&y, b + i, 8);
    d += __builtin_popcountll(x ^ y);
  }
  return d;
}

namespace {

// Sub-pixel corner (OrbFeatureOptions::subpixel); a keypoint whose refinement leaves its
// window, or enters the excluded (person) area, keeps its position. allowed: empty or
// CV_8UC1 of the image's size, 0 = excluded.
void RefineKeypoint(const cv::Mat& gray, const cv::Mat& allowed, double scale_factor,
                    cv::KeyPoint& kp) {
  const float s = std::pow(static_cast<float>(scale_factor), kp.octave);
  const int half_window = std::max(2, static_cast<int>(std::lround(2 * s)));
  if (kp.pt.x < half_window + 1 || kp.pt.y < half_window + 1 ||
      kp.pt.x > gray.cols - half_window - 2 || kp.pt.y > gray.rows - half_window - 2)
    return;
  std::vector<cv::Point2f> point{kp.pt};
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 10, 0.01);
  cv::cornerSubPix(gray, point, {half_window, half_window}, {-1, -1}, criteria);
  const float dx = point[0].x - kp.pt.x, dy = point[0].y - kp.pt.y;
  if (!std::isfinite(dx) || !std::isfinite(dy) || dx * dx + dy * dy > 4 * s * s) return;
  const int x = static_cast<int>(std::lround(point[0].x)),
            y = static_cast<int>(std::lround(point[0].y));
  if (!allowed.empty() && allowed.at<uint8_t>(y, x) == 0) return;
  kp.pt = point[0];
}


// Indices of the kept candidates: cells take turns giving their strongest remaining one.
std::vector<int> SpreadOverGrid(const std::vector<cv::KeyPoint>& candidates, int width, int height,
                                int cell, int keep) {
  const int cols = (width + cell - 1) / cell, rows = (height + cell - 1) / cell;
  std::vector<std::vector<int>> cells(static_cast<size_t>(cols) * rows);
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    const int cx = std::clamp(static_cast<int>(candidates[i].pt.x) / cell, 0, cols - 1);
    const int cy = std::clamp(static_cast<int>(candidates[i].pt.y) / cell, 0, rows - 1);
    cells[static_cast<size_t>(cy) * cols + cx].push_back(i);
  }
  for (auto& c : cells) {
    std::stable_sort(c.begin(), c.end(),
                     [&](int a, int b) { return candidates[a].response > candidates[b].response; });
  }
  std::vector<int> kept;
  for (size_t round = 0; static_cast<int>(kept.size()) < keep; ++round) {
    bool any = false;
    for (const auto& c : cells) {
      if (round < c.size() && static_cast<int>(kept.size()) < keep) {
        kept.push_back(c[round]);
        any = true;
      }
    }
    if (!any) break;
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}

// Depth (metres) at a keypoint, 0 when missing, out of range or on a depth edge.
double ReliableDepth(const ImageDepthMm& depth, double depth_scale_m, int x, int y,
                     const OrbFeatureOptions& o) {
  if (!depth.Contains(x, y) || depth.at(x, y) == 0) return 0;
  const double centre = depth.at(x, y) * depth_scale_m;
  if (centre < o.min_depth_m || centre > o.max_depth_m) return 0;
  const int r = o.depth_edge_radius_px;
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      if (!depth.Contains(x + dx, y + dy)) continue;
      const uint16_t v = depth.at(x + dx, y + dy);
      if (v == 0) continue;
      if (std::abs(v * depth_scale_m - centre) > o.depth_edge_ratio * centre) return 0;
    }
  }
  return centre;
}

}  // namespace

FrameFeatures ExtractOrbFeatures(const cv::Mat& gray, const ImageDepthMm& depth,
                                 double depth_scale_m, const ImageGray8* person_mask,
                                 const PinholeCamera& camera, const OrbFeatureOptions& options) {
  options.Check();
  REENACT_CHECK(gray.type() == CV_8UC1 && gray.cols == camera.width && gray.rows == camera.height,
                "gray image must be CV_8UC1 of the camera's size");
  REENACT_CHECK(depth.width == camera.width && depth.height == camera.height && depth.channels == 1,
                "depth must be registered to the camera (same size, one channel)");
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0, "depth_scale_m must be > 0");

  cv::Mat allowed;
  if (person_mask != nullptr && !person_mask->empty()) {
    REENACT_CHECK(person_mask->width == camera.width && person_mask->height == camera.height &&
                      person_mask->channels == 1,
                  "person mask must be one channel of the camera's size");
    const cv::Mat person(person_mask->height, person_mask->width, CV_8UC1,
                         const_cast<uint8_t*>(person_mask->data.data()));
    cv::Mat grown = person > 127;
    if (options.mask_dilation_px > 0) {
      const int k = 2 * options.mask_dilation_px + 1;
      cv::dilate(grown, grown, cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
    }
    allowed = cv::Mat(camera.height, camera.width, CV_8UC1, cv::Scalar(255));
    allowed.setTo(0, grown);
  }

  const int candidates_wanted =
      std::max(options.num_features,
               static_cast<int>(std::lround(options.candidate_factor * options.num_features)));
  cv::Ptr<cv::ORB> orb = cv::ORB::create(
      candidates_wanted, static_cast<float>(options.scale_factor), options.num_levels, 31, 0, 2,
      cv::ORB::HARRIS_SCORE, 31, options.fast_threshold);
  std::vector<cv::KeyPoint> candidates;
  cv::Mat candidate_descriptors;
  orb->detectAndCompute(gray, allowed, candidates, candidate_descriptors);

  FrameFeatures out;
  if (candidates.empty()) {
    out.descriptors = cv::Mat(0, 32, CV_8UC1);
    return out;
  }
  const std::vector<int> kept = SpreadOverGrid(candidates, camera.width, camera.height,
                                               options.grid_cell_px, options.num_features);
  out.keypoints.reserve(kept.size());
  out.observations.reserve(kept.size());
  out.points_in_camera.reserve(kept.size());
  out.descriptors = cv::Mat(static_cast<int>(kept.size()), 32, CV_8UC1);
  for (size_t k = 0; k < kept.size(); ++k) {
    cv::KeyPoint kp = candidates[kept[k]];
    // OpenCV scales a level's pixel coordinates by s = scale^octave; the level's pixel centre
    // x_l lies at (x_l + 1/2) s - 1/2 in the full image (pixel centres at integers).
    const float half = 0.5f * (std::pow(static_cast<float>(options.scale_factor), kp.octave) - 1);
    kp.pt.x += half;
    kp.pt.y += half;
    if (options.subpixel) RefineKeypoint(gray, allowed, options.scale_factor, kp);
    candidate_descriptors.row(kept[k]).copyTo(out.descriptors.row(static_cast<int>(k)));
    KeypointObservation obs;
    obs.normalized = camera.Undistort({kp.pt.x, kp.pt.y});
    obs.octave = kp.octave;
    const int x = static_cast<int>(std::lround(kp.pt.x)),
              y = static_cast<int>(std::lround(kp.pt.y));
    obs.depth_m = ReliableDepth(depth, depth_scale_m, x, y, options);
    if (obs.depth_m > 0 && options.depth_fit_radius_px > 0) {
      const auto fitted = FitDepthPlane(depth, depth_scale_m, kp.pt.x, kp.pt.y,
                                        {.radius_px = options.depth_fit_radius_px,
                                         .rel_tolerance = options.depth_edge_ratio});
      if (fitted && *fitted >= options.min_depth_m && *fitted <= options.max_depth_m) {
        obs.depth_m = *fitted;
      }
    }
    out.keypoints.push_back(kp);
    out.observations.push_back(obs);
    out.points_in_camera.push_back(
        obs.depth_m > 0 ? Eigen::Vector3d(obs.normalized.x() * obs.depth_m,
                                          obs.normalized.y() * obs.depth_m, obs.depth_m)
                        : Eigen::Vector3d::Zero());
  }
  return out;
}

}  // namespace reenact::vision
