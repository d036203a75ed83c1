#pragma once
// Where the person can be, from the skeleton in the sensor frame (OpenCV axes, metres): the
// union of capsules of radius `margin` around the bones (skeleton_bones.h; a present joint
// without a present neighbour is a sphere), and the image rectangle of the joints' box grown
// by the margin.

#include <Eigen/Core>
#include <vector>

#include "capture-client/segment/pixel_rect.h"
#include "common/geometry/pinhole_camera.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

struct BoneSegment {
  Eigen::Vector3d a;  // proximal joint, sensor frame
  Eigen::Vector3d b;  // distal joint (== a for a lone joint)
};

class BodyBound {
 public:
  // Precondition: margin > 0, valid camera; the skeleton's present joints are finite.
  BodyBound(const Skeleton& skeleton_in_sensor, const PinholeCamera& camera, double margin);

  // Whether a point lies within the margin of some bone.
  bool Contains(const Eigen::Vector3d& p) const { return NearBone(p, margin2_); }
  // Whether a point lies within sqrt(radius2) of some bone.
  bool NearBone(const Eigen::Vector3d& p, double radius2) const;

  const std::vector<BoneSegment>& bones() const { return bones_; }
  // The image rectangle that can hold the person (the whole image when the grown box reaches
  // behind the camera's near plane); empty when the box projects outside the image.
  const PixelRect& rect() const { return rect_; }
  // Whether every present joint lies behind the camera (z <= kNearM).
  bool behind_camera() const { return behind_camera_; }

  static constexpr double kNearM = 0.05;

 private:
  struct Capsule {
    Eigen::Vector3d a, ab;
    double inv_len2;  // 1 / |ab|^2, 0 for a sphere
  };
  std::vector<BoneSegment> bones_;
  std::vector<Capsule> capsules_;
  double margin2_ = 0;
  PixelRect rect_;
  bool behind_camera_ = true;
};

}  // namespace reenact::capture
