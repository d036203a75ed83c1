#include "common/render/cylinder_mesh.h"

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

  // Side: vertex 2i at z = 0, 2i + 1 at z = 1.
  for (uint32_t i = 0; i < n; ++i) {
    const Eigen::Vector3f normal(ring[i].x(), ring[i].y(), 0.0f);
    add(Eigen::Vector3f(ring[i].x(), ring[i].y(), 0.0f), normal);
    add(Eigen::Vector3f(ring[i].x(), ring[i].y(), 1.0f), normal);
  }
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t j = (i + 1) % n;
    triangle(2 * i, 2 * j, 2 * j + 1);
    triangle(2 * i, 2 * j + 1, 2 * i + 1);
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

Eigen::Matrix4d ViewerFromUnitCylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       double radius) {
  const Eigen::Vector3d axis = b - a;
  const Eigen::Vector3d z = axis / axis.norm();
  const Eigen::Vector3d helper =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d x = z.cross(helper).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<3, 1>(0, 0) = x * radius;
  m.block<3, 1>(0, 1) = y * radius;
  m.block<3, 1>(0, 2) = axis;
  m.block<3, 1>(0, 3) = a;
  return m;
}

}  // namespace reenact
