#pragma once
// Similarity transform in 3D: x_in_b = scale * rotation * x_in_a + translation, named
// `b_from_a` like every transform (DESIGN.md). The thesis uses similarities twice: the
// texture mapping Omega = [s R | t] (Eq. 11) and the sensor-to-map alignment (Eq. 17-24,
// common/align/umeyama.h). Rigid transforms stay Eigen::Isometry3d; a Sim3 with scale 1
// converts to one.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

namespace reenact {

struct Sim3 {
  double scale = 1;                                        // > 0, unitless
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // orthonormal, det +1
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();   // in the target frame's units

  Sim3() = default;
  Sim3(double s, const Eigen::Matrix3d& r, const Eigen::Vector3d& t)
      : scale(s), rotation(r), translation(t) {}

  static Sim3 Identity() { return {}; }
  // The rigid transform with scale 1 (or with the given scale).
  static Sim3 FromIsometry(const Eigen::Isometry3d& b_from_a, double scale = 1);

  // Throws CheckError unless scale > 0 and finite, everything finite, and rotation
  // orthonormal with det +1 within `tolerance` (max element of |R^T R - I|).
  void Check(double tolerance = 1e-9) const;

  // b_from_a * x_in_a.
  Eigen::Vector3d operator*(const Eigen::Vector3d& x_in_a) const {
    return scale * (rotation * x_in_a) + translation;
  }
  // Composition: c_from_a = c_from_b * b_from_a.
  Sim3 operator*(const Sim3& b_from_a) const;
  // a_from_b from b_from_a: scale 1/s, rotation R^T, translation -(1/s) R^T t.
  Sim3 Inverse() const;

  // Homogeneous 4x4 [s R | t; 0 0 0 1].
  Eigen::Matrix4d ToMatrix() const;
  // The similarity of a 4x4 matrix [A | t; 0 0 0 1] with A = s R; s = cbrt(det A).
  // nullopt unless the bottom row is (0, 0, 0, 1), everything is finite, det A > 0 and
  // A / s is orthonormal within `tolerance`; the rotation is then projected exactly onto
  // SO(3).
  static std::optional<Sim3> FromMatrix(const Eigen::Matrix4d& m, double tolerance = 1e-9);

  // The rigid part (rotation, translation) as an isometry; the scale is dropped.
  Eigen::Isometry3d RigidPart() const;
};

}  // namespace reenact
