#pragma once
// ApiClient: the reenact HTTP API (proto/API.md) as blocking calls, for the capture client
// (upload) and the viewer client (browse, download). A failed request becomes the server's
// own Error{code, message} (from its JSON error body); transport failures keep the codes of
// HttpClient::Send ("unreachable", "timeout", ...).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common/error/expected.h"
#include "proto/api/api_types.h"
#include "proto/api/http_client.h"
#include "proto/api/retry_policy.h"

namespace reenact::proto {

// A failed attempt that is about to be retried (for progress output).
struct RetryNotice {
  std::string request;  // "PUT /v1/clips/ID/frames/3"
  int attempt = 0;      // 1-based number of the attempt that failed
  int max_attempts = 0;
  double delay_s = 0;   // wait before the next attempt
  Error cause;          // why it failed
};

class ApiClient {
 public:
  // With the default policy a request answered 429 (rate limited) is sent again after the
  // server's Retry-After (clamped to [0.1 s, 10 s]) up to this many times.
  static constexpr int kMaxRateLimitRetries = 10;

  // base_url "http://HOST:PORT"; token may be empty for read-only use. `retry` says which
  // failures are retried and how long to wait (proto/api/retry_policy.h); after the last
  // attempt the error of that attempt is returned, its message noting the attempts made.
  ApiClient(std::string base_url, std::string token, HttpClientOptions options = {},
            RetryPolicy retry = RetryPolicy::RateLimitOnly());

  // Called before each wait for a retry (on the calling thread).
  void set_retry_observer(std::function<void(const RetryNotice&)> observer) {
    observer_ = std::move(observer);
  }

  // POST /v1/clips: creates a draft from the manifest JSON; returns the clip id.
  Expected<std::string> CreateClip(const std::string& manifest_json) const;
  // PUT /v1/clips/{id}/frames/{n}: uploads frame n's bytes (idempotent).
  Status PutFrame(const std::string& id, int64_t n, const std::string& bytes) const;
  // PUT /v1/clips/{id}/map (idempotent).
  Status PutMap(const std::string& id, const std::string& bytes) const;
  // POST /v1/clips/{id}/publish; code "incomplete" naming missing parts.
  Status Publish(const std::string& id) const;
  // GET /v1/clips?near=...: the first page of published clips within radius_m, nearest first.
  Expected<std::vector<ClipSummary>> Nearby(double lat_deg, double lon_deg, double radius_m,
                                            int limit = 20) const;
  // The same with a cursor from a previous page (empty for the first page).
  Expected<NearbyPage> NearbyPageAt(double lat_deg, double lon_deg, double radius_m, int limit,
                                    const std::string& cursor) const;
  // GET /v1/clips/{id}: the manifest JSON exactly as uploaded.
  Expected<std::string> GetManifest(const std::string& id) const;
  Expected<std::string> GetFrame(const std::string& id, int64_t n) const;
  Expected<std::string> GetMap(const std::string& id) const;
  // DELETE /v1/clips/{id} (owner only).
  Status DeleteClip(const std::string& id) const;
  // GET /v1/me/clips: the caller's clips, drafts included (distance_m is 0).
  Expected<std::vector<ClipSummary>> MyClips() const;
  // GET /v1/me/clips?manifest_sha256=H: the caller's clips created from that manifest.
  Expected<std::vector<OwnClip>> MyClipsWithManifest(const std::string& manifest_sha256) const;
  // GET /v1/clips/{id}/parts: every part with what the server holds for it (owner only).
  Expected<ClipParts> ListParts(const std::string& id) const;

  const std::string& base_url() const { return http_.base_url(); }

 private:
  // Sends with the bearer token, retrying per the policy (a non-idempotent request only
  // when it cannot have had an effect); any other status than expected becomes an Error.
  Expected<HttpResponse> Call(HttpRequest request, int expected_status,
                              bool idempotent = true) const;

  HttpClient http_;
  std::string token_;
  RetryPolicy retry_;
  std::function<void(const RetryNotice&)> observer_;
};

}  // namespace reenact::proto
