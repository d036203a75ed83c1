#pragma once
// Descriptor matching between a frame's ORB keypoints and map points:
//  - by projection (tracking): each map point is projected with a predicted pose (through
//    the camera's distortion) and compared with the keypoints within a radius of its
//    projection whose pyramid level is within one of the predicted level; the radius grows
//    with the predicted level's scale. A match needs Hamming distance <= max_distance and,
//    when a second candidate exists, best < ratio * second best;
//  - by descriptor alone (relocalisation): every keypoint against every candidate point,
//    the same distance and ratio rules.
// A keypoint keeps at most one point (the closest in descriptor space).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "vision/features/orb_features.h"
#include "common/geometry/pinhole_camera.h"

namespace reenact::vision {

struct MatchOptions {
  double radius_px = 15;      // search radius at level 0, pixels; > 0
  int max_distance = 64;      // Hamming, [0, 256]
  double ratio = 0.85;        // best / second best, (0, 1]
  double scale_factor = 1.2;  // the ORB pyramid's, > 1 (radius scales with it per level)

  void Check() const;
};

struct MatchCandidate {
  int id = 0;  // caller's point id, returned in the match
  Eigen::Vector3d point_in_world = Eigen::Vector3d::Zero();
  const uint8_t* descriptor = nullptr;  // 32 bytes, alive during the call
  int predicted_octave = -1;            // -1 = any level (no level or radius scaling)
};

struct FeatureMatch {
  int id = 0;        // MatchCandidate::id
  int keypoint = 0;  // index into FrameFeatures
  int distance = 0;  // Hamming
};

// Buckets keypoint indices by pixel for radius queries.
class KeypointGrid {
 public:
  KeypointGrid(const FrameFeatures& features, int width, int height, int cell_px = 16);
  // Keypoints within radius of (x, y) (pixel distance).
  void Query(double x, double y, double radius, std::vector<int>& out) const;

 private:
  const FrameFeatures* features_;
  int cell_, cols_, rows_;
  std::vector<std::vector<int>> cells_;
};

// Matches by projection with sensor_from_world. `in_view` (optional, one entry per candidate)
// is set to 1 for candidates that project inside the image in front of the camera.
std::vector<FeatureMatch> MatchByProjection(const std::vector<MatchCandidate>& candidates,
                                            const FrameFeatures& features, const KeypointGrid& grid,
                                            const Eigen::Isometry3d& sensor_from_world,
                                            const PinholeCamera& camera,
                                            const MatchOptions& options,
                                            std::vector<char>* in_view = nullptr);

// Matches by descriptor only (the radius and octave are ignored).
std::vector<FeatureMatch> MatchByDescriptor(const std::vector<MatchCandidate>& candidates,
                                            const FrameFeatures& features,
                                            const MatchOptions& options);

}  // namespace reenact::vision
