#pragma once
// Pieces of render.json, the per-frame record a headless play writes beside its frames.

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "common/geometry/pinhole_camera.h"
#include "common/texture/subject_light.h"

namespace reenact::viewer {

// A pose as 16 numbers, the 4x4 matrix row-major.
nlohmann::json PoseJson(const Eigen::Isometry3d& pose);

// {"width", "height", "fx", "fy", "cx", "cy", "distortion": [k1, k2, p1, p2, k3]}.
nlohmann::json CameraJson(const PinholeCamera& camera);

// The clip's fitted subject light (common/texture/subject_light.h), so that a user sees
// whether the reenactment is relit: {"found", "light_in_world": [x, y, z], "strength",
// "gain", "samples", "bins"} and "reason" when none was found.
nlohmann::json SubjectLightJson(const SubjectLightFit& fit);

}  // namespace reenact::viewer
