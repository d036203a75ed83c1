#include "vision/features/orb_features.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <ctime>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "common/error/check.h"
#include "vision/features/depth_plane_fit.h"
#include "vision/features/subpixel_corner.h"

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

double CpuMs() { return 1000.0 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

namespace {

// Hamming distance of two 32-byte descriptors; inlined into both variants below.
__attribute__((always_inline)) inline int HammingDistance32(const uint8_t* a, const uint8_t* b) {
  int d = 0;
  for (int i = 0; i < 32; i += 8) {
    uint64_t x, y;
    std::memcpy(&x, a + i, 8);
    std::memcpy(&y, b + i, 8);
    d += __builtin_popcountll(x ^ y);
  }
  return d;
}

int DistancePortable(const uint8_t* a, const uint8_t* b) { return HammingDistance32(a, b); }

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
// The same with the POPCNT instruction (the build targets baseline x86-64, where
// __builtin_popcountll is a dozen instructions), chosen at run time.
__attribute__((target("popcnt"))) int DistancePopcnt(const uint8_t* a, const uint8_t* b) {
  return HammingDistance32(a, b);
}
const bool kHasPopcnt = __builtin_cpu_supports("popcnt");
#endif

}  // namespace

int DescriptorDistance(const uint8_t* a, const uint8_t* b) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  if (kHasPopcnt) return DistancePopcnt(a, b);
#endif
  return DistancePortable(a, b);
}

namespace {

// Sub-pixel corner (OrbFeatureOptions::subpixel); a keypoint whose refinement leaves its
// window, or enters the excluded (person) area, keeps its position. allowed: empty or
// CV_8UC1 of the image's size, 0 = excluded.
void RefineKeypoint(const cv::Mat& gray, const cv::Mat& allowed, double scale_factor,
                    const SubpixelCornerRefiner& refiner, cv::KeyPoint& kp) {
  const float s = std::pow(static_cast<float>(scale_factor), kp.octave);
  const int half_window = std::max(2, static_cast<int>(std::lround(2 * s)));
  if (kp.pt.x < half_window + 1 || kp.pt.y < half_window + 1 ||
      kp.pt.x > gray.cols - half_window - 2 || kp.pt.y > gray.rows - half_window - 2)
    return;
  const std::optional<Eigen::Vector2f> refined =
      refiner.Refine(gray, {kp.pt.x, kp.pt.y}, half_window);
  if (!refined) return;
  const float dx = refined->x() - kp.pt.x, dy = refined->y() - kp.pt.y;
  if (dx * dx + dy * dy > 4 * s * s) return;
  const int x = static_cast<int>(std::lround(refined->x())),
            y = static_cast<int>(std::lround(refined->y()));
  if (!allowed.empty() && allowed.at<uint8_t>(y, x) == 0) return;
  kp.pt = {refined->x(), refined->y()};
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

// Where ORB may detect: everywhere but the person mask grown by mask_dilation_px; empty (all
// of the image) without a mask.
cv::Mat AllowedMask(const ImageGray8* person_mask, const PinholeCamera& camera,
                    const OrbFeatureOptions& options) {
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
  return allowed;
}

// The kept candidates at their pixel centres (OpenCV scales a level's pixel coordinates by
// s = scale^octave; the level's pixel centre x_l lies at (x_l + 1/2) s - 1/2 in the full
// image, pixel centres at integers).
std::vector<cv::KeyPoint> CentredKeypoints(const std::vector<cv::KeyPoint>& candidates,
                                           const std::vector<int>& kept, double scale_factor) {
  std::vector<cv::KeyPoint> keypoints(kept.size());
  for (size_t k = 0; k < kept.size(); ++k) {
    keypoints[k] = candidates[kept[k]];
    const float half = 0.5f * (std::pow(static_cast<float>(scale_factor), keypoints[k].octave) - 1);
    keypoints[k].pt.x += half;
    keypoints[k].pt.y += half;
  }
  return keypoints;
}

// A keypoint's normalised ray, octave and reliable depth (refined by a local plane fit when
// asked; 0 without).
KeypointObservation ObserveKeypoint(const cv::KeyPoint& kp, const ImageDepthMm& depth,
                                    double depth_scale_m, const PinholeCamera& camera,
                                    const OrbFeatureOptions& options) {
  KeypointObservation obs;
  obs.normalized = camera.Undistort({kp.pt.x, kp.pt.y});
  obs.octave = kp.octave;
  const int x = static_cast<int>(std::lround(kp.pt.x)), y = static_cast<int>(std::lround(kp.pt.y));
  obs.depth_m = ReliableDepth(depth, depth_scale_m, x, y, options);
  if (obs.depth_m > 0 && options.depth_fit_radius_px > 0) {
    const auto fitted = FitDepthPlane(
        depth, depth_scale_m, kp.pt.x, kp.pt.y,
        {.radius_px = options.depth_fit_radius_px, .rel_tolerance = options.depth_edge_ratio});
    if (fitted && *fitted >= options.min_depth_m && *fitted <= options.max_depth_m) {
      obs.depth_m = *fitted;
    }
  }
  return obs;
}

}  // namespace

FrameFeatures ExtractOrbFeatures(const cv::Mat& gray, const ImageDepthMm& depth,
                                 double depth_scale_m, const ImageGray8* person_mask,
                                 const PinholeCamera& camera, const OrbFeatureOptions& options,
                                 OrbTimings* timings) {
  const double t_start = timings != nullptr ? CpuMs() : 0;
  double t_subpixel = 0;
  options.Check();
  REENACT_CHECK(gray.type() == CV_8UC1 && gray.cols == camera.width && gray.rows == camera.height,
                "gray image must be CV_8UC1 of the camera's size");
  REENACT_CHECK(depth.width == camera.width && depth.height == camera.height && depth.channels == 1,
                "depth must be registered to the camera (same size, one channel)");
  REENACT_CHECK(std::isfinite(depth_scale_m) && depth_scale_m > 0, "depth_scale_m must be > 0");

  const cv::Mat allowed = AllowedMask(person_mask, camera, options);

  const int candidates_wanted =
      std::max(options.num_features,
               static_cast<int>(std::lround(options.candidate_factor * options.num_features)));
  cv::Ptr<cv::ORB> orb = cv::ORB::create(
      candidates_wanted, static_cast<float>(options.scale_factor), options.num_levels, 31, 0, 2,
      cv::ORB::HARRIS_SCORE, 31, options.fast_threshold);
  std::vector<cv::KeyPoint> candidates;
  cv::Mat candidate_descriptors;
  const double t_detect = timings != nullptr ? CpuMs() : 0;
  orb->detectAndCompute(gray, allowed, candidates, candidate_descriptors);
  const double t_spread = timings != nullptr ? CpuMs() : 0;
  if (timings != nullptr) timings->detect_ms = t_spread - t_detect;

  FrameFeatures out;
  if (candidates.empty()) {
    out.descriptors = cv::Mat(0, 32, CV_8UC1);
    if (timings != nullptr) timings->rest_ms = CpuMs() - t_start - timings->detect_ms;
    return out;
  }
  const std::vector<int> kept = SpreadOverGrid(candidates, camera.width, camera.height,
                                               options.grid_cell_px, options.num_features);
  if (timings != nullptr) timings->spread_ms = CpuMs() - t_spread;
  out.keypoints.reserve(kept.size());
  out.observations.reserve(kept.size());
  out.points_in_camera.reserve(kept.size());
  out.descriptors = cv::Mat(static_cast<int>(kept.size()), 32, CV_8UC1);
  // Keypoints at their pixel centres, then refined.
  std::vector<cv::KeyPoint> keypoints = CentredKeypoints(candidates, kept, options.scale_factor);
  if (options.subpixel) {
    const double t = timings != nullptr ? CpuMs() : 0;
    const SubpixelCornerRefiner refiner;
    for (cv::KeyPoint& kp : keypoints) {
      RefineKeypoint(gray, allowed, options.scale_factor, refiner, kp);
    }
    if (timings != nullptr) t_subpixel = CpuMs() - t;
  }
  for (size_t k = 0; k < kept.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    std::memcpy(out.descriptors.ptr<uint8_t>(static_cast<int>(k)),
                candidate_descriptors.ptr<uint8_t>(kept[k]), 32);
    const KeypointObservation obs = ObserveKeypoint(kp, depth, depth_scale_m, camera, options);
    out.keypoints.push_back(kp);
    out.observations.push_back(obs);
    out.points_in_camera.push_back(
        obs.depth_m > 0 ? Eigen::Vector3d(obs.normalized.x() * obs.depth_m,
                                          obs.normalized.y() * obs.depth_m, obs.depth_m)
                        : Eigen::Vector3d::Zero());
  }
  if (timings != nullptr) {
    timings->subpixel_ms = t_subpixel;
    timings->rest_ms = CpuMs() - t_start - timings->detect_ms - timings->spread_ms - t_subpixel;
  }
  return out;
}

}  // namespace reenact::vision
