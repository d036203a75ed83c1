#pragma once
// A BVH clip (bvh_file.h) as a motion of our 16-joint skeleton in the synthetic world: one
// Skeleton per output frame, world frame (z up, floor z = 0, metres; body_model.h), every
// joint confidence 1.
//
// Steps:
// 1. Joints. The rig's named joints (End Sites excluded) are mapped with
//    common/skeleton/joint_maps.h: CmuBvhJoints() when the names are exactly the CMU rig's
//    (in file order), else JointsByName(). Every one of our 16 joints must resolve.
// 2. Units. CMU rig: its metres_per_unit (1 unit = 1/0.45 inch). Other rigs, unless
//    options.metres_per_unit is given: the unit among metre, centimetre, millimetre and inch
//    that makes the first frame's head-to-lower-ankle height closest to kTypicalStature.
// 3. Axes. BVH is Y up; world = Rx(+90 deg) * bvh, i.e. (x, y, z)_bvh -> (x, -z, y)_world.
// 4. Placement, one rigid motion for the whole clip, from the first frame: a turn about the
//    vertical so that the subject faces world -y (facing = left x up, with left the mean of
//    l_hip - r_hip and l_shoulder - r_shoulder, horizontal), the waist over the world origin,
//    and the lower ankle at options.ankle_height_m (the rule of body_model.h: the foot joint
//    is the ankle, 0.08 m above the sole when standing; the clip's own vertical motion is
//    kept, no per-frame floor snapping).
// 5. Resampling to options.frame_rate_hz: output frame k shows source time k / rate, for
//    k = 0 .. floor(duration * rate + 0.001); joint positions are interpolated linearly between the
//    two nearest source frames (not rotations: at the CMU rate of 120 Hz and 30 Hz output,
//    samples fall within 0.03 source frames of a source frame).

#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "common/skeleton/skeleton.h"
#include "synthetic/bvh_file.h"

namespace reenact::capture {

// Head joint to ankle height used to guess the unit of a non-CMU rig, metres.
inline constexpr double kTypicalStature = 1.5;

struct BvhMotionOptions {
  double frame_rate_hz = 30;     // output rate, > 0
  double metres_per_unit = 0;    // 0: from the rig (see step 2); else > 0, finite
  double ankle_height_m = 0.08;  // the first frame's lower ankle above the floor, >= 0

  // Throws CheckError when a field is out of range.
  void Check() const;
};

struct BvhMotion {
  std::vector<Skeleton> skeletons;  // world frame, one per output frame, all complete
  double frame_rate_hz = 30;
  std::string joint_set;       // "cmu_bvh" or "by_name"
  double metres_per_unit = 1;  // the scale applied to the file's units
  // world_from_bvh after scaling the file's units to metres (axis change and placement).
  Eigen::Isometry3d world_from_bvh = Eigen::Isometry3d::Identity();
};

// Errors ("unsupported"): a rig whose joints do not resolve every one of our 16 joints (the
// message lists the missing joints and the rig's joint names); a first frame where the
// subject's left-right direction is vertical or zero (its facing is undefined).
Expected<BvhMotion> BvhToSkeletons(const BvhClip& clip, const BvhMotionOptions& options = {});

// ReadBvhFile + BvhToSkeletons; every error message starts with the path.
Expected<BvhMotion> LoadBvhMotion(const std::filesystem::path& path,
                                  const BvhMotionOptions& options = {});

}  // namespace reenact::capture
