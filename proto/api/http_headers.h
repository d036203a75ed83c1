#pragma once
// HTTP header lists as both ends of the API hold them: the client (http_client.h) and the
// server's transport-free messages (server/http/message.h). Header names, URL schemes and
// media types compare ASCII case-insensitively.

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace reenact::proto {

// (name, value) pairs in the order sent or received.
using HttpHeaders = std::vector<std::pair<std::string, std::string>>;

// ASCII case-insensitive equality (HTTP header names, URL schemes, media types).
bool EqualsIgnoreCase(std::string_view a, std::string_view b);

// The value of the first header with this name (case-insensitive), or nullopt.
std::optional<std::string> FindHeader(const HttpHeaders& headers, std::string_view name);

}  // namespace reenact::proto
