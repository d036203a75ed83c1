#include "common/geometry/rotation.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

#include "common/error/check.h"

namespace reenact {
namespace {

// Rodrigues with a unit axis n.
Eigen::Matrix3d RodriguesUnit(const Eigen::Vector3d& n, double angle) {
  const Eigen::Matrix3d k = Skew(n);
  const double half_sin = std::sin(0.5 * angle);
  return Eigen::Matrix3d::Identity() + std::sin(angle) * k + (2 * half_sin * half_sin) * (k * k);
}

bool Usable(const Eigen::Vector3d& v) { return v.allFinite() && v != Eigen::Vector3d::Zero(); }

}  // namespace

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d k;
  k << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return k;
}

std::optional<Eigen::Matrix3d> Theta(const Eigen::Vector3d& axis, double angle) {
  if (!Usable(axis) || !std::isfinite(angle)) return std::nullopt;
  return RodriguesUnit(axis.stableNormalized(), angle);
}

Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& omega) {
  REENACT_CHECK(omega.allFinite(), "ExpSo3: rotation vector must be finite");
  const double t = omega.stableNorm();
  if (t >= 1e-4) return RodriguesUnit(omega / t, t);
  const double t2 = t * t;
  const double a = 1 - t2 / 6 * (1 - t2 / 20);     // sin(t) / t
  const double b = 0.5 - t2 / 24 * (1 - t2 / 30);  // (1 - cos t) / t^2
  const Eigen::Matrix3d k = Skew(omega);
  return Eigen::Matrix3d::Identity() + a * k + b * (k * k);
}

std::optional<double> AngleBetween(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  if (!Usable(u) || !Usable(v)) return std::nullopt;
  const Eigen::Vector3d a = u.stableNormalized(), b = v.stableNormalized();
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

std::optional<Eigen::Vector3d> AnyPerpendicular(const Eigen::Vector3d& u) {
  if (!Usable(u)) return std::nullopt;
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(u[i]) < std::abs(u[k])) k = i;
  const Eigen::Vector3d a = u.stableNormalized();
  return a.cross(Eigen::Vector3d::Unit(k)).stableNormalized();
}

std::optional<Eigen::Matrix3d> RotationBetween(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  if (!Usable(u) || !Usable(v)) return std::nullopt;
  const Eigen::Vector3d a = u.stableNormalized(), b = v.stableNormalized();
  const Eigen::Vector3d c = a.cross(b);
  const double angle = std::atan2(c.norm(), a.dot(b));
  // The axis must be orthogonal to a; rounding in c can tilt it by eps / |c|.
  const Eigen::Vector3d axis = c - c.dot(a) * a;
  if (axis.stableNorm() > 0) return RodriguesUnit(axis.stableNormalized(), angle);
  if (a.dot(b) > 0) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d n = *AnyPerpendicular(a);
  return Eigen::Matrix3d(2 * n * n.transpose() - Eigen::Matrix3d::Identity());
}

double RotationAngle(const Eigen::Matrix3d& r) {
  const Eigen::Vector3d vee(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
  return std::atan2(0.5 * vee.norm(), 0.5 * (r.trace() - 1));
}

double OrthonormalityError(const Eigen::Matrix3d& r) {
  return (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
}

Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& m) {
  REENACT_CHECK(m.allFinite(), "NearestRotation: matrix must be finite");
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d d(1, 1, (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1);
  return svd.matrixU() * d.asDiagonal() * svd.matrixV().transpose();
}

}  // namespace reenact
