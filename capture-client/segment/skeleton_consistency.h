#pragma once
// Consistency of a clip's skeletons (issue 5, "Skeleton sources"): frames whose skeleton a
// tracker misregistered are flagged, and texturing and model building skip them.
//
// Per frame, three checks:
//  - missing joints: any joint missing (confidence 0) or not finite. Model building fits every
//    part and texture selection (Eq. 5) compares every joint, so such a frame is unusable
//    for both (it still serves SLAM).
//  - bone length: each bone (skeleton_bones.h) whose length L differs from the clip's median
//    M for that bone (over the frames where both its joints are present) by more than
//    max(max_relative_deviation * M, min_absolute_deviation_m).
//    Why the clip median and not frame-to-frame jumps: a person's bones do not change, so
//    every frame should match one length; the median is that length as long as fewer than
//    half the frames are wrong; a jump test flags the good frame after a bad one too, misses
//    slow drift and a bad first frame, and cannot tell which side of a jump is wrong.
//  - left/right swap: a swap of every left joint with its right twin keeps all bone lengths
//    (the body is symmetric), so it is caught by the shoulder axis (l_shoulder - r_shoulder)
//    and the hip axis: between frames at most max_gap_frames apart, an axis that turns by
//    more than max_axis_turn_deg (no person turns 90 degrees in 1/30 s) marks a flip. Frames
//    are split by flips into runs; within a chain of runs linked by such comparisons, the
//    frames on the side (flipped or not) that holds fewer frames are flagged. A tie flags
//    nothing (no way to tell which side is right).
//
// Pure function over the skeletons in any one frame (the world frame for a clip; lengths
// and angles do not depend on it).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "capture-client/segment/skeleton_bones.h"
#include "common/skeleton/skeleton.h"

namespace reenact::capture {

struct SkeletonConsistencyOptions {
  // Bone length tolerance: relative to the clip's median (default 0.15, in (0, 1]) and at
  // least min_absolute_deviation_m (default 0.02 m, >= 0: a tracker's joint jitter of about
  // 1 cm should not flag the 11 cm head bone).
  double max_relative_deviation = 0.15;
  double min_absolute_deviation_m = 0.02;
  // Left/right swap: the largest turn of the shoulder or hip axis between compared frames,
  // degrees in (0, 180) (default 90), and the largest gap between compared frames, >= 1
  // (default 5: a longer gap starts a new chain). check_left_right = false skips the check.
  bool check_left_right = true;
  double max_axis_turn_deg = 90;
  int max_gap_frames = 5;

  void Check() const;
};

enum class SkeletonIssue { kMissingJoints, kBoneLength, kLeftRightSwap };

struct SkeletonFlag {
  SkeletonIssue issue;
  int bone = -1;        // index into SkeletonBones() for kBoneLength, else -1
  double length_m = 0;  // kBoneLength: this frame's length and the clip's median
  double median_m = 0;
  std::string message;  // for people, e.g. "l_forearm 0.331 m, clip median 0.250 m (+32%)"
};

struct FrameConsistency {
  bool usable = true;  // no flag
  std::vector<SkeletonFlag> flags;
};

struct SkeletonConsistency {
  std::vector<FrameConsistency> frames;  // one per input skeleton
  // Median length of each bone over the frames where it is present; nullopt if never.
  std::array<std::optional<double>, kBoneCount> median_length_m;
  int usable_frames = 0;
};

// Precondition (CHECK): valid options. An empty clip gives an empty result.
SkeletonConsistency CheckSkeletonConsistency(const std::vector<Skeleton>& skeletons,
                                             const SkeletonConsistencyOptions& options = {});

std::string_view SkeletonIssueName(SkeletonIssue issue);

}  // namespace reenact::capture
