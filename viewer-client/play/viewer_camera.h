#pragma once
// The viewer camera of the free-viewpoint presentation: intrinsics (the capture sensor's,
// scaled to the output size, without distortion) and the orbit pose with its floor grid.

#include <optional>

#include <Eigen/Geometry>

#include "common/geometry/pinhole_camera.h"
#include "viewer-client/play/orbit_camera.h"
#include "viewer-client/play/reenactment.h"
#include "viewer-client/render/renderer.h"

namespace reenact::viewer {

// The sensor's intrinsics for an image of width x height (pixel centres kept aligned).
PinholeCamera ScaledViewerCamera(const PinholeCamera& sensor, int width, int height);

struct OrbitView {
  Eigen::Isometry3d world_from_viewer;
  Eigen::Isometry3d viewer_from_world;
  FloorGrid floor;  // under the subject's lowest foot over the clip
};

// Orbit about the clip's subject centre, starting from frame 0's sensor pose; nullopt if the
// camera cannot be placed (sensor on the subject's vertical axis).
std::optional<OrbitView> OrbitViewFor(const Reenactment& reenactment,
                                      const OrbitCameraOptions& orbit);

}  // namespace reenact::viewer
