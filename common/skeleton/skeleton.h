#pragma once
// The 16-joint, 11-part skeleton of DESIGN.md (the NiTE skeleton the thesis used).
// Joint positions are in metres in whatever frame the owner states (world, sensor, viewer);
// every joint carries a confidence in [0, 1], and confidence 0 means "missing": its
// position must not be used (it is kept finite, never NaN).

#include <array>
#include <optional>
#include <string_view>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace reenact {

enum class Joint : int {
  kHead = 0,
  kNeck,
  kTorso,
  kWaist,
  kLeftShoulder,
  kLeftElbow,
  kLeftHand,
  kRightShoulder,
  kRightElbow,
  kRightHand,
  kLeftHip,
  kLeftKnee,
  kLeftFoot,
  kRightHip,
  kRightKnee,
  kRightFoot,
};
inline constexpr int kJointCount = 16;

// Body parts, each a cylinder between two joints (a, b) = PartJoints(part).
enum class BodyPart : int {
  kHead = 0,     // head - neck
  kUpperTorso,   // neck - torso
  kLowerTorso,   // torso - waist
  kLeftUpperArm, // l_shoulder - l_elbow
  kLeftForearm,  // l_elbow - l_hand
  kRightUpperArm,
  kRightForearm,
  kLeftThigh,    // l_hip - l_knee
  kLeftShin,     // l_knee - l_foot
  kRightThigh,
  kRightShin,
};
inline constexpr int kBodyPartCount = 11;

// Label images store part index + 1; 0 is background (see kBackgroundLabel).
inline constexpr int kBackgroundLabel = 0;
inline constexpr int PartLabel(BodyPart p) { return static_cast<int>(p) + 1; }

inline constexpr int Index(Joint j) { return static_cast<int>(j); }
inline constexpr int Index(BodyPart p) { return static_cast<int>(p); }

// Snake-case names as in DESIGN.md and the manifest ("head", "l_shoulder", ...).
std::string_view JointName(Joint j);
std::string_view PartName(BodyPart p);
std::optional<Joint> JointFromName(std::string_view name);
std::optional<BodyPart> PartFromName(std::string_view name);

// The two joints (a, b) whose segment is the part's cylinder axis.
std::pair<Joint, Joint> PartJoints(BodyPart p);

struct Skeleton {
  std::array<Eigen::Vector3d, kJointCount> position;  // metres, frame stated by the owner
  std::array<double, kJointCount> confidence;          // [0, 1]; 0 = missing

  Skeleton();  // every joint missing, at the origin

  const Eigen::Vector3d& operator[](Joint j) const { return position[Index(j)]; }
  Eigen::Vector3d& operator[](Joint j) { return position[Index(j)]; }
  bool Has(Joint j) const { return confidence[Index(j)] > 0; }
  bool HasPart(BodyPart p) const;
  bool Complete() const;  // every joint present

  // Sets a joint present with the given confidence.
  void Set(Joint j, const Eigen::Vector3d& p, double conf = 1.0);

  // The same skeleton in frame b, given b_from_a and this skeleton in frame a.
  Skeleton Transformed(const Eigen::Isometry3d& b_from_a) const;
};

// The neck-relative form used by texture selection (thesis Eq. 5): every present joint i at
// s_i - s_neck, so the neck lands at the origin; missing joints stay missing (at the origin),
// confidences unchanged. nullopt if the neck is missing.
std::optional<Skeleton> NeckRelative(const Skeleton& skeleton);

}  // namespace reenact
