#include <cmath>
#include <map>

#include "proto/api/api_types.h"
#include "proto/clip/content_hash.h"
#include "server/http/handlers.h"

namespace reenact::server::handlers {

namespace {

Response BadRequest(std::string message) {
  return ErrorResponse(400, "bad_request", message);
}

std::optional<double> ParseNumber(const std::string& text) {
  if (text.empty() || text.size() > 64) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<std::map<std::string, std::string>> ParseQuery(const std::string& query) {
  std::map<std::string, std::string> params;
  size_t start = 0;
  while (start < query.size()) {
    size_t end = query.find('&', start);
    if (end == std::string::npos) end = query.size();
    const std::string pair = query.substr(start, end - start);
    start = end + 1;
    if (pair.empty()) continue;
    const size_t eq = pair.find('=');
    auto key = PercentDecode(pair.substr(0, eq));
    auto value = PercentDecode(eq == std::string::npos ? "" : pair.substr(eq + 1));
    if (!key || !value) return std::nullopt;
    params.emplace(*key, *value);
  }
  return params;
}

// True if an If-None-Match header names this entity tag (or "*").
bool MatchesEtag(const Request& request, const std::string& etag) {
  const auto header = request.Header("If-None-Match");
  if (!header) return false;
  std::string_view rest = *header;
  while (!rest.empty()) {
    const size_t comma = rest.find(',');
    std::string_view item = rest.substr(0, comma);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (item.starts_with("W/")) item.remove_prefix(2);
    if (item == "*" || item == etag) return true;
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return false;
}

// The response to a GET of an entity with this SHA-256: 304 when the client holds it
// (If-None-Match), else 200 with its ETag and no body yet.
Response Validated(const Request& request, const std::string& sha256) {
  const std::string etag = "\"" + sha256 + "\"";
  Response response;
  response.headers.emplace_back("ETag", etag);
  response.headers.emplace_back("Cache-Control", "no-cache");
  if (MatchesEtag(request, etag)) {
    response.status = 304;
    response.content_type.clear();
  }
  return response;
}

proto::ClipSummary Summary(const ClipRecord& clip, double distance_m) {
  proto::ClipSummary summary;
  summary.id = clip.id;
  summary.title = clip.title;
  summary.author = clip.author;
  summary.lat_deg = clip.lat_deg;
  summary.lon_deg = clip.lon_deg;
  summary.alt_m = clip.alt_m;
  summary.distance_m = distance_m;
  summary.duration_s = clip.duration_s;
  summary.frame_count = clip.frame_count;
  return summary;
}

}  // namespace

Response ListNearby(const Request& request, ServiceContext& context, const RouteMatch& match) {
  return *ListNearbyBounded(request, context, match, 0);
}

std::optional<Response> ListNearbyBounded(const Request& /*request*/, ServiceContext& context,
                                          const RouteMatch& match, size_t max_scanned) {
  const ServiceLimits& limits = context.limits;
  auto params = ParseQuery(match.query);
  if (!params) return BadRequest("malformed percent-escape in the query string");
  auto near = params->find("near");
  if (near == params->end()) return BadRequest("query parameter near=LAT,LON is required");
  const size_t comma = near->second.find(',');
  const auto lat = ParseNumber(near->second.substr(0, comma));
  const auto lon = comma == std::string::npos ? std::nullopt
                                              : ParseNumber(near->second.substr(comma + 1));
  if (!lat || !lon || *lat < -90 || *lat > 90 || *lon < -180 || *lon > 180) {
    return BadRequest("near must be LAT,LON in degrees with LAT in [-90, 90] and LON in "
                      "[-180, 180]");
  }
  NearbyQuery query;
  query.lat_deg = *lat;
  query.lon_deg = *lon;
  query.radius_m = limits.default_radius_m;
  if (auto it = params->find("radius_m"); it != params->end()) {
    const auto radius = ParseNumber(it->second);
    if (!radius || *radius < 0 || *radius > kMaxNearbyRadiusM) {
      return BadRequest("radius_m must be a number of metres in [0, " +
                        std::to_string(static_cast<int64_t>(kMaxNearbyRadiusM)) + "]");
    }
    query.radius_m = *radius;
  }
  int limit = limits.default_page_size;
  if (auto it = params->find("limit"); it != params->end()) {
    const auto value = ParseNumber(it->second);
    if (!value || *value != std::floor(*value) || *value < 1 || *value > limits.max_page_size) {
      return BadRequest("limit must be an integer in [1, " +
                        std::to_string(limits.max_page_size) + "]");
    }
    limit = static_cast<int>(*value);
  }
  if (auto it = params->find("cursor"); it != params->end() && !it->second.empty()) {
    query.after = DecodeCursor(it->second);
    if (!query.after) return BadRequest("invalid cursor; pass next_cursor of a previous page");
  }
  query.limit = limit + 1;
  query.max_scanned = max_scanned;
  auto hits = context.metadata.Nearby(query);
  if (!hits && hits.error().code == "too_costly" && max_scanned > 0) return std::nullopt;
  if (!hits) return StorageFailure(hits.error());
  const bool more = hits->size() > static_cast<size_t>(limit);
  if (more) hits->resize(limit);
  nlohmann::json clips = nlohmann::json::array();
  for (const NearbyHit& hit : *hits) {
    clips.push_back(proto::ClipSummaryToJson(Summary(hit.clip, hit.distance_m)));
  }
  nlohmann::json body = {{"clips", std::move(clips)}, {"next_cursor", nullptr}};
  if (more) {
    body["next_cursor"] = EncodeCursor({hits->back().distance_m, hits->back().clip.id});
  }
  return JsonResponse(200, body);
}

Response GetManifest(const Request& request, ServiceContext& context, const RouteMatch& match) {
  auto viewer = OptionalUser(request, context);
  if (auto* response = std::get_if<Response>(&viewer)) return std::move(*response);
  auto clip = LoadVisibleClip(context, match.clip_id,
                              std::get<std::optional<UserRecord>>(viewer));
  if (auto* response = std::get_if<Response>(&clip)) return std::move(*response);
  Response response = Validated(request, std::get<ClipRecord>(clip).manifest_sha256);
  if (response.status == 304) return response;
  auto manifest = context.metadata.GetManifest(match.clip_id);
  if (!manifest) return StorageFailure(manifest.error());
  response.body = std::move(*manifest);
  return response;
}

Response GetPart(const Request& request, ServiceContext& context, const RouteMatch& match) {
  auto viewer = OptionalUser(request, context);
  if (auto* response = std::get_if<Response>(&viewer)) return std::move(*response);
  auto clip = LoadVisibleClip(context, match.clip_id,
                              std::get<std::optional<UserRecord>>(viewer));
  if (auto* response = std::get_if<Response>(&clip)) return std::move(*response);
  auto index_or = PartIndex(match);
  if (auto* response = std::get_if<Response>(&index_or)) return std::move(*response);
  const int index = std::get<int>(index_or);
  const std::string name = index == kMapPart ? "the map" : "frame " + std::to_string(index);
  auto part = context.metadata.GetPart(match.clip_id, index);
  if (!part) return StorageFailure(part.error());
  if (!*part) {
    return ErrorResponse(404, "not_found", "clip '" + match.clip_id + "' has no " + name);
  }
  if (!(*part)->present) {
    return ErrorResponse(404, "not_found",
                         name + " of clip '" + match.clip_id + "' has not been uploaded yet");
  }
  Response response = Validated(request, (*part)->spec.sha256);
  if (response.status == 304) return response;
  const std::string key = BlobKey(match.clip_id, index);
  auto reader = context.blobs.OpenReader(key);
  if (!reader) return StorageFailure(reader.error());
  if (!*reader) return StorageFailure(MakeError("storage", "blob " + key + " is missing"));
  response.content_type = "application/octet-stream";
  response.stream = std::move(*reader);
  return response;
}

Response MyClips(const Request& request, ServiceContext& context, const RouteMatch& match) {
  auto user = RequireUser(request, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  auto params = ParseQuery(match.query);
  if (!params) return BadRequest("malformed percent-escape in the query string");
  std::optional<std::string> manifest_sha256;
  for (const auto& [key, value] : *params) {
    if (key != "manifest_sha256") {
      return BadRequest("unknown query parameter '" + key.substr(0, 64) +
                        "'; /v1/me/clips takes only manifest_sha256");
    }
    if (!proto::IsSha256Hex(value)) {
      return BadRequest("manifest_sha256 must be 64 lowercase hex digits");
    }
    manifest_sha256 = value;
  }
  auto clips = context.metadata.ClipsOfOwner(std::get<UserRecord>(user).id);
  if (!clips) return StorageFailure(clips.error());
  nlohmann::json list = nlohmann::json::array();
  for (const ClipRecord& clip : *clips) {
    if (manifest_sha256 && clip.manifest_sha256 != *manifest_sha256) continue;
    nlohmann::json item = proto::ClipSummaryToJson(Summary(clip, 0.0));
    item["state"] = clip.state == ClipState::kPublished ? "published" : "draft";
    item["manifest_sha256"] = clip.manifest_sha256;
    list.push_back(std::move(item));
  }
  return JsonResponse(200, {{"clips", list}, {"next_cursor", nullptr}});
}

Response Health(ServiceContext& context) {
  auto count = context.metadata.CountClips(ClipState::kPublished);
  if (!count) {
    StorageFailure(count.error());
    return ErrorResponse(503, "unavailable", "the database is not answering");
  }
  return JsonResponse(200, {{"status", "ok"}});
}

Response MetricsText(ServiceContext& context) {
  auto drafts = context.metadata.CountClips(ClipState::kDraft);
  auto published = context.metadata.CountClips(ClipState::kPublished);
  if (!drafts) return StorageFailure(drafts.error());
  if (!published) return StorageFailure(published.error());
  Response response;
  response.content_type = "text/plain; version=0.0.4; charset=utf-8";
  response.body = context.metrics.Render(*drafts, *published);
  return response;
}

}  // namespace reenact::server::handlers
