#include "viewer-client/play/viewer_camera.h"

#include <algorithm>

namespace reenact::viewer {

PinholeCamera ScaledViewerCamera(const PinholeCamera& sensor, int width, int height) {
  PinholeCamera c = sensor;
  c.distortion = {};
  const double sx = static_cast<double>(width) / sensor.width;
  const double sy = static_cast<double>(height) / sensor.height;
  c.width = width;
  c.height = height;
  c.fx *= sx;
  c.cx = (c.cx + 0.5) * sx - 0.5;
  c.fy *= sy;
  c.cy = (c.cy + 0.5) * sy - 0.5;
  return c;
}

std::optional<OrbitView> OrbitViewFor(const Reenactment& reenactment,
                                      const OrbitCameraOptions& orbit) {
  const Eigen::Vector3d up = reenactment.manifest().world_up.normalized();
  const Eigen::Vector3d centre = reenactment.SubjectCentre();
  const auto world_from_viewer =
      OrbitWorldFromViewer(reenactment.frame(0).world_from_sensor, centre, up, orbit);
  if (!world_from_viewer) return std::nullopt;
  OrbitView view;
  view.world_from_viewer = *world_from_viewer;
  view.viewer_from_world = world_from_viewer->inverse();
  double lowest = 0;
  for (int n = 0; n < reenactment.frame_count(); ++n)
    for (Joint j : {Joint::kLeftFoot, Joint::kRightFoot})
      if (reenactment.frame(n).skeleton_in_world.Has(j))
        lowest = std::min(lowest, (reenactment.frame(n).skeleton_in_world[j] - centre).dot(up));
  view.floor.viewer_from_world = view.viewer_from_world;
  view.floor.up_in_world = up;
  // Foot joints sit at the ankles, a few centimetres above the floor.
  view.floor.point_on_floor_in_world = centre + (lowest - 0.08) * up;
  return view;
}

}  // namespace reenact::viewer
