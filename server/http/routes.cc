#include "server/http/routes.h"

#include <exception>
#include <iostream>

#include "server/http/handlers.h"
#include "server/http/route_match.h"

namespace reenact::server {

namespace {

Response Dispatch(const Request& request, ServiceContext& context, const RouteMatch& match) {
  const std::string& m = request.method;
  switch (match.route) {
    case RouteId::kHealth: return handlers::Health(context);
    case RouteId::kMetrics: return handlers::MetricsText(context);
    case RouteId::kMyClips: return handlers::MyClips(request, context, match);
    case RouteId::kMyToken: return handlers::RevokeOwnToken(request, context);
    case RouteId::kClips:
      return m == "POST" ? handlers::CreateClip(request, context)
                         : handlers::ListNearby(request, context, match);
    case RouteId::kClip:
      return m == "DELETE" ? handlers::DeleteClip(request, context, match)
                           : handlers::GetManifest(request, context, match);
    case RouteId::kFrame:
    case RouteId::kMap:
      return m == "PUT" ? handlers::PutPart(request, context, match)
                        : handlers::GetPart(request, context, match);
    case RouteId::kPublish: return handlers::Publish(request, context, match);
    case RouteId::kParts: return handlers::ListParts(request, context, match);
    case RouteId::kNone: break;
  }
  return ErrorResponse(404, "not_found", "no such route");
}

}  // namespace

void ServiceLimits::Check() const {
  REENACT_CHECK(max_manifest_bytes > 0, "max_manifest_bytes must be > 0");
  REENACT_CHECK(max_frame_bytes > 0, "max_frame_bytes must be > 0");
  REENACT_CHECK(max_map_bytes > 0, "max_map_bytes must be > 0");
  REENACT_CHECK(max_frame_count >= 1, "max_frame_count must be >= 1");
  REENACT_CHECK(default_page_size >= 1 && default_page_size <= max_page_size,
                "need 1 <= default_page_size <= max_page_size");
  REENACT_CHECK(default_radius_m > 0 && default_radius_m <= kMaxNearbyRadiusM,
                "default_radius_m out of range");
}

Response Handle(const Request& request, ServiceContext& context) {
  const RouteMatch match = MatchRoute(request.target);
  if (match.route == RouteId::kNone) {
    return ErrorResponse(404, "not_found", "no such route; see proto/API.md");
  }
  if (!match.Allows(request.method)) {
    std::string allow;
    for (const auto& method : match.methods) allow += (allow.empty() ? "" : ", ") + method;
    Response response = ErrorResponse(405, "method_not_allowed",
                                      request.method.substr(0, 16) + " is not allowed on " +
                                          match.pattern + "; allowed: " + allow);
    response.headers.emplace_back("Allow", allow);
    return response;
  }
  try {
    return Dispatch(request, context, match);
  } catch (const std::exception& e) {
    std::cerr << "reenact-server: internal error on " << request.method << " " << match.pattern
              << ": " << e.what() << std::endl;
    return ErrorResponse(500, "internal", "internal server error; the server log has details");
  }
}

std::optional<Response> HandleQuick(const Request& request, ServiceContext& context,
                                    size_t max_scanned) {
  if (request.method != "GET") return std::nullopt;
  const RouteMatch match = MatchRoute(request.target);
  if (match.route != RouteId::kClips) return std::nullopt;
  try {
    return handlers::ListNearbyBounded(request, context, match, max_scanned);
  } catch (const std::exception&) {
    return std::nullopt;  // Handle runs it again and reports the failure
  }
}

std::optional<Response> Admit(const Request& head, std::optional<uint64_t> content_length,
                              ServiceContext& context) {
  const RouteMatch match = MatchRoute(head.target);
  try {
    if (head.method == "POST" && match.route == RouteId::kClips) {
      return handlers::AdmitCreateClip(head, context);
    }
    if (head.method == "PUT" && (match.route == RouteId::kFrame || match.route == RouteId::kMap)) {
      return handlers::AdmitPutPart(head, content_length, context, match);
    }
  } catch (const std::exception& e) {
    std::cerr << "reenact-server: internal error admitting " << head.method << " "
              << match.pattern << ": " << e.what() << std::endl;
    return ErrorResponse(500, "internal", "internal server error; the server log has details");
  }
  return std::nullopt;
}

std::string RouteLabel(std::string_view method, std::string_view target) {
  const RouteMatch match = MatchRoute(target);
  if (match.route == RouteId::kNone || !match.Allows(method)) return "unmatched";
  return std::string(method) + " " + match.pattern;
}

size_t BodyLimit(std::string_view method, std::string_view target, const ServiceLimits& limits) {
  const RouteMatch match = MatchRoute(target);
  if (method == "POST" && match.route == RouteId::kClips) return limits.max_manifest_bytes;
  if (method == "PUT" && match.route == RouteId::kFrame) return limits.max_frame_bytes;
  if (method == "PUT" && match.route == RouteId::kMap) return limits.max_map_bytes;
  return 0;
}

}  // namespace reenact::server
