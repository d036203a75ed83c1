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

  // Caps: the pole then kCapRings rings out to the rim, for z = 0 (facing -z) and z = 1.
  for (int cap = 0; cap < 2; ++cap) {
    const float z = static_cast<float>(cap);
    const Eigen::Vector3f normal(0.0f, 0.0f, cap == 0 ? -1.0f : 1.0f);
    const auto pole = static_cast<uint32_t>(mesh.positions.size());
    add(Eigen::Vector3f(0.0f, 0.0f, z), normal);
    for (int m = 1; m <= kCapRings; ++m) {
      const auto rho = static_cast<float>(CapRingRadius(m));
      for (uint32_t i = 0; i < n; ++i) add(Eigen::Vector3f(rho * ring[i].x(), rho * ring[i].y(), z), normal);
    }
    // Wound counter-clockwise seen from outside: -z at z = 0, +z at z = 1.
    auto cap_triangle = [&](uint32_t a, uint32_t b, uint32_t c) {
      if (cap == 0) {
        triangle(a, c, b);
      } else {
        triangle(a, b, c);
      }
    };
    for (uint32_t i = 0; i < n; ++i) cap_triangle(pole, pole + 1 + i, pole + 1 + (i + 1) % n);
    for (uint32_t m = 1; m < static_cast<uint32_t>(kCapRings); ++m) {
      const uint32_t inner = pole + 1 + (m - 1) * n, outer = pole + 1 + m * n;
      for (uint32_t i = 0; i < n; ++i) {
        const uint32_t j = (i + 1) % n;
        cap_triangle(inner + i, outer + i, outer + j);
        cap_triangle(inner + i, outer + j, inner + j);
      }
    }
  }
  return mesh;
}

double CapRingRadius(int m) {
  REENACT_CHECK(m >= 0 && m <= kCapRings, "cap ring index out of range");
  return m == kCapRings ? 1.0 : std::sin(0.5 * std::numbers::pi * m / kCapRings);
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

double SurfaceFactorOfUnitVertex(const PartShape& shape, const Eigen::Vector3d& unit_position) {
  if (shape.surface.IsEmpty() || (unit_position.x() == 0 && unit_position.y() == 0)) return 1.0;
  return shape.surface.FactorAt(RingOfUnitVertex(unit_position.z()),
                                std::atan2(unit_position.y(), unit_position.x()));
}

Eigen::Vector3d ShapedUnitPosition(const PartShape& shape, const Eigen::Vector3d& unit_position,
                                   const Eigen::Vector3d& unit_normal) {
  const int k = RingOfUnitVertex(unit_position.z());
  const double s = SurfaceFactorOfUnitVertex(shape, unit_position);
  double z = unit_position.z();
  if (unit_normal.z() != 0) {
    const double dome = shape.cap_depth[unit_normal.z() < 0 ? 0 : 1];
    const double rho2 = unit_position.head<2>().squaredNorm();
    z += (unit_normal.z() < 0 ? -dome : dome) * std::sqrt(std::max(0.0, 1 - rho2));
  }
  return Eigen::Vector3d(s * shape.width[k] * unit_position.x(),
                         s * shape.depth[k] * unit_position.y(), z);
}

Eigen::Vector3d ShapedUnitNormal(const PartShape& shape, const Eigen::Vector3d& unit_position,
                                 const Eigen::Vector3d& unit_normal) {
  const int k = RingOfUnitVertex(unit_position.z());
  if (unit_normal.z() != 0) {
    const double dome = shape.cap_depth[unit_normal.z() < 0 ? 0 : 1];
    if (dome == 0) return unit_normal;
    const double s = SurfaceFactorOfUnitVertex(shape, unit_position);
    const double rho2 = unit_position.head<2>().squaredNorm();
    return Eigen::Vector3d(unit_position.x() / (s * shape.width[k]),
                           unit_position.y() / (s * shape.depth[k]),
                           unit_normal.z() * std::sqrt(std::max(0.0, 1 - rho2)) / dome);
  }
  const double c = unit_normal.x(), sn = unit_normal.y();
  const PartSurface& surface = shape.surface;
  const double phi = std::atan2(sn, c);
  std::array<double, kShapeRings> w_eff{}, d_eff{};
  for (int r = 0; r < kShapeRings; ++r) {
    const double f = surface.FactorAt(r, phi);
    w_eff[r] = f * shape.width[r];
    d_eff[r] = f * shape.depth[r];
  }
  const double f = surface.FactorAt(k, phi);
  double f_phi = 0;
  if (!surface.IsEmpty()) {
    const double half_step = std::numbers::pi / surface.angles;
    f_phi = (surface.FactorAt(k, phi + half_step) - surface.FactorAt(k, phi - half_step)) /
            (2 * half_step);
  }
  const double w = shape.width[k], d = shape.depth[k];
  const double px = f_phi * w * c - f * w * sn, py = f_phi * d * sn + f * d * c;
  const double zx = RingSlope(w_eff, k) * c, zy = RingSlope(d_eff, k) * sn;
  return Eigen::Vector3d(py, -px, px * zy - py * zx);
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
