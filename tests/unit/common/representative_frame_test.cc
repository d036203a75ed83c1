#include "common/model/representative_frame.h"

#include <vector>

#include <gtest/gtest.h>

#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::StandingPerson;

TEST(RepresentativeFrame, ArmsOutFacingCameraWins) {
  std::vector<Skeleton> clip = {StandingPerson(3, 0, false), StandingPerson(3, 1.2, true),
                                StandingPerson(3, 0, true), StandingPerson(3, 0.6, true)};
  EXPECT_EQ(SelectRepresentativeFrame(clip), 2);
}

TEST(RepresentativeFrame, ScoreMatchesEquationForArmsStraightOut) {
  // Torso vertical, both arms horizontal along x: theta = 90 and l = 1 on each side (Eq. 2),
  // legs apart: g = 1, so F = 90 + 90 + lambda.
  Skeleton s;
  s.Set(Joint::kNeck, {0, -0.5, 3});
  s.Set(Joint::kWaist, {0, 0, 3});
  s.Set(Joint::kLeftShoulder, {0.2, -0.5, 3});
  s.Set(Joint::kLeftHand, {0.8, -0.5, 3});
  s.Set(Joint::kRightShoulder, {-0.2, -0.5, 3});
  s.Set(Joint::kRightHand, {-0.8, -0.5, 3});
  s.Set(Joint::kLeftHip, {0.1, 0, 3});
  s.Set(Joint::kRightHip, {-0.1, 0, 3});
  s.Set(Joint::kLeftKnee, {0.1, 0.5, 3});
  s.Set(Joint::kRightKnee, {-0.1, 0.5, 3});
  s.Set(Joint::kLeftFoot, {0.1, 1, 3});
  s.Set(Joint::kRightFoot, {-0.1, 1, 3});
  EXPECT_NEAR(*RepresentativeScore(s), 90 + 90 + 2000, 1e-9);
  s.Set(Joint::kLeftFoot, {-0.2, 1, 3});  // feet crossed: g = 0
  EXPECT_NEAR(*RepresentativeScore(s), 180, 1e-9);
}

TEST(RepresentativeFrame, CrossedLegsLoseToUncrossed) {
  std::vector<Skeleton> clip = {StandingPerson(3, 0, true, /*crossed_legs=*/true),
                                StandingPerson(3, 0, false)};
  EXPECT_EQ(SelectRepresentativeFrame(clip), 1);
}

TEST(RepresentativeFrame, DegenerateInputsAreNotScored) {
  EXPECT_FALSE(SelectRepresentativeFrame(std::vector<Skeleton>{}));
  Skeleton zero_arm = StandingPerson(3, 0, true);
  zero_arm.Set(Joint::kLeftHand, zero_arm[Joint::kLeftShoulder]);
  EXPECT_FALSE(RepresentativeScore(zero_arm));
  Skeleton missing = StandingPerson(3, 0, true);
  missing.confidence[Index(Joint::kWaist)] = 0;
  EXPECT_FALSE(RepresentativeScore(missing));
  std::vector<Skeleton> clip = {missing, StandingPerson(3, 0, false)};
  EXPECT_EQ(SelectRepresentativeFrame(clip), 1);
}

}  // namespace
}  // namespace reenact
