#pragma once
// Internal to server/http: one function per route (dispatched by routes.cc) and the checks
// they share. A handler's precondition is that the route and method matched.

#include <optional>
#include <string>
#include <variant>

#include "common/error/expected.h"
#include "server/http/message.h"
#include "server/http/route_match.h"
#include "server/http/service_context.h"

namespace reenact::server::handlers {

// The caller's user, or the 401/500 response to send instead.
std::variant<UserRecord, Response> RequireUser(const Request& request, ServiceContext& context);
// Like RequireUser, but a request without Authorization is anonymous (nullopt) rather than 401.
std::variant<std::optional<UserRecord>, Response> OptionalUser(const Request& request,
                                                               ServiceContext& context);
// The clip if the viewer may read it (published, or a draft of theirs), else 404.
std::variant<ClipRecord, Response> LoadVisibleClip(ServiceContext& context, const std::string& id,
                                                   const std::optional<UserRecord>& viewer);
// The clip if the user owns it: 404 if absent or another's draft, 403 if another's published.
std::variant<ClipRecord, Response> LoadOwnedClip(ServiceContext& context, const std::string& id,
                                                 const UserRecord& user);
// Retry-After of a 503 for a database that cannot be reached.
inline constexpr int kDatabaseRetryAfterSeconds = 2;
// 503 "unavailable" with Retry-After for a database that cannot be reached (code
// "unavailable"), 500 "internal" for any other failure of the store; the details go to stderr
// only.
Response StorageFailure(const Error& error);
// The part index of a route: frame n (>= 0) or kMapPart; 400 for a malformed n.
std::variant<int, Response> PartIndex(const RouteMatch& match);

// Opaque keyset cursor of nearby pagination.
std::string EncodeCursor(const NearbyQuery::Key& key);
std::optional<NearbyQuery::Key> DecodeCursor(std::string_view cursor);

// Checks made from a request's header alone, before its body is read (routes.h, Admit): the
// refusal, or nullopt to read the body. head has no body; content_length is the declared one
// (nullopt for a chunked body).
std::optional<Response> AdmitCreateClip(const Request& head, ServiceContext& context);
std::optional<Response> AdmitPutPart(const Request& head, std::optional<uint64_t> content_length,
                                     ServiceContext& context, const RouteMatch& match);

Response CreateClip(const Request& request, ServiceContext& context);
Response PutPart(const Request& request, ServiceContext& context, const RouteMatch& match);
Response Publish(const Request& request, ServiceContext& context, const RouteMatch& match);
Response DeleteClip(const Request& request, ServiceContext& context, const RouteMatch& match);
Response ListNearby(const Request& request, ServiceContext& context, const RouteMatch& match);
// ListNearby examining at most max_scanned rows of the search box (0 = no bound); nullopt when
// the box holds more.
std::optional<Response> ListNearbyBounded(const Request& request, ServiceContext& context,
                                          const RouteMatch& match, size_t max_scanned);
Response GetManifest(const Request& request, ServiceContext& context, const RouteMatch& match);
Response GetPart(const Request& request, ServiceContext& context, const RouteMatch& match);
// GET /v1/me/clips[?manifest_sha256=HEX]: the caller's clips, optionally only those created
// from the manifest with that hash (how an interrupted upload finds its draft again).
Response MyClips(const Request& request, ServiceContext& context, const RouteMatch& match);
// GET /v1/clips/{id}/parts (owner only): every promised part with the size and SHA-256 of the
// bytes the server actually holds for it, hashed afresh from the blob store.
Response ListParts(const Request& request, ServiceContext& context, const RouteMatch& match);
// The parts of a clip whose stored bytes are absent or differ from the manifest's SHA-256
// (kMapPart for the map), found by re-reading and hashing every stored part.
Expected<std::vector<int>> DamagedParts(ServiceContext& context, const std::string& clip_id);
// DELETE /v1/me/token: revokes the token the request carries (a leaked token's owner stops
// it at once; a new one comes from the operator's `reenact-server token add`).
Response RevokeOwnToken(const Request& request, ServiceContext& context);
Response Health(ServiceContext& context);
Response MetricsText(ServiceContext& context);

}  // namespace reenact::server::handlers
