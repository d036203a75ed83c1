#pragma once
// Person segmentation from depth and a skeleton (issue 5): a mask of the subject per frame.
//
//  1. Floor: a RANSAC plane (floor_plane.h) through depth points near the floor height the
//     skeleton implies, roughly perpendicular to the body's up axis (the world's up when the
//     frame knows it, else the cached floor's normal, else the skeleton's waist-to-neck axis).
//     The plane is cached (in the world frame when the sensor pose is known, else in the
//     sensor frame, i.e. for a static sensor) and re-fitted only when it stops fitting.
//     Points less than floor_clearance(z) above it are never person.
//  2. Seeds: samples along each projected bone (skeleton_bones.h) where the depth seen agrees
//     with the bone's depth (the surface lies up to seed_in_front_m in front of the joints).
//  3. Region growing (4-connected) from the seeds across neighbours whose depths differ by at
//     most depth_step(z) (a Kinect-like threshold growing with z^2), never onto holes, the
//     floor or points farther than body_margin_m from every bone; bounded by the image
//     rectangle of the skeleton's box grown by body_margin_m.
//  4. Holes (mask_fill.h): runs of pixels without a reading along a row join the mask when
//     the surface at their farther end is in it (a projector's shadow falls on the farther
//     surface: the shadow of an arm on the torso joins, the shadow beside the body on the
//     wall does not); enclosed regions whose readings lie at the person's depth join.
//
// Frames: the skeleton in the sensor frame (OpenCV axes, metres), or in the world frame with
// world_from_sensor. Depth registered to the depth camera, depth_scale_m metres per unit.
// Not thread-safe: one segmenter per stream (it caches the floor and scratch buffers).

#include <Eigen/Geometry>
#include <optional>
#include <string_view>
#include <vector>

#include "capture-client/segment/floor_plane.h"
#include "capture-client/segment/pixel_rays.h"
#include "capture-client/segment/segment_options.h"
#include "capture-client/source/frame_source.h"
#include "common/error/expected.h"
#include "common/image/image.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

enum class SegmentStatus {
  kOk = 0,
  kNoDepth,               // no depth reading in range anywhere: empty mask
  kSkeletonBehindCamera,  // every present joint lies behind the sensor: empty mask
  kSkeletonOutsideImage,  // no bone projects into the image: empty mask
  kNoSeeds,               // the depth nowhere agrees with the skeleton: empty mask
};
std::string_view SegmentStatusName(SegmentStatus status);

struct PersonSegmentation {
  SegmentStatus status = SegmentStatus::kOk;
  ImageGray8 mask;  // depth-sized, 255 = person, 0 = not (always allocated)
  int mask_pixels = 0;
  int seed_pixels = 0;
  int filled_pixels = 0;  // added by hole filling (step 4)
  // The floor used for this frame (sensor frame, normal towards up), and whether it was
  // fitted on this frame (false: the cached plane still fitted, or no floor).
  std::optional<Plane3> floor_in_sensor;
  bool floor_refitted = false;
};

// What the caller knows about the frame besides depth and skeleton.
struct SegmentFrameGeometry {
  // The sensor pose: the floor is then cached in the world frame (moving sensors keep it).
  std::optional<Eigen::Isometry3d> world_from_sensor;
  // The world's up direction (unit), used with world_from_sensor.
  std::optional<Eigen::Vector3d> world_up;
};

class PersonSegmenter {
 public:
  // Preconditions (CHECK): valid camera, depth_scale_m > 0 and finite, valid options.
  PersonSegmenter(const PinholeCamera& depth_camera, double depth_scale_m,
                  const PersonSegmentOptions& options = {});

  // Errors ("invalid_argument"): a depth image that is not one channel of the camera's size;
  // a skeleton without any present joint ("no skeleton"); a present joint that is not finite;
  // a world_up that is not a finite non-zero vector. Degenerate frames give an empty mask and
  // a status (SegmentStatus) instead.
  Expected<PersonSegmentation> Segment(const ImageDepthMm& depth,
                                       const Skeleton& skeleton_in_sensor,
                                       const SegmentFrameGeometry& geometry = {});

  // A frame source's frame: its skeleton_in_world moved into the sensor frame through its
  // world_from_sensor; world_up as SensorInfo gives it. Errors as Segment(), and
  // "invalid_argument" for a frame without a skeleton or with a skeleton but no sensor pose.
  Expected<PersonSegmentation> SegmentFrame(const SensorFrame& frame,
                                            const std::optional<Eigen::Vector3d>& world_up);

  // Forgets the cached floor (a new scene, a moved static sensor).
  void ResetFloor() { floor_.reset(); }

  const PersonSegmentOptions& options() const { return options_; }

 private:
  struct CachedFloor {
    Plane3 plane;  // in the world frame when in_world, else the sensor frame
    bool in_world = false;
    double inlier_ratio = 0;  // when fitted
  };

  std::optional<Plane3> UpdateFloor(const ImageDepthMm& depth, const Skeleton& skeleton,
                                    const SegmentFrameGeometry& geometry, bool* refitted);

  PinholeCamera camera_;
  double depth_scale_m_;
  PersonSegmentOptions options_;
  PixelRays rays_;
  std::optional<CachedFloor> floor_;
  std::vector<uint8_t> state_;  // scratch: per-pixel region-growing state
};

}  // namespace reenact::capture
