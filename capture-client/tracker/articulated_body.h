#pragma once
// The tracker's articulated body: 12 rigid segments in a kinematic tree rooted at the pelvis,
// fixed bone lengths (set at calibration), and capsules attached to the segments for fitting.
//
// Frames. Every posed quantity is in the sensor frame (OpenCV axes, metres). Each segment has
// a local frame that, in the rest pose, is the body frame: x forward (the way the subject
// faces), y to the subject's left, z up; standing straight with the arms hanging down.
//
// Pose. world_from_pelvis = (root_rotation, root_translation at the waist joint); every other
// segment s has a local rotation local[s] relative to its parent, turning about its proximal
// joint:  R_s = R_parent(s) * local[s],  joint(s) = joint(parent) + R_parent * offset(s).
// Ball joints (spine, neck, shoulders, hips) turn freely up to a cone of max_angle around the
// rest orientation; the spine's two segments and the thighs also twist about their own axis
// (local z) by at most a twist limit (local[s] = swing * Rz(twist), the twist clamped); elbows and
// knees are hinges about the segment's local y axis with one angle in [0, max_flexion]: elbows bend
// the forearm forwards (local[s] = Ry(-angle)), knees the shin backwards (local[s] = Ry(+angle)).
//
// Parameters of a Gauss-Newton step (ParameterCount() = 31): root translation (3), root
// rotation (3, world axes about the waist), then per segment in Segment order 3 (ball, world
// axes about its proximal joint) or 1 (hinge angle). A step turns a segment and everything
// below it in the tree, so d(x)/d(omega) = omega x (x - joint) for every point x carried by
// the segment or its descendants.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "common/skeleton/skeleton.h"

namespace reenact::capture {

enum class BodySegment : int {
  kPelvis = 0,  // root: waist joint, hips
  kLowerSpine,  // waist -> torso
  kChest,       // torso -> neck, shoulders
  kHead,        // neck -> head
  kLeftUpperArm,
  kLeftForearm,  // hinge (elbow)
  kRightUpperArm,
  kRightForearm,  // hinge
  kLeftThigh,
  kLeftShin,  // hinge (knee)
  kRightThigh,
  kRightShin,  // hinge
};
inline constexpr int kBodySegmentCount = 12;

// Parent segment (-1 for the pelvis), whether the segment is a hinge, and its limits.
int SegmentParent(BodySegment s);
bool IsHinge(BodySegment s);

// The four limbs, each an upper segment on a ball joint and a lower one on a hinge.
enum class Limb { kLeftArm = 0, kRightArm, kLeftLeg, kRightLeg };
inline constexpr int kLimbCount = 4;
BodySegment LimbUpper(Limb limb);
BodySegment LimbLower(Limb limb);

// A capsule (the points within radius of the segment a-b) fixed to a segment; a and b in the
// segment's local frame, metres. The tracker fits 17: head; the chest, the abdomen and the
// pelvis each as a pair of parallel capsules (a rounded box, wider than deep); upper arms,
// forearms (elbow to palm centre, the fingers in the end cap); thighs, shins, and a foot on
// each shin, forward from the ankle (the ankle is not articulated).
struct BodyCapsule {
  BodySegment segment = BodySegment::kPelvis;
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  double radius = 0;
};

// Bone lengths and offsets (metres), in the rest pose's body frame; see the joint placement of
// DESIGN.md's skeleton. Built by calibration (body_calibration.h), then fixed.
struct BodyShape {
  double hip_half_width = 0.09;  // hips lateral of the waist
  double hip_drop = 0.08;        // hips below the waist
  double lower_spine = 0.22;     // waist -> torso
  double upper_spine = 0.29;     // torso -> neck
  double shoulder_half_width = 0.185;
  double shoulder_drop = 0.06;  // shoulders below the neck
  double head_rise = 0.12;      // neck -> head centre
  double upper_arm = 0.29;      // shoulder -> elbow
  double forearm = 0.32;        // elbow -> hand joint (palm centre)
  double thigh = 0.43;          // hip -> knee
  double shin = 0.41;           // knee -> foot joint (ankle)
  double ankle_height = 0.08;   // ankle above the sole
  // Capsule radii, metres: head, torso (each of the two parallel capsules; their axes lie
  // torso_half_spread to either side of the spine), upper arm, forearm, thigh, shin.
  double head_radius = 0.1;
  double torso_radius = 0.1;
  double torso_half_spread = 0.07;
  double upper_arm_radius = 0.045;
  double forearm_radius = 0.038;
  double thigh_radius = 0.07;
  double shin_radius = 0.05;
  double foot_radius = 0.04;  // foot capsule: ankle -> foot_length forward, foot_radius
  double foot_length = 0.12;

  // A shape scaled from an average adult (anthropometric proportions of Drillis and Contini,
  // as fractions of the standing height) to standing height height_m (> 0).
  static BodyShape FromHeight(double height_m);

  // Joints of the rest pose (standing, arms hanging, facing body +x), feet on z = 0.
  Skeleton RestSkeleton() const;
  // The standing height implied (head top above the floor in the rest pose).
  double StandingHeight() const;
  // Bone lengths of the 11 body parts (Index(BodyPart)), metres.
  std::array<double, kBodyPartCount> PartLengths() const;
  // Radius of each body part's single cylinder (torso parts: the mean of the half width and
  // half depth of the capsule pair), metres.
  std::array<double, kBodyPartCount> PartRadii() const;
  std::vector<BodyCapsule> Capsules() const;
};

struct ArticulatedPose {
  Eigen::Vector3d root_translation = Eigen::Vector3d::Zero();   // waist joint, sensor frame
  Eigen::Matrix3d root_rotation = Eigen::Matrix3d::Identity();  // sensor_from_pelvis
  std::array<Eigen::Matrix3d, kBodySegmentCount> local;         // [0] unused (identity)
  std::array<double, kBodySegmentCount> hinge_angle{};          // radians, hinges only

  ArticulatedPose();
};

// Limits (radians) of the joints; see articulated_body.h's header comment.
struct JointLimits {
  double spine_max = 0.9;  // each spine segment's cone, about 50 degrees
  double head_max = 1.2;
  double shoulder_max = 3.14;  // the arm reaches every direction
  double hip_max = 2.2;
  double elbow_max = 2.6;  // flexion, about 150 degrees
  double knee_max = 2.6;
  // Axial rotation, each about the segment's own axis. The two spine segments together turn
  // the shoulders up to 57 degrees from the pelvis, about the thoracolumbar spine's range to
  // either side; the thigh turns 46 degrees inwards or outwards, about the hip's range. Without
  // them the cones allow 100 and 126 degrees, and a body seen from the side, whose depth says
  // little about the twist, can be fitted with the pelvis turned far from the shoulders.
  double spine_twist_max = 0.5;
  double hip_twist_max = 0.8;
};

// Forward kinematics result: each segment's sensor_from_segment, and the skeleton.
struct PosedBody3 {
  std::array<Eigen::Isometry3d, kBodySegmentCount> sensor_from_segment;
  Skeleton skeleton;  // sensor frame; every joint present with confidence 1
};

class ArticulatedBody {
 public:
  static constexpr int kParameterCount = 31;

  explicit ArticulatedBody(const BodyShape& shape);

  const BodyShape& shape() const { return shape_; }
  const std::vector<BodyCapsule>& capsules() const { return capsules_; }
  // Offset of segment s's proximal joint from its parent's, in the parent's local frame.
  const Eigen::Vector3d& offset(BodySegment s) const { return offset_[static_cast<int>(s)]; }

  PosedBody3 Pose(const ArticulatedPose& pose) const;

  // First parameter index of segment s (the root: 3, its rotation; pelvis translation at 0).
  static int ParameterIndex(BodySegment s);

  // Applies a step delta (kParameterCount) at the current pose (see the header comment) and
  // clamps the joints to the limits.
  ArticulatedPose Step(const ArticulatedPose& pose, const PosedBody3& posed,
                       const Eigen::VectorXd& delta, const JointLimits& limits) const;

  // Clamps every joint into its limit (ball joints: the twist first where limited, then their
  // rotation angle to the cone's edge).
  static void Clamp(ArticulatedPose* pose, const JointLimits& limits);

  // The pose whose skeleton is nearest (least squares over the joints) to a target skeleton
  // in the rest pose's shape: root from the pelvis and torso joints, limbs by their bone
  // directions. Used to start from a detected calibration pose and in tests.
  ArticulatedPose PoseFromSkeleton(const Skeleton& target_in_sensor) const;

 private:
  BodyShape shape_;
  std::array<Eigen::Vector3d, kBodySegmentCount> offset_;
  std::vector<BodyCapsule> capsules_;
};

// A rotation about a unit axis by an angle (exp map of angle * axis); identity for a zero
// vector.
Eigen::Matrix3d ExpRotation(const Eigen::Vector3d& omega);

}  // namespace reenact::capture
