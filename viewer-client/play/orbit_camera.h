#pragma once
// The free-viewpoint camera: the capture sensor's position turned about the vertical axis
// (world_up) through the subject's centre by an angle, looking at the subject's centre, so a
// viewer sees the reenactment from where nobody recorded it.

#include <optional>

#include <Eigen/Geometry>

namespace reenact::viewer {

struct OrbitCameraOptions {
  double angle_deg = 60;       // turn about the vertical axis, positive counter-clockwise seen
                               // from above (right-handed about world_up)
  double distance_scale = 1;   // > 0: horizontal distance to the centre, times the sensor's
  double height_offset_m = 0;  // added to the sensor's height along world_up

  void Check() const;
};

// OpenCV camera looking from eye at target with world_up roughly up in the image (y down);
// nullopt if eye == target or the view direction is parallel to world_up.
std::optional<Eigen::Isometry3d> LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                                        const Eigen::Vector3d& world_up);

// world_from_viewer of the orbit camera; nullopt for degenerate input (see LookAt, or a
// zero world_up).
std::optional<Eigen::Isometry3d> OrbitWorldFromViewer(const Eigen::Isometry3d& world_from_sensor,
                                                      const Eigen::Vector3d& subject_centre,
                                                      const Eigen::Vector3d& world_up,
                                                      const OrbitCameraOptions& options);

}  // namespace reenact::viewer
