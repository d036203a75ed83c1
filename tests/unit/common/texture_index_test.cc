#include "common/texture/texture_index.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "common/error/check.h"
#include "common/texture/texture_selection.h"
#include "tests/unit/common/test_clips.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::ExpectSameRanking;
using testing::Query;
using testing::RandomClip;
using testing::SmoothClip;
using testing::StandingPerson;

void ExpectMatchesScan(const std::vector<Skeleton>& clip, std::span<const bool> usable,
                       const TextureIndex& index, const Skeleton& viewer,
                       const TextureSelectionOptions& options) {
  ExpectSameRanking(index.Rank(viewer, options), RankTextureFrames(viewer, clip, options, usable));
}

TEST(TextureIndex, SmoothClipsMatchScanForSizesAndK) {
  std::mt19937 rng(1);
  for (int n : {1, 2, 7, 50, 333, 2000, 20000}) {
    const auto clip = SmoothClip(n, rng);
    for (int leaf : {1, 8, 32}) {
      const TextureIndex index(clip, {}, {.leaf_size = leaf});
      EXPECT_EQ(index.indexed_count(), n);
      for (int k : {1, 3, 10, 1000}) {
        for (int t = 0; t < 5; ++t) {
          SCOPED_TRACE("n " + std::to_string(n) + " leaf " + std::to_string(leaf) + " k " +
                       std::to_string(k));
          const Skeleton viewer = t == 0 ? clip[t] : Query(clip, rng);
          ExpectMatchesScan(clip, {}, index, viewer, {.top_k = k});
        }
      }
    }
  }
}

TEST(TextureIndex, IndependentSkeletonsMatchScan) {
  std::mt19937 rng(2);
  const auto clip = RandomClip(3000, rng);
  const TextureIndex index(clip);
  for (int t = 0; t < 50; ++t) ExpectMatchesScan(clip, {}, index, Query(clip, rng), {.top_k = 5});
}

TEST(TextureIndex, UsableFlagsAreHonoured) {
  std::mt19937 rng(3);
  const auto clip = SmoothClip(4000, rng);
  std::bernoulli_distribution keep(0.3);
  auto usable = std::make_unique<bool[]>(clip.size());  // std::vector<bool> has no span
  int kept = 0;
  for (size_t n = 0; n < clip.size(); ++n) kept += (usable[n] = keep(rng));
  const std::span<const bool> span(usable.get(), clip.size());
  const TextureIndex index(clip, span);
  EXPECT_EQ(index.indexed_count(), kept);
  EXPECT_EQ(index.stored_count(), 4000);
  for (int t = 0; t < 30; ++t) {
    const Skeleton viewer = Query(clip, rng);
    ExpectMatchesScan(clip, span, index, viewer, {.top_k = 4});
    for (const auto& c : index.Rank(viewer, {.top_k = 4})) EXPECT_TRUE(usable[c.frame]);
  }
}

TEST(TextureIndex, MissingJointsMatchScanForSeveralCosts) {
  std::mt19937 rng(4);
  auto clip = SmoothClip(3000, rng, 0.1);
  // Some frames without a neck: they cannot be scored.
  for (int n = 0; n < 3000; n += 97) clip[n].confidence[Index(Joint::kNeck)] = 0;
  const TextureIndex index(clip);
  EXPECT_EQ(index.indexed_count(), 3000 - 31);
  for (double m : {0.0, 0.05, 1.0, 100.0}) {
    for (int t = 0; t < 20; ++t) {
      Skeleton viewer = Query(clip, rng);
      if (t % 3 == 0) viewer.confidence[Index(Joint::kLeftHand)] = 0;  // viewer lacks joints
      if (t % 5 == 0) viewer.confidence[Index(Joint::kHead)] = 0;
      SCOPED_TRACE("missing cost " + std::to_string(m));
      ExpectMatchesScan(clip, {}, index, viewer, {.top_k = 6, .missing_joint_cost_m = m});
    }
  }
}

TEST(TextureIndex, SkeletonsWithOnlyANeckMatchScan) {
  std::mt19937 rng(5);
  auto clip = SmoothClip(200, rng);
  Skeleton only_neck;
  only_neck.Set(Joint::kNeck, {0, 0, 3});
  for (int n = 0; n < 200; n += 3) clip[n] = only_neck;
  const TextureIndex index(clip);
  ExpectMatchesScan(clip, {}, index, Query(clip, rng), {.top_k = 100});
  ExpectMatchesScan(clip, {}, index, only_neck, {.top_k = 100});
}

TEST(TextureIndex, DuplicateFramesTieToLowerIndex) {
  const Skeleton a = StandingPerson(3.0, 0.2, true), b = StandingPerson(3.0, 1.4, false);
  std::vector<Skeleton> clip;
  for (int n = 0; n < 300; ++n) clip.push_back(n % 3 == 2 ? b : a);
  const TextureIndex index(clip, {}, {.leaf_size = 4});
  const auto ranked = index.Rank(a, {.top_k = 5});
  ASSERT_EQ(ranked.size(), 5u);
  const int want[] = {0, 1, 3, 4, 6};  // copies of a, in frame order
  for (int r = 0; r < 5; ++r) {
    EXPECT_EQ(ranked[r].frame, want[r]);
    EXPECT_EQ(ranked[r].cost, 0.0);
  }
  ExpectMatchesScan(clip, {}, index, b, {.top_k = 150});
}

TEST(TextureIndex, ExactTiesBetweenDistinctFramesAreDeterministic) {
  // Offsets on a grid of halves (exact in binary): many distinct frames share a cost exactly.
  Skeleton viewer;
  for (int i = 0; i < kJointCount; ++i) viewer.Set(static_cast<Joint>(i), {0, 0, 2});
  std::mt19937 rng(6);
  std::uniform_int_distribution<int> axis(0, 2), sign(0, 1);
  std::vector<Skeleton> clip;
  for (int n = 0; n < 500; ++n) {
    Skeleton s = viewer;
    for (int i = 0; i < kJointCount; ++i) {
      if (i == Index(Joint::kNeck)) continue;
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d[axis(rng)] = sign(rng) ? 0.5 : -0.5;
      s.position[i] += d * (n % 2);
    }
    clip.push_back(s);
  }
  const TextureIndex index(clip, {}, {.leaf_size = 2});
  const auto ranked = index.Rank(viewer, {.top_k = 300});
  ExpectSameRanking(ranked, RankTextureFrames(viewer, clip, {.top_k = 300}));
  // Even frames cost 0 and come first in frame order; odd frames cost 15 * 0.5 = 7.5 exactly.
  for (int r = 0; r < 250; ++r) EXPECT_EQ(ranked[r].frame, 2 * r);
  for (int r = 250; r < 300; ++r) {
    EXPECT_EQ(ranked[r].frame, 2 * (r - 250) + 1);
    EXPECT_EQ(ranked[r].cost, 7.5);
  }
}

TEST(TextureIndex, OneFrame) {
  const std::vector<Skeleton> clip = {StandingPerson(3.0, 0.5, true)};
  const TextureIndex index(clip);
  const Skeleton viewer = StandingPerson(2.0, 0.1, false);
  const auto ranked = index.Rank(viewer, {.top_k = 3});
  ASSERT_EQ(ranked.size(), 1u);
  EXPECT_EQ(ranked[0].frame, 0);
  EXPECT_EQ(ranked[0].cost, *TextureSelectionCost(viewer, clip[0]));
}

TEST(TextureIndex, EmptyIndexAndUnscorableQueriesGiveNothing) {
  const Skeleton viewer = StandingPerson(3.0, 0.0, true);
  EXPECT_TRUE(TextureIndex().Rank(viewer).empty());
  EXPECT_TRUE(TextureIndex(std::vector<Skeleton>{}).Rank(viewer).empty());
  const std::vector<Skeleton> clip = {viewer, viewer};
  Skeleton no_neck = viewer;
  no_neck.confidence[Index(Joint::kNeck)] = 0;
  EXPECT_TRUE(TextureIndex(clip).Rank(no_neck).empty());
  EXPECT_TRUE(TextureIndex(std::vector<Skeleton>{no_neck, no_neck}).Rank(viewer).empty());
}

TEST(TextureIndex, AllFramesUnusableGiveNothing) {
  std::mt19937 rng(7);
  const auto clip = SmoothClip(100, rng);
  const auto usable = std::make_unique<bool[]>(clip.size());  // all false
  const TextureIndex index(clip, std::span<const bool>(usable.get(), clip.size()));
  EXPECT_EQ(index.indexed_count(), 0);
  EXPECT_TRUE(index.Rank(clip[0], {.top_k = 5}).empty());
}

TEST(TextureIndex, PrunesMostFramesOfASmoothClip) {
  std::mt19937 rng(8);
  const auto clip = SmoothClip(20000, rng);
  const TextureIndex index(clip);
  int64_t evaluated = 0;
  for (int t = 0; t < 20; ++t) {
    TextureIndexStats stats;
    index.Rank(Query(clip, rng), {.top_k = 1}, &stats);
    evaluated += stats.frames_evaluated;
  }
  EXPECT_LT(evaluated / 20, 20000 / 4);  // a scan evaluates all 20000
}

TEST(TextureIndex, BadInputIsRejected) {
  const std::vector<Skeleton> clip = {StandingPerson(3.0, 0.0, true)};
  const bool two_flags[] = {true, true};
  EXPECT_THROW(TextureIndex(clip, two_flags), CheckError);
  EXPECT_THROW(TextureIndex(clip, {}, {.leaf_size = 0}), CheckError);
  const TextureIndex index(clip);
  EXPECT_THROW(index.Rank(clip[0], {.top_k = 0}), CheckError);
  EXPECT_THROW(index.Rank(clip[0], {.top_k = 1, .missing_joint_cost_m = -1}), CheckError);
}

}  // namespace
}  // namespace reenact
