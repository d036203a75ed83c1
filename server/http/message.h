#pragma once
// Transport-free HTTP messages: what the route handlers consume and produce, so that routes
// are pure functions testable without sockets (server/http/routes.h).

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "proto/api/http_headers.h"

namespace reenact::server {

class BlobReader;  // server/storage/blob_store.h

using proto::EqualsIgnoreCase;

using HeaderList = proto::HttpHeaders;

struct Request {
  std::string method;  // "GET", "POST", ...
  std::string target;  // path and optional query as received: "/v1/clips?near=1,2"
  HeaderList headers;  // as received; look up with Header()
  std::string body;

  // The first header with this name (case-insensitive), or nullopt.
  std::optional<std::string> Header(std::string_view name) const;
};

struct Response {
  int status = 200;
  std::string content_type = "application/json";  // empty: no Content-Type (204, 304)
  HeaderList headers;  // extra headers (ETag, Location, Allow, WWW-Authenticate, ...)
  std::string body;
  // When set, the body is this stored payload instead, sent in pieces as the client takes
  // them (a large download holds one piece in memory, never the whole payload).
  std::shared_ptr<BlobReader> stream;
};

// {"error":{"code","message"}} with the given status.
Response ErrorResponse(int status, std::string_view code, std::string_view message);
// A JSON body (invalid UTF-8 in strings is replaced, never thrown on).
Response JsonResponse(int status, const nlohmann::json& body);

}  // namespace reenact::server
