#include "common/skeleton/skeleton.h"

#include "common/error/check.h"

namespace reenact {
namespace {

constexpr std::array<std::string_view, kJointCount> kJointNames = {
    "head",    "neck",       "torso",  "waist",  "l_shoulder", "l_elbow",
    "l_hand",  "r_shoulder", "r_elbow", "r_hand", "l_hip",      "l_knee",
    "l_foot",  "r_hip",      "r_knee", "r_foot"};

constexpr std::array<std::string_view, kBodyPartCount> kPartNames = {
    "head",        "upper_torso", "lower_torso", "l_upper_arm", "l_forearm", "r_upper_arm",
    "r_forearm",   "l_thigh",     "l_shin",      "r_thigh",     "r_shin"};

constexpr std::array<std::pair<Joint, Joint>, kBodyPartCount> kPartJoints = {{
    {Joint::kHead, Joint::kNeck},
    {Joint::kNeck, Joint::kTorso},
    {Joint::kTorso, Joint::kWaist},
    {Joint::kLeftShoulder, Joint::kLeftElbow},
    {Joint::kLeftElbow, Joint::kLeftHand},
    {Joint::kRightShoulder, Joint::kRightElbow},
    {Joint::kRightElbow, Joint::kRightHand},
    {Joint::kLeftHip, Joint::kLeftKnee},
    {Joint::kLeftKnee, Joint::kLeftFoot},
    {Joint::kRightHip, Joint::kRightKnee},
    {Joint::kRightKnee, Joint::kRightFoot},
}};

}  // namespace

std::string_view JointName(Joint j) {
  REENACT_CHECK(Index(j) >= 0 && Index(j) < kJointCount, "joint out of range");
  return kJointNames[Index(j)];
}

std::string_view PartName(BodyPart p) {
  REENACT_CHECK(Index(p) >= 0 && Index(p) < kBodyPartCount, "part out of range");
  return kPartNames[Index(p)];
}

std::optional<Joint> JointFromName(std::string_view name) {
  for (int i = 0; i < kJointCount; ++i)
    if (kJointNames[i] == name) return static_cast<Joint>(i);
  return std::nullopt;
}

std::optional<BodyPart> PartFromName(std::string_view name) {
  for (int i = 0; i < kBodyPartCount; ++i)
    if (kPartNames[i] == name) return static_cast<BodyPart>(i);
  return std::nullopt;
}

std::pair<Joint, Joint> PartJoints(BodyPart p) {
  REENACT_CHECK(Index(p) >= 0 && Index(p) < kBodyPartCount, "part out of range");
  return kPartJoints[Index(p)];
}

Skeleton::Skeleton() {
  position.fill(Eigen::Vector3d::Zero());
  confidence.fill(0.0);
}

bool Skeleton::HasPart(BodyPart p) const {
  const auto [a, b] = PartJoints(p);
  return Has(a) && Has(b);
}

bool Skeleton::Complete() const {
  for (double c : confidence)
    if (!(c > 0)) return false;
  return true;
}

void Skeleton::Set(Joint j, const Eigen::Vector3d& p, double conf) {
  REENACT_CHECK(p.allFinite(), "joint position must be finite");
  REENACT_CHECK(conf >= 0 && conf <= 1, "confidence must lie in [0, 1]");
  position[Index(j)] = p;
  confidence[Index(j)] = conf;
}

Skeleton Skeleton::Transformed(const Eigen::Isometry3d& b_from_a) const {
  Skeleton out = *this;
  for (int i = 0; i < kJointCount; ++i) out.position[i] = b_from_a * position[i];
  return out;
}

std::optional<Skeleton> NeckRelative(const Skeleton& skeleton) {
  if (!skeleton.Has(Joint::kNeck)) return std::nullopt;
  Skeleton out = skeleton;
  const Eigen::Vector3d neck = skeleton[Joint::kNeck];
  for (int i = 0; i < kJointCount; ++i)
    out.position[i] = out.confidence[i] > 0 ? Eigen::Vector3d(skeleton.position[i] - neck)
                                            : Eigen::Vector3d::Zero();
  return out;
}

}  // namespace reenact
