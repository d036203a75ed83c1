#include "viewer-client/play/orbit_camera.h"

#include <cmath>
#include <numbers>

#include "common/error/check.h"

namespace reenact::viewer {

void OrbitCameraOptions::Check() const {
  REENACT_CHECK(std::isfinite(angle_deg), "angle_deg must be finite");
  REENACT_CHECK(std::isfinite(distance_scale) && distance_scale > 0, "distance_scale must be > 0");
  REENACT_CHECK(std::isfinite(height_offset_m), "height_offset_m must be finite");
}

std::optional<Eigen::Isometry3d> LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                                        const Eigen::Vector3d& world_up) {
  const Eigen::Vector3d forward = target - eye;
  if (!(forward.norm() > 1e-9) || !(world_up.norm() > 1e-9)) return std::nullopt;
  const Eigen::Vector3d z = forward.normalized();
  const Eigen::Vector3d x = z.cross(world_up.normalized());  // image right
  if (!(x.norm() > 1e-9)) return std::nullopt;
  Eigen::Matrix3d r;
  r.col(0) = x.normalized();
  r.col(2) = z;
  r.col(1) = z.cross(r.col(0));  // image down
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
  world_from_camera.linear() = r;
  world_from_camera.translation() = eye;
  return world_from_camera;
}

std::optional<Eigen::Isometry3d> OrbitWorldFromViewer(const Eigen::Isometry3d& world_from_sensor,
                                                      const Eigen::Vector3d& subject_centre,
                                                      const Eigen::Vector3d& world_up,
                                                      const OrbitCameraOptions& options) {
  options.Check();
  if (!(world_up.norm() > 1e-9)) return std::nullopt;
  const Eigen::Vector3d up = world_up.normalized();
  const Eigen::Vector3d offset = world_from_sensor.translation() - subject_centre;
  const Eigen::Vector3d vertical = offset.dot(up) * up;
  const Eigen::Vector3d horizontal = offset - vertical;
  const Eigen::AngleAxisd turn(options.angle_deg * std::numbers::pi / 180.0, up);
  const Eigen::Vector3d eye = subject_centre + vertical + options.height_offset_m * up +
                              options.distance_scale * (turn * horizontal);
  return LookAt(eye, subject_centre, up);
}

}  // namespace reenact::viewer
