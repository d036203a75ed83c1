// The gap ratio of the tracker's prediction in time: frames dropped between the last tracked
// pose and this one scale the carried-on displacement; unknown, non-increasing or non-finite
// times count as evenly spaced frames.
#include "capture-client/tracker/gap_ratio.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/error/check.h"

namespace reenact::capture {
namespace {

constexpr double kInterval = 1.0 / 30;

TEST(GapRatio, CountsTheIntervalsSinceTheLastPose) {
  // Poses at frames 10 and 11 of a 30 fps stream; this frame is 11 + k, k - 1 frames dropped.
  const double t0 = 10 * kInterval, t1 = 11 * kInterval;
  for (int k = 1; k <= 4; ++k) EXPECT_NEAR(GapRatio((11 + k) * kInterval, t1, t0, 4), k, 1e-9) << k;
  // A gap before the last pose: the last interval was two frames, this one is one.
  EXPECT_NEAR(GapRatio(12 * kInterval, t1, 9 * kInterval, 4), 0.5, 1e-9);
}

TEST(GapRatio, EvenlyTimedFramesGiveExactlyOne) {
  // f / 30 for successive f does not give equal differences in floating point; the ratio is
  // still exactly 1, as without timestamps.
  for (int f = 2; f < 2000; ++f)
    ASSERT_EQ(GapRatio(f / 30.0, (f - 1) / 30.0, (f - 2) / 30.0, 4), 1.0) << f;
}

TEST(GapRatio, ALongGapIsClamped) {
  EXPECT_EQ(GapRatio(40 * kInterval, kInterval, 0, 4), 4);
  EXPECT_EQ(GapRatio(40 * kInterval, kInterval, 0, 1), 1);
}

TEST(GapRatio, UnknownOrBadTimesCountAsEvenlySpaced) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(GapRatio(std::nullopt, 1, 0, 4), 1);
  EXPECT_EQ(GapRatio(2, std::nullopt, 0, 4), 1);
  EXPECT_EQ(GapRatio(2, 1, std::nullopt, 4), 1);
  EXPECT_EQ(GapRatio(1, 1, 0, 4), 1);    // the same time as the last pose
  EXPECT_EQ(GapRatio(0.5, 1, 0, 4), 1);  // back in time
  EXPECT_EQ(GapRatio(2, 1, 1, 4), 1);    // the last two poses at one time
  EXPECT_EQ(GapRatio(2, 0, 1, 4), 1);    // the last two poses out of order
  EXPECT_EQ(GapRatio(nan, 1, 0, 4), 1);
  EXPECT_EQ(GapRatio(inf, 1, 0, 4), 1);
  EXPECT_EQ(GapRatio(2, 1, -inf, 4), 1);
  EXPECT_THROW(GapRatio(2, 1, 0, 0.5), CheckError);
  EXPECT_THROW(GapRatio(2, 1, 0, nan), CheckError);
}

}  // namespace
}  // namespace reenact::capture
