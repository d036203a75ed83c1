#include "common/texture/texture_selection.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::StandingPerson;

TEST(TextureSelection, PicksStoredViewClosestInYaw) {
  // Stored frames: the person turning in 10-degree steps; the viewer sees them at 63 degrees.
  std::vector<Skeleton> stored;
  for (int d = 0; d < 360; d += 10) stored.push_back(StandingPerson(3.0, d * M_PI / 180, true));
  const Skeleton viewer = StandingPerson(2.5, 63 * M_PI / 180, true);
  const auto ranked = RankTextureFrames(viewer, stored, {.top_k = 3});
  ASSERT_EQ(ranked.size(), 3u);
  EXPECT_EQ(ranked[0].frame, 6);  // 60 degrees
  EXPECT_EQ(ranked[1].frame, 7);  // 70 degrees
  EXPECT_LE(ranked[0].cost, ranked[1].cost);
  EXPECT_LE(ranked[1].cost, ranked[2].cost);
}

TEST(TextureSelection, IdenticalSkeletonHasZeroCostAndTiesGoToLowerIndex) {
  const Skeleton s = StandingPerson(3.0, 0.3, false);
  std::vector<Skeleton> stored = {StandingPerson(3.0, 1.0, false), s, s};
  const auto ranked = RankTextureFrames(s, stored, {.top_k = 2});
  ASSERT_EQ(ranked.size(), 2u);
  EXPECT_EQ(ranked[0].frame, 1);
  EXPECT_EQ(ranked[1].frame, 2);
  EXPECT_NEAR(ranked[0].cost, 0.0, 1e-12);
}

TEST(TextureSelection, CostIsTranslationInvariantThroughNeck) {
  const Skeleton a = StandingPerson(3.0, 0.5, true);
  const Skeleton b = StandingPerson(7.0, 0.5, true);  // same pose, further away
  EXPECT_NEAR(*TextureSelectionCost(a, b), 0.0, 1e-12);
}

TEST(TextureSelection, EmptyAndUnscorableSetsGiveNoCandidate) {
  const Skeleton viewer = StandingPerson(3.0, 0.0, true);
  EXPECT_TRUE(RankTextureFrames(viewer, std::vector<Skeleton>{}).empty());
  Skeleton no_neck = viewer;
  no_neck.confidence[Index(Joint::kNeck)] = 0;
  EXPECT_TRUE(RankTextureFrames(viewer, std::vector<Skeleton>{no_neck}).empty());
  EXPECT_FALSE(TextureSelectionCost(no_neck, viewer));
}

TEST(TextureSelection, UnusableFramesAreSkipped) {
  const Skeleton viewer = StandingPerson(3.0, 0.0, true);
  std::vector<Skeleton> stored = {viewer, StandingPerson(3.0, 0.4, true)};
  const bool usable[] = {false, true};
  const auto ranked = RankTextureFrames(viewer, stored, {}, usable);
  ASSERT_EQ(ranked.size(), 1u);
  EXPECT_EQ(ranked[0].frame, 1);
}

TEST(TextureSelection, MissingJointCostsTheStatedPenalty) {
  const Skeleton viewer = StandingPerson(3.0, 0.0, true);
  Skeleton stored = viewer;
  stored.confidence[Index(Joint::kLeftHand)] = 0;
  EXPECT_NEAR(*TextureSelectionCost(viewer, stored, 0.7), 0.7, 1e-12);
}

}  // namespace
}  // namespace reenact

namespace reenact {
namespace {

TEST(TextureSelection, OneFrameIsAlwaysChosen) {
  const std::vector<Skeleton> stored = {testing::StandingPerson(3.0, 2.0, false)};
  const auto ranked = RankTextureFrames(testing::StandingPerson(3.0, 0.0, true), stored, {.top_k = 5});
  ASSERT_EQ(ranked.size(), 1u);
  EXPECT_EQ(ranked[0].frame, 0);
  EXPECT_GT(ranked[0].cost, 0.0);
}

TEST(TextureSelection, EveryJointMissingGivesNoCandidate) {
  const Skeleton empty;
  const std::vector<Skeleton> stored = {empty, testing::StandingPerson(3.0, 0.0, true)};
  EXPECT_TRUE(RankTextureFrames(empty, stored).empty());
  const auto ranked = RankTextureFrames(testing::StandingPerson(3.0, 0.0, true), stored);
  ASSERT_EQ(ranked.size(), 1u);
  EXPECT_EQ(ranked[0].frame, 1);
}

TEST(TextureSelection, AllFramesUnusableGivesNoCandidate) {
  const std::vector<Skeleton> stored = {testing::StandingPerson(3.0, 0.0, true),
                                        testing::StandingPerson(3.0, 1.0, true)};
  const bool usable[] = {false, false};
  EXPECT_TRUE(RankTextureFrames(stored[0], stored, {}, usable).empty());
}

}  // namespace
}  // namespace reenact
