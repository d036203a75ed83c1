#include "common/texture/part_selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error/check.h"
#include "common/texture/texture_selection.h"
#include "tests/unit/common/test_skeletons.h"

namespace reenact {
namespace {

using testing::StandingPerson;

double Deg(double d) { return d * M_PI / 180; }

// The person turning on the spot in 10-degree steps, arms down (frames 0-35) then arms out
// (frames 36-71), 3 m in front of the sensor.
std::vector<Skeleton> TurningClip() {
  std::vector<Skeleton> stored;
  for (bool arms_out : {false, true})
    for (int d = 0; d < 360; d += 10) stored.push_back(StandingPerson(3.0, Deg(d), arms_out));
  return stored;
}

// Left arm taken from `arms_out` pose, the rest from the arms-down pose, same yaw.
Skeleton LeftArmOut(double distance, double yaw) {
  Skeleton s = StandingPerson(distance, yaw, false);
  const Skeleton out = StandingPerson(distance, yaw, true);
  for (Joint j : {Joint::kLeftElbow, Joint::kLeftHand}) s.Set(j, out[j]);
  return s;
}

TEST(PartSelection, EachPartTakesTheFrameThatShowsItsOwnPoseAndView) {
  const std::vector<Skeleton> stored = TurningClip();
  const PartTextureIndex index(stored);
  const Skeleton viewer = LeftArmOut(3.0, Deg(62));
  const PartCandidates chosen = index.Select(viewer, {});
  ASSERT_EQ(chosen[Index(BodyPart::kLeftForearm)].size(), 1u);
  // The left forearm from the arms-out frame at 60 degrees, the right one and the legs from
  // the arms-down frame at 60 degrees.
  EXPECT_EQ(chosen[Index(BodyPart::kLeftForearm)][0].frame, 36 + 6);
  EXPECT_EQ(chosen[Index(BodyPart::kRightForearm)][0].frame, 6);
  EXPECT_EQ(chosen[Index(BodyPart::kLeftShin)][0].frame, 6);
}

TEST(PartSelection, TurningTheCameraAboutItsCentreChangesNoPartsCost) {
  // A camera turned about its own centre sees every part from the same direction, only at
  // another place in the image: the per-part cost is zero (up to rounding), whereas Eq. 5's
  // neck-relative offsets turn with the camera.
  const Skeleton stored = StandingPerson(3.0, Deg(20), true);
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(Deg(25), Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(Deg(-10), Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  const Skeleton viewer = stored.Transformed(Eigen::Isometry3d(turn));
  const PartTextureIndex index(std::vector<Skeleton>{stored});
  for (int p = 0; p < kBodyPartCount; ++p) {
    const auto cost = index.Cost(static_cast<BodyPart>(p), viewer, 0);
    ASSERT_TRUE(cost) << p;
    EXPECT_NEAR(*cost, 0.0, 1e-9) << PartName(static_cast<BodyPart>(p));
  }
  EXPECT_GT(*TextureSelectionCost(viewer, stored), 0.5);
}

TEST(PartSelection, WeightsFollowTheLumigraphRuleAndSumToOne) {
  const std::vector<Skeleton> stored = TurningClip();
  const PartTextureIndex index(stored);
  const Skeleton viewer = StandingPerson(3.0, Deg(13), false);
  const PartCandidates chosen = index.Select(viewer, {.top_k = 3});
  for (int p = 0; p < kBodyPartCount; ++p) {
    const BodyPart part = static_cast<BodyPart>(p);
    ASSERT_EQ(chosen[p].size(), 3u);
    // The fourth-best cost over all frames, from Cost() directly.
    std::vector<double> costs;
    for (int n = 0; n < index.stored_count(); ++n) costs.push_back(*index.Cost(part, viewer, n));
    std::sort(costs.begin(), costs.end());
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
      EXPECT_DOUBLE_EQ(chosen[p][i].cost, costs[i]);
      sum += 1 - costs[i] / costs[3];
    }
    double total = 0;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(chosen[p][i].weight, (1 - costs[i] / costs[3]) / sum, 1e-12);
      total += chosen[p][i].weight;
    }
    EXPECT_NEAR(total, 1.0, 1e-12);
    EXPECT_GE(chosen[p][0].weight, chosen[p][1].weight);
  }
}

TEST(PartSelection, BlendWeightsChangeContinuouslyAsTheViewerTurns) {
  // Stored every 10 degrees (arms down only: duplicate frames would tie in groups larger
  // than top_k, where no fixed-size set can change continuously); the viewer turns in
  // 0.25-degree steps. A candidate entering the set enters with a weight near zero, and no
  // weight jumps.
  std::vector<Skeleton> stored = TurningClip();
  stored.resize(36);
  const PartTextureIndex index(stored);
  PartCandidates previous;
  for (double yaw = 0; yaw <= 40; yaw += 0.25) {
    const PartCandidates now = index.Select(StandingPerson(3.0, Deg(yaw), false), {.top_k = 2});
    if (yaw > 0) {
      for (int p = 0; p < kBodyPartCount; ++p)
        for (const PartCandidate& c : now[p]) {
          double before = 0;
          for (const PartCandidate& b : previous[p])
            if (b.frame == c.frame) before = b.weight;
          EXPECT_LT(std::abs(c.weight - before), 0.1) << "yaw " << yaw << " part " << p;
        }
    }
    previous = now;
  }
}

// The yaw at which the chosen frame for the upper torso first leaves frame 0 as the viewer
// turns from 0 towards 10 degrees (the two stored views).
double SwitchYaw(double hysteresis) {
  const std::vector<Skeleton> stored = {StandingPerson(3.0, 0, false),
                                        StandingPerson(3.0, Deg(10), false)};
  const PartTextureIndex index(stored);
  PartSelectionHistory history;
  for (double yaw = 0; yaw <= 10; yaw += 0.1) {
    const PartCandidates c =
        index.Select(StandingPerson(3.0, Deg(yaw), false), {.hysteresis = hysteresis}, &history);
    if (c[Index(BodyPart::kUpperTorso)][0].frame == 1) return yaw;
  }
  return 99;
}

TEST(PartSelection, HysteresisKeepsThePreviousFrameUntilAnotherIsClearlyBetter) {
  // Without hysteresis the choice flips half-way (the cost grows symmetrically with the yaw
  // difference); with 0.3 the previous frame keeps it until the new one costs 30% less.
  const double plain = SwitchYaw(0.0);
  const double held = SwitchYaw(0.3);
  EXPECT_NEAR(plain, 5.0, 0.15);
  EXPECT_GT(held, plain + 0.7);
  EXPECT_LT(held, 10.0);
}

TEST(PartSelection, MissingJointsDisallowedPartsAndEmptySetsGiveNoCandidate) {
  const Skeleton viewer = StandingPerson(3.0, 0, true);
  EXPECT_TRUE(PartTextureIndex().Select(viewer, {})[0].empty());

  Skeleton no_hand = viewer;
  no_hand.confidence[Index(Joint::kLeftHand)] = 0;
  const std::vector<Skeleton> stored = {viewer, no_hand};
  // Frame 0 may texture everything but the head.
  const uint16_t allowed[] = {static_cast<uint16_t>(0x7ff & ~(1u << Index(BodyPart::kHead))),
                              0x7ff};
  const PartTextureIndex index(stored, allowed);
  const PartCandidates c = index.Select(viewer, {.top_k = 2});
  ASSERT_EQ(c[Index(BodyPart::kHead)].size(), 1u);
  EXPECT_EQ(c[Index(BodyPart::kHead)][0].frame, 1);
  ASSERT_EQ(c[Index(BodyPart::kLeftForearm)].size(), 1u);  // frame 1 lacks the hand
  EXPECT_EQ(c[Index(BodyPart::kLeftForearm)][0].frame, 0);
  EXPECT_EQ(c[Index(BodyPart::kRightForearm)].size(), 2u);
  // The viewer lacking the hand: no candidate for that forearm.
  EXPECT_TRUE(index.Select(no_hand, {})[Index(BodyPart::kLeftForearm)].empty());
  EXPECT_FALSE(index.Cost(BodyPart::kLeftForearm, viewer, 1));
  EXPECT_FALSE(index.Cost(BodyPart::kLeftForearm, viewer, 7));  // no such frame
  EXPECT_THROW(PartTextureIndex(stored, std::vector<uint16_t>{1}), CheckError);
}

TEST(PartSelection, DegenerateGeometryGivesFiniteDescriptors) {
  // A zero-length bone, a part at the camera centre, and a part straight behind the camera.
  Skeleton s = StandingPerson(3.0, 0, true);
  s.Set(Joint::kLeftHand, s[Joint::kLeftElbow]);
  Skeleton at_centre = s;
  at_centre.Set(Joint::kHead, Eigen::Vector3d(0, 0, 0.01));
  at_centre.Set(Joint::kNeck, Eigen::Vector3d(0, 0, -0.01));
  Skeleton behind = s.Transformed(Eigen::Isometry3d(Eigen::Translation3d(0, 0, -6.0)));
  for (const Skeleton& k : {s, at_centre, behind})
    for (int p = 0; p < kBodyPartCount; ++p) {
      const auto d = DescribePart(static_cast<BodyPart>(p), k);
      ASSERT_TRUE(d);
      for (const Eigen::Vector3d& o : d->offset) EXPECT_TRUE(o.allFinite());
    }
  const PartTextureIndex index(std::vector<Skeleton>{s, behind});
  const PartCandidates c = index.Select(at_centre, {.top_k = 2});
  for (int p = 0; p < kBodyPartCount; ++p)
    for (const PartCandidate& x : c[p]) {
      EXPECT_TRUE(std::isfinite(x.cost));
      EXPECT_TRUE(std::isfinite(x.weight));
    }
}

// The cells at angles [first, last] of the facing half, every height.
PartCoverage Angles(int first, int last, int height_first = 0,
                    int height_last = kCoverageHeights - 1) {
  PartCoverage out = 0;
  for (int i = first; i <= last; ++i)
    for (int j = height_first; j <= height_last; ++j)
      out |= PartCoverage{1} << (i * kCoverageHeights + j);
  return out;
}

TEST(PartSelection, FallbacksCoverWhatTheRankedCandidatesDoNotSee) {
  const std::vector<Skeleton> stored = TurningClip();
  const Skeleton viewer = LeftArmOut(3.0, Deg(62));
  constexpr BodyPart kPart = BodyPart::kLeftForearm;
  const PartSelectionOptions ranked{.top_k = 3};
  const std::vector<PartCandidate> main =
      PartTextureIndex(stored).Select(viewer, ranked)[Index(kPart)];
  ASSERT_EQ(main.size(), 3u);

  // Every frame sees the left half of the part's facing half; three others see more of the
  // right half: A heights 0-3, B heights 3-4, C height 4, with C cheaper than B.
  std::vector<std::pair<double, int>> others;
  for (int n = 0; n < static_cast<int>(stored.size()); ++n)
    if (std::none_of(main.begin(), main.end(),
                     [n](const PartCandidate& c) { return c.frame == n; }))
      others.push_back({*PartTextureIndex(stored).Cost(kPart, viewer, n), n});
  std::sort(others.begin(), others.end());
  const int a = others.back().second, c = others[5].second, b = others[10].second;
  const int half = kCoverageAngles / 2;
  std::vector<PartCoverages> coverage(stored.size(), PartCoverages{});
  for (PartCoverages& frame : coverage) frame[Index(kPart)] = Angles(0, half - 1);
  coverage[a][Index(kPart)] |= Angles(half, kCoverageAngles - 1, 0, 3);
  coverage[b][Index(kPart)] |= Angles(half, kCoverageAngles - 1, 3, 4);
  coverage[c][Index(kPart)] |= Angles(half, kCoverageAngles - 1, 4, 4);
  const PartTextureIndex index(stored, {}, coverage);

  PartSelectionOptions options = ranked;
  options.fallback_k = 3;
  const PartCandidates chosen = index.Select(viewer, options);
  const std::vector<PartCandidate>& part = chosen[Index(kPart)];
  // The ranked three unchanged; then A (the most cells, though the dearest frame), then of B
  // and C, which both add the last row, the cheaper C; then nothing is left to cover.
  ASSERT_EQ(part.size(), 5u);
  for (size_t i = 0; i < main.size(); ++i) {
    EXPECT_EQ(part[i].frame, main[i].frame);
    EXPECT_DOUBLE_EQ(part[i].weight, main[i].weight);
    EXPECT_FALSE(part[i].fallback);
  }
  EXPECT_EQ(part[3].frame, a);
  EXPECT_EQ(part[4].frame, c);
  for (size_t i = 3; i < part.size(); ++i) {
    EXPECT_TRUE(part[i].fallback);
    EXPECT_EQ(part[i].weight, 0.0);
  }
  // With one fallback allowed, only A.
  options.fallback_k = 1;
  EXPECT_EQ(index.Select(viewer, options)[Index(kPart)].size(), 4u);
  // Parts without coverage (every other one here) get no fallback.
  EXPECT_EQ(chosen[Index(BodyPart::kRightForearm)].size(), 3u);
}

TEST(PartSelection, NoFallbackWhereTheRankedCandidatesSeeEverything) {
  const std::vector<Skeleton> stored = TurningClip();
  std::vector<PartCoverages> coverage(stored.size(), PartCoverages{});
  for (PartCoverages& frame : coverage) frame.fill(kFullCoverage);
  const PartTextureIndex index(stored, {}, coverage);
  const PartCandidates chosen =
      index.Select(LeftArmOut(3.0, Deg(62)), {.top_k = 2, .fallback_k = 4});
  for (int p = 0; p < kBodyPartCount; ++p) EXPECT_EQ(chosen[p].size(), 2u) << p;
  EXPECT_THROW(PartTextureIndex(stored, {}, std::vector<PartCoverages>(3)), CheckError);
}

TEST(PartSelection, OptionsAreChecked) {
  EXPECT_THROW(PartSelectionOptions{.top_k = 0}.Check(), CheckError);
  EXPECT_THROW(PartSelectionOptions{.top_k = 9}.Check(), CheckError);
  EXPECT_THROW(PartSelectionOptions{.missing_joint_cost_m = -1}.Check(), CheckError);
  EXPECT_THROW(PartSelectionOptions{.hysteresis = 1.0}.Check(), CheckError);
  EXPECT_THROW(PartSelectionOptions{.fallback_k = -1}.Check(), CheckError);
  EXPECT_THROW(PartSelectionOptions{.fallback_k = 9}.Check(), CheckError);
  EXPECT_NO_THROW(PartSelectionOptions{}.Check());
}

}  // namespace
}  // namespace reenact
