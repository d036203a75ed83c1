#include "proto/api/api_client.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <thread>

namespace reenact::proto {

namespace {

// A uniform draw in [0, 1) for backoff jitter.
double JitterDraw() {
  thread_local std::mt19937_64 rng{std::random_device{}()};
  return std::uniform_real_distribution<double>(0.0, 1.0)(rng);
}

Error ErrorOf(const HttpRequest& request, const HttpResponse& response) {
  if (auto error = ParseErrorBody(response.body)) return *error;
  return MakeError("http_" + std::to_string(response.status),
                   request.method + " " + request.target + " failed with HTTP status " +
                       std::to_string(response.status));
}

// Percent-encodes a query value (RFC 3986 unreserved characters pass through).
std::string EncodeQueryValue(std::string_view value) {
  std::string out;
  for (unsigned char c : value) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~' || c == ',') {
      out.push_back(static_cast<char>(c));
    } else {
      char hex[4];
      std::snprintf(hex, sizeof(hex), "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

std::string Number(double value) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

HttpRequest Make(std::string method, std::string target) {
  HttpRequest request;
  request.method = std::move(method);
  request.target = std::move(target);
  return request;
}

}  // namespace

ApiClient::ApiClient(std::string base_url, std::string token, HttpClientOptions options,
                     RetryPolicy retry)
    : http_(std::move(base_url), options), token_(std::move(token)), retry_(retry) {
  retry_.Check();
}

Expected<HttpResponse> ApiClient::Call(HttpRequest request, int expected_status,
                                       bool idempotent) const {
  if (!token_.empty()) request.headers.emplace_back("Authorization", "Bearer " + token_);
  for (int attempt = 1;; ++attempt) {
    auto response = http_.Send(request);
    if (response && response->status == expected_status) return response;
    Error error = response ? ErrorOf(request, *response) : response.error();
    const FailureKind kind =
        response ? ClassifyStatus(response->status) : ClassifyTransportError(error.code);
    if (!retry_.ShouldRetry(kind, idempotent)) return error;
    if (attempt >= retry_.max_attempts) {
      if (attempt > 1) error.message += " (gave up after " + std::to_string(attempt) + " attempts)";
      return error;
    }
    std::optional<double> retry_after;
    if (response) {
      if (auto header = response->Header("Retry-After")) retry_after = ParseRetryAfter(*header);
      if (!retry_after && kind == FailureKind::kRateLimited) retry_after = 1.0;
    }
    const double delay_s = retry_.DelayS(attempt - 1, JitterDraw(), retry_after);
    if (observer_) {
      observer_(RetryNotice{request.method + " " + request.target, attempt, retry_.max_attempts,
                            delay_s, error});
    }
    std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
  }
}

Expected<std::string> ApiClient::CreateClip(const std::string& manifest_json) const {
  HttpRequest request = Make("POST", "/v1/clips");
  request.content_type = "application/json";
  request.body = manifest_json;
  auto response = Call(std::move(request), 201, /*idempotent=*/false);
  if (!response) return response.error();
  const auto parsed = nlohmann::json::parse(response->body, nullptr, false);
  if (parsed.is_discarded() || !parsed.is_object() || !parsed.contains("id") ||
      !parsed["id"].is_string()) {
    return MakeError("network", "server answered POST /v1/clips without a clip id");
  }
  return parsed["id"].get<std::string>();
}

Status ApiClient::PutFrame(const std::string& id, int64_t n, const std::string& bytes) const {
  HttpRequest request =
      Make("PUT", "/v1/clips/" + EncodeQueryValue(id) + "/frames/" + std::to_string(n));
  request.content_type = "application/octet-stream";
  request.body = bytes;
  auto response = Call(std::move(request), 204);
  if (!response) return response.error();
  return {};
}

Status ApiClient::PutMap(const std::string& id, const std::string& bytes) const {
  HttpRequest request = Make("PUT", "/v1/clips/" + EncodeQueryValue(id) + "/map");
  request.content_type = "application/octet-stream";
  request.body = bytes;
  auto response = Call(std::move(request), 204);
  if (!response) return response.error();
  return {};
}

Status ApiClient::Publish(const std::string& id) const {
  auto response = Call(Make("POST", "/v1/clips/" + EncodeQueryValue(id) + "/publish"), 200);
  if (!response) return response.error();
  return {};
}

Expected<NearbyPage> ApiClient::NearbyPageAt(double lat_deg, double lon_deg, double radius_m,
                                             int limit, const std::string& cursor) const {
  std::string target = "/v1/clips?near=" + Number(lat_deg) + "," + Number(lon_deg) +
                       "&radius_m=" + Number(radius_m) + "&limit=" + std::to_string(limit);
  if (!cursor.empty()) target += "&cursor=" + EncodeQueryValue(cursor);
  auto response = Call(Make("GET", target), 200);
  if (!response) return response.error();
  return ParseNearbyPage(response->body);
}

Expected<std::vector<ClipSummary>> ApiClient::Nearby(double lat_deg, double lon_deg,
                                                     double radius_m, int limit) const {
  auto page = NearbyPageAt(lat_deg, lon_deg, radius_m, limit, "");
  if (!page) return page.error();
  return std::move(page->clips);
}

Expected<std::string> ApiClient::GetManifest(const std::string& id) const {
  auto response = Call(Make("GET", "/v1/clips/" + EncodeQueryValue(id)), 200);
  if (!response) return response.error();
  return std::move(response->body);
}

Expected<std::string> ApiClient::GetFrame(const std::string& id, int64_t n) const {
  auto response = Call(
      Make("GET", "/v1/clips/" + EncodeQueryValue(id) + "/frames/" + std::to_string(n)), 200);
  if (!response) return response.error();
  return std::move(response->body);
}

Expected<std::string> ApiClient::GetMap(const std::string& id) const {
  auto response = Call(Make("GET", "/v1/clips/" + EncodeQueryValue(id) + "/map"), 200);
  if (!response) return response.error();
  return std::move(response->body);
}

Status ApiClient::DeleteClip(const std::string& id) const {
  auto response = Call(Make("DELETE", "/v1/clips/" + EncodeQueryValue(id)), 204);
  if (!response) return response.error();
  return {};
}

Expected<std::vector<ClipSummary>> ApiClient::MyClips() const {
  auto response = Call(Make("GET", "/v1/me/clips"), 200);
  if (!response) return response.error();
  auto page = ParseNearbyPage(response->body);
  if (!page) return page.error();
  return std::move(page->clips);
}

Expected<std::vector<OwnClip>> ApiClient::MyClipsWithManifest(
    const std::string& manifest_sha256) const {
  auto response =
      Call(Make("GET", "/v1/me/clips?manifest_sha256=" + EncodeQueryValue(manifest_sha256)), 200);
  if (!response) return response.error();
  return ParseOwnClips(response->body);
}

Expected<ClipParts> ApiClient::ListParts(const std::string& id) const {
  auto response = Call(Make("GET", "/v1/clips/" + EncodeQueryValue(id) + "/parts"), 200);
  if (!response) return response.error();
  return ParseClipParts(response->body);
}

}  // namespace reenact::proto
