#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "server/auth/token.h"
#include "server/http/handlers.h"

namespace reenact::server::handlers {

namespace {

Response Unauthorized(std::string_view message) {
  Response response = ErrorResponse(401, "unauthorized", message);
  response.headers.emplace_back("WWW-Authenticate", "Bearer realm=\"reenact\"");
  return response;
}

std::string NotFoundMessage(const std::string& id) { return "no clip '" + id.substr(0, 64) + "'"; }

}  // namespace

Response StorageFailure(const Error& error) {
  std::cerr << "reenact-server: storage error [" << error.code << "]: " << error.message
            << std::endl;
  if (error.code == "unavailable") {
    Response response = ErrorResponse(
        503, "unavailable",
        "the database is not reachable; retry in a few seconds (the server log has details)");
    response.headers.emplace_back("Retry-After", std::to_string(kDatabaseRetryAfterSeconds));
    return response;
  }
  return ErrorResponse(500, "internal", "internal storage error; the server log has details");
}

std::variant<std::optional<UserRecord>, Response> OptionalUser(const Request& request,
                                                               ServiceContext& context) {
  const auto header = request.Header("Authorization");
  if (!header) return std::optional<UserRecord>();
  const auto token = ParseBearer(*header);
  if (!token) return Unauthorized("Authorization must be 'Bearer <token>'");
  auto user = Authenticate(context.metadata, *token);
  if (!user) return StorageFailure(user.error());
  if (!*user) {
    return Unauthorized(
        "unknown token (or a revoked one); ask the operator for one (reenact-server token add)");
  }
  return *user;
}

std::variant<UserRecord, Response> RequireUser(const Request& request, ServiceContext& context) {
  auto user = OptionalUser(request, context);
  if (auto* response = std::get_if<Response>(&user)) return std::move(*response);
  auto& optional_user = std::get<std::optional<UserRecord>>(user);
  if (!optional_user) return Unauthorized("this request needs 'Authorization: Bearer <token>'");
  return *optional_user;
}

std::variant<ClipRecord, Response> LoadVisibleClip(ServiceContext& context, const std::string& id,
                                                   const std::optional<UserRecord>& viewer) {
  auto clip = context.metadata.GetClip(id);
  if (!clip) return StorageFailure(clip.error());
  if (!*clip) return ErrorResponse(404, "not_found", NotFoundMessage(id));
  const bool owner = viewer && viewer->id == (*clip)->owner_id;
  if ((*clip)->state != ClipState::kPublished && !owner) {
    return ErrorResponse(404, "not_found", NotFoundMessage(id));
  }
  return **clip;
}

std::variant<ClipRecord, Response> LoadOwnedClip(ServiceContext& context, const std::string& id,
                                                 const UserRecord& user) {
  auto clip = context.metadata.GetClip(id);
  if (!clip) return StorageFailure(clip.error());
  if (!*clip) return ErrorResponse(404, "not_found", NotFoundMessage(id));
  if ((*clip)->owner_id != user.id) {
    if ((*clip)->state != ClipState::kPublished) {
      return ErrorResponse(404, "not_found", NotFoundMessage(id));
    }
    return ErrorResponse(403, "forbidden", "clip '" + id + "' belongs to another user");
  }
  return **clip;
}

std::variant<int, Response> PartIndex(const RouteMatch& match) {
  if (match.route == RouteId::kMap) return kMapPart;
  const std::string& text = match.frame_text;
  int value = -1;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || value < 0) {
    return ErrorResponse(
        400, "bad_request",
        "frame number must be a non-negative integer, got '" + text.substr(0, 32) + "'");
  }
  return value;
}

std::string EncodeCursor(const NearbyQuery::Key& key) {
  char distance[40];
  std::snprintf(distance, sizeof(distance), "%.17g", key.distance_m);
  const std::string plain = std::string(distance) + ":" + key.id;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (unsigned char c : plain) {
    out.push_back(kHex[c >> 4]);
    out.push_back(kHex[c & 15]);
  }
  return out;
}

std::optional<NearbyQuery::Key> DecodeCursor(std::string_view cursor) {
  if (cursor.empty() || cursor.size() % 2 != 0 || cursor.size() > 512) return std::nullopt;
  std::string plain;
  for (size_t i = 0; i < cursor.size(); i += 2) {
    unsigned value = 0;
    auto [end, ec] = std::from_chars(cursor.data() + i, cursor.data() + i + 2, value, 16);
    if (ec != std::errc() || end != cursor.data() + i + 2) return std::nullopt;
    plain.push_back(static_cast<char>(value));
  }
  const size_t colon = plain.find(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == plain.size()) return std::nullopt;
  const std::string distance_text = plain.substr(0, colon);
  char* end = nullptr;
  const double distance = std::strtod(distance_text.c_str(), &end);
  if (end != distance_text.c_str() + distance_text.size() || !std::isfinite(distance) ||
      distance < 0) {
    return std::nullopt;
  }
  return NearbyQuery::Key{distance, plain.substr(colon + 1)};
}

}  // namespace reenact::server::handlers
