#pragma once
// Scripted motions of the synthetic subject: a pose per frame and a static sensor.
//
// "turn-and-kick" (30 fps, 180 frames = 6 s):
//   0.0-0.7 s  calibration pose: facing the sensor, arms held out to the sides
//   0.7-1.2 s  arms come down to the sides
//   1.2-4.0 s  a full 360-degree turn in place (to the subject's left), stepping, with
//              swinging arms
//   4.0-5.0 s  a front kick with the right leg, arms in guard
//   5.0-6.0 s  the right arm raised overhead, the left arm out sideways, then lowered
// "calibration" (30 fps, 30 frames): the calibration pose held still.

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "capture-client/synthetic/body_model.h"
#include "common/error/expected.h"

namespace reenact::capture {

struct Scenario {
  std::string name;
  double frame_rate_hz = 30;
  std::vector<BodyPose> poses;  // one per frame
  // The static sensor: about 3 m in front of the subject at 1.3 m height, looking at it.
  Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d::Identity();
};

std::vector<std::string> SyntheticScenarioNames();

// The named scenario; an Error listing the known names when it is unknown.
Expected<Scenario> MakeScenario(std::string_view name);

// world_from_camera of an OpenCV camera at `eye` looking at `target`, image up along world
// +z (eye and target in the world frame; the view direction must not be vertical).
Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);

}  // namespace reenact::capture
