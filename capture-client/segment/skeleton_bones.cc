#include "capture-client/segment/skeleton_bones.h"

namespace reenact::capture {

const std::array<Bone, kBoneCount>& SkeletonBones() {
  static const std::array<Bone, kBoneCount> bones = [] {
    std::array<Bone, kBoneCount> out{};
    for (int p = 0; p < kBodyPartCount; ++p) {
      const auto part = static_cast<BodyPart>(p);
      const auto [a, b] = PartJoints(part);
      out[p] = Bone{a, b, PartName(part)};
    }
    out[11] = Bone{Joint::kNeck, Joint::kLeftShoulder, "l_collar"};
    out[12] = Bone{Joint::kNeck, Joint::kRightShoulder, "r_collar"};
    out[13] = Bone{Joint::kWaist, Joint::kLeftHip, "l_pelvis"};
    out[14] = Bone{Joint::kWaist, Joint::kRightHip, "r_pelvis"};
    return out;
  }();
  return bones;
}

}  // namespace reenact::capture
