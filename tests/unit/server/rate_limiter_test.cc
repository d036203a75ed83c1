// Token buckets checked against their arithmetic: burst B, refill R per second.
#include "server/http/rate_limiter.h"

#include <gtest/gtest.h>

namespace reenact::server {
namespace {

using Clock = RateLimiter::Clock;
using std::chrono::milliseconds;

TEST(RateLimiter, BurstThenRefillAtTheConfiguredRate) {
  RateLimiter limiter({/*per_second=*/10.0, /*burst=*/5.0, /*max_keys=*/100});
  const Clock::time_point t0 = Clock::now();
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(limiter.Acquire("k", t0).allowed) << i;
  const RateDecision refused = limiter.Acquire("k", t0);
  EXPECT_FALSE(refused.allowed);
  // Empty bucket, 10 credits/s: one credit returns after 0.1 s.
  EXPECT_NEAR(refused.retry_after_s, 0.1, 1e-9);
  EXPECT_FALSE(limiter.Acquire("k", t0 + milliseconds(90)).allowed);
  EXPECT_TRUE(limiter.Acquire("k", t0 + milliseconds(200)).allowed);
  // 1 s idle refills 10 credits but the bucket holds at most the burst of 5.
  const Clock::time_point t1 = t0 + milliseconds(1200);
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(limiter.Acquire("k", t1).allowed) << i;
  EXPECT_FALSE(limiter.Acquire("k", t1).allowed);
}

TEST(RateLimiter, KeysAreIndependent) {
  RateLimiter limiter({1.0, 1.0, 100});
  const Clock::time_point t0 = Clock::now();
  EXPECT_TRUE(limiter.Acquire("alice", t0).allowed);
  EXPECT_FALSE(limiter.Acquire("alice", t0).allowed);
  EXPECT_TRUE(limiter.Acquire("bob", t0).allowed);
}

TEST(RateLimiter, ZeroRateMeansNoLimit) {
  RateLimiter limiter({0.0, 1.0, 1});
  for (int i = 0; i < 1000; ++i) ASSERT_TRUE(limiter.Acquire("k").allowed);
  EXPECT_EQ(limiter.tracked_keys(), 0u);
}

TEST(RateLimiter, MemoryStaysBounded) {
  RateLimiter limiter({1.0, 2.0, 64});
  const Clock::time_point t0 = Clock::now();
  for (int i = 0; i < 10000; ++i) {
    limiter.Acquire("key-" + std::to_string(i), t0 + milliseconds(i));
    ASSERT_LE(limiter.tracked_keys(), 64u);
  }
}

TEST(RateLimiter, BadOptionsAreRefused) {
  EXPECT_ANY_THROW(RateLimiter({-1.0, 1.0, 1}));
  EXPECT_ANY_THROW(RateLimiter({1.0, 0.5, 1}));
  EXPECT_ANY_THROW(RateLimiter({1.0, 1.0, 0}));
}

}  // namespace
}  // namespace reenact::server
