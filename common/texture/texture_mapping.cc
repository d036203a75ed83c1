#include "common/texture/texture_mapping.h"

#include <cmath>

namespace reenact {
namespace {

constexpr double kMinAxisLength = 1e-9;

std::optional<Eigen::Matrix3d> CylinderBasis(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const std::optional<Eigen::Vector3d> f = FacingDirection(a, b);
  if (!f) return std::nullopt;
  const Eigen::Vector3d u = (b - a).normalized();
  Eigen::Matrix3d basis;
  basis.col(0) = u;
  basis.col(1) = *f;
  basis.col(2) = u.cross(*f);
  return basis;
}

}  // namespace

std::optional<Eigen::Vector3d> FacingDirection(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d axis = b - a;
  const double length = axis.norm();
  if (!(length >= kMinAxisLength) || !a.allFinite() || !b.allFinite()) return std::nullopt;
  const Eigen::Vector3d u = axis / length;
  const Eigen::Vector3d to_camera = -0.5 * (a + b);
  Eigen::Vector3d f = to_camera - to_camera.dot(u) * u;
  if (f.norm() < 1e-9 * std::max(1.0, to_camera.norm())) {
    // Camera on the axis line: any orthogonal direction is as good; take a fixed one.
    const Eigen::Vector3d helper =
        std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    f = helper - helper.dot(u) * u;
  }
  return f.normalized();
}

std::optional<Eigen::Matrix4d> StoredFromViewerMapping(const Eigen::Vector3d& a_viewer,
                                                       const Eigen::Vector3d& b_viewer,
                                                       const Eigen::Vector3d& a_stored,
                                                       const Eigen::Vector3d& b_stored) {
  const auto viewer_basis = CylinderBasis(a_viewer, b_viewer);
  const auto stored_basis = CylinderBasis(a_stored, b_stored);
  if (!viewer_basis || !stored_basis) return std::nullopt;
  const double scale = (b_stored - a_stored).norm() / (b_viewer - a_viewer).norm();
  const Eigen::Matrix3d linear = scale * (*stored_basis) * viewer_basis->transpose();
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = linear;
  m.topRightCorner<3, 1>() = a_stored - linear * a_viewer;
  return m;
}

}  // namespace reenact
