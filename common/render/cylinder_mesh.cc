#include "common/render/cylinder_mesh.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error/check.h"

namespace reenact {

CylinderMesh MakeUnitCylinderMesh(int segments) {
  REENACT_CHECK(segments >= 3, "a cylinder needs at least 3 segments");
  CylinderMesh mesh;
  const auto n = static_cast<uint32_t>(segments);
  std::vector<Eigen::Vector2f> ring(n);
  for (uint32_t i = 0; i < n; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / n;
    ring[i] =
        Eigen::Vector2f(static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle)));
  }
  auto add = [&mesh](const Eigen::Vector3f& p, const Eigen::Vector3f& normal) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(normal);
  };
  auto triangle = [&mesh](uint32_t a, uint32_t b, uint32_t c) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
  };
  const auto ring_z = [](int k) { return static_cast<float>(k) / (kShapeRings - 1); };

  // Side: vertex k n + i is vertex i of ring k.
  for (int k = 0; k < kShapeRings; ++k)
    for (uint32_t i = 0; i < n; ++i)
      add(Eigen::Vector3f(ring[i].x(), ring[i].y(), ring_z(k)),
          Eigen::Vector3f(ring[i].x(), ring[i].y(), 0.0f));
  for (uint32_t k = 0; k + 1 < static_cast<uint32_t>(kShapeRings); ++k)
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t j = (i + 1) % n;
      const uint32_t lo = k * n, hi = (k + 1) * n;
      triangle(lo + i, lo + j, hi + j);
      triangle(lo + i, hi + j, hi + i);
    }

  // Caps: a centre then the ring, for z = 0 (facing -z) and z = 1 (facing +z).
  for (int cap = 0; cap < 2; ++cap) {
    const float z = static_cast<float>(cap);
    const Eigen::Vector3f normal(0.0f, 0.0f, cap == 0 ? -1.0f : 1.0f);
    const auto centre = static_cast<uint32_t>(mesh.positions.size());
    add(Eigen::Vector3f(0.0f, 0.0f, z), normal);
    for (uint32_t i = 0; i < n; ++i) add(Eigen::Vector3f(ring[i].x(), ring[i].y(), z), normal);
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t a = centre + 1 + i, b = centre + 1 + (i + 1) % n;
      if (cap == 0) {
        triangle(centre, b, a);
      } else {
        triangle(centre, a, b);
      }
    }
  }
  return mesh;
}

int RingOfUnitVertex(double z) {
  const double k = std::round(z * (kShapeRings - 1));
  if (!(k > 0)) return 0;
  return static_cast<int>(std::min<double>(k, kShapeRings - 1));
}

double RingSlope(const std::array<double, kShapeRings>& values, int k) {
  REENACT_CHECK(k >= 0 && k < kShapeRings, "ring index out of range");
  const int lo = std::max(k - 1, 0), hi = std::min(k + 1, kShapeRings - 1);
  return (values[hi] - values[lo]) * (kShapeRings - 1) / (hi - lo);
}

Eigen::Vector3d ShapedUnitPosition(const PartShape& shape, const Eigen::Vector3d& unit_position) {
  const int k = RingOfUnitVertex(unit_position.z());
  return Eigen::Vector3d(shape.width[k] * unit_position.x(), shape.depth[k] * unit_position.y(),
                         unit_position.z());
}

Eigen::Vector3d ShapedUnitNormal(const PartShape& shape, const Eigen::Vector3d& unit_position,
                                 const Eigen::Vector3d& unit_normal) {
  if (unit_normal.z() != 0) return unit_normal;
  const int k = RingOfUnitVertex(unit_position.z());
  const double w = shape.width[k], d = shape.depth[k];
  const double w_slope = RingSlope(shape.width, k), d_slope = RingSlope(shape.depth, k);
  const double c = unit_normal.x(), s = unit_normal.y();
  return Eigen::Vector3d(d * c, w * s, -(w * d_slope * s * s + d * w_slope * c * c));
}

Eigen::Matrix4d ViewerFromUnitCylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       double radius,
                                       const std::optional<Eigen::Vector3d>& width_direction) {
  const Eigen::Vector3d axis = b - a;
  const Eigen::Vector3d z = axis / axis.norm();
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  if (width_direction) {
    const Eigen::Vector3d& w = *width_direction;
    const Eigen::Vector3d across = w - w.dot(z) * z;
    if (across.norm() >= 1e-9 * w.norm() && across.norm() > 0) x = across.normalized();
  }
  if (x.isZero()) {
    const Eigen::Vector3d helper =
        std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    x = z.cross(helper).normalized();
  }
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<3, 1>(0, 0) = x * radius;
  m.block<3, 1>(0, 1) = y * radius;
  m.block<3, 1>(0, 2) = axis;
  m.block<3, 1>(0, 3) = a;
  return m;
}

Eigen::Matrix4d ViewerFromUnitCylinder(const Cylinder& cylinder) {
  return ViewerFromUnitCylinder(cylinder.a, cylinder.b, cylinder.radius, cylinder.width_direction);
}

Eigen::Matrix3d NormalFromUnitCylinder(const Eigen::Matrix4d& viewer_from_cylinder) {
  Eigen::Matrix3d n;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d column = viewer_from_cylinder.block<3, 1>(0, j);
    n.col(j) = column / column.squaredNorm();
  }
  return n;
}

}  // namespace reenact
