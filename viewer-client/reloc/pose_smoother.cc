#include "viewer-client/reloc/pose_smoother.h"

#include <cmath>

#include "common/error/check.h"
#include "vision/pose/observation_model.h"

namespace reenact::viewer {

void PoseSmootherOptions::Check() const {
  REENACT_CHECK(std::isfinite(acceleration_m) && acceleration_m > 0, "acceleration_m must be > 0");
  REENACT_CHECK(std::isfinite(acceleration_deg) && acceleration_deg > 0,
                "acceleration_deg must be > 0");
  REENACT_CHECK(std::isfinite(gate_chi2) && gate_chi2 > 0, "gate_chi2 must be > 0");
}

Eigen::Matrix<double, 6, 1> PoseDelta(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Matrix3d r = b.linear() * a.linear().transpose();
  const Eigen::AngleAxisd angle_axis(r);
  Eigen::Matrix<double, 6, 1> delta;
  delta.head<3>() = b.translation() - r * a.translation();
  delta.tail<3>() = angle_axis.axis() * angle_axis.angle();
  return delta;
}

PoseSmoother::PoseSmoother(const PoseSmootherOptions& options) : options_(options) {
  options_.Check();
}

std::optional<Eigen::Isometry3d> PoseSmoother::Predict() const {
  if (!pose_) return std::nullopt;
  return vision::ApplyPoseUpdate(velocity_, *pose_);
}

void PoseSmoother::Restart(const Eigen::Isometry3d& measured,
                           const Eigen::Matrix<double, 6, 6>& covariance) {
  pose_ = measured;
  velocity_.setZero();
  covariance_.setZero();
  covariance_.topLeftCorner<6, 6>() = covariance;
  // Unknown velocity: a few frames' worth of the largest motion the acceleration allows.
  const double t = 10 * options_.acceleration_m, r = 10 * options_.acceleration_deg * M_PI / 180;
  covariance_.bottomRightCorner<6, 6>().diagonal() << t * t, t * t, t * t, r * r, r * r, r * r;
  restarted_ = true;
}

Eigen::Isometry3d PoseSmoother::Update(const Eigen::Isometry3d& measured,
                                       const Eigen::Matrix<double, 6, 6>& information) {
  if (!measured.matrix().allFinite() || !information.allFinite()) {
    return Predict().value_or(measured);
  }
  // A floor on the information (1 mm, 0.06 degrees of standard deviation at most) keeps the
  // covariance finite where a frame says nothing.
  Eigen::Matrix<double, 6, 6> info = 0.5 * (information + information.transpose());
  info.diagonal().array() += 1e-6;
  const Eigen::Matrix<double, 6, 6> measurement_cov = info.inverse();
  if (!pose_) {
    Restart(measured, measurement_cov);
    return measured;
  }
  Matrix12 f = Matrix12::Identity();
  f.topRightCorner<6, 6>().setIdentity();
  Eigen::Matrix<double, 12, 6> g;
  g.topRows<6>() = 0.5 * Eigen::Matrix<double, 6, 6>::Identity();
  g.bottomRows<6>().setIdentity();
  Eigen::Matrix<double, 6, 1> accel;
  const double t = options_.acceleration_m, r = options_.acceleration_deg * M_PI / 180;
  accel << t * t, t * t, t * t, r * r, r * r, r * r;
  const Eigen::Isometry3d predicted = *Predict();
  const Matrix12 p = f * covariance_ * f.transpose() + g * accel.asDiagonal() * g.transpose();

  const Eigen::Matrix<double, 6, 1> y = PoseDelta(predicted, measured);
  const Eigen::Matrix<double, 6, 6> s = p.topLeftCorner<6, 6>() + measurement_cov;
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> s_ldlt(s);
  const double mahalanobis = y.dot(s_ldlt.solve(y));
  if (!std::isfinite(mahalanobis) || mahalanobis > options_.gate_chi2) {
    Restart(measured, measurement_cov);
    return measured;
  }
  const Eigen::Matrix<double, 12, 6> k =
      p.leftCols<6>() * s_ldlt.solve(Eigen::Matrix<double, 6, 6>::Identity());
  const Eigen::Matrix<double, 12, 1> correction = k * y;
  pose_ = vision::ApplyPoseUpdate(correction.head<6>(), predicted);
  velocity_ += correction.tail<6>();
  Matrix12 i_kh = Matrix12::Identity();
  i_kh.leftCols<6>() -= k;
  covariance_ = i_kh * p;
  covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
  restarted_ = false;
  return *pose_;
}

}  // namespace reenact::viewer
