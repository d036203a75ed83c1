#include "common/filter/steady_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "common/error/check.h"

namespace reenact {
namespace {

Skeleton At(double x, double conf = 1.0) {
  Skeleton s;
  for (int j = 0; j < kJointCount; ++j)
    s.Set(static_cast<Joint>(j), Eigen::Vector3d(x, j, 2), conf);
  return s;
}

TEST(SteadyMotion, FlaggedSkeletonsAreInterpolatedInTimeFromTheirNeighbours) {
  // x = 0 at t = 0, flagged garbage at t = 0.1 and 0.3, x = 4 at t = 0.4: the flagged ones
  // land on the line through the neighbours (uneven times: weights by time, not index).
  const std::vector<Skeleton> track = {At(0), At(100), At(-50), At(4)};
  const std::vector<double> times = {0.0, 0.1, 0.3, 0.4};
  const bool flagged[] = {false, true, true, false};
  const auto out = InterpolateFlaggedSkeletons(track, times, flagged);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].position, track[0].position);
  EXPECT_EQ(out[3].position, track[3].position);
  for (int j = 0; j < kJointCount; ++j) {
    EXPECT_NEAR(out[1].position[j].x(), 1.0, 1e-12);
    EXPECT_NEAR(out[2].position[j].x(), 3.0, 1e-12);
    EXPECT_NEAR(out[2].position[j].y(), j, 1e-12);
  }
}

TEST(SteadyMotion, FlaggedAtTheEndsHoldTheNearestAndJointsMissingOnOneSideAreHeld) {
  Skeleton late = At(2, 0.5);
  late.confidence[Index(Joint::kHead)] = 0;  // head missing after the gap
  Skeleton early = At(0);
  early.confidence[Index(Joint::kLeftHand)] = 0;
  early.confidence[Index(Joint::kHead)] = 0;  // and before: missing in both
  const std::vector<Skeleton> track = {At(9), early, At(9), late, At(9)};
  const std::vector<double> times = {0, 1, 2, 3, 4};
  const bool flagged[] = {true, false, true, false, true};
  const auto out = InterpolateFlaggedSkeletons(track, times, flagged);
  EXPECT_EQ(out[0].position, early.position);  // before the first unflagged: held
  EXPECT_EQ(out[4].position, late.position);   // after the last: held
  EXPECT_NEAR(out[2][Joint::kTorso].x(), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(out[2].confidence[Index(Joint::kTorso)], 0.5);  // min of the two
  EXPECT_NEAR(out[2][Joint::kLeftHand].x(), 2.0, 1e-12);           // only after: held
  EXPECT_FALSE(out[2].Has(Joint::kHead));
}

TEST(SteadyMotion, EqualTimesInterpolateByFrameIndexAndAllFlaggedIsLeftAsGiven) {
  const std::vector<Skeleton> track = {At(0), At(7), At(7), At(3)};
  const std::vector<double> times = {1, 1, 1, 1};
  const bool flagged[] = {false, true, true, false};
  const auto out = InterpolateFlaggedSkeletons(track, times, flagged);
  EXPECT_NEAR(out[1][Joint::kNeck].x(), 1.0, 1e-12);
  EXPECT_NEAR(out[2][Joint::kNeck].x(), 2.0, 1e-12);

  const bool all[] = {true, true, true, true};
  const auto same = InterpolateFlaggedSkeletons(track, times, all);
  for (size_t n = 0; n < track.size(); ++n) EXPECT_EQ(same[n].position, track[n].position);
}

TEST(SteadyMotion, MismatchedSizesAreRejected) {
  const std::vector<Skeleton> track = {At(0), At(1)};
  const std::vector<double> times = {0};
  const bool flagged[] = {false, false};
  EXPECT_THROW(InterpolateFlaggedSkeletons(track, times, flagged), CheckError);
  const std::vector<double> bad_times = {0, NAN};
  EXPECT_THROW(SteadySkeletonTrack(track, bad_times, flagged, {}), CheckError);
}

TEST(SteadyMotion, FilterSmoothsEveryJointAndRestartsAfterAMissingJoint) {
  // A static skeleton with one frame's torso kicked by 10 cm: the filter passes the static
  // joints unchanged and shrinks the kick; the hand, missing at frame 3, stays missing and
  // its filter restarts, so frame 4's hand equals the input exactly.
  std::vector<Skeleton> track;
  std::vector<double> times;
  for (int n = 0; n < 8; ++n) {
    track.push_back(At(0));
    times.push_back(n / 30.0);
  }
  track[2][Joint::kTorso].x() = 0.1;
  track[3].confidence[Index(Joint::kLeftHand)] = 0;
  track[4][Joint::kLeftHand].x() = 0.05;
  std::unique_ptr<bool[]> flagged(new bool[track.size()]());
  SteadyMotionOptions options;
  options.zero_phase = false;
  options.one_euro = {.min_cutoff_hz = 1.0, .beta = 2.0, .derivative_cutoff_hz = 1.0};
  const auto out = SteadySkeletonTrack(track, times, {flagged.get(), track.size()}, options);
  EXPECT_EQ(out[5][Joint::kNeck], track[5][Joint::kNeck]);
  // Frame 2: raw speed 0.1 m / (1/30 s) = 3 m/s, filtered alpha_d * 3 (from 0), so the cutoff
  // is min_cutoff + beta alpha_d 3 and the output alpha(cutoff) * 0.1.
  const double dt = 1 / 30.0;
  const double speed = OneEuroAlpha(options.one_euro.derivative_cutoff_hz, dt) * 3.0;
  const double alpha =
      OneEuroAlpha(options.one_euro.min_cutoff_hz + options.one_euro.beta * speed, dt);
  EXPECT_NEAR(out[2][Joint::kTorso].x(), alpha * 0.1, 1e-12);
  EXPECT_LT(out[2][Joint::kTorso].x(), 0.05);
  EXPECT_FALSE(out[3].Has(Joint::kLeftHand));
  EXPECT_EQ(out[4][Joint::kLeftHand], track[4][Joint::kLeftHand]);

  // Flagged frames are interpolated before filtering.
  flagged[2] = true;
  const auto steady = SteadySkeletonTrack(track, times, {flagged.get(), track.size()}, options);
  EXPECT_NEAR(steady[2][Joint::kTorso].x(), 0.0, 1e-12);
}

TEST(SteadyMotion, ZeroPhaseCancelsTheRampLagOfTheForwardPass) {
  // A joint moving at v = 1 m/s for 20 s at 30 fps: forward only it lags by v tau(f) with
  // f = min_cutoff + beta v (one_euro_filter.h); forward + backward the lag cancels away from
  // the ends, where the start-up transients have decayed.
  const double v = 1.0, dt = 1.0 / 30;
  std::vector<Skeleton> track;
  std::vector<double> times;
  for (int n = 0; n < 600; ++n) {
    times.push_back(n * dt);
    track.push_back(At(v * times.back()));
  }
  std::unique_ptr<bool[]> flagged(new bool[track.size()]());
  SteadyMotionOptions options;
  options.zero_phase = false;
  const auto causal = SteadySkeletonTrack(track, times, {flagged.get(), track.size()}, options);
  options.zero_phase = true;
  const auto steady = SteadySkeletonTrack(track, times, {flagged.get(), track.size()}, options);
  const double f = options.one_euro.min_cutoff_hz + options.one_euro.beta * v;
  const double tau = 1.0 / (2.0 * M_PI * f);
  for (int n : {250, 300, 350}) {
    EXPECT_NEAR(track[n][Joint::kWaist].x() - causal[n][Joint::kWaist].x(), v * tau, 1e-9) << n;
    EXPECT_NEAR(steady[n][Joint::kWaist].x(), track[n][Joint::kWaist].x(), 1e-9) << n;
  }
}

}  // namespace
}  // namespace reenact
