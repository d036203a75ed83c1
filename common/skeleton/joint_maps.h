#pragma once
// Mapping tables from other joint sets onto the 16-joint skeleton of skeleton.h, in one place
// (DESIGN.md, "Skeleton"). A JointSetDefinition names the source joints in the source's own
// index order and gives, for each of our joints, a list of recipes in order of preference.
// A recipe is one named source joint or a weighted mean of several; the first recipe whose
// source joints are all present is used. Where none is, our joint is missing (confidence 0,
// position at the origin): a missing source joint never turns into a NaN.
//
// The built-in tables and where our joints without a direct counterpart come from:
// - KinectV1Joints(): Microsoft Kinect SDK v1, 20 joints in NUI_SKELETON_POSITION_INDEX order
//   (the order of the public UTKinect-Action3D and MSR Action3D skeleton files).
//   neck = ShoulderCenter, torso = Spine, waist = HipCenter; hand = HandLeft (else WristLeft);
//   foot = AnkleLeft (else FootLeft), since our shin ends at the ankle as NiTE's foot does.
// - NiteJoints(): OpenNI 1 / NiTE 1, the 15 joints NiTE tracks, in XnSkeletonJoint order
//   without the untracked ones (HEAD, NECK, TORSO, LEFT_SHOULDER, LEFT_ELBOW, LEFT_HAND,
//   RIGHT_SHOULDER, RIGHT_ELBOW, RIGHT_HAND, LEFT_HIP, LEFT_KNEE, LEFT_FOOT, RIGHT_HIP,
//   RIGHT_KNEE, RIGHT_FOOT). NiTE has no waist: waist = mean(LEFT_HIP, RIGHT_HIP).
// - Nite2Joints(): the same 15 joints in NiTE 2's nite::JointType order (HEAD, NECK,
//   LEFT_SHOULDER, RIGHT_SHOULDER, LEFT_ELBOW, RIGHT_ELBOW, LEFT_HAND, RIGHT_HAND, TORSO,
//   LEFT_HIP, RIGHT_HIP, LEFT_KNEE, RIGHT_KNEE, LEFT_FOOT, RIGHT_FOOT); waist as NiTE 1.
// - CmuBvhJoints(): the 31-joint CMU rig of the 3ds-Max-friendly BVH conversion, in file
//   order (Hips, LHipJoint, LeftHip, LeftKnee, LeftAnkle, LeftToe, RHipJoint, ..., lowerback,
//   Chest, Chest2, lowerneck, Neck, Head, LeftCollar, LeftShoulder, LeftElbow, LeftWrist,
//   lhand, LFingers, LThumb, RightCollar, ...). A BVH joint's position is its local origin:
//   head = Head (the base of the skull: the rig has no joint at the head's centre),
//   neck = Neck (at shoulder height), torso = mean(Chest, Chest2) (about half way from the
//   hips to the neck), waist = Hips, shoulder = LeftShoulder, elbow = LeftElbow,
//   hand = LeftWrist (else lhand), hip = LeftHip, knee = LeftKnee, foot = LeftAnkle.
//   metres_per_unit = 0.0254 / 0.45 (CMU units: 1/0.45 inch).
// - JointsByName() / GltfJointsByName(): any rig given by joint names (glTF skins, BVH files
//   of other conversions, Mixamo, VRM humanoid, Blender rigify, the Kinect and CMU names).
//   Names are matched case-insensitively after dropping any namespace prefix ("mixamorig:",
//   "Armature|") and every character that is not a letter or digit, against the tables in
//   joint_maps.cc, in order of preference (so Mixamo's LeftArm, the upper arm whose origin is
//   the shoulder, wins over its LeftShoulder, the clavicle). Where no torso name matches,
//   torso = mean(neck, waist) of the matched joints.
//
// Positions are mapped in the source's own frame (no axis change); only the unit is scaled.

#include <Eigen/Core>
#include <array>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/error/expected.h"
#include "common/skeleton/skeleton.h"

namespace reenact {

// One way to obtain our joint: sum_i weight[i] * source position source[i].
struct JointRecipe {
  std::vector<int> source;     // source joint indices, each in [0, source_names.size())
  std::vector<double> weight;  // same length as source, each > 0, summing to 1
};

struct JointSetDefinition {
  std::string name;                       // e.g. "kinect_v1"
  std::vector<std::string> source_names;  // source joint names, index = source index
  // For each of our joints (index = Index(Joint)): recipes in order of preference; empty
  // means the source set has no counterpart (the joint is always missing).
  std::array<std::vector<JointRecipe>, kJointCount> recipes;
  double metres_per_unit = 1.0;  // scale from source units to metres, finite, > 0

  // Throws CheckError if a recipe is malformed (index out of range, sizes, weights).
  void Check() const;
};

// The built-in tables (see the header comment).
const JointSetDefinition& KinectV1Joints();
const JointSetDefinition& NiteJoints();
const JointSetDefinition& Nite2Joints();
const JointSetDefinition& CmuBvhJoints();

// A definition for a rig known only by its joint names (index = position in names).
// Errors ("invalid_argument"): no names, two names equal after normalisation, or no name
// matches any of our joints.
Expected<JointSetDefinition> JointsByName(std::vector<std::string> names,
                                          std::string set_name = "by_name");
// JointsByName for a glTF skin's joint names (skin.joints order).
Expected<JointSetDefinition> GltfJointsByName(std::vector<std::string> names);

// The source's joint name normalised as JointsByName compares it: lower case, letters and
// digits only, namespace prefix (up to the last ':' or '|') dropped.
std::string NormalizeJointName(std::string_view name);

// Maps one source skeleton onto ours. positions: one per source joint, source units, in any
// frame (the result is in the same frame, in metres). confidences: one per source joint in
// [0, 1] (0 = missing), or empty for "all present". A source joint with a non-finite
// position counts as missing. A mapped joint's confidence is the least of its sources'.
// Errors ("invalid_argument"): a size that differs from definition.source_names, or a
// confidence outside [0, 1] or NaN.
Expected<Skeleton> MapSkeleton(const JointSetDefinition& definition,
                               std::span<const Eigen::Vector3d> positions,
                               std::span<const double> confidences = {});

}  // namespace reenact
