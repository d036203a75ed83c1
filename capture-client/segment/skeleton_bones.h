#pragma once
// The 15 bones of the 16-joint skeleton (common/skeleton/skeleton.h) as a tree rooted at the
// waist: the 11 body parts (cylinders) plus the four links that join the limbs to the trunk
// (neck-shoulder and waist-hip). Segmentation seeds along every bone; the consistency check
// measures every bone's length.

#include <array>
#include <string_view>

#include "common/skeleton/skeleton.h"

namespace reenact::capture {

struct Bone {
  Joint a;                // proximal joint
  Joint b;                // distal joint
  std::string_view name;  // part name ("l_forearm") or link name ("l_collar", "l_pelvis")
};

inline constexpr int kBoneCount = 15;

// Parts in BodyPart order (index = Index(part)), then l_collar (neck-l_shoulder), r_collar,
// l_pelvis (waist-l_hip), r_pelvis.
const std::array<Bone, kBoneCount>& SkeletonBones();

}  // namespace reenact::capture
