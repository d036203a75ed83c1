#pragma once
// Hand-built skeletons for tests, in a camera frame (x right, y down, z forward), metres.

#include <Eigen/Geometry>

#include "common/skeleton/skeleton.h"

namespace reenact::testing {

// A person standing `distance` metres in front of the camera, facing it, rotated by yaw
// (radians, about the vertical -y axis through the waist). arms_out: held out sideways,
// else hanging down. crossed_legs swaps the feet across the midline.
inline Skeleton StandingPerson(double distance, double yaw, bool arms_out,
                               bool crossed_legs = false) {
  // Facing the camera: the person's left is the camera's +x... no: a person facing the camera
  // has their left hand on the image's right (+x).
  Skeleton s;
  const double arm_y = arms_out ? -0.35 : 0.2;  // hand height relative to origin (y down)
  const double arm_x = arms_out ? 0.8 : 0.25;
  const double foot_x = crossed_legs ? -0.05 : 0.12;
  const Eigen::Vector3d local[16] = {
      {0, -0.75, 0},                          // head
      {0, -0.55, 0},                          // neck
      {0, -0.3, 0},                           // torso
      {0, 0.0, 0},                            // waist
      {0.2, -0.5, 0},     {arm_x * 0.6, arms_out ? -0.45 : -0.15, 0}, {arm_x, arm_y, 0},
      {-0.2, -0.5, 0},    {-arm_x * 0.6, arms_out ? -0.45 : -0.15, 0}, {-arm_x, arm_y, 0},
      {0.1, 0.05, 0},     {0.11, 0.5, 0.02},  {foot_x, 0.95, 0},
      {-0.1, 0.05, 0},    {-0.11, 0.5, 0.02}, {-foot_x, 0.95, 0},
  };
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(yaw, -Eigen::Vector3d::UnitY()).toRotationMatrix();
  for (int i = 0; i < kJointCount; ++i)
    s.Set(static_cast<Joint>(i), rot * local[i] + Eigen::Vector3d(0, 0, distance));
  return s;
}

}  // namespace reenact::testing
