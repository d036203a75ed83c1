#include "server/http/rate_limiter.h"

#include <algorithm>
#include <vector>

#include "common/error/check.h"

namespace reenact::server {

void RateLimitOptions::Check() const {
  REENACT_CHECK(per_second >= 0.0, "rate limit per_second must be >= 0");
  REENACT_CHECK(burst >= 1.0, "rate limit burst must be >= 1");
  REENACT_CHECK(max_keys >= 1, "rate limit max_keys must be >= 1");
}

RateLimiter::RateLimiter(RateLimitOptions options) : options_(options) { options_.Check(); }

RateDecision RateLimiter::Acquire(const std::string& key, Clock::time_point now) {
  if (options_.per_second <= 0.0) return {};
  std::lock_guard lock(mutex_);
  auto it = buckets_.find(key);
  if (it == buckets_.end()) {
    if (buckets_.size() >= options_.max_keys) Evict(now);
    it = buckets_.emplace(key, Bucket{options_.burst, now}).first;
  }
  Bucket& bucket = it->second;
  const double elapsed_s = std::chrono::duration<double>(now - bucket.updated).count();
  if (elapsed_s > 0) {
    bucket.credit = std::min(options_.burst, bucket.credit + elapsed_s * options_.per_second);
    bucket.updated = now;
  }
  if (bucket.credit >= 1.0) {
    bucket.credit -= 1.0;
    return {};
  }
  return {false, (1.0 - bucket.credit) / options_.per_second};
}

size_t RateLimiter::tracked_keys() const {
  std::lock_guard lock(mutex_);
  return buckets_.size();
}

void RateLimiter::Evict(Clock::time_point now) {
  std::erase_if(buckets_, [&](const auto& entry) {
    const double elapsed_s = std::chrono::duration<double>(now - entry.second.updated).count();
    return entry.second.credit + elapsed_s * options_.per_second >= options_.burst;
  });
  if (buckets_.size() < options_.max_keys) return;
  std::vector<Clock::time_point> times;
  times.reserve(buckets_.size());
  for (const auto& entry : buckets_) times.push_back(entry.second.updated);
  auto middle = times.begin() + times.size() / 2;
  std::nth_element(times.begin(), middle, times.end());
  const Clock::time_point cutoff = *middle;
  std::erase_if(buckets_, [&](const auto& entry) { return entry.second.updated <= cutoff; });
}

}  // namespace reenact::server
