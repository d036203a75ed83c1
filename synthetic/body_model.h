#pragma once
// The synthetic subject's skeleton and forward kinematics: a ~1.75 m adult with the 16-joint
// skeleton of common/skeleton/skeleton.h, posed from a handful of angles.
//
// Frames. World: z up, floor at z = 0, metres. Body frame (rest): x forward (the way the
// subject faces), y to the subject's left, z up. With root_yaw = 0 the subject faces world
// -y, i.e. body x = world -y and body y = world +x; root_yaw turns the body about world z
// (counter-clockwise seen from above, so positive yaw turns the subject to its left).
//
// Joint placement (all inside the body):
//   head      centre of the head ellipsoid (about 1.63 m standing)
//   neck      base of the head, top of the neck (1.51 m)
//   torso     mid-spine, chest centre (1.22 m);  waist: pelvis centre (1.00 m)
//   shoulders top of the upper-arm segment (glenohumeral centre, 1.45 m, 0.185 m lateral)
//   elbows    elbow centre;  hands: palm centre, 0.07 m beyond the wrist
//   hips      hip joint centre (0.92 m, 0.09 m lateral);  knees: knee centre
//   feet      ankle centre (0.08 m above the floor when standing)
//
// Each segment (a rigid piece of surface, see body_mesh.h) has a frame that, in the rest
// pose, is parallel to the body frame, with its origin at the segment's proximal joint.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "common/skeleton/skeleton.h"

namespace reenact::capture {

enum class Segment : int {
  kHead = 0,
  kNeck,
  kUpperTorso,
  kLowerTorso,  // abdomen and pelvis
  kLeftUpperArm,
  kLeftForearm,
  kLeftHand,
  kRightUpperArm,
  kRightForearm,
  kRightHand,
  kLeftThigh,
  kLeftShin,
  kLeftFoot,
  kRightThigh,
  kRightShin,
  kRightFoot,
};
inline constexpr int kSegmentCount = 16;

// The body part whose label a segment's pixels carry (hands belong to the forearms, feet to
// the shins, the neck to the upper torso).
BodyPart SegmentPart(Segment s);

// Bone lengths and offsets of the subject, metres (see the joint placement above).
struct BodyDimensions {
  double hip_half_width = 0.09;        // lateral offset of each hip joint from the waist
  double hip_drop = 0.08;              // hips below the waist joint
  double lower_spine = 0.22;           // waist -> torso
  double upper_spine = 0.29;           // torso -> neck
  double shoulder_half_width = 0.185;  // lateral offset of each shoulder from the neck
  double shoulder_drop = 0.06;         // shoulders below the neck
  double head_forward = 0.01;          // head centre ahead of the neck
  double head_rise = 0.115;            // head centre above the neck
  double upper_arm = 0.29;             // shoulder -> elbow
  double forearm = 0.25;               // elbow -> wrist
  double wrist_to_palm = 0.07;         // wrist -> hand joint
  double thigh = 0.43;                 // hip -> knee
  double shin = 0.41;                  // knee -> ankle
  double ankle_height = 0.08;          // ankle above the sole
};

struct ArmPose {
  double abduction = 0;  // radians; raises the arm sideways (pi/2: horizontal, out)
  double flexion = 0;    // radians; raises the arm forwards (pi/2: horizontal, forward)
  double elbow = 0;      // radians; bends the forearm forwards, 0 = straight
};

struct LegPose {
  double flexion = 0;     // radians; swings the thigh forwards (pi/2: horizontal)
  double abduction = 0;   // radians; swings the leg outwards
  double knee = 0;        // radians; bends the shin backwards, 0 = straight
  double ankle = 0;       // radians; tips the toes down (plantar flexion)
  double ankle_roll = 0;  // radians; turns the foot about its long axis after `ankle`, the
                          // sole's outer edge up (inversion); -abduction keeps the sole flat
};

struct BodyPose {
  Eigen::Vector2d root_xy = Eigen::Vector2d::Zero();  // world x, y of the waist joint, metres
  double root_yaw = 0;                                // radians about world z; 0 = facing world -y
  double spine_bend = 0;   // radians, forward bend (half at the waist, half at the torso)
  double spine_twist = 0;  // radians, upper body turned to the left about the spine
  double head_pitch = 0;   // radians, nod forward
  ArmPose left_arm, right_arm;
  LegPose left_leg, right_leg;
};

struct PosedBody {
  Skeleton skeleton;  // world frame, every joint confidence 1
  std::array<Eigen::Isometry3d, kSegmentCount> world_from_segment;
};

// Forward kinematics. The waist height is chosen so that the lower ankle lies ankle_height
// above the floor (the subject stands on the floor).
PosedBody PoseBody(const BodyPose& pose, const BodyDimensions& dims = {});

}  // namespace reenact::capture
