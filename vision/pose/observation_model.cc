#include "vision/pose/observation_model.h"

#include <algorithm>
#include <cmath>

#include "common/error/check.h"
#include "common/geometry/rotation.h"

namespace reenact::vision {

void ObservationNoise::Check() const {
  REENACT_CHECK(std::isfinite(pixel_sigma_px) && pixel_sigma_px > 0, "pixel_sigma_px must be > 0");
  REENACT_CHECK(std::isfinite(scale_factor) && scale_factor > 1, "scale_factor must be > 1");
  REENACT_CHECK(std::isfinite(depth_sigma_1m_m) && depth_sigma_1m_m > 0,
                "depth_sigma_1m_m must be > 0");
}

double ObservationNoise::PixelSigma(int octave) const {
  return pixel_sigma_px * std::pow(scale_factor, std::max(0, octave));
}

double ObservationNoise::DepthSigma(double depth_m, int octave) const {
  const double level = octave_scales_depth ? std::pow(scale_factor, std::max(0, octave)) : 1.0;
  return depth_sigma_1m_m * depth_m * depth_m * level;
}

double ObservationResidual::HuberWeight() const {
  const double norm = r.norm();
  const double delta = std::sqrt(Chi2Threshold());
  return norm <= delta ? 1.0 : delta / norm;
}

double ObservationResidual::HuberCost() const {
  const double norm = r.norm();
  const double delta = std::sqrt(Chi2Threshold());
  return norm <= delta ? 0.5 * norm * norm : delta * (norm - 0.5 * delta);
}

ObservationResidual EvaluateObservation(const Eigen::Vector3d& point_in_camera,
                                        const KeypointObservation& observation, double fx,
                                        double fy, const ObservationNoise& noise) {
  ObservationResidual out;
  const double z = point_in_camera.z();
  if (!(z > 0.01) || !point_in_camera.allFinite()) return out;
  out.valid = true;
  const double inv_z = 1.0 / z;
  const double x_n = point_in_camera.x() * inv_z, y_n = point_in_camera.y() * inv_z;
  const double sp = 1.0 / noise.PixelSigma(observation.octave);
  out.r(0) = fx * (x_n - observation.normalized.x()) * sp;
  out.r(1) = fy * (y_n - observation.normalized.y()) * sp;
  out.d_r_d_point.row(0) << fx * sp * inv_z, 0, -fx * sp * x_n * inv_z;
  out.d_r_d_point.row(1) << 0, fy * sp * inv_z, -fy * sp * y_n * inv_z;
  if (observation.depth_m > 0) {
    const double sd = 1.0 / noise.DepthSigma(observation.depth_m, observation.octave);
    out.dof = 3;
    out.r(2) = (z - observation.depth_m) * sd;
    out.d_r_d_point.row(2) << 0, 0, sd;
  }
  return out;
}

Eigen::Matrix<double, 3, 6> PointJacobianWrtPose(const Eigen::Vector3d& point_in_camera) {
  Eigen::Matrix<double, 3, 6> j;
  j.leftCols<3>().setIdentity();
  j.rightCols<3>() = -Skew(point_in_camera);
  return j;
}

Eigen::Isometry3d ApplyPoseUpdate(const Eigen::Matrix<double, 6, 1>& delta,
                                  const Eigen::Isometry3d& sensor_from_world) {
  const Eigen::Matrix3d r = ExpSo3(delta.tail<3>());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = NearestRotation(r * sensor_from_world.linear());
  out.translation() = r * sensor_from_world.translation() + delta.head<3>();
  return out;
}

}  // namespace reenact::vision
