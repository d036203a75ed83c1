#pragma once
// Builds the clip's relocalisation map from keyframes: ORB features on the static background
// only (the person mask, dilated, is excluded so the moving subject never enters the map),
// lifted to 3D with the registered depth where it is reliable (vision/features/orb_features.h)
// and moved into the world frame with the keyframe's pose. A feature that lands within
// merge_radius_m of an existing map point with a similar descriptor (Hamming distance <=
// merge_max_hamming) counts as another observation of it.

#include <Eigen/Geometry>
#include <unordered_map>

#include "common/geometry/pinhole_camera.h"
#include "common/image/image.h"
#include "proto/clip/map_codec.h"
#include "vision/features/orb_features.h"

namespace reenact::capture {

// The map's features: ORB spread over the image, depth off depth edges, sub-pixel keypoints
// (a map point's position is only as good as its keypoint: a pixel is 1 cm at 5 m).
vision::OrbFeatureOptions DefaultMapFeatures();

struct BackgroundMapOptions {
  // Features per keyframe (vision/features/orb_features.h); num_features (default 1000),
  // mask_dilation_px (15: the person mask grown), depth range (0.3-8 m), subpixel (on).
  vision::OrbFeatureOptions features = DefaultMapFeatures();
  double merge_radius_m = 0.02;  // > 0
  int merge_max_hamming = 64;    // [0, 256]
  size_t max_points = 50000;     // the map keeps at most this many points

  void Check() const;
};

class BackgroundMapBuilder {
 public:
  explicit BackgroundMapBuilder(BackgroundMapOptions options = {});
  // Goes on from an existing map (e.g. SLAM's): its points merge with the ones added later.
  BackgroundMapBuilder(proto::ClipMap seed, BackgroundMapOptions options);

  // Adds one keyframe; mask may be empty (no person known).
  void AddKeyframe(const ImageRgb8& color, const ImageDepthMm& depth, double depth_scale_m,
                   const ImageGray8& person_mask, const PinholeCamera& camera,
                   const Eigen::Isometry3d& world_from_sensor);

  // One feature (world frame, ORB descriptor): another observation of a map point within
  // merge_radius_m with a similar descriptor, else a new point (while below max_points).
  void AddPoint(const Eigen::Vector3d& point_in_world, const uint8_t* descriptor);

  size_t point_count() const { return map_.points.size(); }
  proto::ClipMap Finish() &&;

 private:
  BackgroundMapOptions options_;
  proto::ClipMap map_;
  std::unordered_multimap<int64_t, size_t> grid_;  // voxel key -> point index
};

}  // namespace reenact::capture
