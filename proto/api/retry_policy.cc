#include "proto/api/retry_policy.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "common/error/check.h"

namespace reenact::proto {

void RetryPolicy::Check() const {
  REENACT_CHECK(max_attempts >= 1, "max_attempts must be >= 1");
  REENACT_CHECK(initial_delay_s > 0, "initial_delay_s must be > 0");
  REENACT_CHECK(multiplier >= 1, "multiplier must be >= 1");
  REENACT_CHECK(max_delay_s >= initial_delay_s, "max_delay_s must be >= initial_delay_s");
  REENACT_CHECK(jitter >= 0 && jitter <= 1, "jitter must be in [0, 1]");
  REENACT_CHECK(min_retry_after_s >= 0 && max_retry_after_s >= min_retry_after_s,
                "need 0 <= min_retry_after_s <= max_retry_after_s");
}

RetryPolicy RetryPolicy::RateLimitOnly() {
  RetryPolicy policy;
  policy.max_attempts = 11;
  policy.max_retry_after_s = 10.0;
  policy.retry_transport_and_5xx = false;
  return policy;
}

double RetryPolicy::BackoffDelayS(int retry, double u) const {
  REENACT_CHECK(retry >= 0, "retry must be >= 0");
  // Capped before it can overflow: multiplier^retry only matters until it passes the cap.
  double base = initial_delay_s;
  for (int k = 0; k < retry && base < max_delay_s; ++k) base *= multiplier;
  base = std::min(base, max_delay_s);
  return base * (1.0 - jitter * std::clamp(u, 0.0, 1.0));
}

double RetryPolicy::DelayS(int retry, double u, std::optional<double> retry_after_s) const {
  if (retry_after_s) return std::clamp(*retry_after_s, min_retry_after_s, max_retry_after_s);
  return BackoffDelayS(retry, u);
}

bool RetryPolicy::ShouldRetry(FailureKind kind, bool idempotent) const {
  switch (kind) {
    case FailureKind::kFatal:
      return false;
    case FailureKind::kRateLimited:
      return true;
    case FailureKind::kNotDelivered:
      return retry_transport_and_5xx;
    case FailureKind::kMaybeDelivered:
      return retry_transport_and_5xx && idempotent;
  }
  return false;
}

FailureKind ClassifyTransportError(std::string_view code) {
  if (code == "unreachable") return FailureKind::kNotDelivered;
  if (code == "timeout" || code == "network") return FailureKind::kMaybeDelivered;
  return FailureKind::kFatal;  // invalid_argument (bad URL), too_large, ...
}

FailureKind ClassifyStatus(int status) {
  if (status == 429) return FailureKind::kRateLimited;
  if (status == 503) return FailureKind::kNotDelivered;
  if (status >= 500) return FailureKind::kMaybeDelivered;
  return FailureKind::kFatal;
}

std::optional<double> ParseRetryAfter(std::string_view value) {
  const std::string text(value);
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double seconds = std::strtod(text.c_str(), &end);
  while (end && *end == ' ') ++end;
  if (end == text.c_str() || *end != '\0' || !std::isfinite(seconds) || seconds < 0) {
    return std::nullopt;
  }
  return seconds;
}

}  // namespace reenact::proto
