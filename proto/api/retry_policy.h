#pragma once
// When and how long a client waits before sending a failed request again: exponential
// backoff with jitter, bounded in attempts, honouring the server's Retry-After.
//
// Delay before retry k (k = 0 for the first retry), with u uniform in [0, 1):
//   base_k  = min(max_delay_s, initial_delay_s * multiplier^k)
//   delay_k = base_k * (1 - jitter * u)        (jitter in [0, 1]; 0 = no randomness)
// Jitter spreads clients that failed together (a restarted server) so they do not come back
// in lock step. A 429 or 503 answer's Retry-After (seconds) replaces delay_k, clamped to
// [min_retry_after_s, max_retry_after_s].

#include <optional>
#include <string_view>

namespace reenact::proto {

// What a failed attempt means for a retry.
enum class FailureKind {
  kFatal,           // 4xx other than 429, malformed URL, oversized answer: retrying cannot help
  kNotDelivered,    // nothing was done: connection refused, unknown host, 503
  kMaybeDelivered,  // the request may have had an effect: broken connection, timeout, other 5xx
  kRateLimited,     // 429: nothing was done; come back after Retry-After
};

struct RetryPolicy {
  // Attempts in all, the first included; >= 1 (1 = never retry).
  int max_attempts = 6;
  double initial_delay_s = 0.25;  // > 0
  double multiplier = 2.0;        // >= 1
  double max_delay_s = 8.0;       // >= initial_delay_s
  double jitter = 0.5;            // [0, 1]
  double min_retry_after_s = 0.1;
  double max_retry_after_s = 30.0;  // >= min_retry_after_s
  // Which failures are retried: 429 always; connection failures and 5xx only when true (the
  // publisher's policy), so that an interactive tool may fail fast instead.
  bool retry_transport_and_5xx = true;

  void Check() const;

  // The default of ApiClient: only 429 is retried (up to 10 times), as a plain client should.
  static RetryPolicy RateLimitOnly();

  // delay_k above for retry k >= 0 and u in [0, 1).
  double BackoffDelayS(int retry, double u) const;
  // The wait before retry k: Retry-After (clamped) when the server sent one, else backoff.
  double DelayS(int retry, double u, std::optional<double> retry_after_s) const;
  // Whether a failure of this kind may be retried, for a request that is idempotent or not
  // (a non-idempotent one is retried only when nothing can have happened on the server).
  bool ShouldRetry(FailureKind kind, bool idempotent) const;
};

// The failure kind of a transport error code of HttpClient::Send ("unreachable", "timeout",
// "network", ...) or of an HTTP status (0 when there was no answer).
FailureKind ClassifyTransportError(std::string_view code);
FailureKind ClassifyStatus(int status);

// Retry-After as delta-seconds ("120"); nullopt when absent or not a non-negative number
// (an HTTP date is not understood and treated as absent).
std::optional<double> ParseRetryAfter(std::string_view value);

}  // namespace reenact::proto
