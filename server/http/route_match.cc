#include "server/http/route_match.h"

#include <algorithm>

namespace reenact::server {

namespace {

std::vector<std::string_view> Split(std::string_view path) {
  std::vector<std::string_view> parts;
  size_t start = 0;
  while (start <= path.size()) {
    const size_t slash = path.find('/', start);
    const size_t end = slash == std::string_view::npos ? path.size() : slash;
    parts.push_back(path.substr(start, end - start));
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  return parts;
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

bool RouteMatch::Allows(std::string_view method) const {
  return std::find(methods.begin(), methods.end(), method) != methods.end();
}

std::optional<std::string> PercentDecode(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      out.push_back(text[i]);
      continue;
    }
    if (i + 2 >= text.size()) return std::nullopt;
    const int hi = HexValue(text[i + 1]);
    const int lo = HexValue(text[i + 2]);
    if (hi < 0 || lo < 0) return std::nullopt;
    out.push_back(static_cast<char>(hi * 16 + lo));
    i += 2;
  }
  return out;
}

RouteMatch MatchRoute(std::string_view target) {
  RouteMatch match;
  const size_t question = target.find('?');
  std::string_view path = target.substr(0, question);
  if (question != std::string_view::npos) match.query = std::string(target.substr(question + 1));
  if (path.size() > 1 && path.back() == '/') path.remove_suffix(1);
  if (path.empty() || path.front() != '/') return match;
  const std::vector<std::string_view> p = Split(path.substr(1));
  auto set = [&](RouteId id, std::string pattern, std::vector<std::string> methods) {
    match.route = id;
    match.pattern = std::move(pattern);
    match.methods = std::move(methods);
  };
  if (p.size() == 1 && p[0] == "healthz") {
    set(RouteId::kHealth, "/healthz", {"GET"});
  } else if (p.size() == 1 && p[0] == "metrics") {
    set(RouteId::kMetrics, "/metrics", {"GET"});
  } else if (p.size() == 3 && p[0] == "v1" && p[1] == "me" && p[2] == "clips") {
    set(RouteId::kMyClips, "/v1/me/clips", {"GET"});
  } else if (p.size() == 3 && p[0] == "v1" && p[1] == "me" && p[2] == "token") {
    set(RouteId::kMyToken, "/v1/me/token", {"DELETE"});
  } else if (p.size() >= 2 && p[0] == "v1" && p[1] == "clips") {
    if (p.size() >= 3) {
      auto id = PercentDecode(p[2]);
      if (!id || id->empty()) return match;
      match.clip_id = *id;
    }
    if (p.size() == 2) {
      set(RouteId::kClips, "/v1/clips", {"GET", "POST"});
    } else if (p.size() == 3) {
      set(RouteId::kClip, "/v1/clips/{id}", {"GET", "DELETE"});
    } else if (p.size() == 4 && p[3] == "map") {
      set(RouteId::kMap, "/v1/clips/{id}/map", {"GET", "PUT"});
    } else if (p.size() == 4 && p[3] == "publish") {
      set(RouteId::kPublish, "/v1/clips/{id}/publish", {"POST"});
    } else if (p.size() == 4 && p[3] == "parts") {
      set(RouteId::kParts, "/v1/clips/{id}/parts", {"GET"});
    } else if (p.size() == 5 && p[3] == "frames") {
      set(RouteId::kFrame, "/v1/clips/{id}/frames/{n}", {"GET", "PUT"});
      match.frame_text = std::string(p[4]);
    }
  }
  return match;
}

}  // namespace reenact::server
