#include "common/geometry/similarity3.h"

#include <cmath>

#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact {

Sim3 Sim3::FromIsometry(const Eigen::Isometry3d& b_from_a, double scale) {
  return Sim3(scale, b_from_a.linear(), b_from_a.translation());
}

void Sim3::Check(double tolerance) const {
  REENACT_CHECK(std::isfinite(scale) && scale > 0, "Sim3: scale must be positive and finite");
  REENACT_CHECK(rotation.allFinite() && translation.allFinite(), "Sim3: values must be finite");
  REENACT_CHECK(OrthonormalityError(rotation) <= tolerance && rotation.determinant() > 0,
                "Sim3: rotation must be orthonormal with det +1");
}

Sim3 Sim3::operator*(const Sim3& b_from_a) const {
  return Sim3(scale * b_from_a.scale, rotation * b_from_a.rotation,
              scale * (rotation * b_from_a.translation) + translation);
}

Sim3 Sim3::Inverse() const {
  const Eigen::Matrix3d rt = rotation.transpose();
  return Sim3(1 / scale, rt, -(rt * translation) / scale);
}

Eigen::Matrix4d Sim3::ToMatrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = scale * rotation;
  m.topRightCorner<3, 1>() = translation;
  return m;
}

std::optional<Sim3> Sim3::FromMatrix(const Eigen::Matrix4d& m, double tolerance) {
  if (!m.allFinite() || m.bottomRows<1>() != Eigen::RowVector4d(0, 0, 0, 1)) return std::nullopt;
  const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
  const double det = a.determinant();
  if (!(det > 0)) return std::nullopt;
  const double s = std::cbrt(det);
  const Eigen::Matrix3d r = a / s;
  if (OrthonormalityError(r) > tolerance) return std::nullopt;
  return Sim3(s, NearestRotation(r), m.topRightCorner<3, 1>());
}

Eigen::Isometry3d Sim3::RigidPart() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation;
  t.translation() = translation;
  return t;
}

}  // namespace reenact
