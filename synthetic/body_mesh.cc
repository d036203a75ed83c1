#include "synthetic/body_mesh.h"

#include <cmath>
#include <numbers>

namespace reenact::capture {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

CapsuleShape Capsule(double z_a, double z_b, Vector2d ra, Vector2d rb, double cap_a, double cap_b) {
  CapsuleShape c;
  c.z_a = z_a;
  c.z_b = z_b;
  c.radii_a = ra;
  c.radii_b = rb;
  c.cap_a = cap_a;
  c.cap_b = cap_b;
  return c;
}

// A limb hanging from the segment origin down to -length.
CapsuleShape Limb(double length, Vector2d r_top, Vector2d r_bottom, double cap_top,
                  double cap_bottom) {
  return Capsule(0, -length, r_top, r_bottom, cap_top, cap_bottom);
}

}  // namespace

std::vector<CapsuleShape> SegmentShapes(Segment s, const BodyDimensions& d) {
  switch (s) {
    case Segment::kHead: {
      CapsuleShape head = Capsule(0, 0, {0.100, 0.078}, {0.100, 0.078}, 0.12, 0.12);
      head.segment_from_shape.translation() = Vector3d(0.005, 0, 0);
      return {head};
    }
    case Segment::kNeck:
      return {Capsule(-0.09, 0.03, {0.055, 0.058}, {0.050, 0.052}, 0.02, 0.02)};
    case Segment::kUpperTorso:
      return {Capsule(0.0, d.upper_spine - 0.05, {0.105, 0.150}, {0.110, 0.168}, 0.03, 0.07)};
    case Segment::kLowerTorso:
      return {Capsule(-0.06, d.lower_spine - 0.02, {0.110, 0.165}, {0.100, 0.145}, 0.09, 0.03)};
    case Segment::kLeftUpperArm:
    case Segment::kRightUpperArm:
      return {Limb(d.upper_arm, {0.050, 0.048}, {0.040, 0.038}, 0.045, 0.035)};
    case Segment::kLeftForearm:
    case Segment::kRightForearm:
      return {Limb(d.forearm, {0.040, 0.037}, {0.028, 0.023}, 0.03, 0.02)};
    case Segment::kLeftHand:
    case Segment::kRightHand:
      // Palm facing the body in the rest pose: wide along x, thin along y.
      return {Capsule(-0.015, -0.13, {0.042, 0.018}, {0.040, 0.014}, 0.02, 0.04)};
    case Segment::kLeftThigh:
    case Segment::kRightThigh:
      return {Limb(d.thigh, {0.085, 0.080}, {0.055, 0.052}, 0.05, 0.04)};
    case Segment::kLeftShin:
    case Segment::kRightShin:
      return {Limb(d.shin, {0.052, 0.050}, {0.036, 0.034}, 0.04, 0.03)};
    case Segment::kLeftFoot:
    case Segment::kRightFoot: {
      // Built along z, turned so that the shape's z runs forward (segment x) and its x runs
      // down; sole at -ankle_height.
      CapsuleShape foot = Capsule(-0.03, 0.15, {0.038, 0.040}, {0.030, 0.048}, 0.04, 0.05);
      foot.segment_from_shape.linear() =
          Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d::UnitY()).toRotationMatrix();
      foot.segment_from_shape.translation() = Vector3d(0, 0, -d.ankle_height + 0.038);
      return {foot};
    }
  }
  return {};
}

void AppendCapsule(const CapsuleShape& c, int sectors, int cap_rings, int body_rings,
                   SegmentMesh* mesh) {
  struct Ring {
    double z;        // ring centre on the axis
    Vector2d base;   // radii of the capsule end (caps) or of this ring (body)
    double scale;    // cos(phi) on the caps, 1 on the body
    double sin_phi;  // signed axial position on a cap, 0 on the body
    double cap;      // cap half-length, 0 on the body
  };
  const double dir = c.z_b >= c.z_a ? 1.0 : -1.0;
  const double half_pi = std::numbers::pi / 2;
  std::vector<Ring> rings;
  for (int k = 0; k <= cap_rings; ++k) {
    const double phi = -half_pi + half_pi * k / cap_rings;
    rings.push_back(
        {c.z_a + dir * c.cap_a * std::sin(phi), c.radii_a, std::cos(phi), std::sin(phi), c.cap_a});
  }
  for (int k = 1; k < body_rings; ++k) {
    const double t = static_cast<double>(k) / body_rings;
    rings.push_back(
        {c.z_a + t * (c.z_b - c.z_a), c.radii_a + t * (c.radii_b - c.radii_a), 1, 0, 0});
  }
  for (int k = 0; k <= cap_rings; ++k) {
    const double phi = half_pi * k / cap_rings;
    rings.push_back(
        {c.z_b + dir * c.cap_b * std::sin(phi), c.radii_b, std::cos(phi), std::sin(phi), c.cap_b});
  }

  const int base = static_cast<int>(mesh->positions.size());
  const Eigen::Matrix3d rot = c.segment_from_shape.linear();
  for (const Ring& ring : rings) {
    for (int j = 0; j < sectors; ++j) {
      const double theta = 2 * std::numbers::pi * j / sectors;
      const double ct = std::cos(theta), st = std::sin(theta);
      const Vector3d p(ring.scale * ring.base.x() * ct, ring.scale * ring.base.y() * st, ring.z);
      // Gradient of the cap ellipsoid; radial on the body.
      const Vector3d n(ring.scale * ct / ring.base.x(), ring.scale * st / ring.base.y(),
                       ring.cap > 0 ? dir * ring.sin_phi / ring.cap : 0.0);
      mesh->positions.push_back(c.segment_from_shape * p);
      mesh->normals.push_back((rot * n).normalized());
    }
  }
  const int ring_count = static_cast<int>(rings.size());
  for (int i = 0; i + 1 < ring_count; ++i)
    for (int j = 0; j < sectors; ++j) {
      const int a = base + i * sectors + j, b = base + i * sectors + (j + 1) % sectors;
      const int e = a + sectors, f = b + sectors;
      for (Eigen::Vector3i t : {Eigen::Vector3i(a, b, f), Eigen::Vector3i(a, f, e)}) {
        const Vector3d& p0 = mesh->positions[t[0]];
        const Vector3d& p1 = mesh->positions[t[1]];
        const Vector3d& p2 = mesh->positions[t[2]];
        const Vector3d outward = mesh->normals[t[0]] + mesh->normals[t[1]] + mesh->normals[t[2]];
        if ((p1 - p0).cross(p2 - p0).dot(outward) < 0) std::swap(t[1], t[2]);
        mesh->triangles.push_back(t);
      }
    }
}

std::array<SegmentMesh, kSegmentCount> BuildBodyMeshes(const BodyDimensions& dims) {
  std::array<SegmentMesh, kSegmentCount> meshes;
  for (int s = 0; s < kSegmentCount; ++s) {
    const Segment segment = static_cast<Segment>(s);
    const bool small = segment == Segment::kNeck || segment == Segment::kLeftHand ||
                       segment == Segment::kRightHand;
    for (const CapsuleShape& shape : SegmentShapes(segment, dims))
      AppendCapsule(shape, small ? 16 : 24, small ? 4 : 6, small ? 3 : 8, &meshes[s]);
  }
  return meshes;
}

}  // namespace reenact::capture
