#include "capture-client/map/background_map_builder.h"

#include <cmath>
#include <cstring>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "common/error/check.h"
#include "common/geometry/voxel_key.h"

namespace reenact::capture {
namespace {

int Hamming(const std::array<uint8_t, 32>& a, const uint8_t* b) {
  int d = 0;
  for (int i = 0; i < 32; ++i) d += __builtin_popcount(static_cast<unsigned>(a[i] ^ b[i]));
  return d;
}

}  // namespace

vision::OrbFeatureOptions DefaultMapFeatures() {
  vision::OrbFeatureOptions o;
  o.max_depth_m = 8.0;
  o.subpixel = true;
  o.depth_fit_radius_px = 4;
  return o;
}

void BackgroundMapOptions::Check() const {
  features.Check();
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
  const vision::FrameFeatures features = vision::ExtractOrbFeatures(
      gray, depth, depth_scale_m, &person_mask, camera, options_.features);

  for (size_t i = 0; i < features.size(); ++i) {
    if (features.observations[i].depth_m <= 0) continue;
    AddPoint(world_from_sensor * features.points_in_camera[i], features.Descriptor(i));
  }
}

BackgroundMapBuilder::BackgroundMapBuilder(proto::ClipMap seed, BackgroundMapOptions options)
    : BackgroundMapBuilder(options) {
  map_ = std::move(seed);
  for (size_t i = 0; i < map_.points.size(); ++i) {
    grid_.emplace(VoxelKey(VoxelCell(map_.points[i].position_in_world, options_.merge_radius_m)),
                  i);
  }
}

void BackgroundMapBuilder::AddPoint(const Eigen::Vector3d& p, const uint8_t* desc) {
  const Eigen::Vector3i cell = VoxelCell(p, options_.merge_radius_m);
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        auto [lo, hi] = grid_.equal_range(VoxelKey(cell + Eigen::Vector3i(dx, dy, dz)));
        for (auto it = lo; it != hi; ++it) {
          proto::MapPoint& mp = map_.points[it->second];
          if ((mp.position_in_world - p).norm() <= options_.merge_radius_m &&
              Hamming(mp.descriptor, desc) <= options_.merge_max_hamming) {
            ++mp.observations;
            return;
          }
        }
      }
  if (map_.points.size() >= options_.max_points) return;
  proto::MapPoint mp;
  mp.position_in_world = p;
  std::memcpy(mp.descriptor.data(), desc, 32);
  mp.observations = 1;
  grid_.emplace(VoxelKey(cell), map_.points.size());
  map_.points.push_back(mp);
}

proto::ClipMap BackgroundMapBuilder::Finish() && { return std::move(map_); }

}  // namespace reenact::capture
