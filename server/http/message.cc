#include "server/http/message.h"

#include "proto/api/api_types.h"

namespace reenact::server {

std::optional<std::string> Request::Header(std::string_view name) const {
  return proto::FindHeader(headers, name);
}

Response ErrorResponse(int status, std::string_view code, std::string_view message) {
  Response response;
  response.status = status;
  response.body = proto::ErrorBodyJson(code, message);
  return response;
}

Response JsonResponse(int status, const nlohmann::json& body) {
  Response response;
  response.status = status;
  response.body = body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return response;
}

}  // namespace reenact::server
