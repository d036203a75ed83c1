#pragma once
// Helpers of the skeleton-track tests: a synthetic subject seen by a sensor in front of it
// (ground truth by construction), and Kinect v1 text files written from it with the inverse
// of the importer's mapping, written out here independently of the importer.

#include <Eigen/Geometry>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "common/skeleton/skeleton.h"
#include "synthetic/body_model.h"
#include "tests/support/temp_dir.h"

namespace reenact::capture::skeleton_test {

using reenact::test_support::TempDir;
namespace fs = std::filesystem;

inline void WriteText(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

// The synthetic subject (facing world -y) in pose `phase`, seen by a level sensor 2.6 m in
// front of it at 1.1 m height looking along world +y: sensor x = world x, sensor y = world
// -z, sensor z = world y.
inline Skeleton SyntheticSkeletonInSensor(double phase) {
  BodyPose pose;
  pose.left_arm.abduction = 0.6 + 0.3 * phase;
  pose.left_arm.elbow = 0.8;
  pose.right_arm.flexion = 1.0 - 0.4 * phase;
  pose.right_leg.flexion = 0.5 * phase;
  pose.right_leg.knee = 0.6 * phase;
  pose.spine_bend = 0.1;
  const Skeleton world = PoseBody(pose).skeleton;
  Eigen::Matrix3d world_from_sensor_r;
  world_from_sensor_r.col(0) = Eigen::Vector3d(1, 0, 0);
  world_from_sensor_r.col(1) = Eigen::Vector3d(0, 0, -1);
  world_from_sensor_r.col(2) = Eigen::Vector3d(0, 1, 0);
  Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d::Identity();
  world_from_sensor.linear() = world_from_sensor_r;
  world_from_sensor.translation() = Eigen::Vector3d(0.1, -2.6, 1.1);
  return world.Transformed(world_from_sensor.inverse());
}

// Kinect skeleton space (x to the sensor's left, y up, z forward) from our sensor frame.
inline Eigen::Vector3d KinectFromSensor(const Eigen::Vector3d& p) {
  return {-p.x(), -p.y(), p.z()};
}

// Kinect SDK joint names in NUI_SKELETON_POSITION_INDEX order.
inline const std::array<std::string, 20>& KinectSdkNames() {
  static const std::array<std::string, 20> names = {
      "HipCenter",  "Spine",     "ShoulderCenter", "Head",          "ShoulderLeft",
      "ElbowLeft",  "WristLeft", "HandLeft",       "ShoulderRight", "ElbowRight",
      "WristRight", "HandRight", "HipLeft",        "KneeLeft",      "AnkleLeft",
      "FootLeft",   "HipRight",  "KneeRight",      "AnkleRight",    "FootRight"};
  return names;
}

// MSR Action3D line order, by Kinect name (kinect_v1_skeleton.h).
inline const std::array<std::string, 20>& MsrAction3dNames() {
  static const std::array<std::string, 20> names = {
      "ShoulderRight", "ShoulderLeft", "ShoulderCenter", "Spine",     "HipRight",
      "HipLeft",       "HipCenter",    "ElbowRight",     "ElbowLeft", "WristRight",
      "WristLeft",     "HandRight",    "HandLeft",       "KneeRight", "KneeLeft",
      "AnkleRight",    "AnkleLeft",    "FootRight",      "FootLeft",  "Head"};
  return names;
}

// UTD-MHAD line order, by Kinect name (the data set's list: head, shoulder_center, spine,
// hip_center, left_shoulder, ..., right_foot).
inline const std::array<std::string, 20>& UtdMhadNames() {
  static const std::array<std::string, 20> names = {
      "Head",       "ShoulderCenter", "Spine",     "HipCenter",     "ShoulderLeft",
      "ElbowLeft",  "WristLeft",      "HandLeft",  "ShoulderRight", "ElbowRight",
      "WristRight", "HandRight",      "HipLeft",   "KneeLeft",      "AnkleLeft",
      "FootLeft",   "HipRight",       "KneeRight", "AnkleRight",    "FootRight"};
  return names;
}

// The 20 Kinect joints of a subject, in skeleton space, by name: our joints where Kinect
// has them, wrists 80% of the way from elbow to hand (the hand joint is 7 cm past the wrist
// on a 25 cm forearm) and the feet 12 cm ahead of and 6 cm below the ankles.
inline std::map<std::string, Eigen::Vector3d> KinectJoints(const Skeleton& s) {
  std::map<std::string, Eigen::Vector3d> k;
  const auto put = [&](const std::string& name, const Eigen::Vector3d& p_sensor) {
    k[name] = KinectFromSensor(p_sensor);
  };
  put("HipCenter", s[Joint::kWaist]);
  put("Spine", s[Joint::kTorso]);
  put("ShoulderCenter", s[Joint::kNeck]);
  put("Head", s[Joint::kHead]);
  put("ShoulderLeft", s[Joint::kLeftShoulder]);
  put("ElbowLeft", s[Joint::kLeftElbow]);
  put("WristLeft", s[Joint::kLeftElbow] + 0.8 * (s[Joint::kLeftHand] - s[Joint::kLeftElbow]));
  put("HandLeft", s[Joint::kLeftHand]);
  put("ShoulderRight", s[Joint::kRightShoulder]);
  put("ElbowRight", s[Joint::kRightElbow]);
  put("WristRight", s[Joint::kRightElbow] + 0.8 * (s[Joint::kRightHand] - s[Joint::kRightElbow]));
  put("HandRight", s[Joint::kRightHand]);
  put("HipLeft", s[Joint::kLeftHip]);
  put("KneeLeft", s[Joint::kLeftKnee]);
  put("AnkleLeft", s[Joint::kLeftFoot]);
  // Sensor frame: toward the sensor is -z, down is +y.
  put("FootLeft", s[Joint::kLeftFoot] + Eigen::Vector3d(0, 0.06, -0.12));
  put("HipRight", s[Joint::kRightHip]);
  put("KneeRight", s[Joint::kRightKnee]);
  put("AnkleRight", s[Joint::kRightFoot]);
  put("FootRight", s[Joint::kRightFoot] + Eigen::Vector3d(0, 0.06, -0.12));
  return k;
}

inline std::string Xyz(const Eigen::Vector3d& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof(buffer), "%.9f %.9f %.9f", p.x(), p.y(), p.z());
  return buffer;
}

// One UTKinect line: frame number, then the 20 joints in SDK order.
inline std::string UtKinectLine(int64_t frame_number,
                                const std::map<std::string, Eigen::Vector3d>& joints) {
  std::string line = std::to_string(frame_number);
  for (const std::string& name : KinectSdkNames()) {
    line += ' ';
    line += Xyz(joints.at(name));
  }
  line += '\n';
  return line;
}

// One MSR Action3D frame: 20 lines "x y z c" in the MSR order (c = 0 as in the data set).
inline std::string MsrAction3dFrame(const std::map<std::string, Eigen::Vector3d>& joints) {
  std::string text;
  for (const std::string& name : MsrAction3dNames()) {
    text += Xyz(joints.at(name));
    text += " 0\n";
  }
  return text;
}

// One UTD-MHAD frame: 20 lines "x y z" in the UTD-MHAD order.
inline std::string UtdMhadFrame(const std::map<std::string, Eigen::Vector3d>& joints) {
  std::string text;
  for (const std::string& name : UtdMhadNames()) {
    text += Xyz(joints.at(name));
    text += '\n';
  }
  return text;
}

}  // namespace reenact::capture::skeleton_test
