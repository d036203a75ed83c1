#pragma once
// The SLAM map: keyframes (pose, features, which map point each keypoint observes) and map
// points (world position, representative ORB descriptor, the keyframes that observe them,
// and how often tracking predicted them in view and found them). World frame: the SLAM
// map's frame (DESIGN.md); positions in metres.
//
// What a clip stores is a filtered copy (ExportClipMap): well-observed points only, with
// their descriptors and observation counts, in the format of proto/clip/map_codec.h.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "capture-client/slam/vision_names.h"
#include "proto/clip/map_codec.h"

namespace reenact::capture::slam {

struct Keyframe {
  int frame_index = 0;  // index of the frame in the input stream
  double timestamp_s = 0;
  Eigen::Isometry3d sensor_from_world = Eigen::Isometry3d::Identity();
  std::vector<KeypointObservation> observations;  // per keypoint
  cv::Mat descriptors;                            // CV_8UC1, one 32-byte row per keypoint
  std::vector<int> point_ids;                     // per keypoint: map point id, -1 = none

  Eigen::Isometry3d world_from_sensor() const { return sensor_from_world.inverse(); }
  Eigen::Vector3d CentreInWorld() const { return world_from_sensor().translation(); }
};

struct MapPoint {
  Eigen::Vector3d position_in_world = Eigen::Vector3d::Zero();
  std::array<uint8_t, 32> descriptor{};           // the medoid of the observing descriptors
  std::vector<std::pair<int, int>> observations;  // (keyframe id, keypoint index)
  int created_by_keyframe = 0;
  double reference_distance_m = 1;  // distance to the creating keyframe's centre
  int reference_octave = 0;         // pyramid level of the creating keypoint
  int visible = 1;                  // frames that predicted it in view
  int found = 1;                    // frames that matched it as an inlier
  bool bad = false;                 // culled: no longer used or exported

  double FoundRatio() const { return visible > 0 ? static_cast<double>(found) / visible : 0; }
};

struct MapExportOptions {
  int min_observations = 3;       // keyframes that saw the point, >= 1
  double min_found_ratio = 0.25;  // found / visible, [0, 1]

  void Check() const;
};

class SlamMap {
 public:
  // Adds a keyframe (point_ids sized to its keypoints, all -1) and returns its id.
  int AddKeyframe(Keyframe keyframe);
  // Adds a point first seen by keypoint `keypoint` of keyframe `keyframe_id`; returns its id.
  int AddPoint(const Eigen::Vector3d& position_in_world, int keyframe_id, int keypoint);
  // Records that keypoint `keypoint` of keyframe `keyframe_id` observes point `point_id`
  // (ignored when the keypoint already observes a point or the point already has an
  // observation in that keyframe).
  void AddObservation(int point_id, int keyframe_id, int keypoint);
  // Removes one observation; a point left without observations becomes bad.
  void RemoveObservation(int point_id, int keyframe_id);
  // Marks a point bad and detaches it from every keyframe.
  void CullPoint(int point_id);
  // Recomputes a point's representative descriptor: the observing descriptor with the
  // least median Hamming distance to the others.
  void UpdateDescriptor(int point_id);

  // Pyramid level at which a point is expected to be detected from distance_m, clamped to
  // [0, num_levels - 1]: reference_octave + log(reference_distance / distance) / log(scale).
  int PredictOctave(int point_id, double distance_m, double scale_factor, int num_levels) const;

  const std::vector<Keyframe>& keyframes() const { return keyframes_; }
  std::vector<Keyframe>& keyframes() { return keyframes_; }
  const std::vector<MapPoint>& points() const { return points_; }
  std::vector<MapPoint>& points() { return points_; }
  int good_point_count() const;

  // Points with at least min_observations observations and the given found ratio.
  proto::ClipMap ExportClipMap(const MapExportOptions& options = {}) const;

 private:
  std::vector<Keyframe> keyframes_;
  std::vector<MapPoint> points_;
};

}  // namespace reenact::capture::slam
