#include "capture-client/map/background_map_builder.h"

#include <cmath>
#include <cstring>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

int64_t VoxelKey(int x, int y, int z) {
  return (static_cast<int64_t>(x) & 0x1FFFFF) | ((static_cast<int64_t>(y) & 0x1FFFFF) << 21) |
         ((static_cast<int64_t>(z) & 0x1FFFFF) << 42);
}

int Hamming(const std::array<uint8_t, 32>& a, const uint8_t* b) {
  int d = 0;
  for (int i = 0; i < 32; ++i) d += __builtin_popcount(static_cast<unsigned>(a[i] ^ b[i]));
  return d;
}

}  // namespace

void BackgroundMapOptions::Check() const {
  REENACT_CHECK(features_per_keyframe >= 1, "features_per_keyframe must be >= 1");
  REENACT_CHECK(mask_dilation_px >= 0, "mask_dilation_px must be >= 0");
  REENACT_CHECK(min_depth_m > 0 && max_depth_m > min_depth_m, "need 0 < min_depth < max_depth");
  REENACT_CHECK(merge_radius_m > 0, "merge_radius_m must be > 0");
  REENACT_CHECK(merge_max_hamming >= 0 && merge_max_hamming <= 256, "merge_max_hamming in [0,256]");
  REENACT_CHECK(max_points >= 1, "max_points must be >= 1");
}

BackgroundMapBuilder::BackgroundMapBuilder(BackgroundMapOptions options) : options_(options) {
  options_.Check();
}

void BackgroundMapBuilder::AddKeyframe(const ImageRgb8& color, const ImageDepthMm& depth,
                                       double depth_scale_m, const ImageGray8& person_mask,
                                       const PinholeCamera& camera,
                                       const Eigen::Isometry3d& world_from_sensor) {
  REENACT_CHECK(color.channels == 3 && depth.width == color.width && depth.height == color.height,
                "colour and registered depth must share one grid");
  const cv::Mat rgb(color.height, color.width, CV_8UC3, const_cast<uint8_t*>(color.data.data()));
  cv::Mat gray;
  cv::cvtColor(rgb, gray, cv::COLOR_RGB2GRAY);
  cv::Mat allowed(color.height, color.width, CV_8UC1, cv::Scalar(255));
  if (!person_mask.empty()) {
    REENACT_CHECK(person_mask.width == color.width && person_mask.height == color.height,
                  "mask must match the colour image");
    cv::Mat person(person_mask.height, person_mask.width, CV_8UC1,
                   const_cast<uint8_t*>(person_mask.data.data()));
    cv::Mat grown;
    const int k = 2 * options_.mask_dilation_px + 1;
    cv::dilate(person > 127, grown, cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
    allowed.setTo(0, grown);
  }
  cv::Ptr<cv::ORB> orb = cv::ORB::create(options_.features_per_keyframe);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb->detectAndCompute(gray, allowed, keypoints, descriptors);
  // OpenCV places a level's pixel x_l at x_l s (s = scale^octave), biased by (s - 1) / 2
  // towards the top-left; its centre lies at (x_l + 1/2) s - 1/2 (as vision/features does).
  for (cv::KeyPoint& kp : keypoints) {
    const float half = 0.5f * (std::pow(orb->getScaleFactor(), static_cast<float>(kp.octave)) - 1);
    kp.pt.x += half;
    kp.pt.y += half;
  }

  const double cell = options_.merge_radius_m;
  for (size_t i = 0; i < keypoints.size() && map_.points.size() < options_.max_points; ++i) {
    const int x = static_cast<int>(std::lround(keypoints[i].pt.x));
    const int y = static_cast<int>(std::lround(keypoints[i].pt.y));
    if (!depth.Contains(x, y) || depth.at(x, y) == 0) continue;
    const double z = depth.at(x, y) * depth_scale_m;
    if (z < options_.min_depth_m || z > options_.max_depth_m) continue;
    const Eigen::Vector3d p = world_from_sensor *
                              camera.Unproject({keypoints[i].pt.x, keypoints[i].pt.y}, z);
    const uint8_t* desc = descriptors.ptr<uint8_t>(static_cast<int>(i));

    const int vx = static_cast<int>(std::floor(p.x() / cell));
    const int vy = static_cast<int>(std::floor(p.y() / cell));
    const int vz = static_cast<int>(std::floor(p.z() / cell));
    bool merged = false;
    for (int dx = -1; dx <= 1 && !merged; ++dx)
      for (int dy = -1; dy <= 1 && !merged; ++dy)
        for (int dz = -1; dz <= 1 && !merged; ++dz) {
          auto [lo, hi] = grid_.equal_range(VoxelKey(vx + dx, vy + dy, vz + dz));
          for (auto it = lo; it != hi; ++it) {
            proto::MapPoint& mp = map_.points[it->second];
            if ((mp.position_in_world - p).norm() <= cell &&
                Hamming(mp.descriptor, desc) <= options_.merge_max_hamming) {
              ++mp.observations;
              merged = true;
              break;
            }
          }
        }
    if (merged) continue;
    proto::MapPoint mp;
    mp.position_in_world = p;
    std::memcpy(mp.descriptor.data(), desc, 32);
    mp.observations = 1;
    grid_.emplace(VoxelKey(vx, vy, vz), map_.points.size());
    map_.points.push_back(mp);
  }
}

proto::ClipMap BackgroundMapBuilder::Finish() && { return std::move(map_); }

}  // namespace reenact::capture
