// Bone-length and left/right consistency of a clip's skeletons, on the synthetic
// turn-and-kick clip (a rigid body: every bone keeps its constructed length) with
// constructed faults.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <utility>

#include "capture-client/segment/skeleton_consistency.h"
#include "common/error/check.h"
#include "synthetic/body_model.h"
#include "synthetic/synthetic_scene.h"

namespace reenact::capture {
namespace {

const std::vector<Skeleton>& Clip() {
  static const std::vector<Skeleton> clip = [] {
    const SyntheticScene scene = SyntheticScene::Create("turn-and-kick", 1).value();
    std::vector<Skeleton> out;
    for (int f = 0; f < scene.frame_count(); ++f) out.push_back(scene.skeleton_in_world(f));
    return out;
  }();
  return clip;
}

int BoneIndex(std::string_view name) {
  for (int b = 0; b < kBoneCount; ++b)
    if (SkeletonBones()[b].name == name) return b;
  return -1;
}

std::vector<int> Flagged(const SkeletonConsistency& c) {
  std::vector<int> out;
  for (int f = 0; f < static_cast<int>(c.frames.size()); ++f)
    if (!c.frames[f].usable) out.push_back(f);
  return out;
}

bool Has(const FrameConsistency& f, SkeletonIssue issue) {
  for (const SkeletonFlag& flag : f.flags)
    if (flag.issue == issue) return true;
  return false;
}

Skeleton SwappedLeftRight(const Skeleton& s) {
  Skeleton out = s;
  const std::pair<Joint, Joint> pairs[] = {
      {Joint::kLeftShoulder, Joint::kRightShoulder}, {Joint::kLeftElbow, Joint::kRightElbow},
      {Joint::kLeftHand, Joint::kRightHand},         {Joint::kLeftHip, Joint::kRightHip},
      {Joint::kLeftKnee, Joint::kRightKnee},         {Joint::kLeftFoot, Joint::kRightFoot}};
  for (const auto& [l, r] : pairs) {
    out[l] = s[r];
    out[r] = s[l];
  }
  return out;
}

TEST(SkeletonConsistency, TheGroundTruthClipIsConsistentAndItsMediansAreTheBody) {
  const SkeletonConsistency c = CheckSkeletonConsistency(Clip());
  ASSERT_EQ(c.frames.size(), Clip().size());
  EXPECT_EQ(c.usable_frames, static_cast<int>(Clip().size()));
  EXPECT_TRUE(Flagged(c).empty());
  const BodyDimensions d;
  const std::pair<const char*, double> expected[] = {{"l_upper_arm", d.upper_arm},
                                                     {"r_forearm", d.forearm + d.wrist_to_palm},
                                                     {"l_thigh", d.thigh},
                                                     {"r_shin", d.shin},
                                                     {"lower_torso", d.lower_spine}};
  for (const auto& [name, length] : expected) {
    ASSERT_TRUE(c.median_length_m[BoneIndex(name)]) << name;
    EXPECT_NEAR(*c.median_length_m[BoneIndex(name)], length, 1e-9) << name;
  }
}

TEST(SkeletonConsistency, JointJitterOfATrackerIsNotAFault) {
  std::vector<Skeleton> clip = Clip();
  std::mt19937 rng(4);
  std::normal_distribution<double> n(0, 0.002);  // 2 mm per axis
  for (Skeleton& s : clip)
    for (auto& p : s.position) p += Eigen::Vector3d(n(rng), n(rng), n(rng));
  EXPECT_TRUE(Flagged(CheckSkeletonConsistency(clip)).empty());
}

TEST(SkeletonConsistency, OneStretchedArmFrameIsFlagged) {
  std::vector<Skeleton> clip = Clip();
  Skeleton& s = clip[50];
  s[Joint::kLeftHand] = s[Joint::kLeftElbow] + 1.3 * (s[Joint::kLeftHand] - s[Joint::kLeftElbow]);
  const SkeletonConsistency c = CheckSkeletonConsistency(clip);
  EXPECT_EQ(Flagged(c), std::vector<int>{50});
  ASSERT_EQ(c.frames[50].flags.size(), 1u);
  const SkeletonFlag& flag = c.frames[50].flags[0];
  EXPECT_EQ(flag.issue, SkeletonIssue::kBoneLength);
  EXPECT_EQ(flag.bone, BoneIndex("l_forearm"));
  const BodyDimensions d;
  EXPECT_NEAR(flag.median_m, d.forearm + d.wrist_to_palm, 1e-9);
  EXPECT_NEAR(flag.length_m, 1.3 * (d.forearm + d.wrist_to_palm), 1e-9);
  EXPECT_NE(flag.message.find("l_forearm"), std::string::npos);
  EXPECT_NE(flag.message.find("+30%"), std::string::npos);
}

TEST(SkeletonConsistency, ADeviationBelowTheToleranceIsNotFlagged) {
  std::vector<Skeleton> clip = Clip();
  Skeleton& s = clip[70];  // thigh 10 % longer: within 15 %
  s[Joint::kRightKnee] = s[Joint::kRightHip] + 1.1 * (s[Joint::kRightKnee] - s[Joint::kRightHip]);
  EXPECT_TRUE(Flagged(CheckSkeletonConsistency(clip)).empty());
  SkeletonConsistencyOptions strict;
  strict.max_relative_deviation = 0.05;
  EXPECT_EQ(Flagged(CheckSkeletonConsistency(clip, strict)), std::vector<int>{70});
}

TEST(SkeletonConsistency, ASwappedLeftRightFrameIsFlagged) {
  std::vector<Skeleton> clip = Clip();
  clip[100] = SwappedLeftRight(clip[100]);  // mid-turn
  const SkeletonConsistency c = CheckSkeletonConsistency(clip);
  EXPECT_EQ(Flagged(c), std::vector<int>{100});
  EXPECT_TRUE(Has(c.frames[100], SkeletonIssue::kLeftRightSwap));
  EXPECT_FALSE(Has(c.frames[100], SkeletonIssue::kBoneLength));  // lengths cannot tell
  SkeletonConsistencyOptions lengths_only;
  lengths_only.check_left_right = false;
  EXPECT_TRUE(Flagged(CheckSkeletonConsistency(clip, lengths_only)).empty());
}

TEST(SkeletonConsistency, ARunOfSwappedFramesAndASwappedFirstFrameAreFlagged) {
  std::vector<Skeleton> clip = Clip();
  for (int f : {0, 120, 121, 122}) clip[f] = SwappedLeftRight(clip[f]);
  EXPECT_EQ(Flagged(CheckSkeletonConsistency(clip)), (std::vector<int>{0, 120, 121, 122}));
}

TEST(SkeletonConsistency, ATieBetweenSidesFlagsNoSide) {
  const std::vector<Skeleton> clip = {Clip()[10], SwappedLeftRight(Clip()[11])};
  EXPECT_TRUE(Flagged(CheckSkeletonConsistency(clip)).empty());
}

TEST(SkeletonConsistency, MissingAndNonFiniteJointsAreFlaggedAndNotMeasured) {
  std::vector<Skeleton> clip = Clip();
  clip[20].confidence[Index(Joint::kLeftKnee)] = 0;
  clip[20][Joint::kLeftKnee] = Eigen::Vector3d(100, 100, 100);  // must not be measured
  clip[30][Joint::kHead].x() = std::numeric_limits<double>::quiet_NaN();
  const SkeletonConsistency c = CheckSkeletonConsistency(clip);
  EXPECT_EQ(Flagged(c), (std::vector<int>{20, 30}));
  ASSERT_EQ(c.frames[20].flags.size(), 1u);
  EXPECT_EQ(c.frames[20].flags[0].issue, SkeletonIssue::kMissingJoints);
  EXPECT_NE(c.frames[20].flags[0].message.find("l_knee"), std::string::npos);
  ASSERT_EQ(c.frames[30].flags.size(), 1u);
  EXPECT_NE(c.frames[30].flags[0].message.find("head"), std::string::npos);
  const BodyDimensions d;
  EXPECT_NEAR(*c.median_length_m[BoneIndex("l_thigh")], d.thigh, 1e-9);
  EXPECT_TRUE(std::isfinite(*c.median_length_m[BoneIndex("head")]));
}

TEST(SkeletonConsistency, EmptyAndJointlessClips) {
  EXPECT_TRUE(CheckSkeletonConsistency({}).frames.empty());
  const SkeletonConsistency c = CheckSkeletonConsistency({Skeleton(), Skeleton()});
  EXPECT_EQ(Flagged(c), (std::vector<int>{0, 1}));
  for (const auto& median : c.median_length_m) EXPECT_FALSE(median.has_value());
  EXPECT_EQ(SkeletonIssueName(c.frames[0].flags[0].issue), "missing_joints");
}

TEST(SkeletonConsistency, OptionsOutOfRangeThrow) {
  SkeletonConsistencyOptions o;
  o.max_relative_deviation = 0;
  EXPECT_THROW(CheckSkeletonConsistency(Clip(), o), CheckError);
  o = {};
  o.max_axis_turn_deg = 180;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.max_gap_frames = 0;
  EXPECT_THROW(o.Check(), CheckError);
  o = {};
  o.min_absolute_deviation_m = -1;
  EXPECT_THROW(o.Check(), CheckError);
}

}  // namespace
}  // namespace reenact::capture
