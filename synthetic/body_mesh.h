#pragma once
// The synthetic subject's surface: per segment (body_model.h) a rigid triangle mesh made of
// tapered elliptic capsules (elliptic cross-sections whose radii change linearly along the
// axis, closed by half-ellipsoid caps), so limbs taper, the torso is wider than deep, the
// head is an ellipsoid and hands and feet are flattened capsules.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "synthetic/body_model.h"

namespace reenact::capture {

// A tapered elliptic capsule in a shape frame: the axis runs along z from z_a to z_b;
// radii (x, y) at z_a and at z_b; the caps bulge cap_a beyond z_a and cap_b beyond z_b
// (metres). z_a == z_b with both caps equal gives an ellipsoid.
struct CapsuleShape {
  Eigen::Isometry3d segment_from_shape = Eigen::Isometry3d::Identity();
  double z_a = 0, z_b = 0;
  Eigen::Vector2d radii_a = Eigen::Vector2d::Zero(), radii_b = Eigen::Vector2d::Zero();
  double cap_a = 0, cap_b = 0;
};

// A closed triangle mesh in its segment's frame with outward unit normals; triangles are
// wound so that (b - a) x (c - a) points outwards.
struct SegmentMesh {
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Vector3d> normals;
  std::vector<Eigen::Vector3i> triangles;
};

// The capsules that make up each segment of a subject with the given dimensions.
std::vector<CapsuleShape> SegmentShapes(Segment s, const BodyDimensions& dims);

// Triangulates a capsule: `sectors` around the axis, `cap_rings` rings per cap and
// `body_rings` rings along the tapered part.
void AppendCapsule(const CapsuleShape& shape, int sectors, int cap_rings, int body_rings,
                   SegmentMesh* mesh);

// All segment meshes of the subject (about 10k triangles in all).
std::array<SegmentMesh, kSegmentCount> BuildBodyMeshes(const BodyDimensions& dims = {});

}  // namespace reenact::capture
