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

#include "common/geometry/pinhole_camera.h"
#include "vision/features/orb_features.h"

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

// Buckets keypoint indices by pixel for radius queries. The cells are stored flat (each
// cell's keypoints contiguous, with their positions beside them), so a query reads a few
// short runs of memory.
class KeypointGrid {
 public:
  KeypointGrid(const FrameFeatures& features, int width, int height, int cell_px = 16);
  // Keypoints within radius of (x, y) (pixel distance), cell by cell, in each cell in
  // increasing index.
  void Query(double x, double y, double radius, std::vector<int>& out) const;

 private:
  int cell_, cols_, rows_;
  std::vector<int> cell_start_;  // per cell, its first entry; one more at the end
  std::vector<int> index_;       // keypoint index per entry
  std::vector<float> x_, y_;     // keypoint position per entry
};

// Work done by one matching call (added to, not reset).
struct MatchStats {
  int64_t projected = 0;    // candidates projected
  int64_t in_view = 0;      // of them, inside the image in front of the camera
  int64_t comparisons = 0;  // descriptor distances computed
};

// Matches by projection with sensor_from_world. `in_view` (optional, one entry per candidate)
// is set to 1 for candidates that project inside the image in front of the camera. `stats`
// (optional) is added to.
std::vector<FeatureMatch> MatchByProjection(const std::vector<MatchCandidate>& candidates,
                                            const FrameFeatures& features, const KeypointGrid& grid,
                                            const Eigen::Isometry3d& sensor_from_world,
                                            const PinholeCamera& camera,
                                            const MatchOptions& options,
                                            std::vector<char>* in_view = nullptr,
                                            MatchStats* stats = nullptr);

// Matches by descriptor only (the radius and octave are ignored).
std::vector<FeatureMatch> MatchByDescriptor(const std::vector<MatchCandidate>& candidates,
                                            const FrameFeatures& features,
                                            const MatchOptions& options);

}  // namespace reenact::vision
