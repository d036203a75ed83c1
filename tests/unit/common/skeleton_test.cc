#include "common/skeleton/skeleton.h"

#include <set>

#include <gtest/gtest.h>

#include "common/error/check.h"

namespace reenact {
namespace {

TEST(Skeleton, NamesRoundTripAndAreUnique) {
  std::set<std::string_view> names;
  for (int i = 0; i < kJointCount; ++i) {
    const auto j = static_cast<Joint>(i);
    EXPECT_EQ(JointFromName(JointName(j)), j);
    names.insert(JointName(j));
  }
  EXPECT_EQ(names.size(), 16u);
  for (int i = 0; i < kBodyPartCount; ++i) {
    const auto p = static_cast<BodyPart>(i);
    EXPECT_EQ(PartFromName(PartName(p)), p);
  }
  EXPECT_FALSE(JointFromName("left_pinky"));
}

TEST(Skeleton, PartsFollowDesignTable) {
  EXPECT_EQ(PartJoints(BodyPart::kHead), std::pair(Joint::kHead, Joint::kNeck));
  EXPECT_EQ(PartJoints(BodyPart::kLowerTorso), std::pair(Joint::kTorso, Joint::kWaist));
  EXPECT_EQ(PartJoints(BodyPart::kRightShin), std::pair(Joint::kRightKnee, Joint::kRightFoot));
  EXPECT_EQ(PartName(BodyPart::kLeftForearm), "l_forearm");
  // Every joint belongs to some part.
  std::set<Joint> used;
  for (int i = 0; i < kBodyPartCount; ++i) {
    used.insert(PartJoints(static_cast<BodyPart>(i)).first);
    used.insert(PartJoints(static_cast<BodyPart>(i)).second);
  }
  EXPECT_EQ(used.size(), 16u);
}

TEST(Skeleton, MissingJointsAreExplicitAndFinite) {
  Skeleton s;
  EXPECT_FALSE(s.Has(Joint::kHead));
  EXPECT_FALSE(s.Complete());
  EXPECT_TRUE(s[Joint::kHead].allFinite());
  s.Set(Joint::kHead, {0, 1, 2}, 0.5);
  s.Set(Joint::kNeck, {0, 1, 1});
  EXPECT_TRUE(s.HasPart(BodyPart::kHead));
  EXPECT_FALSE(s.HasPart(BodyPart::kUpperTorso));
  EXPECT_THROW(s.Set(Joint::kTorso, {std::nan(""), 0, 0}), CheckError);
  EXPECT_THROW(s.Set(Joint::kTorso, {0, 0, 0}, 1.5), CheckError);
}

TEST(Skeleton, TransformedAppliesRigidTransform) {
  Skeleton s;
  s.Set(Joint::kHead, {1, 0, 0});
  Eigen::Isometry3d b_from_a = Eigen::Isometry3d::Identity();
  b_from_a.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  b_from_a.pretranslate(Eigen::Vector3d(0, 0, 5));
  const Skeleton t = s.Transformed(b_from_a);
  EXPECT_LT((t[Joint::kHead] - Eigen::Vector3d(0, 1, 5)).norm(), 1e-12);
  EXPECT_EQ(t.confidence, s.confidence);
}

}  // namespace
}  // namespace reenact
