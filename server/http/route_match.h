#pragma once
// Internal to server/http: which route a request path names, and its path parameters.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace reenact::server {

enum class RouteId {
  kNone,
  kHealth,        // /healthz
  kMetrics,       // /metrics
  kClips,         // /v1/clips
  kClip,          // /v1/clips/{id}
  kFrame,         // /v1/clips/{id}/frames/{n}
  kMap,           // /v1/clips/{id}/map
  kPublish,       // /v1/clips/{id}/publish
  kParts,         // /v1/clips/{id}/parts
  kMyClips,       // /v1/me/clips
  kMyToken,       // /v1/me/token
};

struct RouteMatch {
  RouteId route = RouteId::kNone;
  std::string pattern;                // "/v1/clips/{id}/frames/{n}"
  std::vector<std::string> methods;   // methods the route allows
  std::string clip_id;                // {id}, percent-decoded
  std::string frame_text;             // {n} as written (validated by the handler)
  std::string query;                  // text after '?', undecoded

  bool Allows(std::string_view method) const;
};

RouteMatch MatchRoute(std::string_view target);

// Percent-decoding ('+' stays '+'); nullopt for a malformed escape.
std::optional<std::string> PercentDecode(std::string_view text);

}  // namespace reenact::server
