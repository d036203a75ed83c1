#include "common/texture/texture_graph_index.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <thread>
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

// Whatever the graph finds, each returned cost is Eq. 5 for that frame, bit for bit, and
// the list is ranked as the scan ranks (ascending cost, ties to the lower frame).
void ExpectExactCostsInRankOrder(const std::vector<Skeleton>& clip, const Skeleton& viewer,
                                 const std::vector<TextureCandidate>& got, double missing) {
  for (size_t r = 0; r < got.size(); ++r) {
    EXPECT_EQ(got[r].cost, *TextureSelectionCost(viewer, clip[got[r].frame], missing));
    if (r > 0) {
      EXPECT_TRUE(got[r - 1].cost < got[r].cost ||
                  (got[r - 1].cost == got[r].cost && got[r - 1].frame < got[r].frame));
    }
  }
}

// A beam as wide as the index keeps every frame it reaches, so the search covers the whole
// bottom layer: the answer must be the scan's exactly.
TEST(TextureGraphIndex, FullBeamEqualsScan) {
  std::mt19937 rng(1);
  for (int n : {1, 2, 7, 50, 333, 2000}) {
    const auto clip = SmoothClip(n, rng);
    const TextureGraphIndex index(clip);
    EXPECT_EQ(index.indexed_count(), n);
    for (int k : {1, 3, 10}) {
      for (int t = 0; t < 5; ++t) {
        SCOPED_TRACE("n " + std::to_string(n) + " k " + std::to_string(k));
        const Skeleton viewer = t == 0 ? clip[0] : Query(clip, rng);
        ExpectSameRanking(index.Rank(viewer, {.top_k = k}, {.beam = n}),
                          RankTextureFrames(viewer, clip, {.top_k = k}));
      }
    }
  }
}

// Connectivity: every frame is reachable on the bottom layer, so every stored skeleton,
// used as the query, finds its own frame at cost 0.
TEST(TextureGraphIndex, EveryFrameIsReachable) {
  std::mt19937 rng(2);
  for (const auto& clip : {SmoothClip(1500, rng), RandomClip(1500, rng)}) {
    const TextureGraphIndex index(clip, {}, {.max_neighbors = 4, .build_beam = 8});
    const int n = static_cast<int>(clip.size());
    for (int f = 0; f < n; ++f) {
      const auto got = index.Rank(clip[f], {.top_k = 1}, {.beam = n});
      ASSERT_EQ(got.size(), 1u);
      ASSERT_EQ(got[0].cost, 0.0) << "frame " << f << " unreachable";
    }
  }
}

// The default search is approximate. The requirement it is built for (reenact-bench core
// measures 0.97-1.0 at 10^5 frames): the scan's best frame in at least 9 of 10 queries, and
// the answer never worse than the scan's by more than half its cost.
TEST(TextureGraphIndex, DefaultSearchFindsTheBestFrameNearlyAlways) {
  std::mt19937 rng(3);
  for (const auto& clip : {SmoothClip(10000, rng), RandomClip(10000, rng)}) {
    const TextureGraphIndex index(clip);
    int hits = 0;
    constexpr int kQueries = 100;
    for (int t = 0; t < kQueries; ++t) {
      const Skeleton viewer = Query(clip, rng);
      const auto got = index.Rank(viewer, {.top_k = 3});
      const auto want = RankTextureFrames(viewer, clip, {.top_k = 1});
      ASSERT_EQ(got.size(), 3u);
      ExpectExactCostsInRankOrder(clip, viewer, got, 1.0);
      hits += got[0].frame == want[0].frame;
      EXPECT_LE(got[0].cost, 1.5 * want[0].cost);
    }
    EXPECT_GE(hits, 90);
  }
}

TEST(TextureGraphIndex, UsableFlagsAreHonoured) {
  std::mt19937 rng(4);
  const auto clip = SmoothClip(3000, rng);
  std::bernoulli_distribution keep(0.3);
  auto usable = std::make_unique<bool[]>(clip.size());  // std::vector<bool> has no span
  int kept = 0;
  for (size_t n = 0; n < clip.size(); ++n) kept += (usable[n] = keep(rng));
  const std::span<const bool> span(usable.get(), clip.size());
  const TextureGraphIndex index(clip, span);
  EXPECT_EQ(index.indexed_count(), kept);
  EXPECT_EQ(index.stored_count(), 3000);
  for (int t = 0; t < 20; ++t) {
    const Skeleton viewer = Query(clip, rng);
    ExpectSameRanking(index.Rank(viewer, {.top_k = 4}, {.beam = kept}),
                      RankTextureFrames(viewer, clip, {.top_k = 4}, span));
    for (const auto& c : index.Rank(viewer, {.top_k = 4})) EXPECT_TRUE(usable[c.frame]);
  }
}

TEST(TextureGraphIndex, MissingJointsAndQueryMissingCosts) {
  std::mt19937 rng(5);
  auto clip = SmoothClip(2000, rng, 0.1);
  for (int n = 0; n < 2000; n += 97) clip[n].confidence[Index(Joint::kNeck)] = 0;  // unscorable
  const TextureGraphIndex index(clip);
  EXPECT_EQ(index.indexed_count(), 2000 - 21);
  for (double m : {0.0, 0.05, 1.0, 100.0}) {
    for (int t = 0; t < 10; ++t) {
      Skeleton viewer = Query(clip, rng);
      if (t % 3 == 0) viewer.confidence[Index(Joint::kLeftHand)] = 0;
      if (t % 5 == 0) viewer.confidence[Index(Joint::kHead)] = 0;
      SCOPED_TRACE("missing cost " + std::to_string(m));
      const TextureSelectionOptions options{.top_k = 6, .missing_joint_cost_m = m};
      ExpectSameRanking(index.Rank(viewer, options, {.beam = 2000}),
                        RankTextureFrames(viewer, clip, options));
      ExpectExactCostsInRankOrder(clip, viewer, index.Rank(viewer, options), m);
    }
  }
}

TEST(TextureGraphIndex, DuplicateFramesTieToLowerIndex) {
  const Skeleton a = StandingPerson(3.0, 0.2, true), b = StandingPerson(3.0, 1.4, false);
  std::vector<Skeleton> clip;
  for (int n = 0; n < 300; ++n) clip.push_back(n % 3 == 2 ? b : a);
  const TextureGraphIndex index(clip);
  const auto ranked = index.Rank(a, {.top_k = 5}, {.beam = 300});
  ASSERT_EQ(ranked.size(), 5u);
  const int want[] = {0, 1, 3, 4, 6};  // copies of a, in frame order
  for (int r = 0; r < 5; ++r) {
    EXPECT_EQ(ranked[r].frame, want[r]);
    EXPECT_EQ(ranked[r].cost, 0.0);
  }
  // With the default beam the best cost is still found: every copy of a costs 0.
  const auto approx = index.Rank(a, {.top_k = 1});
  ASSERT_EQ(approx.size(), 1u);
  EXPECT_EQ(approx[0].cost, 0.0);
}

TEST(TextureGraphIndex, TopKBeyondTheIndexReturnsEveryFrameRanked) {
  std::mt19937 rng(6);
  const auto clip = RandomClip(40, rng);
  const TextureGraphIndex index(clip);
  const Skeleton viewer = Query(clip, rng);
  ExpectSameRanking(index.Rank(viewer, {.top_k = 100}),
                    RankTextureFrames(viewer, clip, {.top_k = 100}));
}

TEST(TextureGraphIndex, BuildIsDeterministicAndQueriesAreThreadSafe) {
  std::mt19937 rng(7);
  const auto clip = SmoothClip(5000, rng);
  const TextureGraphIndex first(clip), second(clip);
  std::vector<Skeleton> queries;
  for (int t = 0; t < 200; ++t) queries.push_back(Query(clip, rng));
  std::vector<std::vector<TextureCandidate>> want;
  for (const Skeleton& q : queries) {
    want.push_back(first.Rank(q, {.top_k = 3}));
    ExpectSameRanking(second.Rank(q, {.top_k = 3}), want.back());
  }
  std::vector<std::vector<TextureCandidate>> got[2];
  std::thread threads[2];
  for (int t = 0; t < 2; ++t)
    threads[t] = std::thread([&, t] {
      for (const Skeleton& q : queries) got[t].push_back(first.Rank(q, {.top_k = 3}));
    });
  for (auto& t : threads) t.join();
  for (int t = 0; t < 2; ++t)
    for (size_t q = 0; q < queries.size(); ++q) ExpectSameRanking(got[t][q], want[q]);
}

TEST(TextureGraphIndex, EmptyAndUnscorableGiveNothing) {
  const Skeleton viewer = StandingPerson(3.0, 0.0, true);
  EXPECT_TRUE(TextureGraphIndex().Rank(viewer).empty());
  EXPECT_TRUE(TextureGraphIndex(std::vector<Skeleton>{}).Rank(viewer).empty());
  Skeleton no_neck = viewer;
  no_neck.confidence[Index(Joint::kNeck)] = 0;
  const std::vector<Skeleton> clip = {viewer, viewer};
  EXPECT_TRUE(TextureGraphIndex(clip).Rank(no_neck).empty());
  EXPECT_TRUE(TextureGraphIndex(std::vector<Skeleton>{no_neck, no_neck}).Rank(viewer).empty());
  const bool none[] = {false, false};
  const TextureGraphIndex unusable(clip, none);
  EXPECT_EQ(unusable.indexed_count(), 0);
  EXPECT_TRUE(unusable.Rank(viewer, {.top_k = 5}).empty());
}

TEST(TextureGraphIndex, OneFrame) {
  const std::vector<Skeleton> clip = {StandingPerson(3.0, 0.5, true)};
  const TextureGraphIndex index(clip);
  const Skeleton viewer = StandingPerson(2.0, 0.1, false);
  const auto ranked = index.Rank(viewer, {.top_k = 3});
  ASSERT_EQ(ranked.size(), 1u);
  EXPECT_EQ(ranked[0].frame, 0);
  EXPECT_EQ(ranked[0].cost, *TextureSelectionCost(viewer, clip[0]));
}

TEST(TextureGraphIndex, BadInputIsRejected) {
  const std::vector<Skeleton> clip = {StandingPerson(3.0, 0.0, true)};
  const bool two_flags[] = {true, true};
  EXPECT_THROW(TextureGraphIndex(clip, two_flags), CheckError);
  EXPECT_THROW(TextureGraphIndex(clip, {}, {.max_neighbors = 1}), CheckError);
  EXPECT_THROW(TextureGraphIndex(clip, {}, {.max_neighbors = 16, .build_beam = 8}), CheckError);
  EXPECT_THROW(TextureGraphIndex(clip, {}, {.missing_joint_cost_m = -1}), CheckError);
  const TextureGraphIndex index(clip);
  EXPECT_THROW(index.Rank(clip[0], {.top_k = 0}), CheckError);
  EXPECT_THROW(index.Rank(clip[0], {}, {.beam = 0}), CheckError);
  EXPECT_THROW(index.Rank(clip[0], {.top_k = 1, .missing_joint_cost_m = -1}), CheckError);
}

}  // namespace
}  // namespace reenact
