#pragma once
// Per-key request rate limits (token buckets): each key (the SHA-256 of a bearer token)
// holds up to `burst` requests' worth of credit, refilled at `per_second`. A request spends
// one credit; with none left it is refused (the server answers 429 with Retry-After).
// Thread-safe. Memory is bounded: beyond max_keys, buckets that are full again (idle keys)
// are forgotten first, and if none is full the oldest-touched half is dropped. The buckets live
// in this process: several servers behind one proxy each allow a token the full rate.

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>
#include <unordered_map>

namespace reenact::server {

struct RateLimitOptions {
  // Sustained requests per second per key; >= 0, 0 = no limit. Default 200.
  double per_second = 200.0;
  // Requests a key may send at once after being idle; >= 1. Default 400.
  double burst = 400.0;
  // Keys remembered at most; >= 1. Default 100000.
  size_t max_keys = 100000;

  void Check() const;
};

struct RateDecision {
  bool allowed = true;
  // When refused: seconds until one request's credit is back (> 0).
  double retry_after_s = 0.0;
};

class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;

  explicit RateLimiter(RateLimitOptions options);

  // Spends one request's credit of `key` at time `now` if it has any.
  RateDecision Acquire(const std::string& key, Clock::time_point now = Clock::now());

  size_t tracked_keys() const;

 private:
  struct Bucket {
    double credit = 0.0;
    Clock::time_point updated;
  };

  void Evict(Clock::time_point now);

  const RateLimitOptions options_;
  mutable std::mutex mutex_;
  std::unordered_map<std::string, Bucket> buckets_;
};

}  // namespace reenact::server
