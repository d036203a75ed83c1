#pragma once
// The HTTP API (proto/API.md) as a pure function of the request and the service's stores:
// no sockets, so every route is testable directly. Errors are {"error":{"code","message"}}
// with the fitting status (400 bad_request, 401 unauthorized, 403 forbidden, 404 not_found,
// 405 method_not_allowed, 409 incomplete, 413 too_large, 415 unsupported_media_type,
// 422 invalid_manifest / size_mismatch / hash_mismatch, 500 internal, 503 unavailable).
// Storage failures are logged to stderr; the response says only "internal", or "unavailable"
// (503 with Retry-After) while the database cannot be reached.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "server/http/message.h"
#include "server/http/service_context.h"

namespace reenact::server {

// Handles one request. Never throws for any request content.
Response Handle(const Request& request, ServiceContext& context);

// Rows of a nearby search's box that HandleQuick examines at most (about 1 ms of work).
inline constexpr size_t kQuickScanRows = 2000;

// The response when the request can be answered within a small fixed bound of work, with no
// write and no wait on a lock: a nearby search whose box holds at most max_scanned rows. The
// server answers those on the network thread, saving two hand-offs between threads (a third
// of nearby throughput on 2 cores); nullopt for everything else, which goes to Handle on the
// handler pool. Never throws.
std::optional<Response> HandleQuick(const Request& request, ServiceContext& context,
                                    size_t max_scanned = kQuickScanRows);

// What can be decided from a request's header alone, before its body is read, so that no
// body is read for a caller that may not send it: for POST /v1/clips the token and the
// Content-Type; for PUT of a frame or the map also the clip's owner, the part and the declared
// size against the manifest's. The refusal (401, 403, 404, 415, 422, 500), or nullopt when the
// body should be read and the request handled. head.body is ignored; content_length is the
// declared length (nullopt for a chunked body). Never throws.
std::optional<Response> Admit(const Request& head, std::optional<uint64_t> content_length,
                              ServiceContext& context);

// The route pattern a request falls under, e.g. "PUT /v1/clips/{id}/frames/{n}", or
// "unmatched": the label of metrics, never the raw path.
std::string RouteLabel(std::string_view method, std::string_view target);

// Largest request body a route accepts, bytes (0 for routes that take no body). The server
// refuses larger bodies with 413 before reading them.
size_t BodyLimit(std::string_view method, std::string_view target, const ServiceLimits& limits);

}  // namespace reenact::server
