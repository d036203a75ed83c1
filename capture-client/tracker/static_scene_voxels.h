#pragma once
// The static scene around the person, learned while tracking, so that an object the person
// walks up to (a box, a chair, a table's edge) stops feeding the fit once it touches them.
//
// The person detector (person_detector.h) merges regions that touch the person in the image
// across small depth gaps, and the tracker keeps every point within keep_near_model_m of the
// predicted body; a box beside the legs passes both. Its points are beyond outlier_m of the
// model, so the fit ignores them, but the limb search (limb_search.h), which re-poses a limb
// to reach lost points, reaches for them: while a subject walks past a box, a fifth or more of
// its points can be the box's, enough to swing a foot into it.
//
// The map is a sparse voxel grid in the world frame (voxel_m), so it needs the sensor's pose
// on every frame (a static sensor's, or a moving one's from SLAM or ground truth). On every
// frame that the tracker fitted well, each grid reading outside the person's region (every
// learn_step-th grid pixel in x and y) that lies farther than body_clearance_m from the
// fitted body and higher than floor_clearance_m above the floor counts as the static scene's
// in its voxel, once per frame. A voxel seen so on min_frames frames is static, and data
// points in it are dropped before the fit, as are points lower than floor_clearance_m under
// a static voxel (an object's lowest centimetres, not learned because a floor voxel would
// hold a foot's lowest points as well). A voxel
// within see_through_margin_m of the fitted body that a later frame sees through (the
// readings on the rays through its centre and its eight corners all lie more than
// see_through_m behind those points: the object moved away; a surface that crosses the voxel
// anywhere covers one of them) is forgotten. The voxels are kept in blocks of 8^3, so that
// check visits only the blocks near the person.
// Readings near the fitted body are never learned, so a hand the detector left out of the
// region (raised behind the head) does not become static; nor is anything learned while
// no fit is trusted (waiting for calibration, lost, a bad fit). A part of the person that the
// detector leaves out and the fit misses by more than body_clearance_m, held still for
// min_frames frames, would be learned; and voxels farther from the person than
// see_through_margin_m are not checked for being seen through until the person comes near.
// Not thread-safe.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <utility>

#include "capture-client/segment/floor_plane.h"
#include "capture-client/segment/pixel_rays.h"
#include "capture-client/tracker/articulated_body.h"
#include "capture-client/tracker/body_fit.h"
#include "capture-client/tracker/person_detector.h"
#include "common/geometry/pinhole_camera.h"

namespace reenact::capture {

struct StaticSceneOptions {
  bool enabled = true;
  double voxel_m = 0.04;          // voxel edge, > 0
  int min_frames = 10;            // frames seen beside the person to be static, [1, 255]
  double body_clearance_m = 0.3;  // readings nearer the fitted body's surface are not learned, >= 0
  double see_through_m = 0.1;     // a reading this far behind a voxel sees through it, > 0
  // Voxels are checked for being seen through within this of the fitted skeleton's box
  // (the fit's points lie within keep_near_model_m of the body), > 0.
  double see_through_margin_m = 0.6;
  // Readings less than this above the detector's floor are not learned: the detector drops
  // the floor's own points, and a floor voxel would take a foot's lowest points, >= 0.
  double floor_clearance_m = 0.08;
  int learn_step = 3;  // every learn_step-th grid pixel in x and y is learned, >= 1
  size_t max_blocks = size_t{1} << 13;  // no new blocks of 8^3 voxels (2.5 KB each) beyond, >= 1

  void Check() const;
};

class StaticSceneVoxels {
 public:
  // Preconditions (CHECK): a valid camera (the depth camera the blobs' grids sample), valid
  // options.
  StaticSceneVoxels(const PinholeCamera& camera, const StaticSceneOptions& options);

  // Learns from one well-fitted frame: blob from the person detector, rays the camera's
  // (PersonDetector::rays; another camera's size: CHECK), posed the fit's body (sensor
  // frame). A frame without a grid or with a non-finite pose teaches nothing.
  void Learn(const PersonBlob& blob, const PixelRays& rays,
             const Eigen::Isometry3d& world_from_sensor, const ArticulatedBody& body,
             const PosedBody3& posed);

  // Whether a world point lies in a static voxel.
  bool IsStatic(const Eigen::Vector3d& point_in_world) const;

  // Drops the observation's data points (sensor frame) that lie in static voxels, and those
  // less than floor_clearance_m above the floor whose voxel just above that height is static
  // (an object's lowest centimetres, which are not learned); returns how many were dropped
  // (none for a non-finite pose).
  int DropStatic(const Eigen::Isometry3d& world_from_sensor,
                 const std::optional<Plane3>& floor_in_sensor, BodyObservation* observation) const;

  void Clear();

 private:
  static constexpr int kBlockBits = 3;  // blocks of 8 x 8 x 8 voxels
  static constexpr int kBlockMask = (1 << kBlockBits) - 1;
  static constexpr int kBlockVoxels = 1 << (3 * kBlockBits);
  struct Block {
    std::array<uint8_t, kBlockVoxels> count{};        // frames seen, saturating at min_frames
    std::array<uint32_t, kBlockVoxels> last_frame{};  // the last frame that counted it
  };
  Eigen::Array3i VoxelIndex(const Eigen::Vector3d& point_in_world) const;
  // A voxel's block key and its index within the block.
  static std::pair<uint64_t, int> Slot(const Eigen::Array3i& voxel);

  PinholeCamera camera_;
  StaticSceneOptions options_;
  std::unordered_map<uint64_t, Block> blocks_;  // by block index (BlockKey)
  uint32_t frame_ = 0;
};

}  // namespace reenact::capture
