// The backoff schedule of proto/api/retry_policy.h against its formula, worked by hand.
#include <gtest/gtest.h>

#include "proto/api/retry_policy.h"

namespace reenact::proto {
namespace {

TEST(RetryPolicy, DoublesFromTheInitialDelayUpToTheCap) {
  RetryPolicy p;
  p.initial_delay_s = 0.25;
  p.multiplier = 2;
  p.max_delay_s = 3;
  p.jitter = 0;
  const double expected[] = {0.25, 0.5, 1.0, 2.0, 3.0, 3.0};
  for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(p.BackoffDelayS(k, 0.7), expected[k]) << k;
  // Far beyond the cap: no overflow, still the cap.
  EXPECT_DOUBLE_EQ(p.BackoffDelayS(100000, 0.7), 3.0);
}

TEST(RetryPolicy, JitterShortensTheDelayByUpToItsFraction) {
  RetryPolicy p;
  p.initial_delay_s = 1;
  p.multiplier = 3;
  p.max_delay_s = 100;
  p.jitter = 0.5;
  // base 9 s for k = 2; u = 0 keeps it, u -> 1 halves it, u = 0.5 takes a quarter off.
  EXPECT_DOUBLE_EQ(p.BackoffDelayS(2, 0.0), 9.0);
  EXPECT_DOUBLE_EQ(p.BackoffDelayS(2, 0.5), 6.75);
  EXPECT_NEAR(p.BackoffDelayS(2, 0.999999), 4.5, 1e-5);
  // Out-of-range draws are clamped into [0, 1].
  EXPECT_DOUBLE_EQ(p.BackoffDelayS(2, -3.0), 9.0);
  EXPECT_DOUBLE_EQ(p.BackoffDelayS(2, 7.0), 4.5);
}

TEST(RetryPolicy, RetryAfterReplacesBackoffWithinItsBounds) {
  RetryPolicy p;
  p.min_retry_after_s = 0.1;
  p.max_retry_after_s = 30;
  EXPECT_DOUBLE_EQ(p.DelayS(4, 0.3, 2.0), 2.0);
  EXPECT_DOUBLE_EQ(p.DelayS(0, 0.3, 0.0), 0.1);
  EXPECT_DOUBLE_EQ(p.DelayS(0, 0.3, 3600.0), 30.0);
  EXPECT_DOUBLE_EQ(p.DelayS(1, 0.0, std::nullopt), p.BackoffDelayS(1, 0.0));
}

TEST(RetryPolicy, ParsesRetryAfterSeconds) {
  EXPECT_EQ(ParseRetryAfter("120"), 120.0);
  EXPECT_EQ(ParseRetryAfter("1.5"), 1.5);
  EXPECT_EQ(ParseRetryAfter("0"), 0.0);
  EXPECT_FALSE(ParseRetryAfter(""));
  EXPECT_FALSE(ParseRetryAfter("-1"));
  EXPECT_FALSE(ParseRetryAfter("soon"));
  EXPECT_FALSE(ParseRetryAfter("Wed, 21 Oct 2015 07:28:00 GMT"));
  EXPECT_FALSE(ParseRetryAfter("nan"));
}

TEST(RetryPolicy, RetriesOnlyWhatCanSucceedLater) {
  RetryPolicy publisher;
  EXPECT_EQ(ClassifyStatus(429), FailureKind::kRateLimited);
  EXPECT_EQ(ClassifyStatus(503), FailureKind::kNotDelivered);
  EXPECT_EQ(ClassifyStatus(500), FailureKind::kMaybeDelivered);
  EXPECT_EQ(ClassifyStatus(422), FailureKind::kFatal);
  EXPECT_EQ(ClassifyStatus(404), FailureKind::kFatal);
  EXPECT_EQ(ClassifyTransportError("unreachable"), FailureKind::kNotDelivered);
  EXPECT_EQ(ClassifyTransportError("timeout"), FailureKind::kMaybeDelivered);
  EXPECT_EQ(ClassifyTransportError("network"), FailureKind::kMaybeDelivered);
  EXPECT_EQ(ClassifyTransportError("invalid_argument"), FailureKind::kFatal);

  EXPECT_TRUE(publisher.ShouldRetry(FailureKind::kNotDelivered, false));
  EXPECT_TRUE(publisher.ShouldRetry(FailureKind::kMaybeDelivered, true));
  // A create whose answer was lost may have created the draft: not sent blindly again.
  EXPECT_FALSE(publisher.ShouldRetry(FailureKind::kMaybeDelivered, false));
  EXPECT_TRUE(publisher.ShouldRetry(FailureKind::kRateLimited, false));
  EXPECT_FALSE(publisher.ShouldRetry(FailureKind::kFatal, true));

  const RetryPolicy plain = RetryPolicy::RateLimitOnly();
  EXPECT_TRUE(plain.ShouldRetry(FailureKind::kRateLimited, true));
  EXPECT_FALSE(plain.ShouldRetry(FailureKind::kNotDelivered, true));
  EXPECT_FALSE(plain.ShouldRetry(FailureKind::kMaybeDelivered, true));
}

TEST(RetryPolicy, DefaultScheduleFitsWithinEightSeconds) {
  // Five retries: 0.25 + 0.5 + 1 + 2 + 4 = 7.75 s at most; a dead server is reported soon.
  const RetryPolicy p;
  double total = 0;
  for (int k = 0; k + 1 < p.max_attempts; ++k) total += p.BackoffDelayS(k, 0.0);
  EXPECT_DOUBLE_EQ(total, 7.75);
}

}  // namespace
}  // namespace reenact::proto
